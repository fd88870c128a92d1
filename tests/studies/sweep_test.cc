// Parameter sweeps: refined stability boundaries against closed forms and GSL, mode tracking
// through a crossing, failing points, and the monodromy and Hill routes against each other.
#include "ltp/studies/sweep.h"

#include <gsl/gsl_sf_mathieu.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <mutex>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/hill/hill.h"
#include "ltp/models/scene.h"
#include "ltp/studies/mode_tracking.h"
#include "ltp/studies/stability_boundary.h"
#include "support/rotor_lin.h"
#include "support/sweep.h"

namespace ltp {
namespace {

double MathieuA(int n, double q) {
  gsl_sf_result r;
  EXPECT_EQ(gsl_sf_mathieu_a_e(n, q, &r), 0);
  return r.val;
}
double MathieuB(int n, double q) {
  gsl_sf_result r;
  EXPECT_EQ(gsl_sf_mathieu_b_e(n, q, &r), 0);
  return r.val;
}

TEST(SweepAxis, ParsesAndRejects) {
  const SweepAxis a = SweepAxis::Parse("a=-2:10:0.03");
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.Values().size(), 401u);  // (10 − (−2)) / 0.03 + 1, stop included
  EXPECT_DOUBLE_EQ(a.Values().back(), 10.0);
  EXPECT_NEAR(SweepAxis::Parse("w=0:2*pi:pi/2").Values().back(), 2 * M_PI, 1e-15);
  for (const char* bad : {"a", "a=1:2", "a=1:0:0.1", "a=0:1:0", "a=0:1:x", "=0:1:0.1"})
    EXPECT_THROW(SweepAxis::Parse(bad), InputError) << bad;
  EXPECT_THROW(MakeSweepGrid(LoadScene("mathieu"), {SweepAxis::Parse("nope=0:1:0.5")}), InputError);
}

// Undamped Mathieu y'' + (a − 2q cos 2t) y = 0 at q = 1: unstable for a < a_0, b_1 < a < a_1,
// b_2 < a < a_2 (GSL's characteristic values). The grid (step 0.1) only brackets them; the
// refined ends must match to 1e-8 relative.
TEST(UnstableIntervals, MathieuTonguesMatchGsl) {
  const Scene scene = LoadScene("mathieu");
  ParameterMap base = scene.Resolve({{"c", "0"}, {"q", "1"}});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("a=-2:6:0.1")});
  SweepOptions o;
  o.modes = false;
  o.floquet.integrator.type = IntegratorType::kRkf78;
  const auto points = test::SweepAll(scene, base, grid, o);
  const auto intervals = RefineUnstableIntervals(scene, base, grid, points, o);
  ASSERT_EQ(intervals.size(), 3u);
  EXPECT_TRUE(intervals[0].lo.at_sweep_edge);
  const double expected[][2] = {
      {-2, MathieuA(0, 1)}, {MathieuB(1, 1), MathieuA(1, 1)}, {MathieuB(2, 1), MathieuA(2, 1)}};
  for (size_t i = 0; i < 3; ++i) {
    for (int end = 0; end < 2; ++end) {
      const BoundaryEstimate& e = end ? intervals[i].hi : intervals[i].lo;
      if (e.at_sweep_edge) continue;
      EXPECT_TRUE(e.refined) << e.note;
      EXPECT_NEAR(e.value, expected[i][end], 1e-8 * std::max(1.0, std::abs(expected[i][end])))
          << "interval " << i << (end ? " hi" : " lo");
    }
  }
}

