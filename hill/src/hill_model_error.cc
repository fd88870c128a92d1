// A sampled model's error in Hill's estimate (hill_model_error.h).
#include "ltp/hill/hill_model_error.h"

#include <chrono>
#include <complex>
#include <limits>

#include "ltp/core/elapsed.h"
#include "ltp/floquet/detail/sampling_errors.h"
#include "ltp/floquet/model_error.h"

namespace ltp {

void IncludeModelError(const std::vector<PeriodicSystem>& alternatives,
                       const FloquetOptions& options, HillResult& h) {
  if (alternatives.empty() || h.modes.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::complex<double>> exponents = Exponents(h.modes);
  const SamplingErrors e =
      SamplingErrorsAgainst(alternatives, h.states, h.period, options, exponents);
  // Hill's estimate is one number for every exponent (none: no bound).
  detail::ApplySamplingErrors(e.per_exponent,
                              h.error_estimate.value_or(std::numeric_limits<double>::infinity()),
                              alternatives.size(), h);
  h.elapsed_s += SecondsSince(start);
}

}  // namespace ltp
