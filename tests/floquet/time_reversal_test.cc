// Time-reversal symmetry (floquet/src/time_reversal.h): which systems have it, that the found
// involution satisfies the defining identity, and that the half-period monodromy equals the
// full-period one (another route) and the damped oscillator's closed form.
#include "time_reversal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "ltp/core/fourier_matrix.h"
#include "ltp/floquet/half_period_blocks.h"
#include "ltp/models/scene.h"

namespace ltp::internal {
namespace {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;

PeriodicSystem Mathieu(double a, double q, double c) {
  return LoadScene("mathieu").build({{"a", a}, {"q", q}, {"c", c}});
}

// Two coupled Hill equations p'' + c p' + (K_0 + K_1 cos 2t + K_s sin 2t) p = 0, in [p; p'].
PeriodicSystem CoupledHill(double c, double sine, double stiffness = 1) {
  FourierMatrix A(4, 4, 1);
  MatrixXd k0(2, 2), k1(2, 2);
  k0 << 3.0, -0.7, -0.7, 1.4;
  k0 *= stiffness;
  k1 << 0.9, 0.3, 0.3, -0.5;
  A[0].setZero();
  A[0].topRightCorner(2, 2).setIdentity();
  A[0].bottomLeftCorner(2, 2) = -k0;
  A[0].bottomRightCorner(2, 2) = -c * MatrixXd::Identity(2, 2);
  MatrixXcd a1 = MatrixXcd::Zero(4, 4);
  // e^{2jt} M + c.c. = 2 Re M cos 2t − 2 Im M sin 2t
  a1.bottomLeftCorner(2, 2) = (-0.5 * k1).cast<std::complex<double>>();
  a1(2, 0) += std::complex<double>(0, 0.5 * sine);
  A.SetHarmonic(1, a1);
  return PeriodicSystem::FromFourier(std::numbers::pi, std::move(A));
}

// R (A(−t) − μI) R = −(A(t) − μI) and R² = I, checked on A itself at a few times.
void ExpectReversal(const PeriodicSystem& system, const TimeReversal& r) {
  const int n = system.states();
  const MatrixXd I = MatrixXd::Identity(n, n);
  EXPECT_LT((r.involution * r.involution - I).norm(), 1e-14);
  for (double t : {0.1, 0.77, 1.3, 2.9}) {
    const MatrixXd lhs = r.involution * (system.A(-t) - r.rate * I) * r.involution;
    EXPECT_LT((lhs + (system.A(t) - r.rate * I)).norm(), 1e-13) << "t = " << t;
  }
}

TEST(TimeReversal, FoundForUndampedAndScalarDampedHillEquations) {
  const auto undamped = FindTimeReversal(Mathieu(1.3, 0.8, 0));
  ASSERT_TRUE(undamped);
  EXPECT_EQ(undamped->rate, 0);
  EXPECT_EQ(undamped->involution, (MatrixXd(2, 2) << 1, 0, 0, -1).finished());
  ExpectReversal(Mathieu(1.3, 0.8, 0), *undamped);

  // x = e^{−ct/2} y: μ = −c/2 and R = S⁻¹ diag(1, −1) S with S = [[1, 0], [c/2, 1]].
  const auto damped = FindTimeReversal(Mathieu(1.3, 0.8, 0.02));
  ASSERT_TRUE(damped);
  EXPECT_DOUBLE_EQ(damped->rate, -0.01);
  EXPECT_LT((damped->involution - (MatrixXd(2, 2) << 1, 0, -0.02, -1).finished()).norm(), 1e-16);
  ExpectReversal(Mathieu(1.3, 0.8, 0.02), *damped);

  const auto coupled = FindTimeReversal(CoupledHill(0.3, 0));
  ASSERT_TRUE(coupled);
  ExpectReversal(CoupledHill(0.3, 0), *coupled);
}

TEST(TimeReversal, NotClaimedWhereItFails) {
  // sin 2t in the stiffness: reversible about t = π/4, not about 0.
  EXPECT_FALSE(FindTimeReversal(CoupledHill(0, 0.4)));
  // Unequal damping of the two coordinates: no shear removes it.
  FourierMatrix A(4, 4, 0);
  A[0].setZero();
  A[0].topRightCorner(2, 2).setIdentity();
  A[0](2, 0) = -3;
  A[0](3, 1) = -1;
  A[0](2, 2) = -0.1;
  A[0](3, 3) = -0.3;
  EXPECT_FALSE(FindTimeReversal(PeriodicSystem::FromFourier(1.0, std::move(A))));
  // Time functions are not inspected.
  const Scene meissner = LoadScene("meissner");
  EXPECT_FALSE(FindTimeReversal(meissner.build(meissner.Resolve({}))));
}

TEST(TimeReversal, HalfPeriodMonodromyEqualsTheFullPeriod) {
  IntegratorOptions o;
  o.type = IntegratorType::kRkf78;
  o.rel_tol = 1e-12;
  o.abs_tol = 1e-14;
  // Stable, a tongue's inside (unstable), damped and undamped, 2 and 4 states.
  for (const PeriodicSystem& s : {Mathieu(1.3, 0.3, 0), Mathieu(1.0, 0.8, 0.05),
                                  Mathieu(-0.5, 3.0, 0.2), CoupledHill(0.3, 0)}) {
    const auto reversal = FindTimeReversal(s);
    ASSERT_TRUE(reversal);
    const TransitionResult half = MonodromyFromHalfPeriod(s, *reversal, o);
    const TransitionResult full = StateTransition(s, 0, s.period(), o);
    ASSERT_TRUE(half.ok && full.ok);
    EXPECT_LT((half.phi - full.phi).norm(), 1e-9 * full.phi.norm());
  }
}

// Deep in the instability (a = −100, q = 20: the largest multiplier ~1e13, and Φ(T/2) about as
// ill-conditioned): the largest multiplier keeps the tolerance's relative accuracy, as in the
// full-period product. An inverse with det = ad − bc loses that factor (measured: 2e-3 here);
// the 4-state system with negative stiffness takes the full period instead.
TEST(TimeReversal, LargestMultiplierStaysAccurateWhenHugelyUnstable) {
  IntegratorOptions o;
  o.type = IntegratorType::kRkf78;
  o.rel_tol = 1e-12;
  o.abs_tol = 1e-14;
  const auto largest = [](const Eigen::MatrixXd& m) {
    return m.eigenvalues().cwiseAbs().maxCoeff();
  };
  for (const PeriodicSystem& s : {Mathieu(-100, 20, 0), Mathieu(-100, 20, 0.4), CoupledHill(0.2, 0),
                                  CoupledHill(0.2, 0, -40)}) {
    const auto reversal = FindTimeReversal(s);
    ASSERT_TRUE(reversal);
    const TransitionResult half = MonodromyFromHalfPeriod(s, *reversal, o);
    const TransitionResult full = StateTransition(s, 0, s.period(), o);
    ASSERT_TRUE(half.ok && full.ok);
    const double rho = largest(full.phi);
    EXPECT_LT(std::abs(largest(half.phi) - rho), 1e-9 * rho) << "largest multiplier " << rho;
  }
  EXPECT_GT(largest(StateTransition(Mathieu(-100, 20, 0), 0, std::numbers::pi, o).phi), 1e12);
}

// q = 0: y'' + c y' + a y = 0 has multipliers e^{λT}, λ = −c/2 ± j√(a − c²/4) (closed form).
TEST(TimeReversal, DampedOscillatorMultipliersMatchTheClosedForm) {
  const double a = 2.0, c = 0.3, T = std::numbers::pi;
  const PeriodicSystem s = Mathieu(a, 0, c);
  const auto reversal = FindTimeReversal(s);
  ASSERT_TRUE(reversal);
  IntegratorOptions o;
  o.type = IntegratorType::kBulirschStoer;
  o.rel_tol = 1e-12;
  const TransitionResult half = MonodromyFromHalfPeriod(s, *reversal, o);
  ASSERT_TRUE(half.ok);
  const Eigen::VectorXcd rho = half.phi.eigenvalues();
  const std::complex<double> exact =
      std::exp(std::complex<double>(-c / 2, std::sqrt(a - c * c / 4)) * T);
  const double error = std::min(std::abs(rho(0) - exact), std::abs(rho(1) - exact));
  EXPECT_LT(error, 1e-11);
}

// The half-period factorization (half_period_blocks.h) against the full-period monodromy
// (another route): det(Φ(T) − I) = (−4)^p det Q det U / det Φh, det(Φ(T) + I) = 4^p det P det W /
// det Φh, on two coupled undamped Hill equations (p = 2) at three stiffness scalings.
TEST(HalfPeriodBlocks, FactorTheCharacteristicDeterminants) {
  IntegratorOptions o;
  o.type = IntegratorType::kBulirschStoer;
  o.rel_tol = 1e-12;
  o.abs_tol = 1e-15;
  for (double stiffness : {1.0, 0.31, 2.2}) {
    const PeriodicSystem s = CoupledHill(0, 0, stiffness);
    ASSERT_TRUE(HasHalfPeriodBlocks(s));
    const auto blocks = ComputeHalfPeriodBlocks(s, o);
    ASSERT_TRUE(blocks);
    ASSERT_EQ(blocks->P.rows(), 2);
    const TransitionResult full = StateTransition(s, 0, s.period(), o);
    ASSERT_TRUE(full.ok);
    MatrixXd half(4, 4);
    half << blocks->P, blocks->Q, blocks->U, blocks->W;  // R = diag(1, 1, −1, −1): no reordering
    const double det_half = half.determinant();
    const MatrixXd I = MatrixXd::Identity(4, 4);
    const double minus = (full.phi - I).determinant(), plus = (full.phi + I).determinant();
    const double scale = std::pow(1 + full.phi.norm(), 4);
    EXPECT_NEAR(16 * blocks->Q.determinant() * blocks->U.determinant() / det_half, minus,
                1e-9 * scale)
        << stiffness;
    EXPECT_NEAR(16 * blocks->P.determinant() * blocks->W.determinant() / det_half, plus,
                1e-9 * scale)
        << stiffness;
    EXPECT_NEAR(det_half, 1, 1e-10);  // Liouville: tr A = 0
  }
  // Damping (μ ≠ 0) and a sine term (reversible about T/4, not 0) have no such factorization.
  EXPECT_FALSE(HasHalfPeriodBlocks(CoupledHill(0.1, 0)));
  EXPECT_FALSE(HasHalfPeriodBlocks(CoupledHill(0, 0.2)));
  EXPECT_FALSE(ComputeHalfPeriodBlocks(CoupledHill(0.1, 0), o));
}

// q = 0: y'' + a y = 0 over T/2 = π/2 is the rotation by θ = √a π/2 (closed form).
TEST(HalfPeriodBlocks, MathieuAtZeroExcitationIsTheRotation) {
  const double a = 2.7, w = std::sqrt(a), theta = w * std::numbers::pi / 2;
  IntegratorOptions o;
  o.rel_tol = 1e-12;
  const auto blocks = ComputeHalfPeriodBlocks(Mathieu(a, 0, 0), o);
  ASSERT_TRUE(blocks);
  EXPECT_NEAR(blocks->P(0, 0), std::cos(theta), 1e-11);
  EXPECT_NEAR(blocks->Q(0, 0), std::sin(theta) / w, 1e-11);
  EXPECT_NEAR(blocks->U(0, 0), -w * std::sin(theta), 1e-11);
  EXPECT_NEAR(blocks->W(0, 0), std::cos(theta), 1e-11);
  EXPECT_EQ(&blocks->Factor(1, true), &blocks->U);
  EXPECT_EQ(&blocks->Factor(-1, false), &blocks->W);
}

}  // namespace
}  // namespace ltp::internal
