// The partial-FRF sweep: a primary route on every frequency, check routes on a subset, the
// spread between them (plus the HTF truncation check) as the error estimate of every point,
// and the resonance list.
#include "ltp/htf/pfrf.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>

#include "fft_util.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/integrate/threads.h"
#include "pfrf_route.h"

namespace ltp {

namespace {
using cd = std::complex<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;

struct RouteChoice {
  PfrfRoute primary = PfrfRoute::kModal;
  std::vector<PfrfRoute> checks;
  RouteReason kind = RouteReason::kAsRequested;
  std::string reason;
};

// The automatic choice (PfrfRoute::kAuto), from the study: with the Floquet decomposition
// computed anyway, the modal route is the cheapest per frequency and accurate to ~1e-13 on
// every study scene, jumps included; it says when it is not to be trusted (near-defective
// monodromy, unresolved mode shapes), and then the HTF (smooth A) or shooting (jumps) takes
// over. Checks: the HTF for smooth A(t) (exponential convergence, cheapest per point), shooting
// for jumps (no truncation; the HTF reached only 2e-7 at N = 64 on Meissner). Builds the
// modal model into `r` when it needs it.
bool HasJumps(const PeriodicSystem& system) {
  if (system.form() == PeriodicSystem::Form::kPiecewiseConstant) return true;
  for (double b : system.breakpoints())
    if (b > 0 && b < system.period()) return true;
  return false;
}

// Largest disagreement, relative to the largest |H_z| at a check point, at which the
// automatic choice keeps the modal route: far above the routes' own tolerances (they agree to
// ~1e-12 where both are right), far below a visible error — and above the modal values' own
// rounding, which a right model has too: Ξ and Ξ⁻¹ are each off by about u·cond Ξ, their
// product by u·cond Ξ² (undamped Mathieu 3e-9 from a tongue boundary, cond Ξ 1.8e4: modal
// and htf 4e-11 apart at rel_tol 1e-10, 3e-8 at 1e-11, as the rounding fell). Ten times that
// floor counts, up to 1e-6: beyond, the modal route is kept only if it agrees to 1e-6.
double ModalAgreementLimit(const PfrfOptions& o, double condition) {
  const double rounding = 10 * std::numeric_limits<double>::epsilon() * condition * condition;
  return std::max({1e-8, 100 * o.floquet.integrator.rel_tol, std::min(rounding, 1e-6)});
}

RouteChoice ChooseRoutes(const PeriodicSystem& system, const PfrfOptions& o, PfrfResult& r) {
  const bool jumps = HasJumps(system);
  const PfrfRoute fallback = jumps ? PfrfRoute::kShooting : PfrfRoute::kHtf;
  const char* shape = jumps ? "A(t) jumps" : "A(t) is smooth";
  RouteChoice c;
  std::string why;
  if (o.primary != PfrfRoute::kAuto) {
    c.primary = o.primary;
    c.kind = RouteReason::kAsRequested;
    why = "as requested";
  } else if (!r.floquet.ok) {
    c.primary = fallback;
    c.kind = RouteReason::kNoDecomposition;
    why = std::string("no Floquet decomposition, and ") + shape;
  } else {
    r.modal = BuildModalModel(system, r.floquet, o.modal);
    if (r.modal->reliable) {
      c.primary = PfrfRoute::kModal;
      c.kind = RouteReason::kModalResolved;
      why =
          "the Floquet decomposition is needed anyway and its mode shapes are resolved: "
          "cheapest per frequency; kept only if the check agrees";
    } else {
      c.primary = fallback;
      c.kind = RouteReason::kModalUnreliable;
      why = std::string("the modal model reports itself unreliable, and ") + shape;
    }
  }
  const bool auto_checks =
      std::find(o.checks.begin(), o.checks.end(), PfrfRoute::kAuto) != o.checks.end();
  for (PfrfRoute k : o.checks)
    if (k != PfrfRoute::kAuto && k != c.primary) c.checks.push_back(k);
  if (auto_checks) {
    PfrfRoute k = c.primary == PfrfRoute::kModal ? fallback : PfrfRoute::kModal;
    // An unreliable modal model is no check: use the other truncation-free route.
    if (k == PfrfRoute::kModal && r.modal && !r.modal->reliable)
      k = c.primary == PfrfRoute::kHtf ? PfrfRoute::kShooting : PfrfRoute::kHtf;
    if (std::find(c.checks.begin(), c.checks.end(), k) == c.checks.end() && k != c.primary)
      c.checks.push_back(k);
  }
  std::string checks;
  for (PfrfRoute k : c.checks) checks += (checks.empty() ? "" : ", ") + std::string(ToString(k));
  c.reason = std::string(ToString(c.primary)) + (checks.empty() ? "" : " checked by " + checks) +
             ": " + why;
  return c;
}
}  // namespace

void PfrfOptions::Validate() const {
  const OptionCheck check("PfrfOptions");
  if (frequencies_hz.empty()) check.Fail("frequencies_hz", "{}", "at least one frequency");
  // As the CLI's grids: a million frequencies is hours of work at the slower routes.
  if (frequencies_hz.size() > 1000000)
    check.Fail("frequencies_hz.size()", frequencies_hz.size(), "at most a million per call");
  for (double f : frequencies_hz)
    if (!std::isfinite(f) || std::abs(f) > 1e15)
      check.Fail("frequencies_hz", f,
                 "finite and at most 1e15 Hz in magnitude (beyond, ω·t has no correct digit over "
                 "a period)");
  if (min_order > max_order)
    check.Fail("min_order", min_order,
               "min_order <= max_order (" + std::to_string(max_order) + ")");
  if (std::max(std::abs(min_order), std::abs(max_order)) > 1000)
    check.Fail("min_order..max_order", std::to_string(min_order) + ".." + std::to_string(max_order),
               "orders within ±1000");
  if (input < 0) check.Fail("input", input, ">= 0");
  if (output < 0) check.Fail("output", output, ">= 0");
  if (check_every < 1) check.Fail("check_every", check_every, ">= 1");
  if (!(peak_threshold >= 0 && peak_threshold < 1))
    check.Fail("peak_threshold", peak_threshold, "in [0, 1)");
  if (max_peaks_per_order < 0) check.Fail("max_peaks_per_order", max_peaks_per_order, ">= 0");
  floquet.Validate();
  modal.Validate();
  htf.Validate();
  shooting.Validate();
}

namespace {

// One route over `points` (indices into the frequencies): set up, evaluated (in parallel
// when the route allows), reported.
RouteRun RunRoute(PfrfRoute route, const std::vector<int>& points, const PeriodicSystem& system,
                  const PfrfOptions& options, const std::function<void()>& tick, PfrfResult& r,
                  std::vector<internal::RoutePoint>& at) {
  RouteRun run;
  run.route = route;
  run.points = points;
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<internal::PfrfRouteSolver> solver =
      internal::MakeRouteSolver(route, system, options, r);
  const int n_points = static_cast<int>(points.size());
  solver->Prepare(n_points);
  run.setup_s = SecondsSince(start);
  at.assign(points.size(), {});
#pragma omp parallel for schedule(dynamic) num_threads(ThreadsFor(0)) if (solver->concurrent())
  for (int q = 0; q < n_points; ++q) {
    at[q] = solver->Evaluate(kTwoPi * options.frequencies_hz[points[q]]);
#pragma omp critical(ltp_pfrf_progress)
    tick();
  }
  run.diagnostics = solver->Finish(at);
  run.elapsed_s = SecondsSince(start);
  for (const internal::RoutePoint& p : at) {
    run.values.push_back(p.values);
    run.own_error.push_back(p.measured_error + p.assumed_error);
    if (!p.ok) ++run.failures;
  }
  return run;
}

// The primary's values, with the error it measured at each point.
void AdoptPrimary(const std::vector<internal::RoutePoint>& at, RouteRun& run, PfrfResult& r) {
  run.deviation.assign(at.size(), 0.0);
  for (size_t i = 0; i < at.size(); ++i) {
    r.values[i] = at[i].values;
    for (double& e : r.error_estimate[i]) e = at[i].measured_error;
  }
}

// Per-point deviations of a check route from the primary bound the primary's error only up to
// the check route's own error, so that is added (measured and assumed). Without it the
// estimate fell just below the true error whenever both routes erred the same way. The check's
// rounding is added too: its truncation change does not show it, and near a Jordan block the
// Hill solve is as ill-conditioned as the modes' matrix Ξ, about u·cond Ξ·|H| (undamped Mathieu
// 1e-9 inside a tongue boundary, cond Ξ = 3e4: htf off shooting by 3e-11, 4.5e-12 of |H|).
void MergeCheck(const std::vector<internal::RoutePoint>& at, RouteRun& run, PfrfResult& r) {
  const double condition = r.modal ? std::max(r.modal->condition, 1.0) : 1.0;
  for (size_t q = 0; q < run.points.size(); ++q) {
    const int i = run.points[q];
    const double rounding =
        std::numeric_limits<double>::epsilon() * condition * internal::LargestFinite(at[q].values);
    const double own = run.own_error[q] + rounding;
    double worst = 0;
    for (size_t z = 0; z < r.values[i].size(); ++z) {
      const double d = std::abs(at[q].values[z] - r.values[i][z]) + own;
      if (std::isfinite(d)) {
        worst = std::max(worst, d);
        r.error_estimate[i][z] = std::max(r.error_estimate[i][z], d);
      }
    }
    run.deviation.push_back(worst);
    r.checked[i] = true;
    r.max_disagreement = std::max(r.max_disagreement, worst);
  }
}

// Error estimate between check points: the larger of the neighbours' absolute error and
// their relative error times |H| here.
void EstimateBetweenCheckPoints(const std::vector<int>& check_points, PfrfResult& r) {
  const int F = static_cast<int>(r.values.size());
  const int Z = r.max_order - r.min_order + 1;
  for (int i = 0; i < F; ++i) {
    if (r.checked[i]) continue;
    auto it = std::upper_bound(check_points.begin(), check_points.end(), i);
    const int hi = *it, lo = *(it - 1);
    for (int z = 0; z < Z; ++z) {
      double abs_e = 0, rel_e = 0;
      for (int nb : {lo, hi}) {
        abs_e = std::max(abs_e, r.error_estimate[nb][z]);
        const double mag = std::abs(r.values[nb][z]);
        if (mag > 0) rel_e = std::max(rel_e, r.error_estimate[nb][z] / mag);
      }
      r.error_estimate[i][z] =
          std::max(r.error_estimate[i][z], std::max(abs_e, rel_e * std::abs(r.values[i][z])));
    }
  }
}

// Excitation exactly at a Floquet resonance of an (un)damped mode: H_z has a pole where
// j(ω + uΩp) = λ_k, so when ω is within the exponent's own error of it the value is not
// determined by the data at all — every route still returns a large finite number, and
// their spread says nothing. Flag it and make the estimate infinite.
void FlagExactResonances(const PeriodicSystem& system, PfrfResult& r) {
  const int F = static_cast<int>(r.values.size());
  double scale = 1;
  for (const auto& m : r.floquet.modes) scale = std::max(scale, std::abs(m.exponent));
  const double dl = r.floquet.error_estimate.value_or(0.0) + 1e-13 * scale;
  const double wp = kTwoPi / system.period();
  for (int i = 0; i < F; ++i) {
    const double omega = kTwoPi * r.frequencies_hz[i];
    for (size_t k = 0; k < r.floquet.modes.size(); ++k) {
      const cd lam = r.floquet.modes[k].exponent;
      const double d = std::hypot(lam.real(), std::remainder(omega - lam.imag(), wp));
      if (d > dl) continue;
      for (double& e : r.error_estimate[i]) e = std::numeric_limits<double>::infinity();
      std::ostringstream msg;
      msg << "resonance: the excitation at " << r.frequencies_hz[i] << " Hz is within " << d
          << " 1/s of the Floquet exponent of mode " << k + 1 << " (exponent error " << dl
          << " 1/s): H_z is unbounded there and the values are not meaningful";
      r.diagnostics.push_back({DiagnosticCode::kResonance, Severity::kWarning, msg.str()});
      break;
    }
  }
}

// The evidence that decides the automatic choice: the largest disagreement of a check route
// with the (modal) primary beyond `limit`, relative to the largest response at that check
// point; 0 when every check point agrees within the limit. What the check route's own error
// explains is no evidence against the primary: a coarse HTF truncation must not condemn a
// right modal answer.
double ModalCheckDisagreement(const PfrfResult& r, double limit) {
  double worst = 0;
  for (size_t k = 1; k < r.routes.size(); ++k)
    for (size_t q = 0; q < r.routes[k].points.size(); ++q) {
      double hmax = 0;
      for (const cd& v : r.values[r.routes[k].points[q]]) hmax = std::max(hmax, std::abs(v));
      const double d = std::max(0.0, r.routes[k].deviation[q] - 2 * r.routes[k].own_error[q]);
      if (hmax > 0 && !(d <= limit * hmax)) worst = std::max(worst, d / hmax);
    }
  return worst;
}

// The result's frame: the grid, the orders, zeroed values and estimates, the decomposition.
PfrfResult EmptySweep(const PeriodicSystem& system, const PfrfOptions& options,
                      FloquetResult floquet, std::optional<ModalModel> modal) {
  PfrfResult r;
  const int F = static_cast<int>(options.frequencies_hz.size());
  const int zmin = options.min_order, zmax = options.max_order, Z = zmax - zmin + 1;
  r.frequencies_hz = options.frequencies_hz;
  r.min_order = zmin;
  r.max_order = zmax;
  r.input = options.input;
  r.output = options.output;
  r.period = system.period();
  r.fp_hz = 1.0 / system.period();
  r.values.assign(F, std::vector<cd>(Z, cd(0)));
  r.error_estimate.assign(F, std::vector<double>(Z, 0.0));
  r.checked.assign(F, false);
  r.floquet = std::move(floquet);
  r.modal = std::move(modal);
  if (!r.floquet.ok)
    r.diagnostics.push_back({DiagnosticCode::kFloquetFailed, Severity::kWarning,
                             "Floquet analysis failed: resonances unattributed"});
  return r;
}

// Which routes run where: the primary on every frequency, the checks on every check_every-th
// and the last.
struct SweepPlan {
  PfrfRoute primary = PfrfRoute::kModal;
  std::vector<PfrfRoute> routes;  // the primary first
  std::vector<int> check_points;
  bool any_checks() const { return routes.size() > 1; }
};

SweepPlan PlanSweep(const PeriodicSystem& system, const PfrfOptions& options, PfrfResult& r) {
  const int F = static_cast<int>(options.frequencies_hz.size());
  const RouteChoice choice = ChooseRoutes(system, options, r);
  SweepPlan plan;
  plan.primary = choice.primary;
  r.route_reason = choice.kind;
  r.route_choice = choice.reason;
  if (options.primary == PfrfRoute::kAuto)
    r.diagnostics.push_back(
        {DiagnosticCode::kRoutesChosen, Severity::kNote, "route auto → " + choice.reason});
  plan.routes = {plan.primary};
  for (PfrfRoute c : choice.checks)
    if (std::find(plan.routes.begin(), plan.routes.end(), c) == plan.routes.end())
      plan.routes.push_back(c);
  for (int i = 0; i < F; i += options.check_every) plan.check_points.push_back(i);
  if (plan.check_points.back() != F - 1) plan.check_points.push_back(F - 1);
  return plan;
}

// Every route of the plan over its points, one progress tick per point.
void RunPlannedRoutes(const PeriodicSystem& system, const PfrfOptions& options,
                      const SweepPlan& plan, PfrfResult& r) {
  const int F = static_cast<int>(options.frequencies_hz.size());
  const int total = F + static_cast<int>((plan.routes.size() - 1) * plan.check_points.size());
  int done = 0;
  auto tick = [&] {
    ++done;
    if (options.progress) options.progress(done, total);
  };
  std::vector<int> all(F);
  for (int i = 0; i < F; ++i) all[i] = i;
  for (PfrfRoute route : plan.routes) {
    const bool primary = route == plan.primary;
    std::vector<internal::RoutePoint> at;
    RouteRun run = RunRoute(route, primary ? all : plan.check_points, system, options, tick, r, at);
    if (primary)
      AdoptPrimary(at, run, r);
    else
      MergeCheck(at, run, r);
    r.routes.push_back(std::move(run));
  }
}

// Every point's error estimate beyond the check points' deviations: between check points, at
// exact resonances, the modal tail; and the largest |H_z| per order.
void CompleteErrorEstimates(const PeriodicSystem& system, const SweepPlan& plan, PfrfResult& r) {
  const int F = static_cast<int>(r.values.size());
  const int Z = r.max_order - r.min_order + 1;
  r.order_max.assign(Z, 0.0);
  double global_max = 0;
  for (int i = 0; i < F; ++i)
    for (int z = 0; z < Z; ++z) {
      r.order_max[z] = std::max(r.order_max[z], std::abs(r.values[i][z]));
      global_max = std::max(global_max, std::abs(r.values[i][z]));
    }
  // Error estimate between check points: the larger of the neighbours' absolute error and
  // their relative error times |H| here.
  if (plan.any_checks()) EstimateBetweenCheckPoints(plan.check_points, r);
  if (r.floquet.ok) FlagExactResonances(system, r);
  if (r.modal && plan.primary == PfrfRoute::kModal) {
    // The modal tail bounds what the primary's Fourier truncation can add anywhere.
    for (int i = 0; i < F; ++i)
      for (int z = 0; z < Z; ++z)
        r.error_estimate[i][z] =
            std::max(r.error_estimate[i][z], r.modal->tail * std::abs(r.values[i][z]));
  }
  r.max_relative_disagreement = global_max > 0 ? r.max_disagreement / global_max : 0;
}

// Failures of the primary, an unreliable modal primary, and an unstable or marginal system.
void ReportSweepCaveats(PfrfRoute primary_route, PfrfResult& r) {
  r.ok = r.routes.front().failures == 0;
  if (!r.ok) {
    r.failure = "primary route " + std::string(ToString(primary_route)) + " failed at " +
                std::to_string(r.routes.front().failures) + " frequencies";
    r.diagnostics.push_back({DiagnosticCode::kRouteFailed, Severity::kFailure, r.failure});
  }
  if (r.modal && !r.modal->reliable && primary_route == PfrfRoute::kModal)
    r.diagnostics.push_back({DiagnosticCode::kModalUnreliable, Severity::kWarning,
                             "the modal route reports itself unreliable (see its diagnostics); "
                             "compare with --route htf or shooting"});
  if (r.floquet.ok && r.floquet.verdict == StabilityVerdict::kUnstable)
    r.diagnostics.push_back(
        {DiagnosticCode::kSystemUnstable, Severity::kWarning,
         "the system is unstable (max Re λ = " + std::to_string(r.floquet.max_real_exponent) +
             " 1/s): H_z describes the formal periodic solution, which is not "
             "reached from rest"});
  else if (r.floquet.ok && r.floquet.verdict == StabilityVerdict::kMarginal)
    r.diagnostics.push_back(
        {DiagnosticCode::kStabilityMarginal, Severity::kWarning,
         "stability undecided (marginal): |max Re λ| is within the error estimate, so the "
         "formal periodic solution H_z describes may not be reached from rest"});
}

PfrfResult SweepWithoutModal(const PeriodicSystem& system, const PfrfOptions& options,
                             std::chrono::steady_clock::time_point start, double worst,
                             double limit, PfrfResult r);

// The sweep itself, on a given Floquet decomposition (and modal model, when one was built):
// route choice, primary and check routes, error estimates, resonances. ComputePartialFrf
// validates and decomposes; the automatic choice's fallback comes back here with both.
PfrfResult SweepRoutes(const PeriodicSystem& system, const PfrfOptions& options,
                       std::chrono::steady_clock::time_point start, FloquetResult floquet,
                       std::optional<ModalModel> modal) {
  PfrfResult r = EmptySweep(system, options, std::move(floquet), std::move(modal));
  const SweepPlan plan = PlanSweep(system, options, r);
  RunPlannedRoutes(system, options, plan, r);
  CompleteErrorEstimates(system, plan, r);
  ReportSweepCaveats(plan.primary, r);
  r.resonances = FindResonances(r, r.modal ? &*r.modal : nullptr, options.peak_threshold,
                                options.max_peaks_per_order);
  if (options.primary == PfrfRoute::kAuto && plan.primary == PfrfRoute::kModal &&
      plan.any_checks()) {
    // The evidence that decides the automatic choice: the modal values against the check
    // route at the check points, relative to the largest response there.
    const double limit = ModalAgreementLimit(options, r.modal ? r.modal->condition : 1.0);
    const double worst = ModalCheckDisagreement(r, limit);
    if (worst > 0) return SweepWithoutModal(system, options, start, worst, limit, std::move(r));
  }
  r.elapsed_s = SecondsSince(start);
  return r;
}

// Redo the sweep from the same decomposition and modal model (now the check), after the modal
// primary of `r` disagreed with its check by `worst` (beyond `limit`).
PfrfResult SweepWithoutModal(const PeriodicSystem& system, const PfrfOptions& options,
                             std::chrono::steady_clock::time_point start, double worst,
                             double limit, PfrfResult r) {
  PfrfOptions again = options;
  again.primary = HasJumps(system) ? PfrfRoute::kShooting : PfrfRoute::kHtf;
  again.checks = {PfrfRoute::kModal};
  std::ostringstream s;
  s << ToString(again.primary) << " checked by modal: the modal route was tried first and "
    << "disagreed with its check by " << worst << " of the largest |H_z| (limit " << limit
    << "), so it is UNRELIABLE here";
  r.modal->reliable = false;  // the failed check is the model's verdict, not a footnote
  r.modal->diagnostics.push_back(
      {DiagnosticCode::kModalUnreliable, Severity::kWarning, "modal: UNRELIABLE — " + s.str()});
  PfrfResult fallback = SweepRoutes(system, again, start, std::move(r.floquet), std::move(r.modal));
  fallback.route_reason = RouteReason::kModalCheckFailed;
  fallback.route_choice = s.str();
  fallback.modal_cross_check_failed = true;
  fallback.diagnostics.insert(
      fallback.diagnostics.begin(),
      {DiagnosticCode::kRoutesDisagree, Severity::kWarning, "route auto → " + s.str()});
  fallback.elapsed_s = SecondsSince(start);
  return fallback;
}

}  // namespace

PfrfResult ComputePartialFrf(const PeriodicSystem& system, const PfrfOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  if (system.inputs() < 1 || system.outputs() < 1)
    throw InputError("partial FRFs need at least one input and one output; the system has " +
                     std::to_string(system.inputs()) + " inputs and " +
                     std::to_string(system.outputs()) + " outputs");
  if (options.input >= system.inputs())
    throw InputError("pfrf: input " + std::to_string(options.input) +
                     " out of range (the system has " + std::to_string(system.inputs()) + ")");
  if (options.output >= system.outputs())
    throw InputError("pfrf: output " + std::to_string(options.output) +
                     " out of range (the system has " + std::to_string(system.outputs()) + ")");
  // One Floquet decomposition: the modal route, the time route's settling time, the resonance
  // attribution and the automatic route choice all use it.
  FloquetOptions fo = options.floquet;
  fo.compute_modes = true;
  return SweepRoutes(system, options, start, AnalyzeFloquet(system, fo), std::nullopt);
}

std::vector<Resonance> FindResonances(const PfrfResult& result, const ModalModel* modal,
                                      double threshold, int max_per_order) {
  std::vector<Resonance> out;
  const int F = static_cast<int>(result.frequencies_hz.size());
  const int Z = result.max_order - result.min_order + 1;
  double global_max = 0;
  for (const auto& row : result.values)
    for (const cd& h : row) global_max = std::max(global_max, std::abs(h));
  if (!(global_max > 0) || F < 3) return out;
  const double fp = result.fp_hz;
  for (int zi = 0; zi < Z; ++zi) {
    const int z = result.min_order + zi;
    std::vector<Resonance> peaks;
    for (int i = 1; i + 1 < F; ++i) {
      const double a = std::abs(result.values[i - 1][zi]), b = std::abs(result.values[i][zi]),
                   c = std::abs(result.values[i + 1][zi]);
      if (!(b > a && b >= c && b >= threshold * global_max)) continue;
      Resonance p;
      p.order = z;
      p.f_exc_hz = result.frequencies_hz[i];
      p.f_resp_hz = p.f_exc_hz + z * fp;
      p.magnitude = b;
      const double w = kTwoPi * p.f_exc_hz;
      if (modal) {
        // Among the terms that matter (>= 1% of the largest), the one closest to its
        // resonance j(ω + uΩp) = λ_k in half-power bandwidths |Re λ_k|: an interference peak
        // next to a small resonant term still belongs to that term's line.
        const int V = modal->harmonics;
        double largest = 0, sum = 0;
        for (int k = 0; k < modal->states; ++k)
          for (int u = -V; u <= V; ++u)
            if (std::abs(z - u) <= V) {
              const double t = std::abs(modal->Term(w, k, u, z - u, result.output, result.input));
              largest = std::max(largest, t);
              sum += t;
            }
        double best = std::numeric_limits<double>::infinity(), best_term = 0;
        for (int k = 0; k < modal->states; ++k)
          for (int u = -V; u <= V; ++u) {
            if (std::abs(z - u) > V) continue;
            const double t = std::abs(modal->Term(w, k, u, z - u, result.output, result.input));
            if (!(t >= 1e-2 * largest)) continue;
            const std::complex<double> lk = modal->exponents[k];
            const double width = std::max(std::abs(lk.real()), 1e-9 * modal->omega_p);
            const double distance = std::abs(w + u * modal->omega_p - lk.imag()) / width;
            if (distance < best) {
              best = distance;
              best_term = t;
              p.mode = static_cast<size_t>(k);
              p.harmonic = z - u;
            }
          }
        p.share = sum > 0 ? best_term / sum : 0;
        if (p.mode) p.mode_line_hz = modal->exponents[*p.mode].imag() / kTwoPi + p.harmonic * fp;
      } else if (!result.floquet.modes.empty()) {
        double best = std::numeric_limits<double>::infinity();
        for (size_t k = 0; k < result.floquet.modes.size(); ++k)
          for (int v = z - 20; v <= z + 20; ++v) {
            const double line = result.floquet.modes[k].frequency_hz + v * fp;
            if (std::abs(line - p.f_resp_hz) < best) {
              best = std::abs(line - p.f_resp_hz);
              p.mode = k;
              p.harmonic = v;
              p.mode_line_hz = line;
            }
          }
      }
      peaks.push_back(p);
    }
    std::sort(peaks.begin(), peaks.end(),
              [](const Resonance& a, const Resonance& b) { return a.magnitude > b.magnitude; });
    if (static_cast<int>(peaks.size()) > max_per_order) peaks.resize(max_per_order);
    std::sort(peaks.begin(), peaks.end(),
              [](const Resonance& a, const Resonance& b) { return a.f_exc_hz < b.f_exc_hz; });
    out.insert(out.end(), peaks.begin(), peaks.end());
  }
  return out;
}

}  // namespace ltp
