// StateTransition: input checks, the restart grid, dispatch to the integrator families, the
// automatic resolution loop of the fixed-step methods, and the names of the integrators.
#include "ltp/integrate/integrator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "integrator_internal.h"
#include "ltp/core/error.h"
#include "ltp/integrate/integrator_choice.h"

namespace ltp {

namespace {

struct NamedType {
  IntegratorType type;
  std::string_view name;
};

constexpr std::array<NamedType, 11> kNames = {{
    {IntegratorType::kDopri5, "dopri5"},
    {IntegratorType::kRkf78, "rkf78"},
    {IntegratorType::kBulirschStoer, "bs"},
    {IntegratorType::kCvodeBdf, "cvode"},
    {IntegratorType::kCvodeAdams, "cvode-adams"},
    {IntegratorType::kMagnus4, "magnus4"},
    {IntegratorType::kMagnus6, "magnus6"},
    {IntegratorType::kExpm, "expm"},
    {IntegratorType::kTaylor, "taylor"},
    {IntegratorType::kMagnusFilon, "magnus-filon"},
    {IntegratorType::kAuto, "auto"},
}};

// Automatic resolution: start coarse, double until two successive results agree to rel_tol.
constexpr int kAutoStartSteps = 8;
constexpr int kAutoMaxSteps = 1 << 20;
// Doublings tried while the result is not finite (too-long steps) before reporting overflow.
constexpr long kNonFiniteRefinements = 64;

bool IsFixedStep(IntegratorType type) {
  return type == IntegratorType::kMagnus4 || type == IntegratorType::kMagnus6 ||
         type == IntegratorType::kExpm || type == IntegratorType::kMagnusFilon;
}

// ||Φ_a − Φ_b|| / ||Φ_a|| (Frobenius), 0 when both vanish (e.g. total underflow).
double RelativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const double diff = (a - b).norm();
  const double scale = a.norm();
  if (diff == 0) return 0;
  return scale > 0 ? diff / scale : std::numeric_limits<double>::infinity();
}

// The fixed steps or the automatic resolution loop of `integrator` (FixedStepIntegrator or
// MagnusFilonIntegrator) over the restart points.
template <typename Integrator>
TransitionResult ResolveFixedSteps(const PeriodicSystem& system, Integrator& integrator,
                                   const std::vector<double>& points,
                                   const IntegratorOptions& options) {
  TransitionResult result;
  if (options.steps_per_period > 0) {
    result.phi = integrator.Run(points, options.steps_per_period);
    result.steps_per_period = options.steps_per_period;
    result.ok = true;
  } else {
    // Doubling loop; the Richardson difference of the last two passes is the error estimate.
    // The reported resolution is the step density actually used (short pieces start at one
    // step, so it can exceed kAutoStartSteps · refine).
    const double span = points.back() - points.front();
    auto density = [&] {
      return static_cast<int>(std::lround(integrator.last_pass_steps() * system.period() / span));
    };
    long refine = 1;
    Eigen::MatrixXd coarse = integrator.Run(points, kAutoStartSteps, refine);
    double previous_change = std::numeric_limits<double>::infinity();
    while (true) {
      if (!coarse.allFinite()) {
        // Steps far too long for the Magnus series (h‖A‖ ≫ 1: its commutator terms overflow
        // the exponential) look like this too: refine a few times before calling it overflow.
        if (refine < kNonFiniteRefinements) {
          refine *= 2;
          coarse = integrator.Run(points, kAutoStartSteps, refine);
          continue;
        }
        result.phi = std::move(coarse);
        result.steps_per_period = density();
        break;
      }
      refine *= 2;
      Eigen::MatrixXd fine = integrator.Run(points, kAutoStartSteps, refine);
      const double change = RelativeDifference(fine, coarse);
      result.error_estimate = change;
      result.phi = fine;
      result.steps_per_period = density();
      if (change <= options.rel_tol) {
        result.ok = true;
        break;
      }
      // Round-off plateau: in the asymptotic regime a doubling divides the change by 2^order
      // (16 or 64); once it no longer halves at a level already near round-off, more steps
      // only add expm round-off (seen at rel_tol 1e-12 on the 22-state tower-rotor, where the
      // loop otherwise ran to a million steps per period). Accept, with the plateau as the
      // error estimate.
      if (change < 1e-9 && change > 0.5 * previous_change) {
        result.ok = true;
        std::ostringstream s;
        s << "round-off plateau: relative change " << change << " at " << result.steps_per_period
          << " steps per period (rel_tol " << options.rel_tol << " not reachable)";
        result.message = s.str();
        break;
      }
      previous_change = change;
      if (kAutoStartSteps * refine >= kAutoMaxSteps || !fine.allFinite()) {
        std::ostringstream s;
        s << "did not reach rel_tol = " << options.rel_tol << " with " << result.steps_per_period
          << " steps per period (last relative change " << change << ")";
        result.message = s.str();
        break;
      }
      coarse = std::move(fine);
    }
    // An accepted result ends the loop before the last coarse pass is replaced: that pass is
    // what a run held only to the tolerance gives, and its offset from the reported (finer) one
    // the carried local error (docs/local-error-estimate.md, "Fixed steps").
    if (result.ok && options.carry_local_errors) result.local_error_effect = coarse - result.phi;
  }
  result.steps = integrator.steps();
  result.rhs_evals = integrator.rhs_evals();
  return result;
}

TransitionResult FixedStepTransition(const PeriodicSystem& system,
                                     const std::vector<double>& points,
                                     const IntegratorOptions& options) {
  if (options.type == IntegratorType::kMagnusFilon) {
    internal::MagnusFilonIntegrator integrator(system);
    if (!integrator.unsuitable().empty()) {
      TransitionResult declined;
      declined.message = "magnus-filon does not apply: " + integrator.unsuitable();
      return declined;
    }
    return ResolveFixedSteps(system, integrator, points, options);
  }
  internal::FixedStepIntegrator integrator(system, options.type);
  if (options.type == IntegratorType::kExpm &&
      system.form() == PeriodicSystem::Form::kPiecewiseConstant) {
    TransitionResult result;
    result.phi = integrator.RunPiecewiseConstant(points);
    result.ok = true;
    result.steps = integrator.steps();
    result.rhs_evals = integrator.rhs_evals();
    return result;
  }
  TransitionResult result = ResolveFixedSteps(system, integrator, points, options);
  if (result.ok && options.type == IntegratorType::kExpm)
    result.message =
        "expm on a non-piecewise-constant system: exponential midpoint rule, 2nd order";
  return result;
}

}  // namespace

