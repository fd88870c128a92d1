#include "ltp/core/second_order.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "ltp/core/error.h"
#include "support/throws.h"

namespace ltp {
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;

using test::ThrownMessage;

PeriodicSystem::MatrixFunction Constant(const MatrixXd& m) {
  return [m](double, Eigen::Ref<MatrixXd> out) { out = m; };
}

// 2-DOF example with a non-diagonal mass matrix and a time-varying stiffness:
//   M = [[2, 1], [1, 3]],  K(t) = [[4 + cos t, -1], [-1, 2]],  D = diag(0.1, 0.2),
//   F = [1; 0],  y = p1 + p2'.
SecondOrderSystem TwoDof() {
  SecondOrderSystem s;
  s.period = 2 * pi;
  s.dofs = 2;
  s.inputs = 1;
  s.outputs = 1;
  s.M = Constant((MatrixXd(2, 2) << 2, 1, 1, 3).finished());
  s.K = [](double t, Eigen::Ref<MatrixXd> out) { out << 4 + std::cos(t), -1, -1, 2; };
  s.D = Constant((MatrixXd(2, 2) << 0.1, 0, 0, 0.2).finished());
  s.F = Constant((MatrixXd(2, 1) << 1, 0).finished());
  s.Cd = Constant((MatrixXd(1, 2) << 1, 0).finished());
  s.Cv = Constant((MatrixXd(1, 2) << 0, 1).finished());
  return s;
}

TEST(SecondOrder, TwoDofNonDiagonalMassMatchesHandComputation) {
  const PeriodicSystem sys = FromSecondOrder(TwoDof());
  EXPECT_EQ(sys.states(), 4);
  EXPECT_EQ(sys.inputs(), 1);
  EXPECT_EQ(sys.outputs(), 1);
  EXPECT_EQ(sys.form(), PeriodicSystem::Form::kFunction);

  // By hand: M⁻¹ = (1/5) [[3, -1], [-1, 2]]. At t = π/2, cos t = 0, K = [[4, -1], [-1, 2]]:
  //   M⁻¹K = (1/5) [[13, -5], [-6, 5]] = [[2.6, -1], [-1.2, 1]],
  //   M⁻¹D = (1/5) [[0.3, -0.2], [-0.1, 0.4]],  M⁻¹F = (1/5) [3; -1].
  MatrixXd a(4, 4);
  a << 0, 0, 1, 0,           //
      0, 0, 0, 1,            //
      -2.6, 1, -0.06, 0.04,  //
      1.2, -1, 0.02, -0.08;
  EXPECT_LT((sys.A(pi / 2) - a).norm(), 1e-14);
  // At t = π/3, cos t = 1/2, K11 = 4.5: M⁻¹K = (1/5) [[14.5, -5], [-6.5, 5]].
  a(2, 0) = -2.9;
  a(3, 0) = 1.3;
  EXPECT_LT((sys.A(pi / 3) - a).norm(), 1e-14);

  MatrixXd b(4, 1);
  b << 0, 0, 0.6, -0.2;
  EXPECT_LT((sys.B(1.0) - b).norm(), 1e-15);
  MatrixXd c(1, 4);
  c << 1, 0, 0, 1;  // [Cd, Cv]
  EXPECT_EQ(sys.C(1.0), c);
  EXPECT_EQ(sys.D(1.0), MatrixXd::Zero(1, 1));
}

TEST(SecondOrder, NoDampingNoInputsNoOutputs) {
  // p'' + 4 p = 0: A = [[0, 1], [-4, 0]].
  SecondOrderSystem s;
  s.period = 1;
  s.dofs = 1;
  s.M = Constant(MatrixXd::Ones(1, 1));
  s.K = Constant(MatrixXd::Constant(1, 1, 4));
  const PeriodicSystem sys = FromSecondOrder(s);
  EXPECT_EQ(sys.inputs(), 0);
  EXPECT_EQ(sys.outputs(), 0);
  EXPECT_EQ(sys.A(0.3), (MatrixXd(2, 2) << 0, 1, -4, 0).finished());
}

TEST(SecondOrder, BreakpointsArePassedOn) {
  SecondOrderSystem s = TwoDof();
  s.breakpoints = {3.0, 1.0};
  const PeriodicSystem sys = FromSecondOrder(s);
  EXPECT_EQ(sys.breakpoints(), (std::vector<double>{1.0, 3.0}));
}

TEST(SecondOrder, MassSingularOnTheGridThrows) {
  // M(t) = diag(1, cos t) is singular at t = π/2, which is grid point 16 of 64 over 2π.
  SecondOrderSystem s = TwoDof();
  s.M = [](double t, Eigen::Ref<MatrixXd> out) { out << 1, 0, 0, std::cos(t); };
  const std::string message = ThrownMessage<SingularMassError>([&] { FromSecondOrder(s); });
  EXPECT_NE(message.find("singular at t = 1.5708"), std::string::npos) << message;
  EXPECT_NE(message.find("rcond"), std::string::npos) << message;
}

TEST(SecondOrder, ConstantSingularMassThrows) {
  SecondOrderSystem s = TwoDof();
  s.M = Constant((MatrixXd(2, 2) << 1, 2, 2, 4).finished());  // rank 1
  const std::string message = ThrownMessage<SingularMassError>([&] { FromSecondOrder(s); });
  EXPECT_NE(message.find("mass matrix M(t) is singular at t = 0"), std::string::npos) << message;
  s.M = Constant((MatrixXd(2, 2) << 1, 0, 0, 0).finished());  // an exactly zero pivot
  EXPECT_THROW(FromSecondOrder(s), SingularMassError);
}

TEST(SecondOrder, IllConditionedMassThrows) {
  SecondOrderSystem s = TwoDof();
  s.M = Constant((MatrixXd(2, 2) << 1, 0, 0, 1e-15).finished());  // rcond 1e-15 < 1e-13
  EXPECT_THROW(FromSecondOrder(s), SingularMassError);
  SecondOrderOptions loose;
  loose.min_rcond = 1e-16;
  EXPECT_NO_THROW(FromSecondOrder(s, loose));
}

TEST(SecondOrder, MassSingularOnlyAtABreakpointIsCaught) {
  // M(t) = diag(1, t - 1) is singular only at t = 1, which is no grid point (1 ≠ 2πi/64), but
  // it is a breakpoint, and breakpoints are checked.
  SecondOrderSystem s = TwoDof();
  s.M = [](double t, Eigen::Ref<MatrixXd> out) { out << 1, 0, 0, t - 1; };
  s.breakpoints = {1.0};
  const std::string message = ThrownMessage<SingularMassError>([&] { FromSecondOrder(s); });
  EXPECT_NE(message.find("at t = 1 "), std::string::npos) << message;
  s.breakpoints = {};
  EXPECT_NO_THROW(FromSecondOrder(s));  // the grid alone misses it
}

TEST(SecondOrder, NonFiniteMassThrows) {
  SecondOrderSystem s = TwoDof();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.M = Constant((MatrixXd(2, 2) << 1, 0, 0, nan).finished());
  const std::string message = ThrownMessage<SingularMassError>([&] { FromSecondOrder(s); });
  EXPECT_NE(message.find("not finite at t = 0"), std::string::npos) << message;
}

TEST(SecondOrder, MissingPiecesAreInputErrors) {
  SecondOrderSystem s = TwoDof();
  s.M = nullptr;
  EXPECT_THROW(FromSecondOrder(s), InputError);
  s = TwoDof();
  s.K = nullptr;
  EXPECT_THROW(FromSecondOrder(s), InputError);
  s = TwoDof();
  s.F = nullptr;
  EXPECT_THROW(FromSecondOrder(s), InputError);
  s = TwoDof();
  s.dofs = 0;
  EXPECT_THROW(FromSecondOrder(s), InputError);
  s = TwoDof();
  s.period = -1;
  EXPECT_THROW(FromSecondOrder(s), InputError);
}

}  // namespace
}  // namespace ltp

