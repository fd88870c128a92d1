#pragma once
// The settings of a Campbell diagram or a stability map as `ltp chart` and Python's
// `ltp.chart` take them, with the defaults both share, and the sweep and boundary options they
// become. One swept parameter makes a Campbell/damping diagram (mode shapes for tracking, the
// error estimate on every point); two make a stability map (multipliers only, the estimate on
// every 97th point: a map has thousands of points and the estimate doubles the cost of each).
#include <optional>

#include "ltp/integrate/integrator.h"
#include "ltp/studies/boundary_curves.h"
#include "ltp/studies/campbell.h"
#include "ltp/studies/stability_boundary.h"
#include "ltp/studies/sweep.h"

namespace ltp {

struct ChartOptions {
  SweepMethod method = SweepMethod::kMonodromy;
  /// Monodromy integrator; empty = ChartIntegrator's choice for the kind of chart.
  std::optional<IntegratorType> integrator;
  /// Relative tolerance of the integrator (absolute: tol / 1000), or Hill's truncation tolerance.
  double tol = 1e-10;
  /// Threads over points (0 = all cores).
  int threads = 0;
  /// 1-D: also the eigenvalues of the frozen A(0) and of the averaged A_0 at every point.
  bool compare = false;
  /// Error estimate (a tighter rerun) on every k-th point; 0 = none; empty = every point of a
  /// 1-D sweep, every 97th of a map.
  std::optional<int> check_every;
  /// Refine the stability boundaries beyond the grid (stability_boundary.h).
  bool refine = true;
  /// Relative bracket width of a refined boundary.
  double refine_tol = 1e-8;
  /// Maps: grid lines per axis along which boundaries are refined (0 or less = all).
  int refine_lines = 50;
  /// Maps: trace the boundaries through the refined points as curves (boundary_curves.h).
  bool curves = true;
  BoundaryCurveOptions curve;
  /// 1-D: per-rev lines, crossings, weakly damped regions and mode names.
  CampbellOptions campbell;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// The integrator of a chart: `options.integrator` if set; else, for maps, matrix exponentials
/// when A(t) is constant between breakpoints (exact; Meissner's 34 k-point map 2.3× faster than
/// Bulirsch–Stoer, estimates 5e-12 instead of 1e-10), Taylor series where they pay
/// (TaylorSeriesPay: a Fourier series of ≤ 2 states) and Bulirsch–Stoer otherwise — the
/// cheapest routes to 1e-8 multipliers on smooth small systems (docs/benchmarks.md,
/// stability-chart benchmark) — and rkf78 for 1-D sweeps, which suits their short mode-shape
/// segments. `base`: the scene's system at the chart's base point (a scene keeps its form over
/// its parameters).
IntegratorType ChartIntegrator(const ChartOptions& options, bool map, const PeriodicSystem& base);

/// The per-point options of the sweep (`map`: two swept parameters; `base` as for
/// ChartIntegrator). @throws InputError.
SweepOptions ChartSweepOptions(const ChartOptions& options, bool map, const PeriodicSystem& base);

/// The refinement of the boundaries found by that sweep.
BoundaryOptions ChartBoundaryOptions(const ChartOptions& options);

}  // namespace ltp
