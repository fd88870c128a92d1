// The harmonic transfer function as an operator and its norms (htf/harmonic_transfer_function.h).
// References: closed forms of an LTI oscillator written in rotating coordinates (periodic
// matrices, LTI input–output map), a brute-force frequency grid of an LTI formula, and the two
// routes of every quantity against each other.
#include "ltp/htf/harmonic_transfer_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "ltp/core/error.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

constexpr double kK = 2, kC = 0.1, kRate = 0.7;

TEST(HarmonicTransferFunction, RotatingOscillatorIsItsTransferFunctionOffTheAxis) {
  const HarmonicTransferFunction htf(test::RotatingOscillator(kK, kC, kRate));
  for (const cd s : {cd(0, 1.3), cd(-0.4, 0.9), cd(0.3, -2.1)}) {
    const cd g = 1.0 / (s * s + kC * s + kK);
    for (const OperatorRoute route : {OperatorRoute::kModal, OperatorRoute::kHill}) {
      const PartialFrfs h = htf.Partial(s, -2, 2, route);
      EXPECT_NEAR(std::abs(h[2](0, 0) - g), 0, 1e-8 * std::abs(g)) << ToString(route) << " " << s;
      for (int z : {0, 1, 3, 4}) EXPECT_LT(std::abs(h[z](0, 0)), 1e-8 * std::abs(g));
    }
  }
}

TEST(HarmonicTransferFunction, SectionBlocksAreShiftedPartialFunctions) {
  // Damped Mathieu with input and output: block (v, u) of the section is H_{v−u}(s + juΩp),
  // and the modal and Hill routes agree off the axis.
  const HarmonicTransferFunction htf(test::MathieuIo(1.7, 0.6, 0.08));
  const cd s(-0.05, 0.8);
  const int K = 3;
  const Eigen::MatrixXcd modal = htf.Section(s, K, OperatorRoute::kModal);
  const Eigen::MatrixXcd hill = htf.Section(s, K, OperatorRoute::kHill);
  ASSERT_EQ(modal.rows(), 2 * K + 1);
  EXPECT_LT((modal - hill).cwiseAbs().maxCoeff(), 1e-9 * modal.cwiseAbs().maxCoeff());
  for (int u = -K; u <= K; ++u) {
    const PartialFrfs h = htf.Partial(s + cd(0, 2.0 * u), -2 * K, 2 * K);
    for (int v = -K; v <= K; ++v)
      EXPECT_EQ(modal(v + K, u + K), h[v - u + 2 * K](0, 0)) << v << " " << u;
  }
}

TEST(HarmonicTransferFunction, NormsOfTheRotatingOscillatorMatchTheClosedForms) {
  const HarmonicTransferFunction htf(test::RotatingOscillator(kK, kC, kRate));
  const double hinf = 1 / (kC * std::sqrt(kK - kC * kC / 4)), h2 = 1 / std::sqrt(2 * kC * kK);
  const HinfNorm inf = htf.Hinf();
  ASSERT_TRUE(inf.ok) << inf.failure;
  EXPECT_NEAR(inf.value, hinf, 1e-7 * hinf);
  EXPECT_LE(std::abs(inf.value - hinf), inf.error_estimate + 1e-12 * hinf);
  EXPECT_LE(inf.lower, hinf * (1 + 1e-9));
  EXPECT_GE(inf.upper, hinf * (1 - 1e-9));
  // The peak of |G(jω)| is at ω² = k − c²/2 (or its shift by a multiple of Ωp).
  const double peak = std::sqrt(kK - kC * kC / 2);
  EXPECT_NEAR(std::remainder(inf.peak_omega - peak, kRate), 0, 1e-3);
  const H2Norm two = htf.H2();
  ASSERT_TRUE(two.ok) << two.failure;
  ASSERT_TRUE(two.lyapunov_value.has_value());
  EXPECT_NEAR(two.value, h2, 1e-8 * h2);
  EXPECT_NEAR(two.modal_value, h2, 1e-8 * h2);
  EXPECT_LE(std::abs(two.value - h2), two.error_estimate + 1e-12 * h2);
}

