#include "ltp/studies/chart.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <utility>

#include "ltp/core/elapsed.h"

namespace ltp {

ChartPlan PlanChart(const Scene& scene, const PeriodicSystem& base_system,
                    std::vector<SweepAxis> axes, const ChartOptions& options) {
  options.Validate();
  ChartPlan plan;
  plan.grid = MakeSweepGrid(scene, std::move(axes));
  plan.map = plan.grid.axes.size() == 2;
  plan.chart = options;
  plan.sweep = ChartSweepOptions(options, plan.map, base_system);
  return plan;
}

bool ChartPoints::complete() const {
  return std::all_of(have.begin(), have.end(), [](char h) { return h != 0; });
}

ChartPoints SweepChart(const Scene& scene, const ParameterMap& base, const ChartPlan& plan,
                       const ChartSweepHooks& hooks) {
  const size_t size = plan.grid.size();
  ChartPoints r;
  r.points.assign(size, {});
  r.have.assign(size, 0);
  for (const SweepPoint& p : hooks.resumed)
    if (p.index < size && !r.have[p.index]) {
      r.points[p.index] = p;
      r.have[p.index] = 1;
      ++r.resumed;
    }
  std::vector<size_t> todo;
  for (size_t i = 0; i < size; ++i)
    if (!r.have[i]) todo.push_back(i);
  std::mutex mutex;
  auto on_point = [&](SweepPoint&& p) {
    const size_t index = p.index;
    std::lock_guard<std::mutex> lock(mutex);
    if (hooks.on_point) hooks.on_point(p);
    r.points[index] = std::move(p);
    r.have[index] = 1;
  };
  if (hooks.on_start) hooks.on_start(r.resumed);
  const auto start = std::chrono::steady_clock::now();
  if (hooks.runner)
    hooks.runner(todo, on_point, hooks.cancel);
  else
    RunSweep(scene, base, plan.grid, todo, plan.sweep, on_point, hooks.cancel);
  r.sweep_s = SecondsSince(start);
  return r;
}

ChartAnalysis AnalyseChart(const Scene& scene, const ParameterMap& base, const SystemLabels& labels,
                           const ChartPlan& plan, const std::vector<SweepPoint>& points) {
  ChartAnalysis a;
  if (!plan.map) {
    a.tracking = TrackModes(points);
    a.campbell = MakeCampbellDiagram(points, a.tracking, labels, plan.chart.campbell);
  }
  const auto start = std::chrono::steady_clock::now();
  const BoundaryOptions boundary = ChartBoundaryOptions(plan.chart);
  if (!plan.map) {
    a.intervals = RefineUnstableIntervals(scene, base, plan.grid, points, plan.sweep, boundary);
  } else if (plan.chart.refine) {
    a.boundary = RefineBoundaryPoints(scene, base, plan.grid, points, plan.sweep, boundary);
  }
  a.refine_s = SecondsSince(start);
  if (plan.map && plan.chart.refine && plan.chart.curves) {
    const auto traced = std::chrono::steady_clock::now();
    a.curves = TraceBoundaryCurves(scene, base, plan.grid, a.boundary, plan.sweep, boundary,
                                   plan.chart.curve);
    a.curves_s = SecondsSince(traced);
  }
  a.tally = TallySweep(points);
  return a;
}

Chart ComputeChart(const Scene& scene, const ParameterMap& base, const PeriodicSystem& base_system,
                   std::vector<SweepAxis> axes, const ChartOptions& options) {
  Chart c;
  c.plan = PlanChart(scene, base_system, std::move(axes), options);
  ChartPoints swept = SweepChart(scene, base, c.plan);
  c.points = std::move(swept.points);
  c.sweep_s = swept.sweep_s;
  c.analysis = AnalyseChart(scene, base, base_system.labels(), c.plan, c.points);
  return c;
}

}  // namespace ltp