namespace ltp {
namespace {

// The 2-DOF example above as Fourier coefficients: K(t) = K_0 + (K_c/2)(e^{jt} + e^{−jt}).
FourierMatrix Harmonic1(const MatrixXd& k0, const MatrixXd& kc) {
  FourierMatrix f(static_cast<int>(k0.rows()), static_cast<int>(k0.cols()), 1);
  f.SetHarmonic(0, k0.cast<std::complex<double>>());
  f.SetHarmonic(1, (0.5 * kc).cast<std::complex<double>>());
  return f;
}

TEST(SecondOrderSeries, ConstantMassIsAnExactFourierSystemMatchingTheHandComputation) {
  const MatrixXd m = (MatrixXd(2, 2) << 2, 1, 1, 3).finished();
  const FourierMatrix K = Harmonic1((MatrixXd(2, 2) << 4, -1, -1, 2).finished(),
                                    (MatrixXd(2, 2) << 1, 0, 0, 0).finished());
  const PeriodicSystem sys =
      FromSecondOrderSeries(2 * pi, FourierMatrix::Constant(m),
                            FourierMatrix::Constant((MatrixXd(2, 2) << 0.1, 0, 0, 0.2).finished()),
                            K, FourierMatrix::Constant((MatrixXd(2, 1) << 1, 0).finished()),
                            FourierMatrix::Constant((MatrixXd(1, 2) << 1, 0).finished()),
                            FourierMatrix::Constant((MatrixXd(1, 2) << 0, 1).finished()));
  EXPECT_EQ(sys.form(), PeriodicSystem::Form::kFourier);
  ASSERT_NE(sys.fourier_A(), nullptr);
  EXPECT_EQ(sys.fourier_A()->max_harmonic(), 1);
  // The function-form conversion of the same model, whose values are checked by hand above.
  const PeriodicSystem reference = FromSecondOrder(TwoDof());
  for (double t : {0.0, pi / 3, pi / 2, 2.5}) {
    EXPECT_LT((sys.A(t) - reference.A(t)).norm(), 1e-14) << t;
    EXPECT_LT((sys.B(t) - reference.B(t)).norm(), 1e-15) << t;
    EXPECT_EQ(sys.C(t), reference.C(t)) << t;
  }
}

TEST(SecondOrderSeries, PeriodicMassGivesTheFunctionForm) {
  // M(t) = [[2 + 0.5 cos t, 1], [1, 3]]: A(t) = [[0, I], [−M(t)⁻¹K, −M(t)⁻¹D]] at each t.
  const MatrixXd k = (MatrixXd(2, 2) << 4, -1, -1, 2).finished();
  const MatrixXd d = (MatrixXd(2, 2) << 0.1, 0, 0, 0.2).finished();
  const FourierMatrix M = Harmonic1((MatrixXd(2, 2) << 2, 1, 1, 3).finished(),
                                    (MatrixXd(2, 2) << 0.5, 0, 0, 0).finished());
  const PeriodicSystem sys =
      FromSecondOrderSeries(2 * pi, M, FourierMatrix::Constant(d), FourierMatrix::Constant(k));
  EXPECT_EQ(sys.form(), PeriodicSystem::Form::kFunction);
  for (double t : {0.3, 1.7}) {
    const MatrixXd mt = (MatrixXd(2, 2) << 2 + 0.5 * std::cos(t), 1, 1, 3).finished();
    MatrixXd a = MatrixXd::Zero(4, 4);
    a.topRightCorner(2, 2).setIdentity();
    a.bottomLeftCorner(2, 2) = -mt.inverse() * k;
    a.bottomRightCorner(2, 2) = -mt.inverse() * d;
    EXPECT_LT((sys.A(t) - a).norm(), 1e-14) << t;
  }
}

TEST(SecondOrderSeries, BadInputIsRefusedWithTheReason) {
  const FourierMatrix k = FourierMatrix::Constant(MatrixXd::Identity(2, 2));
  EXPECT_THROW(FromSecondOrderSeries(1.0, FourierMatrix::Constant(MatrixXd::Zero(2, 2)), {}, k),
               SingularMassError);
  EXPECT_NE(ThrownMessage<InputError>([&] {
              FromSecondOrderSeries(1.0, FourierMatrix::Constant(MatrixXd::Identity(2, 2)), {},
                                    FourierMatrix::Constant(MatrixXd::Identity(3, 3)));
            }).find("expected 2×2"),
            std::string::npos);
  EXPECT_THROW(FromSecondOrderSeries(0.0, FourierMatrix::Constant(MatrixXd::Identity(2, 2)), {}, k),
               InputError);
  EXPECT_THROW(FromSecondOrderSeries(1.0, {}, {}, k), InputError);
}

}  // namespace
}  // namespace ltp
