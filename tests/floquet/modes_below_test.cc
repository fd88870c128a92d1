// Floquet analysis of the modes below a frequency (FloquetOptions::modes_below,
// docs/model-sizes.md). References: an isotropic rotor written at 3 azimuths whose exact
// exponents are eig(A_MBC) modulo jΩ (tests/support/isotropic_rotor_lin.h); coupled Mathieu
// oscillators analysed in full by the same library (another route: no projection), whose own
// estimate is 1e-8 of the differences tested.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/floquet/floquet.h"
#include "ltp/floquet/model_error.h"
#include "ltp/models/scene_input.h"
#include "support/isotropic_rotor_lin.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

// x_i'' + 2ζ w_i x_i' + w_i² x_i + κ cos(t) Σ_{j≠i} x_j = 0 (the periodic part couples every
// pair), `unstable` flips the sign of the damping of the fastest oscillator.
PeriodicSystem CoupledOscillators(const std::vector<double>& w, double kappa, bool unstable) {
  const int d = static_cast<int>(w.size()), n = 2 * d;
  FourierMatrix a(n, n, 1);
  Eigen::MatrixXd a0 = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXcd a1 = Eigen::MatrixXcd::Zero(n, n);
  for (int i = 0; i < d; ++i) {
    a0(i, d + i) = 1;
    a0(d + i, i) = -w[i] * w[i];
    a0(d + i, d + i) = -2 * 0.02 * w[i] * (unstable && i == d - 1 ? -1 : 1);
    for (int j = 0; j < d; ++j)
      if (j != i) a1(d + i, j) = -kappa / 2;  // κ cos t = κ/2 (e^{jt} + e^{-jt})
  }
  a.SetHarmonic(0, a0.cast<cd>());
  a.SetHarmonic(1, a1);
  return PeriodicSystem::FromFourier(2 * std::numbers::pi, a);
}

TEST(ModesBelow, IsotropicRotorSpanningDecadesMatchesItsExactExponents) {
  // 3 blades × 6 DOFs + 4 tower DOFs = 44 states, natural frequencies 0.3…300 rad/s spread
  // log-uniformly, Ω = 1 rad/s: constant in multi-blade coordinates, so the exponents are
  // eig(A_MBC) modulo jΩ, and those below 3 rad/s are what the cut-off keeps.
  const test::IsotropicRotorLin model =
      test::MakeIsotropicRotorLin(6, 4, test::EvenAzimuths(3), 1.0, 7, 0.0, 0.02, 0.3, 300.0, true);
  const std::string dir = test::WriteLinDirectory(model.files, ::testing::TempDir() + "iso-below");
  const LoadedScene l = LoadSceneInput({dir}, {});
  FloquetOptions o;
  o.modes_below = 3.0;
  FloquetResult r = AnalyzeFloquet(l.system, o);
  IncludeModelError(l.model_alternatives, o, r);
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_TRUE(r.reduction);
  std::vector<cd> slow;
  for (const cd& e : model.exponents)
    if (std::abs(e) <= 3.0) slow.push_back(e);
  EXPECT_EQ(r.reduction->kept, static_cast<int>(slow.size()));
  EXPECT_LT(r.reduction->kept, l.system.states() / 2);  // the cut-off leaves most modes out
  const std::vector<double> d = MatchExponents(Exponents(r.modes), slow, l.system.omega());
  for (size_t k = 0; k < r.modes.size(); ++k) {
    ASSERT_TRUE(r.modes[k].error_estimate);
    EXPECT_LE(d[k], *r.modes[k].error_estimate) << "mode " << k;
    EXPECT_LT(d[k], 1e-8);
  }
  EXPECT_EQ(r.verdict, StabilityVerdict::kStable)
      << ::testing::PrintToString(r.diagnostics);  // every mode damped, the dropped ones too
  ASSERT_FALSE(r.mode_samples.empty());
  EXPECT_EQ(r.mode_samples.front().rows(), l.system.states());  // shapes in the given states
  EXPECT_EQ(r.mode_samples.front().cols(), r.reduction->kept);
}

TEST(ModesBelow, EstimateCoversWhatTheFastModesChange) {
  // Three oscillators at 1, 3.3 and 9.7 rad/s, strongly coupled by κ cos t: the slow mode's
  // exponents move when the faster ones are left out. Cut-off 2 keeps the slowest, the check
  // at 4 adds the middle one; the reference is the full analysis (all three).
  const PeriodicSystem s = CoupledOscillators({1.0, 3.3, 9.7}, 0.6, false);
  const FloquetResult full = AnalyzeFloquet(s);
  ASSERT_TRUE(full.ok);
  FloquetOptions o;
  o.modes_below = 2.0;
  const FloquetResult r = AnalyzeFloquet(s, o);
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_EQ(r.modes.size(), 2u);
  EXPECT_EQ(r.reduction->check_kept, 4);
  // The truncation matters here (it is not a trivially exact projection) …
  EXPECT_GT(r.reduction->truncation_change, 1e-4);
  // … and each estimate is at least the exponent's distance to the full analysis.
  const std::vector<double> d =
      MatchExponents(Exponents(r.modes), Exponents(full.modes), s.omega());
  for (size_t k = 0; k < r.modes.size(); ++k) {
    EXPECT_LE(d[k], *r.modes[k].error_estimate - *full.error_estimate) << "mode " << k;
    EXPECT_GT(d[k], 1e-6);  // the fast mode's effect is real
  }
}

TEST(ModesBelow, AnUnstableModeLeftOutKeepsTheVerdictUndecided) {
  // The 9.7 rad/s oscillator has negative damping (Re λ ≈ +0.19): the slow modes alone are
  // stable, but the analysis cannot call the system stable without them.
  const PeriodicSystem s = CoupledOscillators({1.0, 3.3, 9.7}, 0.01, true);
  FloquetOptions o;
  o.modes_below = 2.0;
  const FloquetResult r = AnalyzeFloquet(s, o);
  ASSERT_TRUE(r.ok) << r.failure;
  EXPECT_LT(r.max_real_exponent, 0);
  EXPECT_EQ(r.verdict, StabilityVerdict::kMarginal);
  EXPECT_FALSE(r.stable);
  EXPECT_GT(std::max_element(r.reduction->dropped.begin(), r.reduction->dropped.end(),
                             [](cd a, cd b) { return a.real() < b.real(); })
                ->real(),
            0.1);
}

TEST(ModesBelow, RefusesBadCutOffsAndSaysWhenNoModeIsBelowIt) {
  const PeriodicSystem s = CoupledOscillators({1.0, 3.3}, 0.1, false);
  FloquetOptions o;
  o.modes_below = -1;
  EXPECT_THROW(AnalyzeFloquet(s, o), InputError);
  o.modes_below = std::numeric_limits<double>::infinity();
  EXPECT_THROW(AnalyzeFloquet(s, o), InputError);
  o.modes_below = 0.5;  // both oscillators are faster
  const FloquetResult r = AnalyzeFloquet(s, o);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.verdict, StabilityVerdict::kFailed);
  EXPECT_EQ(r.termination, Termination::kNoModesBelowCutoff);
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kNoModesBelowCutoff));
}

}  // namespace
}  // namespace ltp