// The same boundaries found in a 2-D map: every refined point lies on one of the curves
// a_n(q), b_n(q) at its own q (or, refined along q, at its own a).
TEST(BoundaryPoints, InceStruttChartMatchesGsl) {
  const Scene scene = LoadScene("mathieu");
  ParameterMap base = scene.Resolve({{"c", "0"}});
  const SweepGrid grid =
      MakeSweepGrid(scene, {SweepAxis::Parse("a=-1:5:0.25"), SweepAxis::Parse("q=0.5:3:0.5")});
  SweepOptions o;
  o.modes = false;
  o.floquet.integrator.type = IntegratorType::kRkf78;
  const auto points = test::SweepAll(scene, base, grid, o);
  BoundaryOptions b;
  b.max_lines = 0;
  const auto boundary = RefineBoundaryPoints(scene, base, grid, points, o, b);
  int along_a = 0;
  for (const BoundaryPoint& p : boundary) {
    ASSERT_TRUE(p.estimate.refined) << p.estimate.note;
    if (p.axis != 0) continue;  // along q the curves are checked by the 1-D test's logic
    ++along_a;
    const double a = p.values[0], q = p.values[1];
    double nearest = INFINITY;
    for (int n = 0; n <= 4; ++n) {
      nearest = std::min(nearest, std::abs(a - MathieuA(n, q)));
      if (n >= 1) nearest = std::min(nearest, std::abs(a - MathieuB(n, q)));
    }
    EXPECT_LT(nearest, 1e-8 * std::max(1.0, std::abs(a))) << "a = " << a << ", q = " << q;
  }
  // Every row (q ≥ 0.5) crosses a_0, b_1 and a_1 in a ∈ [−1, 5] with tongue 1 wider than the
  // step; the narrower higher tongues may fall between grid points.
  EXPECT_GE(along_a, 6 * 3);
}

// Asymmetric shaft (Jeffcott, undamped): unstable exactly for sqrt(k1/m) < Ω < sqrt(k2/m).
// The grid has a point exactly on the lower edge (Ω = 1), where the monodromy is defective.
TEST(UnstableIntervals, AsymmetricShaftBandEdges) {
  const Scene scene = LoadScene("jeffcott");
  ParameterMap base = scene.Resolve({{"k1", "1"}, {"k2", "1.5"}, {"m", "1"}, {"c", "0"}});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("Omega=0.6:1.6:0.05")});
  SweepOptions o;
  o.modes = true;
  const auto points = test::SweepAll(scene, base, grid, o);
  const auto intervals = RefineUnstableIntervals(scene, base, grid, points, o);
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_TRUE(intervals[0].lo.refined && intervals[0].hi.refined);
  EXPECT_NEAR(intervals[0].lo.value, 1.0, 1e-8);
  EXPECT_NEAR(intervals[0].hi.value, std::sqrt(1.5), 1e-8 * std::sqrt(1.5));
}

// A rotor with two blades (ground resonance, light damping): the unstable interval of the
// monodromy route equals the one found independently by Hill's method.
TEST(UnstableIntervals, TwoBladedRotorMonodromyEqualsHill) {
  const Scene scene = LoadScene("rotor");
  ParameterMap base =
      scene.Resolve({{"blades", "2"}, {"C_zeta", "0.02"}, {"cx", "0.2"}, {"cy", "0.2"}});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("Omega=0.57:0.63:0.02")});
  std::vector<std::vector<UnstableInterval>> found;
  for (SweepMethod method : {SweepMethod::kMonodromy, SweepMethod::kHill}) {
    SweepOptions o;
    o.method = method;
    o.modes = false;
    const auto points = test::SweepAll(scene, base, grid, o);
    found.push_back(RefineUnstableIntervals(scene, base, grid, points, o));
    ASSERT_EQ(found.back().size(), 1u) << ToString(method);
    EXPECT_TRUE(found.back()[0].lo.refined && found.back()[0].hi.refined) << ToString(method);
  }
  EXPECT_NEAR(found[0][0].lo.value, found[1][0].lo.value, 1e-8);
  EXPECT_NEAR(found[0][0].hi.value, found[1][0].hi.value, 1e-8);
  EXPECT_GT(found[0][0].hi.value - found[0][0].lo.value, 0.01);  // a real interval, not a point
}

// A point whose system cannot be built (m = 0: singular mass) fails with its reason; the
// others go on.
TEST(RunSweep, FailingPointIsRecordedNotFatal) {
  const Scene scene = LoadScene("jeffcott");
  ParameterMap base = scene.Resolve({});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("m=-1:1:0.5")});
  SweepOptions o;
  o.modes = false;
  const auto points = test::SweepAll(scene, base, grid, o);
  int failed = 0;
  for (const SweepPoint& p : points) {
    if (p.values[0] <= 0) {
      EXPECT_FALSE(p.ok);
      EXPECT_EQ(p.verdict, StabilityVerdict::kFailed);
      EXPECT_FALSE(p.failure.empty());
      ++failed;
    } else {
      EXPECT_TRUE(p.ok) << p.failure;
    }
  }
  EXPECT_EQ(failed, 3);
}

