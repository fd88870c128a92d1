#pragma once
// How a model's sampling error enters a result of either route (monodromy, Hill): shared by
// floquet/src/model_error.cc and hill/src/hill_model_error.cc, not part of the API.
#include <algorithm>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/floquet/floquet.h"

namespace ltp::detail {

/// What the estimate now contains, one line.
std::string SamplingErrorLine(double term, size_t alternatives);

/// Gives each mode its band (own estimate, else `integration`, + e_k) and returns the band on
/// max Re λ that the verdict uses; says so in `diagnostics` when it is narrower than `estimate`.
double SamplingBand(const std::vector<double>& e, double integration, double max_real,
                    double estimate, std::vector<FloquetMode>& modes,
                    std::vector<Diagnostic>& diagnostics);

extern const char* const kModelUndecided;

/// The term in a result of either route: e_k on each mode's band, the largest on the estimate,
/// the verdict from the per-mode band; `integration` is the route's own estimate.
template <class Result>
void ApplySamplingErrors(const std::vector<double>& e, double integration, size_t alternatives,
                         Result& r) {
  const double term = e.empty() ? 0.0 : *std::max_element(e.begin(), e.end());
  r.model_error = term;
  r.error_estimate = integration + term;
  r.diagnostics.push_back({DiagnosticCode::kModelErrorIncluded, Severity::kNote,
                           SamplingErrorLine(term, alternatives)});
  // The verdict asks whether any Re λ_k ± (integration + e_k) crosses 0.
  const double band =
      SamplingBand(e, integration, r.max_real_exponent, *r.error_estimate, r.modes, r.diagnostics);
  const StabilityVerdict before = r.verdict;
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, band);
  r.stable = r.verdict == StabilityVerdict::kStable;
  if (r.verdict == StabilityVerdict::kMarginal && before != StabilityVerdict::kMarginal)
    r.diagnostics.push_back(
        {DiagnosticCode::kStabilityMarginal, Severity::kWarning, kModelUndecided});
}

}  // namespace ltp::detail
