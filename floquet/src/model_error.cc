// The model error of a sampled system in a Floquet result (ltp/floquet/model_error.h).
#include "ltp/floquet/model_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/floquet/detail/sampling_errors.h"

namespace ltp {

namespace {

// The other models' integrator tolerance: their exponents need only be good to a small part of
// the models' difference (measured: 5e-5 1/s on a 124-state rotor, where 1e-7 leaves an
// integration error of ~1e-9 1/s) — an explicit method's work per radian is about half of
// that at 1e-10 (docs/model-sizes.md).
constexpr double kAlternativeTolerance = 1e-7;

// An alternative's analysis for the comparison: multipliers only (exponents modulo jΩp are all
// it needs); for a cut-off analysis, the modes below twice it (one projection, no check), so
// that each of ours finds its match although the other model's mean places the modes near the
// cut-off a little differently. `grid_segments` > 0 starts it from the analysed model's grid.
FloquetResult AnalyzeAlternative(const PeriodicSystem& alternative, const std::string& name,
                                 const FloquetOptions& options, int grid_segments) {
  FloquetOptions o = options;
  o.compute_modes = false;
  // The term it gives is the models' difference, orders above a tight tolerance wherever it
  // matters: the other model runs at kAlternativeTolerance (where the user's is tighter), its own
  // error estimated in the same pass (Bulirsch–Stoer's carried local errors, Taylor series'
  // order-p product; a refined run for other integrators) and added to each distance, so the term
  // stays at least the difference to the other model's exact exponents.
  o.integrator.rel_tol = std::max(options.integrator.rel_tol, kAlternativeTolerance);
  o.integrator.abs_tol = std::max(options.integrator.abs_tol, 1e-3 * kAlternativeTolerance);
  o.estimate_error = true;
  o.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
  if (options.modes_below > 0) o.modes_below = kModesBelowCheck * options.modes_below;
  if (alternative.form() == PeriodicSystem::Form::kPiecewiseConstant)
    o.integrator.type = IntegratorType::kExpm;  // exact for held samples
  // The same samples, so factors grow alike: start from the analysed model's grid.
  if (options.segments == 0 && options.initial_segments == 0 && grid_segments > 0)
    o.initial_segments = grid_segments;
  o.on_progress = PrefixedProgress(options.on_progress, name + ": ");  // named as such
  return AnalyzeFloquet(alternative, o);
}

// Each exponent's sampling error: the largest distance (modulo jΩp) of exponents[k] to its
// match among each alternative's exponents (+inf when an analysis failed or found too few).
// A cut-off analysis's alternatives hold more modes than ours; a full one's the same count.
std::vector<double> SamplingErrorsOf(const std::vector<FloquetResult>& analysed,
                                     const std::vector<std::complex<double>>& exponents,
                                     double period, bool cut_off) {
  const double inf = std::numeric_limits<double>::infinity();
  const double omega = 2 * std::acos(-1.0) / period;
  std::vector<double> e(exponents.size(), 0.0);
  for (const FloquetResult& other : analysed) {
    if (cut_off ? other.modes.size() < exponents.size() : other.modes.size() != exponents.size()) {
      std::fill(e.begin(), e.end(), inf);
      continue;
    }
    const std::vector<std::complex<double>> b = Exponents(other.modes);
    const std::vector<int> match = MatchExponentIndices(exponents, b, omega);
    for (size_t k = 0; k < exponents.size(); ++k) {
      if (match[k] < 0) {
        e[k] = inf;
        continue;
      }
      const FloquetMode& m = other.modes[static_cast<size_t>(match[k])];
      const double own = m.error_estimate.value_or(other.error_estimate.value_or(0.0));
      e[k] = std::max(e[k], ExponentDistance(exponents[k], b[match[k]], omega) + own);
    }
  }
  return e;
}

void CheckAlternative(const PeriodicSystem& alternative, int states, double period) {
  if (alternative.states() != states || std::abs(alternative.period() - period) > 1e-12 * period)
    throw InputError("IncludeModelError: an alternative model has another size or period");
}

// Every alternative analysed (in order, named "other model i of m"), and what they cost.
struct AnalysedAlternatives {
  std::vector<FloquetResult> results;
  long evaluations = 0;
};

AnalysedAlternatives AnalyzeAlternatives(const std::vector<PeriodicSystem>& alternatives,
                                         int states, double period, const FloquetOptions& options,
                                         int grid_segments) {
  AnalysedAlternatives a;
  for (size_t i = 0; i < alternatives.size(); ++i) {
    CheckAlternative(alternatives[i], states, period);
    const std::string name =
        "other model " + std::to_string(i + 1) + " of " + std::to_string(alternatives.size());
    a.results.push_back(AnalyzeAlternative(alternatives[i], name, options, grid_segments));
    a.evaluations += a.results.back().rhs_evals;  // the work reported is the whole analysis's
  }
  return a;
}

}  // namespace

namespace detail {

std::string SamplingErrorLine(double term, size_t alternatives) {
  std::ostringstream s;
  if (std::isfinite(term)) {
    s << "error estimate includes the model's sampling error " << term
      << " 1/s: the exponents of the same samples interpolated the other way"
      << (alternatives > 1 ? " or in the other coordinates (multi-blade ↔ the files')" : "")
      << " differ by that much (docs/sampled-models.md)";
  } else {
    s << "another model of the same samples could not be analysed, so the model's "
         "sampling error is unknown and so is the verdict";
  }
  return s.str();
}

// Gives each mode its band (own estimate + e_k) and returns the band on max Re λ that the
// verdict uses; says so when it is narrower than the largest.
double SamplingBand(const std::vector<double>& e, double integration, double max_real,
                    double estimate, std::vector<FloquetMode>& modes,
                    std::vector<Diagnostic>& diagnostics) {
  for (size_t k = 0; k < modes.size(); ++k)
    modes[k].error_estimate = e[k] + modes[k].error_estimate.value_or(integration);
  const double band = PerModeBand(modes, max_real, estimate);
  if (band < estimate) {
    std::ostringstream v;
    v << "verdict: max Re λ is within ±" << band
      << " 1/s — each exponent with its own sampling error, not the largest one";
    diagnostics.push_back({DiagnosticCode::kVerdictPerModeBand, Severity::kNote, v.str()});
  }
  return band;
}

const char* const kModelUndecided =
    "stability undecided (marginal): |max Re λ| is within its error estimate once the model's "
    "sampling error is included — linearise at more azimuths";

}  // namespace detail

SamplingErrors SamplingErrorsAgainst(const std::vector<PeriodicSystem>& alternatives, int states,
                                     double period, const FloquetOptions& options,
                                     const std::vector<std::complex<double>>& exponents,
                                     int grid_segments) {
  const AnalysedAlternatives a =
      AnalyzeAlternatives(alternatives, states, period, options, grid_segments);
  return {SamplingErrorsOf(a.results, exponents, period, options.modes_below > 0), a.evaluations};
}

void IncludeModelError(const std::vector<PeriodicSystem>& alternatives,
                       const FloquetOptions& options, FloquetResult& r) {
  if (alternatives.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  const AnalysedAlternatives a =
      AnalyzeAlternatives(alternatives, r.states, r.period, options, r.grid_segments);
  r.rhs_evals += a.evaluations;
  IncludeModelError(a.results, r);
  r.elapsed_s += SecondsSince(start);  // the reported time is the whole analysis
}

void IncludeModelError(const std::vector<FloquetResult>& analysed, FloquetResult& r) {
  if (analysed.empty()) return;
  for (const FloquetResult& other : analysed)
    if (other.states != r.states || std::abs(other.period - r.period) > 1e-12 * r.period)
      throw InputError("IncludeModelError: an alternative model has another size or period");
  const std::vector<double> e =
      SamplingErrorsOf(analysed, Exponents(r.modes), r.period, r.reduction.has_value());
  detail::ApplySamplingErrors(e, r.error_estimate.value_or(0), analysed.size(), r);
}

double PerModeBand(const std::vector<FloquetMode>& modes, double max_real, double fallback) {
  std::vector<double> real_parts, own;
  std::vector<bool> rigid;
  for (const FloquetMode& m : modes) {
    real_parts.push_back(m.exponent.real());
    own.push_back(m.error_estimate.value_or(fallback));
    rigid.push_back(m.rigid_body);
  }
  return PerExponentBand(real_parts, own, rigid, 0, max_real, fallback);
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