// A checked map point's estimate bounds its own value's error against a reference
// (AnalyzeFloquet, rkf78 at 1e-13 over the full period) and covers the distance to the route
// its unchecked neighbours take (for the damped Mathieu equation half a period,
// docs/time-reversal.md), so the map's checked sample measures that route.
TEST(RunSweep, CheckedEstimateCoversTheUncheckedRoute) {
  const Scene scene = LoadScene("mathieu");
  ParameterMap base = scene.Resolve({{"q", "2.5"}, {"c", "0.05"}});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("a=-1:6:0.25")});
  SweepOptions o;
  o.modes = false;
  o.floquet.integrator.rel_tol = 1e-7;
  o.check_every = 0;
  const auto unchecked = test::SweepAll(scene, base, grid, o);
  o.check_every = 1;
  const auto checked = test::SweepAll(scene, base, grid, o);
  FloquetOptions ref;
  ref.integrator.type = IntegratorType::kRkf78;
  ref.integrator.rel_tol = 1e-13;
  ref.compute_modes = false;
  ref.estimate_error = false;
  int unstable = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    ParameterMap params = base;
    params["a"] = grid.values[0][i];
    const FloquetResult r = AnalyzeFloquet(scene.build(params), ref);
    ASSERT_TRUE(r.ok && unchecked[i].ok && checked[i].ok && checked[i].error_estimate);
    EXPECT_FALSE(unchecked[i].error_estimate);
    const double estimate = *checked[i].error_estimate;
    EXPECT_LE(std::abs(checked[i].max_real_exponent - r.max_real_exponent), estimate)
        << "a = " << grid.values[0][i];
    // (the same difference, once of exponents of size ~1 and once of log multipliers / T: they
    // round differently by a few 1e-16)
    EXPECT_LE(std::abs(unchecked[i].max_real_exponent - checked[i].max_real_exponent),
              estimate + 1e-14)
        << "a = " << grid.values[0][i];
    unstable += r.max_real_exponent > 0;
  }
  EXPECT_GT(unstable, 3);  // the line crosses tongues
}

// A hugely unstable map point (a = −100, q = 20, c = 0.4: multipliers e^{±31}): the formed
// 2×2 product holds the small multiplier only as round-off of the large one's size; it comes
// from Liouville's det instead. Both exponents against AnalyzeFloquet's segmented analysis
// (rkf78 at 1e-12, independent of the formed product), whose exponents sum to tr A_0 = −c.
TEST(RunSweep, HugelyUnstablePointKeepsBothExponents) {
  const Scene scene = LoadScene("mathieu");
  const ParameterMap base = scene.Resolve({{"a", "-100"}, {"q", "20"}, {"c", "0.4"}});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("a=-100:-100:1")});
  SweepOptions o;
  o.modes = false;
  o.check_every = 0;
  const auto points = test::SweepAll(scene, base, grid, o);
  ASSERT_TRUE(points[0].ok);
  FloquetOptions ref;
  ref.integrator.type = IntegratorType::kRkf78;
  ref.integrator.rel_tol = 1e-12;
  ref.compute_modes = false;
  const FloquetResult r = AnalyzeFloquet(scene.build(base), ref);
  ASSERT_TRUE(r.ok);
  std::vector<std::complex<double>> got, want;
  for (const FloquetMode& m : points[0].modes) got.push_back(m.exponent);
  for (const FloquetMode& m : r.modes) want.push_back(m.exponent);
  EXPECT_GT(r.max_real_exponent * r.period, 30);
  EXPECT_LT(MaxExponentMismatch(got, want, 2.0), 1e-8);
}

