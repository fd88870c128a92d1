#include "ltp/studies/stability_boundary.h"

#include <omp.h>

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>
#include <map>

#include "ltp/core/error.h"
#include "ltp/integrate/threads.h"

namespace ltp {

namespace {

// One evaluation at the refinement tolerance: max log|ρ| and, when `checked`, its own error
// in log|ρ| (noise = error estimate × T; the monodromy route gets it from a refined run, about
// twice the work). g = max log|ρ| − (level + noise) is positive only where the growth is
// certain, so a flat, noisy max log|ρ| ≈ 0 on the stable side of an undamped boundary (thin
// stable bands, conservative rotors) never reads as a crossing (docs/stability-boundaries.md).
struct Evaluation {
  bool ok = false;  // false: failed, or (checked) no finite error estimate
  double log_rho = 0;
  double noise = 0;
};

Evaluation Evaluate(const Scene& scene, ParameterMap params, const SweepOptions& sweep,
                    const BoundaryOptions& options, bool checked) {
  const SweepPoint point = AnalyzeBoundaryPoint(scene, params, sweep, options, checked);
  Evaluation e;
  if (!point.ok) return e;
  if (checked) {
    if (!point.error_estimate || !std::isfinite(*point.error_estimate)) return e;
    e.noise = *point.error_estimate * point.period;
  }
  e.log_rho = point.max_log_multiplier;
  e.ok = std::isfinite(e.log_rho);
  return e;
}

// Root of g along `axis` between a (g < 0 side) and b (g > 0 side), either order.
// `a_far`: a further grid point on the stable side (NaN if none), used when `a` sits on the
// boundary itself: there the monodromy is defective and its computed multipliers split by the
// square root of the integration error, which can put g(a) above the level.
//
// The root of g is where the growth becomes certain; the boundary itself (max log|ρ| = 0) lies
// on the stable side of it, by (level + noise)/slope for a crossing with a finite slope and by
// ((level + noise)/c)² on a square-root branch c√δ. The secant of max log|ρ| over the final
// bracket bounds both (on the square-root branch by twice the offset), and the reported
// bracket is the final bracket plus that offset: the boundary lies within ±bracket of value.
BoundaryEstimate Refine(const Scene& scene, const ParameterMap& base, const std::string& axis,
                        double a, double b, double a_far, double span, const SweepOptions& sweep,
                        const BoundaryOptions& options) {
  BoundaryEstimate e;
  e.value = 0.5 * (a + b);
  e.bracket = std::abs(b - a);
  auto evaluate = [&](double p, bool checked) {
    ParameterMap params = base;
    params[axis] = p;
    ++e.evaluations;
    return Evaluate(scene, params, sweep, options, checked);
  };
  // The noise of the search: twice the larger of the two ends' own (it varies slowly along a
  // bracket); the search's evaluations are unchecked, and the final ends are checked below.
  const Evaluation ea = evaluate(a, true), eb = evaluate(b, true);
  if (!ea.ok || !eb.ok) {
    e.note = "not refined: the analysis failed (or gave no finite error estimate) at a bracket end";
    return e;
  }
  const double noise = 2 * std::max(ea.noise, eb.noise);
  std::map<double, double> log_rho;  // every evaluation of the search
  auto g = [&](double p) {
    const Evaluation v = evaluate(p, false);
    if (!v.ok) return std::numeric_limits<double>::quiet_NaN();
    log_rho[p] = v.log_rho;
    return v.log_rho - (options.level + noise);
  };
  double ga = ea.log_rho - (options.level + noise);
  const double gb = eb.log_rho - (options.level + noise);
  log_rho[a] = ea.log_rho;
  log_rho[b] = eb.log_rho;
  if ((ga < 0) == (gb < 0) && std::isfinite(a_far)) {
    a = a_far;
    ga = g(a);
  }
  if (!std::isfinite(ga)) {
    e.note = "not refined: the analysis failed at a bracket end";
    return e;
  }
  if ((ga < 0) == (gb < 0) || ga == 0 || gb == 0) {
    e.note =
        "not refined: at the refinement tolerance the growth is not certain on either side "
        "beyond the evaluations' own error (the boundary lies within the marginal band, or the "
        "bracket holds two crossings)";
    return e;
  }
  const double scale = std::max(std::max(std::abs(a), std::abs(b)), 1e-3 * span);
  const double width = options.rel_tol * scale;
  std::uintmax_t iterations = static_cast<std::uintmax_t>(options.max_iterations);
  try {
    const auto [lo, hi] = boost::math::tools::toms748_solve(
        [&](double p) {
          const double v = g(p);
          // A failure inside the bracket: treat it as the unstable side so the search
          // continues; the note below says the result is unreliable.
          if (!std::isfinite(v)) {
            e.note = "an evaluation inside the bracket failed";
            return 1.0;
          }
          return v;
        },
        a < b ? a : b, a < b ? b : a, a < b ? ga : gb, a < b ? gb : ga,
        [width](double x, double y) { return std::abs(y - x) <= width; }, iterations);
    e.value = 0.5 * (lo + hi);
    e.bracket = hi - lo;
    // The unstable end of the final bracket, checked with its own error estimate: its growth
    // must be certain (its own verdict unstable), or the boundary is not located.
    const bool lo_unstable = log_rho.count(lo) && log_rho[lo] > options.level + noise;
    const double u = lo_unstable ? lo : hi, st = lo_unstable ? hi : lo;
    const Evaluation check = evaluate(u, true);
    const double rise = check.ok && log_rho.count(st) ? check.log_rho - log_rho[st] : 0;
    if (!check.ok || check.log_rho <= options.level + check.noise) {
      e.bracket = std::abs(b - a);
      e.note =
          "not refined: the unstable end of the final bracket is not certainly unstable by its "
          "own error estimate";
    } else if (!(rise > 0) || hi <= lo) {
      e.bracket = std::abs(b - a);
      e.note = "not refined: max log|ρ| does not rise across the final bracket (noise)";
    } else {
      // The boundary lies on the stable side of the root, by (level + noise)/slope.
      e.bracket += (options.level + std::max(noise, check.noise)) * (hi - lo) / rise;
    }
    e.refined = e.bracket <= width && e.note.empty();
    if (e.note.empty() && e.bracket > width)
      e.note = "located within ±" + MessageNumber(e.bracket, 2) +
               ", wider than the tolerance: the evaluations' own error moves the boundary by "
               "that much (a nearly tangent crossing), or max_iterations ran out";
  } catch (const std::exception& ex) {
    e.note = std::string("not refined: ") + ex.what();
  }
  return e;
}

bool Unstable(const SweepPoint& p) { return p.ok && p.verdict == StabilityVerdict::kUnstable; }
bool Settled(const SweepPoint& p) { return p.ok && p.verdict != StabilityVerdict::kUnstable; }

std::vector<size_t> SpreadLines(size_t count, int max_lines) {
  std::vector<size_t> lines;
  if (max_lines <= 0 || count <= static_cast<size_t>(max_lines)) {
    for (size_t i = 0; i < count; ++i) lines.push_back(i);
    return lines;
  }
  for (int i = 0; i < max_lines; ++i) {
    const size_t line =
        static_cast<size_t>(std::llround(double(i) * double(count - 1) / (max_lines - 1)));
    if (lines.empty() || lines.back() != line) lines.push_back(line);
  }
  return lines;
}

}  // namespace

IntegratorOptions BoundaryIntegrator(const SweepOptions& sweep, const BoundaryOptions& options) {
  IntegratorOptions o = sweep.floquet.integrator;
  o.rel_tol = std::min(o.rel_tol, options.rel_tol_integrator);
  o.abs_tol = std::min(o.abs_tol, options.rel_tol_integrator * 1e-3);
  return o;
}

SweepPoint AnalyzeBoundaryPoint(const Scene& scene, const ParameterMap& params,
                                const SweepOptions& sweep, const BoundaryOptions& options,
                                bool checked) {
  SweepOptions tight = sweep;
  tight.modes = false;
  tight.floquet.integrator = BoundaryIntegrator(sweep, options);
  tight.hill_tol = std::min(sweep.hill_tol, options.rel_tol_integrator * 10);
  const SweepGrid none;  // no swept axes: the point is `params` itself
  return AnalyzeSweepPoint(scene, params, none, 0, tight, checked);
}

std::vector<UnstableInterval> RefineUnstableIntervals(const Scene& scene, const ParameterMap& base,
                                                      const SweepGrid& grid,
                                                      const std::vector<SweepPoint>& points,
                                                      const SweepOptions& sweep,
                                                      const BoundaryOptions& options) {
  std::vector<UnstableInterval> intervals;
  if (grid.axes.size() != 1) return intervals;
  const auto& x = grid.values[0];
  const std::string& name = grid.axes[0].name;
  const double span = x.back() - x.front();
  struct Job {
    size_t interval;
    bool hi;
    double a, b;   // stable side, unstable side
    double a_far;  // next grid point beyond a on the stable side, or NaN
  };
  const double none = std::numeric_limits<double>::quiet_NaN();
  std::vector<Job> jobs;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!Unstable(points[i]) || (i > 0 && Unstable(points[i - 1]))) continue;
    size_t j = i;
    while (j + 1 < points.size() && Unstable(points[j + 1])) ++j;
    UnstableInterval in;
    in.lo.value = x[i];
    in.hi.value = x[j];
    in.lo.bracket = in.hi.bracket = 0;
    if (i == 0) {
      in.lo.at_sweep_edge = true;
      in.lo.note = "unstable at the start of the sweep";
    } else if (!Settled(points[i - 1])) {
      in.lo.note = "not refined: the grid point below failed";
    } else {
      jobs.push_back({intervals.size(), false, x[i - 1], x[i],
                      i >= 2 && Settled(points[i - 2]) ? x[i - 2] : none});
    }
    if (j + 1 == points.size()) {
      in.hi.at_sweep_edge = true;
      in.hi.note = "unstable at the end of the sweep";
    } else if (!Settled(points[j + 1])) {
      in.hi.note = "not refined: the grid point above failed";
    } else {
      jobs.push_back({intervals.size(), true, x[j + 1], x[j],
                      j + 2 < points.size() && Settled(points[j + 2]) ? x[j + 2] : none});
    }
    intervals.push_back(in);
    i = j;
  }
  std::vector<BoundaryEstimate> results(jobs.size());
  if (!options.refine) {
    for (size_t k = 0; k < jobs.size(); ++k) {
      results[k].value = jobs[k].b;  // the unstable grid point
      results[k].bracket = std::abs(jobs[k].b - jobs[k].a);
      results[k].note = "not refined (refinement off): the grid value";
    }
  }
  const int threads = ThreadsFor(options.threads);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long k = 0; k < (options.refine ? static_cast<long>(jobs.size()) : 0L); ++k) {
    const Job& job = jobs[static_cast<size_t>(k)];
    results[static_cast<size_t>(k)] =
        Refine(scene, base, name, job.a, job.b, job.a_far, span, sweep, options);
  }
  for (size_t k = 0; k < jobs.size(); ++k)
    (jobs[k].hi ? intervals[jobs[k].interval].hi : intervals[jobs[k].interval].lo) = results[k];
  return intervals;
}

