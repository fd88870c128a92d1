#pragma once
// What every fuzz target shares. A target may refuse an input only with an ltp::Error (the
// library's typed errors, which the CLI turns into one line and exit 2); any other exception
// (std::bad_alloc, a parser library's own exception, std::out_of_range, ...) would reach the
// user as an internal message, so it is a finding and the target aborts on it.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "ltp/core/error.h"

namespace ltp::fuzz {

template <class Work>
void RefuseOnlyWithLtpErrors(Work&& work) {
  try {
    work();
  } catch (const ltp::Error&) {
    // a clear refusal: fine
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz finding: untyped exception escaped: %s\n", e.what());
    std::abort();
  }
}

}  // namespace ltp::fuzz