// Two uncoupled oscillators whose frequencies cross: the display order (by frequency) swaps at
// the crossing, the tracked labels must not (shapes e1 and e2 never change).
TEST(TrackModes, CrossingKeepsLabels) {
  std::vector<SweepPoint> points;
  for (int i = 0; i <= 10; ++i) {
    const double x = 0.5 + 0.1 * i;  // oscillator 1: ω = x; oscillator 2: ω = 1
    SweepPoint p;
    p.ok = true;
    p.period = 1;
    p.values = {x};
    struct M {
      double w;
      int axis;
    };
    std::vector<M> ms = {{x, 0}, {1.0, 1}};
    std::sort(ms.begin(), ms.end(), [](const M& a, const M& b) { return a.w < b.w; });
    p.shapes = Eigen::MatrixXcd::Zero(2, 2);
    for (int k = 0; k < 2; ++k) {
      FloquetMode m;
      m.exponent = {-0.01, ms[k].w};
      m.frequency_hz = ms[k].w / (2 * M_PI);
      p.modes.push_back(m);
      p.shapes(ms[k].axis, k) = 1;
    }
    points.push_back(p);
  }
  const ModeTracking t = TrackModes(points);
  for (size_t i = 0; i < points.size(); ++i) {
    // Label 0 is oscillator 1 (smaller frequency at x = 0.5): frequency x/2π throughout.
    const double x = points[i].values[0];
    EXPECT_NEAR(t.frequency_hz[i][0], x / (2 * M_PI), 1e-12) << "x = " << x;
    EXPECT_NEAR(t.frequency_hz[i][1], 1 / (2 * M_PI), 1e-12) << "x = " << x;
  }
  EXPECT_NEAR(t.min_mac, 1.0, 1e-12);
}

// An asymmetric shaft on an anisotropic stator (laval4, kbx = 2e4, kby = 6e4): past the
// critical range near 200 rad/s the first line followed 2Ω/2π − 31.3 Hz, an alias, to
// 223.3 Hz at 800 rad/s, while every point's own shape put 99.9 % of its energy on harmonic 0
// at 31.3 Hz. Where a point's shape names its branch, each line's frequency must be a physical
// frequency of that point — one of Hill's exponents, selected by its own eigenvectors (an
// independent route), compared as frequencies, not modulo Ωp.
TEST(TrackModes, LinesKeepTheBranchTheirShapesName) {
  const Scene scene = LoadScene(test::SourceDir() + "/tests/data/laval4.yaml");
  const ParameterMap base = scene.Resolve({{"kbx", "2e4"}, {"kby", "6e4"}});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("Omega=185:285:5")});
  SweepOptions o;  // as `ltp chart` sweeps a Campbell diagram of this scene
  o.modes = true;
  o.floquet.integrator.type = IntegratorType::kRkf78;
  const std::vector<SweepPoint> points = test::SweepAll(scene, base, grid, o);
  const ModeTracking t = TrackModes(points);
  int compared = 0;
  for (size_t p = 0; p < points.size(); ++p) {
    ASSERT_TRUE(points[p].ok);
    const double omega = points[p].values[0];
    HillOptions ho;
    const HillResult hill = AnalyzeHillAuto(
        scene.Build({{"kbx", "2e4"}, {"kby", "6e4"}, {"Omega", std::to_string(omega)}}), ho, 1e-10,
        64);
    ASSERT_TRUE(hill.ok) << hill.BriefReport();
    for (size_t k = 0; k < t.labels[p].size(); ++k) {
      const FloquetMode& m = points[p].modes[t.labels[p][k]];
      if (m.branch_margin < 0.25) continue;  // a tie: the line's continuity decides
      double nearest = INFINITY;
      for (const FloquetMode& h : hill.modes)
        nearest =
            std::min(nearest, std::abs(std::abs(t.frequency_hz[p][k]) - std::abs(h.frequency_hz)));
      EXPECT_LT(nearest, 1e-6) << "line " << k + 1 << " at Omega = " << omega << ": "
                               << t.frequency_hz[p][k] << " Hz";
      ++compared;
    }
  }
  EXPECT_GT(compared, static_cast<int>(points.size()) * 3);
}

}  // namespace
}  // namespace ltp
