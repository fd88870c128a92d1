#pragma once
// Stability boundaries of a sweep, refined beyond the grid: the grid only brackets a boundary
// (a neighbour pair whose verdicts differ); the refinement finds the root of
//   g(p) = max log|ρ(p)| − (level + noise(p))
// in the swept parameter by TOMS 748 (Boost.Math), every evaluation at a tighter tolerance than
// the grid and with its own error estimate (noise = estimate × T): g > 0 only where the growth
// is certain. The boundary itself lies on the stable side of that root, by about
// (level + noise)/slope; the reported bracket includes that offset (docs/stability-boundaries.md).
// `level` is a small positive number: damped systems cross with a finite slope (the root moves
// by level / slope), undamped ones touch it with a square-root branch (the root moves by
// ~level²).
#include <string>
#include <vector>

#include "ltp/studies/sweep.h"

namespace ltp {

struct BoundaryOptions {
  /// Bracket width at which a boundary counts as refined, relative to max(|p|, 1e-3 · span).
  double rel_tol = 1e-8;
  /// Root level in log|ρ| per period (see above).
  double level = 1e-10;
  /// Integrator tolerance of the evaluations during refinement (monodromy route) and Hill
  /// tolerance (Hill route).
  double rel_tol_integrator = 1e-13;
  int max_iterations = 100;
  /// 2-D maps: refine along at most this many grid lines per axis (evenly spread); 0 = all.
  int max_lines = 50;
  int threads = 0;
  /// false: intervals keep their grid values (no evaluations at all), each boundary noting why.
  bool refine = true;
};

struct BoundaryEstimate {
  double value = 0;      ///< boundary location in the swept parameter
  bool refined = false;  ///< false: the grid value (reason in `note`)
  /// The boundary lies within ±bracket of value: the final bracket plus the offset the
  /// evaluations' own error allows (refined), or the grid step (not refined).
  double bracket = 0;
  bool at_sweep_edge = false;  ///< the interval extends beyond the sweep: value is the sweep end
  int evaluations = 0;
  std::string note;
};

/// The integrator of every evaluation during refinement and tracing: the sweep's, at the
/// refinement tolerance (`options.rel_tol_integrator`) where that is tighter.
IntegratorOptions BoundaryIntegrator(const SweepOptions& sweep, const BoundaryOptions& options);

/// One evaluation during refinement and tracing: AnalyzeSweepPoint of the scene at `params`
/// (no swept axes) at the refinement tolerance (`options.rel_tol_integrator`, tighter than the
/// grid's), multipliers only; `checked`: with its own error estimate (about twice the work).
SweepPoint AnalyzeBoundaryPoint(const Scene& scene, const ParameterMap& params,
                                const SweepOptions& sweep, const BoundaryOptions& options,
                                bool checked);

struct UnstableInterval {
  BoundaryEstimate lo, hi;
};

/// Unstable intervals of a 1-D sweep (maximal runs of unstable grid points), both ends
/// refined. `points` holds the whole grid in index order.
std::vector<UnstableInterval> RefineUnstableIntervals(const Scene& scene, const ParameterMap& base,
                                                      const SweepGrid& grid,
                                                      const std::vector<SweepPoint>& points,
                                                      const SweepOptions& sweep,
                                                      const BoundaryOptions& options = {});

struct BoundaryPoint {
  std::vector<double> values;  ///< both parameters; values[axis] is the refined one
  int axis = 0;                ///< the parameter that was refined (the other is a grid value)
  BoundaryEstimate estimate;
  bool entering_unstable = false;  ///< unstable on the larger side of the refined parameter
};

/// Boundary points of a 2-D map: along grid lines of both axes, every neighbour pair that
/// changes between unstable and not unstable, refined along that line.
std::vector<BoundaryPoint> RefineBoundaryPoints(const Scene& scene, const ParameterMap& base,
                                                const SweepGrid& grid,
                                                const std::vector<SweepPoint>& points,
                                                const SweepOptions& sweep,
                                                const BoundaryOptions& options = {});

}  // namespace ltp