std::vector<BoundaryPoint> RefineBoundaryPoints(const Scene& scene, const ParameterMap& base,
                                                const SweepGrid& grid,
                                                const std::vector<SweepPoint>& points,
                                                const SweepOptions& sweep,
                                                const BoundaryOptions& options) {
  std::vector<BoundaryPoint> out;
  if (grid.axes.size() != 2) return out;
  const size_t n0 = grid.values[0].size(), n1 = grid.values[1].size();
  struct Job {
    BoundaryPoint point;
    double a, b;  // stable side, unstable side along point.axis
  };
  std::vector<Job> jobs;
  auto at = [&](size_t i0, size_t i1) -> const SweepPoint& { return points[i0 + n0 * i1]; };
  for (int axis = 0; axis < 2; ++axis) {
    const size_t along = axis == 0 ? n0 : n1, across = axis == 0 ? n1 : n0;
    for (size_t line : SpreadLines(across, options.max_lines)) {
      for (size_t i = 0; i + 1 < along; ++i) {
        const SweepPoint& p = axis == 0 ? at(i, line) : at(line, i);
        const SweepPoint& q = axis == 0 ? at(i + 1, line) : at(line, i + 1);
        if (!((Unstable(p) && Settled(q)) || (Settled(p) && Unstable(q)))) continue;
        Job job;
        job.point.axis = axis;
        job.point.values = p.values;
        job.point.entering_unstable = Unstable(q);
        job.a = Unstable(q) ? p.values[axis] : q.values[axis];
        job.b = Unstable(q) ? q.values[axis] : p.values[axis];
        jobs.push_back(job);
      }
    }
  }
  const int threads = ThreadsFor(options.threads);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long k = 0; k < static_cast<long>(jobs.size()); ++k) {
    Job& job = jobs[static_cast<size_t>(k)];
    ParameterMap params = base;
    const int other = 1 - job.point.axis;
    params[grid.axes[other].name] = job.point.values[other];
    const auto& v = grid.values[job.point.axis];
    job.point.estimate =
        Refine(scene, params, grid.axes[job.point.axis].name, job.a, job.b,
               std::numeric_limits<double>::quiet_NaN(), v.back() - v.front(), sweep, options);
    job.point.values[job.point.axis] = job.point.estimate.value;
  }
  for (auto& job : jobs) out.push_back(std::move(job.point));
  return out;
}

}  // namespace ltp
