#include "ltp/integrate/detail/segment_grid.h"

#include <lapacke.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <sstream>

#include "integrator_internal.h"
#include "ltp/integrate/detail/condition_number.h"
#include "ltp/integrate/detail/matrix_product.h"

namespace ltp::internal {

namespace {

// σmax/σmin of a factor after diagonal balancing (LAPACK dgebal, scaling only); +inf for a
// singular one. Balancing matters: in [p; p'] coordinates an oscillator's factor has singular
// values ω and 1/ω although nothing grows or decays, and the raw condition number would split
// the period into thousands of segments for no gain in accuracy.
double BalancedCondition(const Eigen::MatrixXd& f) {
  Eigen::MatrixXd b = f;
  const lapack_int n = static_cast<lapack_int>(b.rows());
  lapack_int ilo = 0, ihi = 0;
  std::vector<double> scale(n);
  if (LAPACKE_dgebal(LAPACK_COL_MAJOR, 'S', n, b.data(), n, &ilo, &ihi, scale.data()) != 0) b = f;
  return ConditionNumber(b);
}

// A factor's condition as the grid judges it (+inf when not finite). With a modal basis W (given
// with its LU) the factor is first taken into the mean's modes, W⁻¹ Φ W, and the states' measure
// is consulted only when that one exceeds the limit: a factor either measure accepts is
// accepted, so the basis never asks for more segments than the states would.
double FactorCondition(const Eigen::MatrixXd& f, const SegmentGridOptions& options,
                       const Eigen::PartialPivLU<Eigen::MatrixXd>* modal_lu) {
  if (f.size() == 0) return 1;
  if (!f.allFinite()) return std::numeric_limits<double>::infinity();
  if (!modal_lu) return BalancedCondition(f);
  Eigen::MatrixXd fw(f.rows(), f.cols());
  MultiplyInto(f, *options.modal_basis, fw);
  const double modal = BalancedCondition(modal_lu->solve(fw));
  return modal <= options.max_factor_condition ? modal : std::min(modal, BalancedCondition(f));
}

// How many equal parts a piece of condition `cond` is split into (log cond is additive along
// the segment for a steady rate); a condition near 1/eps is itself unreliable (σmin is
// round-off): split harder. The states' measure takes the count plus one. The modes' measure
// follows the rates closely, so a fifth to spare is enough, rounded up to a power of two: the
// starting grids and the mode samples are powers of two, so the samples stay on grid points and
// the refined run's halving adds none (250-state set: 8 → 24 segments and 64 in the refined
// run with the count plus one; 16 and 32 so). The states' rule is kept for the other
// integrators: at rel_tol 1e-3 on stiff.yaml, Bulirsch–Stoer's local-error estimate fell below
// the true error on the power-of-two grid (67 against 111 1/s).
int SplitParts(double cond, double log_limit, bool modal) {
  if (!std::isfinite(cond) || cond >= 1e14) return 16;
  const double count = std::log(cond) / log_limit;
  if (!modal) return std::max(2, static_cast<int>(std::ceil(count)) + 1);
  return static_cast<int>(
      std::bit_ceil(static_cast<unsigned>(std::max(2.0, std::ceil(1.2 * count)))));
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
               const std::vector<size_t>& todo, const SegmentGridOptions& options,
               const Eigen::PartialPivLU<Eigen::MatrixXd>* modal_lu) {
  const IntegratorOptions& integrator = options.integrator;
  const int threads = options.threads;
  std::vector<std::pair<double, double>> intervals;
  for (size_t i : todo) intervals.emplace_back(pieces[i].t0, pieces[i].t1);
  std::vector<TransitionResult> results =
      IntervalTransitions(system, intervals, integrator, threads);
  const long count = static_cast<long>(todo.size());
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1))
  for (long j = 0; j < count; ++j) {
    Segment& p = pieces[todo[j]];
    p.tr = std::move(results[j]);
    // Only a grid that refines needs the conditions (an SVD per factor).
    p.cond = !p.tr.ok         ? std::numeric_limits<double>::infinity()
             : options.refine ? FactorCondition(p.tr.phi, options, modal_lu)
                              : 1;
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
  std::optional<Eigen::PartialPivLU<Eigen::MatrixXd>> modal_lu;
  if (options.modal_basis && options.refine) modal_lu.emplace(*options.modal_basis);
  for (int round = 0;; ++round) {
    Integrate(system, pieces, todo, options, modal_lu ? &*modal_lu : nullptr);
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
      const int parts = SplitParts(p.cond, log_limit, options.modal_basis.has_value());
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