std::string_view ToString(IntegratorType type) {
  for (const auto& [t, name] : kNames)
    if (t == type) return name;
  return "unknown";
}

std::optional<IntegratorType> ParseIntegratorType(std::string_view name) {
  for (const auto& [t, n] : kNames)
    if (n == name) return t;
  return std::nullopt;
}

std::string IntegratorNames() {
  std::string names(ToString(IntegratorType::kAuto));
  for (IntegratorType t : AllIntegrators()) (names += ", ") += ToString(t);
  return names;
}

std::vector<IntegratorType> AllIntegrators() {
  std::vector<IntegratorType> all;
  for (const auto& named : kNames)
    if (named.type != IntegratorType::kAuto) all.push_back(named.type);
  return all;
}

IntegratorOptions RefinedIntegratorOptions(const IntegratorOptions& options) {
  IntegratorOptions fine = options;
  fine.rel_tol = std::max(options.rel_tol * 1e-2, 1e-15);
  fine.abs_tol = options.abs_tol * 1e-2;
  if (fine.steps_per_period > 0) fine.steps_per_period *= 2;
  return fine;
}

void IntegratorOptions::Validate() const {
  const OptionCheck check("IntegratorOptions");
  if (!ParseIntegratorType(ToString(type)))
    check.Fail("type", static_cast<int>(type), "one of the IntegratorType values");
  // Below ~1e-15 no integrator in double precision can deliver the tolerance (eps = 2.2e-16
  // per operation, accumulated over the steps): refuse it rather than fail at run time.
  if (!(rel_tol >= 1e-15 && rel_tol < 1))
    check.Fail("rel_tol", rel_tol, "1e-15 <= rel_tol < 1 (double precision delivers no more)");
  if (!(abs_tol >= 0 && std::isfinite(abs_tol)))
    check.Fail("abs_tol", abs_tol, "0 <= abs_tol < inf");
  // 10^8 steps per period is hours of fixed steps already; the refined run doubles the count,
  // which must stay an int.
  if (steps_per_period < 0 || steps_per_period > 100000000)
    check.Fail("steps_per_period", steps_per_period, "0 <= steps_per_period <= 1e8");
  if (max_steps <= 0) check.Fail("max_steps", max_steps, "max_steps > 0");
}

