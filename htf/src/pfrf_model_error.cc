// The sampling error of a sampled model in a partial-FRF sweep (ltp/htf/pfrf_model_error.h).
#include "ltp/htf/pfrf_model_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <string>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/floquet/model_error.h"

namespace ltp {

namespace {

// The other model's sweep: the same points without check routes, the modal route unless it
// says it is unreliable (then the HTF or shooting, as route auto chooses).
PfrfResult SweepOf(const PeriodicSystem& alternative, const PfrfOptions& options) {
  PfrfOptions o = options;
  o.primary = PfrfRoute::kAuto;
  o.checks.clear();
  o.progress = nullptr;
  if (alternative.form() == PeriodicSystem::Form::kPiecewiseConstant)
    o.floquet.integrator.type = IntegratorType::kExpm;  // exact for held samples
  return ComputePartialFrf(alternative, o);
}

std::string ModelErrorLine(double term, double peak, size_t alternatives) {
  std::ostringstream s;
  if (std::isfinite(term))
    s << "error estimate includes the model's sampling error: H_z of the same samples "
      << (alternatives > 1 ? "interpolated the other way or in the other coordinates"
                           : "interpolated the other way")
      << " differs by up to " << term << " (" << term / std::max(peak, 1e-300)
      << " of max |H_z|; docs/sampled-models.md)";
  else
    s << "another model of the same samples could not be swept, so the model's sampling error "
         "is unknown: every estimate is infinite";
  return s.str();
}

}  // namespace

void IncludeModelError(const std::vector<PeriodicSystem>& alternatives, const PfrfOptions& options,
                       PfrfResult& r) {
  if (alternatives.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  const double inf = std::numeric_limits<double>::infinity();
  double term = 0;
  std::vector<FloquetResult> analysed;
  for (const PeriodicSystem& alternative : alternatives) {
    if ((r.floquet.states > 0 && alternative.states() != r.floquet.states) ||
        alternative.inputs() <= options.input || alternative.outputs() <= options.output ||
        std::abs(alternative.period() - r.period) > 1e-12 * r.period)
      throw InputError(
          "IncludeModelError: an alternative model has another size, channels or period");
    PfrfResult other = SweepOf(alternative, options);
    for (size_t i = 0; i < r.values.size(); ++i)
      for (size_t z = 0; z < r.values[i].size(); ++z) {
        double d = inf;
        if (other.ok && i < other.values.size()) d = std::abs(other.values[i][z] - r.values[i][z]);
        if (!std::isfinite(d)) d = inf;
        r.error_estimate[i][z] += d;
        term = std::max(term, d);
      }
    r.floquet.rhs_evals += other.floquet.rhs_evals;
    analysed.push_back(std::move(other.floquet));  // its exponents, for the Floquet term
  }
  r.model_error = term;
  double peak = 0;
  for (double m : r.order_max) peak = std::max(peak, m);
  r.diagnostics.push_back({DiagnosticCode::kModelErrorIncluded, Severity::kNote,
                           ModelErrorLine(term, peak, alternatives.size())});
  IncludeModelError(analysed, r.floquet);
  r.elapsed_s += SecondsSince(start);  // the reported time is the whole sweep's
}

}  // namespace ltp
