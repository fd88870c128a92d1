// The exact exponential integrals of the Magnus–Filon integrator (integrate/src/
// oscillatory_integrals.h) against closed forms and a tensor Gauss–Legendre quadrature.
#include "oscillatory_integrals.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>

namespace ltp::internal {
namespace {

double Rel(Complex got, Complex want) { return std::abs(got - want) / std::abs(want); }

// ∫_0^h ∫_0^{s1} e^{a s1 + b s2} by 40 × 40 Gauss–Legendre points on the square, the inner
// integral mapped onto [0, s1]: exact to round-off for these smooth integrands.
Complex TriangleByQuadrature(Complex a, Complex b, double h) {
  // Nodes and weights on [0, 1] by Golub–Welsch (Eigen's symmetric eigensolver).
  const int n = 40;
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) jacobi(k, k - 1) = jacobi(k - 1, k) = k / std::sqrt(4.0 * k * k - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jacobi);
  const Eigen::VectorXd x = (eig.eigenvalues().array() + 1) / 2;
  const Eigen::VectorXd w = eig.eigenvectors().row(0).array().square();
  Complex sum = 0;
  for (int i = 0; i < n; ++i) {
    const double s1 = h * x(i);
    for (int j = 0; j < n; ++j) {
      const double s2 = s1 * x(j);
      sum += w(i) * w(j) * h * s1 * std::exp(a * s1 + b * s2);
    }
  }
  return sum;
}

TEST(OscillatoryIntegrals, Phi1KeepsFullAccuracyNearZero) {
  EXPECT_EQ(Phi1(0.0), Complex(1));
  // φ1(z) = 1 + z/2 + z²/6 + z³/24 + …: at |z| = 1e-9 the quotient (e^z − 1)/z formed naively
  // loses 7 digits.
  const Complex z(1e-9, -2e-9);
  EXPECT_LT(Rel(Phi1(z), 1.0 + z / 2.0 + z * z / 6.0), 4e-16);
  const Complex big(-3, 40);
  EXPECT_LT(Rel(Phi1(big), (std::exp(big) - 1.0) / big), 1e-15);
}

TEST(OscillatoryIntegrals, TriangleMatchesClosedForms) {
  const double h = 0.7;
  EXPECT_LT(Rel(TriangleIntegral(0.0, 0.0, h), h * h / 2), 1e-15);
  // b = 0: ∫_0^h s e^{as} ds = (e^{ah}(ah − 1) + 1)/a².
  for (Complex a : {Complex(2, 0), Complex(-0.5, 30), Complex(0, 1e-4), Complex(1e-7, 0)}) {
    const Complex want = std::abs(a * h) > 1e-2 ? (std::exp(a * h) * (a * h - 1.0) + 1.0) / (a * a)
                                                : h * h * (0.5 + a * h / 3.0 + a * a * h * h / 8.0);
    EXPECT_LT(Rel(TriangleIntegral(a, 0.0, h), want), 1e-13) << a;
  }
  // b = −a: ∫_0^h (e^{a s} − 1)/a ds = h(φ1(ah) − 1)/a.
  const Complex a(0.3, 25);
  EXPECT_LT(Rel(TriangleIntegral(a, -a, h), h * (Phi1(a * h) - 1.0) / a), 1e-14);
}

TEST(OscillatoryIntegrals, TriangleMatchesQuadratureAcrossTheThresholds) {
  // Pairs on both sides of the divided difference's switch (|b h| = 1/4), resonant and not.
  const double h = 0.5;
  for (Complex a : {Complex(0, 6), Complex(-1, 0.2), Complex(0.4, -3)})
    for (Complex b : {Complex(0, 0.49), Complex(0, 0.51), Complex(1e-6, 0), Complex(-2, 7),
                      -a + Complex(0, 1e-3)})
      EXPECT_LT(Rel(TriangleIntegral(a, b, h), TriangleByQuadrature(a, b, h)), 1e-13)
          << a << " " << b;
}

}  // namespace
}  // namespace ltp::internal
