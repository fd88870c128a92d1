#include "ltp/integrate/detail/segment_grid.h"

#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "integrator_internal.h"
#include "ltp/integrate/detail/condition_number.h"

namespace ltp::internal {

namespace {

// σmax/σmin of a factor after diagonal balancing (LAPACK dgebal, scaling only); +inf for a
// non-finite or singular one. Balancing matters: in [p; p'] coordinates an oscillator's factor
// has singular values ω and 1/ω although nothing grows or decays, and the raw condition number
// would split the period into thousands of segments for no gain in accuracy.
double FactorCondition(const Eigen::MatrixXd& f) {
  if (f.size() == 0) return 1;
  if (!f.allFinite()) return std::numeric_limits<double>::infinity();
  Eigen::MatrixXd b = f;
  const lapack_int n = static_cast<lapack_int>(b.rows());
  lapack_int ilo = 0, ihi = 0;
  std::vector<double> scale(n);
  if (LAPACKE_dgebal(LAPACK_COL_MAJOR, 'S', n, b.data(), n, &ilo, &ihi, scale.data()) != 0) b = f;
  return ConditionNumber(b);
}

// One segment of the grid with its transition factor and that factor's condition number.
struct Segment {
  double t0, t1;
  TransitionResult tr;
  double cond = 1;
};

// Integrates the pieces listed in `todo` (sorted; chains of neighbouring pieces share one
// integrator pass, see IntervalTransitions) and measures each factor's condition.
void Integrate(const PeriodicSystem& system, std::vector<Segment>& pieces,
               const std::vector<size_t>& todo, const IntegratorOptions& integrator, int threads) {
  std::vector<std::pair<double, double>> intervals;
  for (size_t i : todo) intervals.emplace_back(pieces[i].t0, pieces[i].t1);
  std::vector<TransitionResult> results =
      IntervalTransitions(system, intervals, integrator, threads);
  const long count = static_cast<long>(todo.size());
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1))
  for (long j = 0; j < count; ++j) {
    Segment& p = pieces[todo[j]];
    p.tr = std::move(results[j]);
    p.cond = p.tr.ok ? FactorCondition(p.tr.phi) : std::numeric_limits<double>::infinity();
  }
}

}  // namespace

SegmentGrid ComputeSegmentGrid(const PeriodicSystem& system, const SegmentGridOptions& options) {
  SegmentGrid grid;
  const double T = system.period();
  std::vector<Segment> pieces;
  if (!options.fixed_times.empty()) {
    for (size_t i = 0; i + 1 < options.fixed_times.size(); ++i)
      pieces.push_back({options.fixed_times[i], options.fixed_times[i + 1], {}, 1});
  } else {
    const int k = std::max(1, options.uniform_segments);
    for (int i = 0; i < k; ++i)
      pieces.push_back({T * i / k, i + 1 == k ? T : T * (i + 1) / k, {}, 1});
  }
  std::vector<size_t> todo(pieces.size());
  for (size_t i = 0; i < todo.size(); ++i) todo[i] = i;
  const double log_limit = std::log(options.max_factor_condition);
  for (int round = 0;; ++round) {
    Integrate(system, pieces, todo, options.integrator, options.threads);
    for (size_t i : todo) grid.rhs_evals += pieces[i].tr.rhs_evals;
    if (!options.refine) break;
    // Split every piece whose factor is too ill-conditioned into as many equal parts as its
    // condition number asks for (log cond is additive along the segment for a steady rate).
    std::vector<Segment> next;
    std::vector<size_t> next_todo;
    bool split = false;
    for (Segment& p : pieces) {
      if (p.cond <= options.max_factor_condition) {
        next.push_back(std::move(p));
        continue;
      }
      // A condition number near 1/eps is itself unreliable (σmin is round-off): split harder.
      int parts = std::isfinite(p.cond) && p.cond < 1e14
                      ? static_cast<int>(std::ceil(std::log(p.cond) / log_limit)) + 1
                      : 16;
      parts = std::max(parts, 2);
      if (static_cast<int>(next.size() + pieces.size()) + parts > options.max_segments) {
        next.push_back(std::move(p));
        continue;
      }
      split = true;
      for (int q = 0; q < parts; ++q) {
        next_todo.push_back(next.size());
        next.push_back({p.t0 + (p.t1 - p.t0) * q / parts,
                        q + 1 == parts ? p.t1 : p.t0 + (p.t1 - p.t0) * (q + 1) / parts,
                        {},
                        1});
      }
    }
    pieces = std::move(next);
    todo = std::move(next_todo);
    if (!split || round > 12) break;
  }
  grid.ok = true;
  double worst = 1;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const Segment& p = pieces[i];
    if (!p.tr.ok) {
      grid.ok = false;
      std::ostringstream s;
      s << "segment [" << p.t0 << ", " << p.t1 << "]: " << p.tr.message;
      grid.diagnostics.push_back(
          {DiagnosticCode::kSegmentIntegrationFailed, Severity::kFailure, s.str()});
    }
    worst = std::max(worst, p.cond);
  }
  if (options.refine && worst > options.max_factor_condition) {
    std::ostringstream s;
    s << "segment refinement stopped with a factor of condition " << worst << " (limit "
      << options.max_factor_condition << ", at most " << options.max_segments
      << " segments): the smallest multipliers may be inaccurate";
    grid.diagnostics.push_back(
        {DiagnosticCode::kSegmentRefinementStopped, Severity::kWarning, s.str()});
  }
  const bool effects = std::all_of(pieces.begin(), pieces.end(), [](const Segment& p) {
    return p.tr.local_error_effect.size() > 0 && p.tr.local_error_effect.allFinite();
  });
  grid.times.reserve(pieces.size() + 1);
  for (const Segment& p : pieces) {
    grid.times.push_back(p.t0);
    grid.factors.push_back(p.tr.phi);
    if (effects && !pieces.empty()) grid.local_error_effects.push_back(p.tr.local_error_effect);
    // At least these: a segment cut at breakpoints takes StepsOnPiece on every piece.
    if (p.tr.steps_per_period > 0)
      grid.fixed_steps += StepsOnPiece(p.tr.steps_per_period, p.t1 - p.t0, T);
  }
  grid.times.push_back(pieces.empty() ? T : pieces.back().t1);
  grid.initial_segments = options.fixed_times.empty()
                              ? std::max(1, options.uniform_segments)
                              : static_cast<int>(options.fixed_times.size()) - 1;
  grid.worst_condition = worst;
  return grid;
}

}  // namespace ltp::internal
