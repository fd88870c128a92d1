#pragma once
// A chart over a scene's parameters — a Campbell/damping diagram (one swept parameter) or a
// stability map (two) — as one pipeline that `ltp chart`, Python's `ltp.chart` and the
// benchmarks share: plan (grid and per-point options), sweep (every point, with hooks for a
// journal, progress, cancellation and MPI), analyse (mode tracking, the Campbell diagram,
// refined stability boundaries, the tally). ComputeChart runs all three.
#include <atomic>
#include <functional>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/models/scene.h"
#include "ltp/studies/boundary_curves.h"
#include "ltp/studies/campbell.h"
#include "ltp/studies/chart_options.h"
#include "ltp/studies/mode_tracking.h"
#include "ltp/studies/stability_boundary.h"
#include "ltp/studies/sweep.h"

namespace ltp {

/// What is fixed before the first point: the grid and the settings of every point.
struct ChartPlan {
  SweepGrid grid;
  bool map = false;  ///< two swept parameters
  ChartOptions chart;
  SweepOptions sweep;  ///< per point; sweep.floquet.integrator.type is the chart's integrator
};

/// @throws InputError for bad axes or options. `base_system`: the scene's system at the base
/// point (it decides the integrator; a scene keeps its form over its parameters).
ChartPlan PlanChart(const Scene& scene, const PeriodicSystem& base_system,
                    std::vector<SweepAxis> axes, const ChartOptions& options);

/// Runs the points `indices` of a sweep, handing each to `on_point` as it completes (possibly
/// from several threads at once; distinct indices); returns how many it ran. The default is
/// RunSweep on this process's threads; `ltp chart` passes its distribution over MPI ranks.
using SweepRunner = std::function<size_t(const std::vector<size_t>& indices,
                                         const std::function<void(SweepPoint&&)>& on_point,
                                         const std::atomic<bool>* cancel)>;

struct ChartSweepHooks {
  /// Points computed earlier (a journal): they are kept, not recomputed. Indices past the grid
  /// and repeats are ignored.
  std::vector<SweepPoint> resumed;
  /// Once, before the first new point: how many of the grid's points were resumed (progress).
  std::function<void(size_t resumed)> on_start;
  /// Each new point, one call at a time (journal, progress).
  std::function<void(const SweepPoint&)> on_point;
  /// Set to stop after the points under way.
  const std::atomic<bool>* cancel = nullptr;
  SweepRunner runner;  ///< empty: RunSweep
};

struct ChartPoints {
  std::vector<SweepPoint> points;  ///< grid order; entries not computed are default points
  std::vector<char> have;          ///< per grid point: computed or resumed
  size_t resumed = 0;              ///< of them taken from ChartSweepHooks::resumed
  double sweep_s = 0;              ///< wall time of the sweep
  /// Every grid point is there (false when cancelled, or on an MPI rank other than the first).
  bool complete() const;
};

ChartPoints SweepChart(const Scene& scene, const ParameterMap& base, const ChartPlan& plan,
                       const ChartSweepHooks& hooks = {});

/// What the points say together.
struct ChartAnalysis {
  ModeTracking tracking;                    ///< 1-D
  CampbellDiagram campbell;                 ///< 1-D
  std::vector<UnstableInterval> intervals;  ///< 1-D: refined beyond the grid
  std::vector<BoundaryPoint> boundary;      ///< maps, when ChartOptions::refine
  BoundaryCurves curves;                    ///< maps, when ChartOptions::refine and ::curves
  SweepTally tally;
  double refine_s = 0;  ///< wall time of the refinement (points)
  double curves_s = 0;  ///< wall time of tracing the boundary curves
};

/// `points`: the complete sweep in grid order; `labels`: those of the scene's system (they
/// name the Campbell lines).
ChartAnalysis AnalyseChart(const Scene& scene, const ParameterMap& base, const SystemLabels& labels,
                           const ChartPlan& plan, const std::vector<SweepPoint>& points);

struct Chart {
  ChartPlan plan;
  std::vector<SweepPoint> points;  ///< grid order
  double sweep_s = 0;
  ChartAnalysis analysis;
};

/// Plan, sweep on this process's threads, analyse. @throws InputError as PlanChart.
Chart ComputeChart(const Scene& scene, const ParameterMap& base, const PeriodicSystem& base_system,
                   std::vector<SweepAxis> axes, const ChartOptions& options);

}  // namespace ltp
