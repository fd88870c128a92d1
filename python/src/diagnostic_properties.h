#pragma once
// A result's diagnostics as Python shows them: `diagnostics`, the sentences (list of str), and
// `diagnostic_codes`, the kind of each in the same order (CodeName, ltp/core/diagnostic.h),
// for code that tests or branches on what a result said.
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"

namespace ltp::python {

inline constexpr const char* kDiagnosticCodesDoc =
    "the kind of each of `diagnostics`, in the same order: stable snake_case names such as "
    "'liouville_check_failed', for code that tests what a result said (the sentences may change)";

inline std::vector<std::string> CodeNames(const std::vector<Diagnostic>& diagnostics) {
  std::vector<std::string> names;
  names.reserve(diagnostics.size());
  for (const Diagnostic& d : diagnostics) names.emplace_back(CodeName(d.code));
  return names;
}

/// The getter of `diagnostics` for a result whose member `field` holds them.
template <class Result>
auto DiagnosticTexts(std::vector<Diagnostic> Result::*field) {
  return [field](const Result& r) { return Texts(r.*field); };
}

/// The getter of `diagnostic_codes` for a result whose member `field` holds the diagnostics.
template <class Result>
auto DiagnosticCodes(std::vector<Diagnostic> Result::*field) {
  return [field](const Result& r) { return CodeNames(r.*field); };
}

}  // namespace ltp::python
