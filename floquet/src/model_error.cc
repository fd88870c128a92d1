// The model error of a sampled system in a Floquet result (ltp/floquet/model_error.h).
#include "ltp/floquet/model_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <vector>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"

namespace ltp {

void IncludeModelError(const std::vector<PeriodicSystem>& alternatives,
                       const FloquetOptions& options, FloquetResult& r) {
  if (alternatives.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  const double inf = std::numeric_limits<double>::infinity();
  const double omega = 2 * std::acos(-1.0) / r.period;
  std::vector<std::complex<double>> a;
  for (const FloquetMode& m : r.modes) a.push_back(m.exponent);
  // Each exponent's own sampling error e_k: its largest distance to its match.
  std::vector<double> e(a.size(), 0.0);
  for (const PeriodicSystem& alternative : alternatives) {
    if (alternative.states() != r.states ||
        std::abs(alternative.period() - r.period) > 1e-12 * r.period)
      throw InputError("IncludeModelError: an alternative model has another size or period");
    FloquetOptions o = options;
    o.compute_modes = false;  // exponents modulo jΩp are all the comparison needs
    // Its own integration error is at the tolerance; the term it gives is the models'
    // difference, orders larger wherever it matters.
    o.estimate_error = false;
    if (alternative.form() == PeriodicSystem::Form::kPiecewiseConstant)
      o.integrator.type = IntegratorType::kExpm;  // exact for held samples
    // The same samples, so factors grow alike: start from r's grid.
    if (options.segments == 0 && options.initial_segments == 0 && r.grid_segments > 0)
      o.initial_segments = r.grid_segments;
    const FloquetResult other = AnalyzeFloquet(alternative, o);
    r.rhs_evals += other.rhs_evals;  // the work reported is the whole analysis's, like its time
    if (other.modes.size() != a.size()) {
      std::fill(e.begin(), e.end(), inf);
      continue;
    }
    std::vector<std::complex<double>> b;
    for (const FloquetMode& m : other.modes) b.push_back(m.exponent);
    const std::vector<int> match = MatchExponentIndices(a, b, omega);
    for (size_t k = 0; k < a.size(); ++k)
      e[k] = std::max(e[k], match[k] < 0 ? inf : ExponentDistance(a[k], b[match[k]], omega));
  }
  const double integration = r.error_estimate.value_or(0);
  const double term = e.empty() ? 0.0 : *std::max_element(e.begin(), e.end());
  // Each exponent's band: its own integration estimate (when the analysis gave one) and its own
  // sampling error.
  std::vector<double> real_parts, own;
  std::vector<bool> rigid;
  for (size_t k = 0; k < a.size(); ++k) {
    real_parts.push_back(a[k].real());
    own.push_back(e[k] + r.modes[k].error_estimate.value_or(integration));
    rigid.push_back(r.modes[k].rigid_body);
    r.modes[k].error_estimate = own.back();
  }
  r.model_error = term;
  r.error_estimate = integration + term;
  std::ostringstream s;
  if (std::isfinite(term)) {
    s << "error estimate includes the model's sampling error " << term
      << " 1/s: the exponents of the same samples interpolated the other way"
      << (alternatives.size() > 1 ? " or in the other coordinates (multi-blade ↔ the files')" : "")
      << " differ by that much (docs/sampled-models.md)";
  } else {
    s << "another model of the same samples could not be analysed, so the model's "
         "sampling error is unknown and so is the verdict";
  }
  r.diagnostics.push_back(s.str());
  // The verdict asks whether any Re λ_k ± (integration + e_k) crosses 0.
  const double band =
      PerExponentBand(real_parts, own, rigid, 0, r.max_real_exponent, *r.error_estimate);
  if (band < *r.error_estimate) {
    std::ostringstream v;
    v << "verdict: max Re λ is within ±" << band
      << " 1/s — each exponent with its own sampling error, not the largest one";
    r.diagnostics.push_back(v.str());
  }
  const StabilityVerdict before = r.verdict;
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, band);
  r.stable = r.verdict == StabilityVerdict::kStable;
  if (r.verdict == StabilityVerdict::kMarginal && before != StabilityVerdict::kMarginal)
    r.diagnostics.push_back(
        "stability undecided (marginal): |max Re λ| is within its error estimate once the "
        "model's sampling error is included — linearise at more azimuths");
  r.elapsed_s += SecondsSince(start);  // the reported time is the whole analysis
}

double PerExponentBand(const std::vector<double>& real_parts, const std::vector<double>& own,
                       const std::vector<bool>& skip, double integration, double max_real,
                       double fallback) {
  double upper = -std::numeric_limits<double>::infinity(), lower = upper;
  for (size_t k = 0; k < real_parts.size(); ++k) {
    if (skip[k]) continue;
    upper = std::max(upper, real_parts[k] + integration + own[k]);
    lower = std::max(lower, real_parts[k] - integration - own[k]);
  }
  return std::isfinite(upper) && std::isfinite(lower) ? std::max(upper - max_real, max_real - lower)
                                                      : fallback;
}

}  // namespace ltp