namespace internal {

namespace {
// Points of [t0, t1] this close are one point: a piece shorter would only carry round-off.
double MergeDistance(double t0, double t1, double period) {
  return 64 * std::numeric_limits<double>::epsilon() *
         std::max({std::abs(t0), std::abs(t1), period});
}
}  // namespace

std::vector<double> RestartPoints(const PeriodicSystem& system, double t0, double t1) {
  std::vector<double> points = {t0};
  const double period = system.period();
  const double merge = MergeDistance(t0, t1, period);
  const auto& breaks = system.breakpoints();
  if (!breaks.empty()) {
    const double first = std::floor(t0 / period);
    const double last = std::ceil(t1 / period);
    for (double k = first; k <= last; ++k) {
      for (double b : breaks) {
        const double t = k * period + b;
        if (t > t0 + merge && t < t1 - merge && t > points.back() + merge) points.push_back(t);
      }
    }
  }
  if (t1 > points.back()) points.push_back(t1);
  return points;
}

std::vector<Piece> TransitionPieces(const PeriodicSystem& system,
                                    const std::vector<double>& times) {
  std::vector<Piece> pieces;
  const double period = system.period();
  for (size_t i = 0; i + 1 < times.size(); ++i) {
    const std::vector<double> points = RestartPoints(system, times[i], times[i + 1]);
    // Does times[i] itself sit on a breakpoint copy (within the merge distance)?
    bool on_jump = i == 0;
    const double merge = MergeDistance(times[i], times[i + 1], period);
    for (double b : system.breakpoints()) {
      const double copy = b + std::round((times[i] - b) / period) * period;
      on_jump = on_jump || std::abs(copy - times[i]) <= merge;
    }
    for (size_t p = 0; p + 1 < points.size(); ++p)
      pieces.push_back({points[p], points[p + 1], p > 0 || on_jump, p + 2 == points.size()});
  }
  return pieces;
}

PieceWindow::PieceWindow(double a, double b) {
  const double margin =
      8 * std::numeric_limits<double>::epsilon() * std::max(std::abs(a), std::abs(b));
  lo_ = a + margin;
  hi_ = b - margin;
  if (lo_ > hi_) lo_ = hi_ = 0.5 * (a + b);  // a sliver piece: its midpoint
}

double InitialStep(double norm_a, double length, double rel_tol, int order, double error_constant) {
  if (!(norm_a > 0) || !std::isfinite(norm_a)) return length;
  return std::min(length, std::pow(rel_tol / error_constant, 1.0 / (order + 1)) / norm_a);
}

double TaylorErrorConstant(int order) { return 1 / std::tgamma(order + 2.0); }

}  // namespace internal

TransitionResult StateTransition(const PeriodicSystem& system, double t0, double t1,
                                 const IntegratorOptions& requested) {
  requested.Validate();
  const IntegratorOptions options = ResolveIntegrator(system, requested);
  if (!std::isfinite(t0) || !std::isfinite(t1)) {
    std::ostringstream s;
    s << "StateTransition: t0 = " << t0 << ", t1 = " << t1 << " must be finite";
    throw InputError(s.str());
  }
  if (t1 < t0) {
    std::ostringstream s;
    s << "StateTransition: t1 = " << t1 << " < t0 = " << t0 << " (only forward transitions)";
    throw InputError(s.str());
  }
  const int n = system.states();
  if (t1 == t0 || n == 0) {
    TransitionResult result;
    result.phi = Eigen::MatrixXd::Identity(n, n);
    result.ok = true;
    return result;
  }

  const std::vector<double> points = internal::RestartPoints(system, t0, t1);
  TransitionResult result;
  switch (options.type) {
    case IntegratorType::kDopri5:
    case IntegratorType::kRkf78:
    case IntegratorType::kBulirschStoer:
      result = std::move(
          internal::OdeintTransitions(system, internal::TransitionPieces(system, {t0, t1}), options)
              .back());
      break;
    case IntegratorType::kCvodeBdf:
    case IntegratorType::kCvodeAdams:
      result = internal::CvodeTransition(system, points, options);
      break;
    case IntegratorType::kMagnus4:
    case IntegratorType::kMagnus6:
    case IntegratorType::kExpm:
    case IntegratorType::kMagnusFilon:
      result = FixedStepTransition(system, points, options);
      break;
    case IntegratorType::kTaylor:
      result = std::move(internal::TaylorTransitions(system, {t0, t1}, options).back());
      break;
    case IntegratorType::kAuto:  // resolved above
      break;
  }
  if (!IsFixedStep(options.type)) result.error_estimate.reset();
  if (!result.phi.allFinite()) {
    result.ok = false;
    result.message = internal::kNotFiniteMessage;
  }
  return result;
}

