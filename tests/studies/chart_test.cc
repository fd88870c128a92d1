// The chart pipeline (plan, sweep with hooks, analyse) that `ltp chart`, Python and the
// benchmarks share: its boundaries against a closed form, and its hooks — resumed points kept
// and not recomputed, cancellation — against an uninterrupted sweep.
#include "ltp/studies/chart.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "ltp/models/scene.h"

namespace ltp {
namespace {

struct Mathieu {
  Scene scene = LoadScene("mathieu");
  ParameterMap base = scene.Resolve({{"q", "0"}, {"c", "0.02"}});
  PeriodicSystem system = scene.build(base);
};

TEST(Chart, OneSweepFindsTheClosedFormBoundary) {
  // q = 0: x'' + c x' + a x = 0 has exponents −c/2 ± sqrt(c²/4 − a), unstable exactly for a < 0
  // (the grid steps over a = 0, which is marginal).
  const Mathieu m;
  const Chart chart =
      ComputeChart(m.scene, m.base, m.system, {SweepAxis::Parse("a=-0.45:0.55:0.1")}, {});
  EXPECT_FALSE(chart.plan.map);
  ASSERT_EQ(chart.points.size(), 11u);
  for (const SweepPoint& p : chart.points) {
    ASSERT_TRUE(p.ok);
    const double a = p.values[0];
    const double exact = a < 1e-4 ? -0.01 + std::sqrt(1e-4 - a) : -0.01;  // max Re λ
    EXPECT_NEAR(p.max_real_exponent, exact, 1e-8) << "a = " << a;
  }
  ASSERT_EQ(chart.analysis.intervals.size(), 1u);
  const BoundaryEstimate& hi = chart.analysis.intervals[0].hi;
  EXPECT_TRUE(hi.refined) << hi.note;
  EXPECT_LE(std::abs(hi.value - 0.0), hi.bracket + 1e-12) << hi.value << " ± " << hi.bracket;
  EXPECT_TRUE(chart.analysis.intervals[0].lo.at_sweep_edge);
  EXPECT_EQ(chart.analysis.tally.counts.at(StabilityVerdict::kUnstable), 5u);
  EXPECT_FALSE(chart.analysis.campbell.lines.empty());
}

TEST(Chart, ResumedPointsAreKeptAndNotRecomputed) {
  const Mathieu m;
  const ChartPlan plan =
      PlanChart(m.scene, m.system, {SweepAxis::Parse("a=-0.45:0.55:0.1")}, ChartOptions{});
  const ChartPoints full = SweepChart(m.scene, m.base, plan);
  ASSERT_TRUE(full.complete());

  ChartSweepHooks hooks;
  for (size_t i = 0; i < full.points.size(); i += 2) hooks.resumed.push_back(full.points[i]);
  hooks.resumed.push_back(full.points[0]);  // a repeat is ignored
  std::vector<size_t> computed;
  hooks.on_point = [&](const SweepPoint& p) { computed.push_back(p.index); };
  const ChartPoints resumed = SweepChart(m.scene, m.base, plan, hooks);
  EXPECT_TRUE(resumed.complete());
  EXPECT_EQ(resumed.resumed, 6u);
  EXPECT_EQ(computed.size(), 5u);
  for (size_t index : computed) EXPECT_EQ(index % 2, 1u);
  for (size_t i = 0; i < full.points.size(); ++i)
    EXPECT_EQ(resumed.points[i].max_real_exponent, full.points[i].max_real_exponent) << i;
}

TEST(Chart, CancelledBeforeTheStartComputesNothing) {
  const Mathieu m;
  const ChartPlan plan =
      PlanChart(m.scene, m.system, {SweepAxis::Parse("a=0:2:0.5"), SweepAxis::Parse("q=0:1:0.5")},
                ChartOptions{});
  EXPECT_TRUE(plan.map);
  EXPECT_FALSE(plan.sweep.modes);
  std::atomic<bool> cancel{true};
  ChartSweepHooks hooks;
  hooks.cancel = &cancel;
  const ChartPoints r = SweepChart(m.scene, m.base, plan, hooks);
  EXPECT_FALSE(r.complete());
  for (char have : r.have) EXPECT_EQ(have, 0);
}

}  // namespace
}  // namespace ltp