TEST(HarmonicTransferFunction, NormsOfTheDampedMathieuAgreeByTwoRoutes) {
  // Inside the first stable region near the a = 1 tongue: strong parametric coupling.
  const HarmonicTransferFunction htf(test::MathieuIo(1.7, 0.6, 0.08));
  const HinfNorm inf = htf.Hinf();
  ASSERT_TRUE(inf.ok) << inf.failure;
  EXPECT_LE(inf.search_value, inf.upper);
  EXPECT_LT(inf.upper - inf.lower, 1e-7 * inf.value);
  // Every H_0(jω) is a block of the operator: its magnitude is below the norm.
  for (double w = 0; w < 4; w += 0.01)
    EXPECT_LE(std::abs(htf.Partial(cd(0, w), 0, 0)[0](0, 0)), inf.upper * (1 + 1e-9)) << w;
  const H2Norm two = htf.H2();
  ASSERT_TRUE(two.ok) << two.failure;
  ASSERT_TRUE(two.lyapunov_value.has_value());
  EXPECT_NEAR(two.modal_value, *two.lyapunov_value, 1e-8 * two.value);
}

TEST(HarmonicTransferFunction, HinfOfAnLtiSystemWithFeedthroughMatchesAFineGrid) {
  // A 3-state LTI system as a periodic one (T = 1.3) with D = 0.25: the reference is the
  // largest |C (jωI − A)⁻¹ B + D| on a grid of 2e5 points refined around its best point.
  Eigen::MatrixXd a(3, 3), b(3, 1), c(1, 3), d(1, 1);
  a << -0.3, 2.0, 0.1, -2.0, -0.3, 0.4, 0.2, 0.0, -0.9;
  b << 1, 0.5, -1;
  c << 0.7, -1.2, 0.4;
  d << 0.25;
  const PeriodicSystem sys =
      PeriodicSystem::FromFourier(1.3, FourierMatrix::Constant(a), FourierMatrix::Constant(b),
                                  FourierMatrix::Constant(c), FourierMatrix::Constant(d));
  auto gain = [&](double w) {
    const Eigen::MatrixXcd m = cd(0, w) * Eigen::MatrixXcd::Identity(3, 3) - a.cast<cd>();
    return std::abs((c.cast<cd>() * m.partialPivLu().solve(b.cast<cd>()))(0, 0) + d(0, 0));
  };
  double best = 0, at = 0;
  for (int i = 0; i <= 200000; ++i)
    if (gain(i * 1e-4) > best) best = gain(i * 1e-4), at = i * 1e-4;
  for (int i = -1000; i <= 1000; ++i) best = std::max(best, gain(at + i * 1e-7));
  const HinfNorm inf = HarmonicTransferFunction(sys).Hinf();
  ASSERT_TRUE(inf.ok) << inf.failure;
  EXPECT_NEAR(inf.value, best, 1e-8 * best);
  // The feedthrough makes the H2 norm infinite.
  const H2Norm two = HarmonicTransferFunction(sys).H2();
  EXPECT_TRUE(two.ok);
  EXPECT_TRUE(std::isinf(two.value));
}

TEST(HarmonicTransferFunction, UnstableSystemHasInfiniteNorms) {
  // a = 1, q = 0.3, c = 0.02: inside the first Mathieu tongue (unstable).
  const HarmonicTransferFunction htf(test::MathieuIo(1.0, 0.3, 0.02));
  ASSERT_EQ(htf.floquet().verdict, StabilityVerdict::kUnstable);
  const HinfNorm inf = htf.Hinf();
  EXPECT_TRUE(inf.ok);
  EXPECT_TRUE(std::isinf(inf.value));
  EXPECT_TRUE(std::isinf(htf.H2().value));
}

TEST(HarmonicTransferFunction, BadInputIsRefused) {
  const HarmonicTransferFunction htf(test::MathieuIo(1.7, 0.6, 0.08));
  EXPECT_THROW(htf.Partial(cd(std::nan(""), 1), 0, 0), InputError);
  EXPECT_THROW(htf.Partial(cd(0, 1), 1, 0), InputError);
  EXPECT_THROW(htf.Section(cd(0, 1), -1), InputError);
  NormOptions bad;
  bad.rel_tol = 0;
  EXPECT_THROW(htf.Hinf(bad), InputError);
  EXPECT_THROW(HarmonicTransferFunction(test::Mathieu(1, 0.1)), InputError);  // no I/O
}

}  // namespace
}  // namespace ltp