std::vector<TransitionResult> ConsecutiveTransitions(const PeriodicSystem& system,
                                                     const std::vector<double>& times,
                                                     const IntegratorOptions& requested) {
  requested.Validate();
  const IntegratorOptions options = ResolveIntegrator(system, requested);
  for (size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1]))) {
      std::ostringstream s;
      s << "ConsecutiveTransitions: times must be finite and strictly increasing (entry " << i
        << " = " << times[i] << ")";
      throw InputError(s.str());
    }
  }
  std::vector<TransitionResult> results;
  if (times.size() < 2) return results;
  const bool adaptive_odeint = options.type == IntegratorType::kDopri5 ||
                               options.type == IntegratorType::kRkf78 ||
                               options.type == IntegratorType::kBulirschStoer;
  if (options.type == IntegratorType::kTaylor && system.states() > 0) {
    results = internal::TaylorTransitions(system, times, options);
    if (options.on_advance) options.on_advance(times.back() - times.front());
    return results;
  }
  if (!adaptive_odeint || system.states() == 0) {
    for (size_t i = 0; i + 1 < times.size(); ++i) {
      results.push_back(StateTransition(system, times[i], times[i + 1], options));
      if (options.on_advance) options.on_advance(times[i + 1] - times[i]);
    }
    return results;
  }
  results = internal::OdeintTransitions(system, internal::TransitionPieces(system, times), options);
  for (TransitionResult& r : results) {
    if (r.ok && !r.phi.allFinite()) {
      r.ok = false;
      r.message = internal::kNotFiniteMessage;
    }
  }
  return results;
}

std::vector<TransitionResult> IntervalTransitions(
    const PeriodicSystem& system, const std::vector<std::pair<double, double>>& intervals,
    const IntegratorOptions& options, int threads) {
  options.Validate();
  std::vector<std::pair<size_t, size_t>> jobs;  // [first, last) ranges of intervals
  const size_t target =
      std::max<size_t>(1, intervals.size() / (2 * static_cast<size_t>(std::max(threads, 1))));
  for (size_t j = 0; j < intervals.size();) {
    size_t k = j + 1;
    while (k < intervals.size() && k - j < target && intervals[k].first == intervals[k - 1].second)
      ++k;
    jobs.emplace_back(j, k);
    j = k;
  }
  std::vector<TransitionResult> results(intervals.size());
  const long count = static_cast<long>(jobs.size());
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1))
  for (long job = 0; job < count; ++job) {
    const auto [first, last] = jobs[job];
    std::vector<double> times = {intervals[first].first};
    for (size_t j = first; j < last; ++j) times.push_back(intervals[j].second);
    std::vector<TransitionResult> pass;
    std::string failure = "not integrated: an earlier factor of the same pass failed";
    try {
      pass = ConsecutiveTransitions(system, times, options);
    } catch (const std::exception& e) {  // never let an exception cross the OpenMP region
      failure = e.what();
    }
    for (size_t j = first; j < last; ++j) {
      if (j - first < pass.size()) {
        results[j] = std::move(pass[j - first]);
      } else {
        results[j].ok = false;
        results[j].message = failure;
      }
    }
  }
  return results;
}

}  // namespace ltp
