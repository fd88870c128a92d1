// Transmission zeros of the HTF (HarmonicTransferFunction::Zeros). References: closed forms
// (an LTI transfer function written in rotating coordinates; the mean of a scalar zero
// dynamics; a zero dynamics on ker C that is a scalar equation), and the two routes — the
// harmonic pencil and the zero dynamics' Floquet exponents — against each other.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <utility>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/htf/harmonic_transfer_function.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr double kK = 2, kC = 0.1, kRate = 0.7;

// Every zero agrees with its check route within the estimates, and the estimates are small.
void ExpectRoutesAgree(const TransmissionZeros& r, double omega, double estimate_below) {
  for (const TransmissionZero& z : r.zeros) {
    ASSERT_TRUE(z.check_value.has_value());
    const double d = ExponentDistance(z.centred, *z.check_value, omega);
    EXPECT_LE(d, z.error_estimate + *z.check_error_estimate + 1e-12) << z.centred;
    EXPECT_LT(z.error_estimate, estimate_below) << z.centred;
  }
}

// Bad options are refused before any work, naming the field and the constraint in the one
// style of every Validate() (OptionCheck).
TEST(TransmissionZeros, BadOptionsNameTheFieldAndTheConstraint) {
  for (auto [field, set] : std::initializer_list<std::pair<const char*, void (*)(ZerosOptions&)>>{
           {"ZerosOptions::tol = 0.5. Violated constraint: 0 < tol < 0.1",
            [](ZerosOptions& o) { o.tol = 0.5; }},
           {"ZerosOptions::harmonics = -1. Violated constraint: harmonics >= 0",
            [](ZerosOptions& o) { o.harmonics = -1; }},
           {"ZerosOptions::max_pencil_size = 0. Violated constraint: max_pencil_size >= 1",
            [](ZerosOptions& o) { o.max_pencil_size = 0; }}}) {
    ZerosOptions o;
    set(o);
    try {
      o.Validate();
      ADD_FAILURE() << field << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

TEST(TransmissionZeros, RotatingOscillatorWithFeedthroughHasTheZerosOfG) {
  // G(s) = 1/(s² + cs + k) + d vanishes where s² + cs + k + 1/d = 0. D = d is invertible: the
  // zero-dynamics route checks.
  const double d = 0.5;
  const HarmonicTransferFunction htf(test::RotatingOscillator(kK, kC, kRate, {1, 0}, d));
  const TransmissionZeros r = htf.Zeros();
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_EQ(r.check_route, ZeroRoute::kZeroDynamics);
  ASSERT_EQ(r.zeros.size(), 2u);
  const double im = std::sqrt(kK + 1 / d - kC * kC / 4);
  EXPECT_LT(std::abs(r.zeros[0].centred - cd(-kC / 2, im)), 1e-10);
  EXPECT_LT(std::abs(r.zeros[1].centred - cd(-kC / 2, -im)), 1e-10);
  for (const TransmissionZero& z : r.zeros) {
    EXPECT_LE(std::abs(z.value.imag()), kRate / 2);
    EXPECT_LT(ExponentDistance(z.value, z.centred, kRate), 1e-12);
  }
  ExpectRoutesAgree(r, kRate, 1e-8);
}

TEST(TransmissionZeros, RotatingOscillatorOfRelativeDegreeOneHasTheZeroOfG) {
  // y = 0.3 z + z': G(s) = (s + 0.3)/(s² + cs + k), one zero at −0.3. D = 0 and C(t)B(t) = 1:
  // the relative-degree-one route checks.
  const HarmonicTransferFunction htf(test::RotatingOscillator(kK, kC, kRate, {0.3, 1}));
  const TransmissionZeros r = htf.Zeros();
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_EQ(r.check_route, ZeroRoute::kRelativeDegreeOne);
  ASSERT_EQ(r.zeros.size(), 1u);
  EXPECT_LT(std::abs(r.zeros[0].centred - cd(-0.3, 0)), 1e-10);
  ExpectRoutesAgree(r, kRate, 1e-8);
}

TEST(TransmissionZeros, RotatingOscillatorObservedByPositionHasNoZeros) {
  // G(s) = 1/(s² + cs + k) has no finite zeros; relative degree two: no check route.
  const HarmonicTransferFunction htf(test::RotatingOscillator(kK, kC, kRate));
  const TransmissionZeros r = htf.Zeros();
  ASSERT_TRUE(r.ok) << r.failure;
  EXPECT_TRUE(r.zeros.empty());
  EXPECT_FALSE(r.check_route.has_value());
  EXPECT_GT(r.infinite_eigenvalues, 0);
}

// Damped Mathieu y'' + 0.08 y' + (1.7 − 1.2 cos 2t) y = (1 + 0.3 sin 2t) u, observed as
// y + 0.2 cos 2t · y' + (0.8 + 0.2 cos 2t) u: periodic A, B, C and D, D invertible.
PeriodicSystem PeriodicWithFeedthrough() {
  FourierMatrix a(2, 2, 1), b(2, 1, 1), c(1, 2, 1), d(1, 1, 1);
  a.SetHarmonic(0, (Eigen::MatrixXcd(2, 2) << 0, 1, -1.7, -0.08).finished());
  a.SetHarmonic(1, (Eigen::MatrixXcd(2, 2) << 0, 0, 0.6, 0).finished());
  b.SetHarmonic(0, (Eigen::MatrixXcd(2, 1) << 0, 1).finished());
  b.SetHarmonic(1, (Eigen::MatrixXcd(2, 1) << 0, cd(0, -0.15)).finished());  // 0.3 sin 2t
  c.SetHarmonic(0, (Eigen::MatrixXcd(1, 2) << 1, 0).finished());
  c.SetHarmonic(1, (Eigen::MatrixXcd(1, 2) << 0, 0.1).finished());  // 0.2 cos 2t
  d.SetHarmonic(0, Eigen::MatrixXcd::Constant(1, 1, 0.8));
  d.SetHarmonic(1, Eigen::MatrixXcd::Constant(1, 1, 0.1));
  return PeriodicSystem::FromFourier(kPi, a, b, c, d);
}

TEST(TransmissionZeros, PeriodicSystemWithInvertibleFeedthroughByBothRoutes) {
  // Reference: the monodromy route's exponents of A − B D⁻¹ C; the Hill route must equal them
  // within the estimates. Independent reference: SciPy's monodromy of the same zero dynamics
  // (DOP853 at rtol 1e-12 and 1e-13, agreeing to 5e-14): −0.0236022205057 ± 0.3188939165632j.
  const HarmonicTransferFunction htf(PeriodicWithFeedthrough());
  const TransmissionZeros r = htf.Zeros();
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_EQ(r.check_route, ZeroRoute::kZeroDynamics);
  ASSERT_EQ(r.zeros.size(), 2u);
  ExpectRoutesAgree(r, 2.0, 1e-8);
  const cd scipy(-0.0236022205057, 0.3188939165632);
  EXPECT_LT(
      MaxExponentMismatch({r.zeros[0].value, r.zeros[1].value}, {scipy, std::conj(scipy)}, 2.0),
      1e-11);
}

TEST(TransmissionZeros, ScalarZeroIsTheMeanOfItsZeroDynamics) {
  // x' = a(t) x + b(t) u, y = c(t) x + d u: u = −c x/d gives x' = (a − bc/d) x, so the zero is
  // the mean of a − bc/d, exactly. a = −0.5 + 0.8 cos Ωt, b = 1 + 0.5 cos Ωt + 0.2 sin 2Ωt,
  // c = 0.7 + 0.3 cos Ωt − 0.4 sin 2Ωt, d = 2: mean(bc) = 0.7 + 0.075 − 0.04 = 0.735, zero
  // −0.5 − 0.3675 = −0.8675.
  const double period = 1.3, omega = 2 * kPi / period;
  FourierMatrix a(1, 1, 1), b(1, 1, 2), c(1, 1, 2);
  a.SetHarmonic(0, Eigen::MatrixXcd::Constant(1, 1, -0.5));
  a.SetHarmonic(1, Eigen::MatrixXcd::Constant(1, 1, 0.4));
  b.SetHarmonic(0, Eigen::MatrixXcd::Constant(1, 1, 1.0));
  b.SetHarmonic(1, Eigen::MatrixXcd::Constant(1, 1, 0.25));
  b.SetHarmonic(2, Eigen::MatrixXcd::Constant(1, 1, cd(0, -0.1)));  // 0.2 sin 2Ωt
  c.SetHarmonic(0, Eigen::MatrixXcd::Constant(1, 1, 0.7));
  c.SetHarmonic(1, Eigen::MatrixXcd::Constant(1, 1, 0.15));
  c.SetHarmonic(2, Eigen::MatrixXcd::Constant(1, 1, cd(0, 0.2)));  // −0.4 sin 2Ωt
  const PeriodicSystem sys = PeriodicSystem::FromFourier(
      period, a, b, c, FourierMatrix::Constant(Eigen::MatrixXd::Constant(1, 1, 2.0)));
  const TransmissionZeros r = HarmonicTransferFunction(sys).Zeros();
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_EQ(r.zeros.size(), 1u);
  EXPECT_LT(ExponentDistance(r.zeros[0].value, -0.8675, omega), 1e-12);
  EXPECT_LT(std::abs(r.zeros[0].value - cd(-0.8675, 0)), 1e-12);
  ExpectRoutesAgree(r, omega, 1e-9);
}

TEST(TransmissionZeros, RelativeDegreeOneZeroOnKerCIsTheMeanOfItsWeight) {
  // The Mathieu oscillator x1' = x2, x2' = −(1.7 − 1.2 cos 2t) x1 − 0.08 x2 + (1 + 0.3 sin 2t) u
  // observed as y = (1 + 0.5 cos 2t) x1 + x2, D = 0, C B = 1 + 0.3 sin 2t. On y ≡ 0,
  // x1' = x2 = −(1 + 0.5 cos 2t) x1: the zero is −mean(1 + 0.5 cos 2t) = −1, exactly.
  const PeriodicSystem mathieu = test::Mathieu(1.7, 0.6, 0.08);
  FourierMatrix b(2, 1, 1), c(1, 2, 1);
  b.SetHarmonic(0, (Eigen::MatrixXcd(2, 1) << 0, 1).finished());
  b.SetHarmonic(1, (Eigen::MatrixXcd(2, 1) << 0, cd(0, -0.15)).finished());
  c.SetHarmonic(0, (Eigen::MatrixXcd(1, 2) << 1, 1).finished());
  c.SetHarmonic(1, (Eigen::MatrixXcd(1, 2) << 0.25, 0).finished());
  const HarmonicTransferFunction htf(PeriodicSystem::FromFourier(kPi, *mathieu.fourier_A(), b, c));
  const TransmissionZeros r = htf.Zeros();
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_EQ(r.check_route, ZeroRoute::kRelativeDegreeOne);
  ASSERT_EQ(r.zeros.size(), 1u);
  EXPECT_LT(ExponentDistance(r.zeros[0].value, -1.0, 2.0), 1e-10);
  ExpectRoutesAgree(r, 2.0, 1e-9);
}

TEST(TransmissionZeros, SquareWaveCoefficientsConvergeSlowlyAndTheCheckRouteIsReported) {
  // The scalar closed form with a(t), b(t), c(t) square waves s(t) = ±1 (jumps at 0 and T/2):
  // a = −0.5 + 0.8 s, b = 1 + 0.5 s, c = 0.7 + 0.3 s, d = 2; s² = 1, so mean(bc) = 0.85 and the
  // zero is −0.5 − 0.425 = −0.925, exactly. The coefficients' Fourier series decay like 1/w:
  // the pencil converges like 1/N and does not reach tol.
  auto square = [](double t) { return std::fmod(t, 1.0) < 0.5 ? 1.0 : -1.0; };
  PeriodicSystem::Functions f;
  f.A = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) { out(0, 0) = -0.5 + 0.8 * square(t); };
  f.B = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) { out(0, 0) = 1 + 0.5 * square(t); };
  f.C = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) { out(0, 0) = 0.7 + 0.3 * square(t); };
  f.D = [](double, Eigen::Ref<Eigen::MatrixXd> out) { out(0, 0) = 2; };
  const HarmonicTransferFunction htf(PeriodicSystem::FromFunctions(1.0, 1, 1, 1, f, {0.0, 0.5}));
  ZerosOptions o;
  o.harmonics = 16;
  o.check = false;
  const TransmissionZeros alone = htf.Zeros(o);
  EXPECT_FALSE(alone.ok);
  ASSERT_EQ(alone.zeros.size(), 1u);
  // Its estimate (the change from N to N + Δ times (N + Δ)/Δ) covers its error.
  const double error = ExponentDistance(alone.zeros[0].value, -0.925, 2 * kPi);
  EXPECT_GT(error, 1e-4);
  EXPECT_LE(error, alone.zeros[0].error_estimate);
  o.check = true;
  const TransmissionZeros checked = htf.Zeros(o);
  ASSERT_TRUE(checked.ok) << checked.failure;
  EXPECT_EQ(checked.route, ZeroRoute::kZeroDynamics);
  ASSERT_EQ(checked.zeros.size(), 1u);
  EXPECT_LT(std::abs(checked.zeros[0].value - cd(-0.925, 0)), 1e-10);
  EXPECT_LT(checked.zeros[0].error_estimate, 1e-9);
  EXPECT_EQ(checked.zeros[0].hill_value, alone.zeros[0].centred);
}

TEST(TransmissionZeros, NonSquareSystemsAndBadOptionsAreRefused) {
  const PeriodicSystem mathieu = test::Mathieu(1.7, 0.6, 0.08);
  const PeriodicSystem two_outputs = PeriodicSystem::FromFourier(
      kPi, *mathieu.fourier_A(), FourierMatrix::Constant(Eigen::Vector2d(0, 1)),
      FourierMatrix::Constant(Eigen::Matrix2d::Identity()));
  EXPECT_THROW(HarmonicTransferFunction(two_outputs).Zeros(), InputError);
  const HarmonicTransferFunction square(test::MathieuIo(1.7, 0.6, 0.08));
  ZerosOptions bad;
  bad.tol = 0;
  EXPECT_THROW(square.Zeros(bad), InputError);
  bad = {};
  bad.max_harmonics = 0;
  EXPECT_THROW(square.Zeros(bad), InputError);
}

}  // namespace
}  // namespace ltp
