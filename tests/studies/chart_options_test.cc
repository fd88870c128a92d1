// The chart defaults the CLI and the Python module share (ChartOptions), and the Hill
// truncation that `harmonics = auto` means (AnalyzeHillToTolerance): what each turns into.
// Reference: the values `ltp chart` and `ltp floquet --method hill` used before they moved
// into the library (docs/benchmarks.md, stability-chart benchmark and work-precision study).
#include "ltp/studies/chart_options.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ltp/core/error.h"
#include "ltp/hill/hill.h"
#include "ltp/models/scene.h"

namespace ltp {
namespace {

// A Fourier-form scene (Mathieu), one whose A(t) is constant between jumps (Meissner's square
// wave), and a smooth A(t) given as a function.
PeriodicSystem FourierScene() {
  return LoadScene("mathieu").build(LoadScene("mathieu").Resolve({}));
}
PeriodicSystem JumpScene() {
  return LoadScene("meissner").build(LoadScene("meissner").Resolve({}));
}
PeriodicSystem SmoothFunction() {
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out << 0, 1, -(1.5 - 0.4 * std::cos(2 * t)), -0.02;
  };
  return PeriodicSystem::FromFunctions(3.141592653589793, 2, 0, 0, f);
}

TEST(ChartOptions, MapsAndCampbellSweepsGetTheirOwnDefaults) {
  const ChartOptions defaults;
  const SweepOptions line = ChartSweepOptions(defaults, false, FourierScene()),
                     map = ChartSweepOptions(defaults, true, FourierScene());
  EXPECT_EQ(line.floquet.integrator.type, IntegratorType::kRkf78);
  // Maps: Taylor series where A(t) is a Fourier series, exact exponentials where it is constant
  // between jumps, Bulirsch–Stoer elsewhere.
  EXPECT_EQ(map.floquet.integrator.type, IntegratorType::kTaylor);
  EXPECT_EQ(ChartSweepOptions(defaults, true, JumpScene()).floquet.integrator.type,
            IntegratorType::kExpm);
  EXPECT_EQ(ChartSweepOptions(defaults, true, SmoothFunction()).floquet.integrator.type,
            IntegratorType::kBulirschStoer);
  EXPECT_EQ(line.check_every, 1);
  EXPECT_EQ(map.check_every, 97);
  EXPECT_TRUE(line.modes);
  EXPECT_FALSE(map.modes);
  EXPECT_EQ(line.floquet.integrator.rel_tol, 1e-10);
  EXPECT_EQ(line.floquet.integrator.abs_tol, 1e-13);
  EXPECT_EQ(line.hill_tol, 1e-10);
}

TEST(ChartOptions, NegativeCheckEveryIsRefusedWithItsField) {
  ChartOptions o;
  o.check_every = -1;
  try {
    ChartSweepOptions(o, true, FourierScene());
    FAIL() << "accepted check_every = -1";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("check_every"), std::string::npos) << e.what();
  }
}

TEST(ChartOptions, ChoicesGivenWin) {
  ChartOptions o;
  o.integrator = IntegratorType::kDopri5;
  o.check_every = 0;
  o.compare = true;
  o.tol = 1e-8;
  const SweepOptions map = ChartSweepOptions(o, true, JumpScene()),
                     line = ChartSweepOptions(o, false, JumpScene());
  EXPECT_EQ(map.floquet.integrator.type, IntegratorType::kDopri5);
  EXPECT_EQ(map.check_every, 0);
  EXPECT_FALSE(map.snapshot);  // the frozen/averaged comparison is a Campbell-diagram feature
  EXPECT_TRUE(line.snapshot);
  EXPECT_DOUBLE_EQ(line.floquet.integrator.abs_tol, 1e-11);
  const BoundaryOptions b = ChartBoundaryOptions(o);
  EXPECT_EQ(b.rel_tol, 1e-8);
  EXPECT_EQ(b.max_lines, 50);
  EXPECT_TRUE(b.refine);
}

TEST(ChartOptions, RejectsToleranceOutsideZeroOne) {
  ChartOptions o;
  o.tol = 1;
  EXPECT_THROW(ChartSweepOptions(o, false, FourierScene()), InputError);
  o.tol = 1e-10;
  o.refine_tol = 0.5;
  EXPECT_THROW(o.Validate(), InputError);
}

TEST(HillAuto, ToleranceFollowsTheIntegratorsWithARoundOffFloor) {
  EXPECT_EQ(HillAutoTolerance(1e-8), 1e-8);
  EXPECT_EQ(HillAutoTolerance(1e-14), 1e-12);
  const PeriodicSystem mathieu = LoadScene("mathieu").Build({{"a", "1.5"}, {"q", "2"}});
  HillOptions start;
  start.harmonics = kHillAutoStartHarmonics;
  const HillResult direct = AnalyzeHillAuto(mathieu, start, 1e-10);
  const HillResult shared = AnalyzeHillToTolerance(mathieu, HillOptions{}, 1e-10);
  ASSERT_EQ(direct.modes.size(), shared.modes.size());
  EXPECT_EQ(direct.harmonics, shared.harmonics);
  for (size_t k = 0; k < direct.modes.size(); ++k)
    EXPECT_EQ(direct.modes[k].exponent, shared.modes[k].exponent);
}

}  // namespace
}  // namespace ltp
