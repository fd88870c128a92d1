// ExpInto (BLAS products, LAPACK solve) against closed forms: e^{S D S⁻¹} = S e^D S⁻¹ for a
// diagonal D and an orthogonal/unitary S (so the reference is as accurate as e^{d_k}), across
// every Padé degree's range of the 1-norm and into scaling and squaring; and against Eigen's
// MatrixExponential (the same algorithm in Eigen's kernels) on a non-normal matrix.
#include "ltp/integrate/detail/matrix_exponential.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

namespace ltp::internal {
namespace {

using Complex = std::complex<double>;

Eigen::MatrixXcd Unitary(int n, std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::MatrixXcd m(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m(i, j) = Complex(g(rng), g(rng));
  return Eigen::HouseholderQR<Eigen::MatrixXcd>(m).householderQ();
}

// D with eigenvalues of real parts in [−1, 0.2] and imaginary parts up to `scale` (oscillation,
// as in the integrators' steps), scaled so the 1-norm of S D S* sweeps the Padé ranges.
TEST(MatrixExponential, ComplexMatchesTheDiagonalClosedForm) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n : {20, 64, 130})
    for (double scale : {1e-3, 0.1, 0.6, 1.5, 4.0, 40.0, 400.0}) {
      Eigen::VectorXcd d(n);
      for (int k = 0; k < n; ++k) d(k) = scale * Complex(0.6 * u(rng) - 0.4, u(rng)) / 1.5;
      const Eigen::MatrixXcd s = Unitary(n, rng);
      const Eigen::MatrixXcd a = s * d.asDiagonal() * s.adjoint();
      const Eigen::MatrixXcd exact = s * d.array().exp().matrix().asDiagonal() * s.adjoint();
      Eigen::MatrixXcd e(n, n);
      ExpInto(a, e);
      // Scaling and squaring loses about the norm's bits: ε·‖A‖ relative (Higham 2005, §3).
      const double tolerance = 1e-13 * std::max(1.0, scale) * std::sqrt(n);
      EXPECT_LE((e - exact).norm(), tolerance * exact.norm()) << "n = " << n << ", scale " << scale;
    }
}

// A real matrix with rotation blocks [[α, −θ], [θ, α]] (closed form e^α (cos θ, −sin θ; …)) in
// an orthogonal basis.
TEST(MatrixExponential, RealMatchesRotationBlocks) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n : {32, 100})
    for (double scale : {1e-2, 0.3, 2.0, 30.0, 300.0}) {
      Eigen::MatrixXd block = Eigen::MatrixXd::Zero(n, n), exact_block = block;
      for (int k = 0; k + 1 < n; k += 2) {
        const double alpha = scale * (0.3 * u(rng) - 0.2) / 2, theta = scale * u(rng);
        block(k, k) = block(k + 1, k + 1) = alpha;
        block(k, k + 1) = -theta;
        block(k + 1, k) = theta;
        exact_block(k, k) = exact_block(k + 1, k + 1) = std::exp(alpha) * std::cos(theta);
        exact_block(k, k + 1) = -std::exp(alpha) * std::sin(theta);
        exact_block(k + 1, k) = std::exp(alpha) * std::sin(theta);
      }
      Eigen::MatrixXd g(n, n);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) g(i, j) = u(rng);
      const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(g).householderQ();
      const Eigen::MatrixXd a = q * block * q.transpose();
      const Eigen::MatrixXd exact = q * exact_block * q.transpose();
      Eigen::MatrixXd e(n, n);
      ExpInto(a, e);
      const double tolerance = 1e-13 * std::max(1.0, scale) * std::sqrt(n);
      EXPECT_LE((e - exact).norm(), tolerance * exact.norm()) << "n = " << n << ", " << scale;
    }
}

// Non-normal (an upper-triangular shear on top of a random matrix): no closed form, so the
// reference is Eigen's implementation of the same algorithm; the two differ only in the
// rounding of their products and solves.
TEST(MatrixExponential, NonNormalAgreesWithEigen) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double scale : {0.05, 1.0, 8.0}) {
    const int n = 48;
    Eigen::MatrixXd a(n, n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) a(i, j) = scale * (u(rng) + (i < j ? 0.5 : 0)) / std::sqrt(n);
    Eigen::MatrixXd e(n, n);
    ExpInto(a, e);
    const Eigen::MatrixXd reference = a.exp();
    EXPECT_LE((e - reference).norm(), 1e-12 * std::max(1.0, scale) * reference.norm()) << scale;
  }
}

// A stiff second-order form h[0 I; −K −C] (K = Q diag(ω²) Qᵀ, C = Q diag(2ζω) Qᵀ, ω up to
// 600 rad/s, h = 0.2): its 1-norm, about hω², is hundreds of times its spectral radius, which
// is where ExpInto balances before scaling and squaring. Closed form: each mode's damped
// oscillator, e^{αh}[cos βh − (α/β) sin βh, sin βh/β; −(ω²/β) sin βh, cos βh + (α/β) sin βh]
// with α = −ζω, β = ω√(1 − ζ²), carried by Q. Compared block by block (the blocks of e^{hA}
// differ by ω² in size): balanced 4e-13 at most, where scaling and squaring the given matrix
// (14 squarings instead of 6) was 6e-12 — 8.8e-12 in Eigen's kernels, the sanitizers' build,
// which does not balance.
TEST(MatrixExponential, StiffSecondOrderFormMatchesItsOscillators) {
  const int m = 60, n = 2 * m;
  const double h = 0.2;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> log_omega(0, std::log(600.0)), zeta(0.001, 0.2);
  const Eigen::MatrixXd q = Unitary(m, rng).real().householderQr().householderQ();
  Eigen::VectorXd omega(m), z(m);
  for (int k = 0; k < m; ++k) omega(k) = std::exp(log_omega(rng)), z(k) = zeta(rng);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  a.topRightCorner(m, m).setIdentity();
  a.bottomLeftCorner(m, m) = -q * omega.cwiseAbs2().asDiagonal() * q.transpose();
  a.bottomRightCorner(m, m) = -q * (2 * z.cwiseProduct(omega)).asDiagonal() * q.transpose();
  a *= h;
  Eigen::MatrixXd xx(m, m), xv(m, m), vx(m, m), vv(m, m);
  {
    Eigen::VectorXd dxx(m), dxv(m), dvx(m), dvv(m);
    for (int k = 0; k < m; ++k) {
      const double al = -z(k) * omega(k), be = omega(k) * std::sqrt(1 - z(k) * z(k));
      const double e = std::exp(al * h), c = std::cos(be * h), s = std::sin(be * h);
      dxx(k) = e * (c - al / be * s);
      dxv(k) = e * s / be;
      dvx(k) = -e * omega(k) * omega(k) / be * s;
      dvv(k) = e * (c + al / be * s);
    }
    xx = q * dxx.asDiagonal() * q.transpose();
    xv = q * dxv.asDiagonal() * q.transpose();
    vx = q * dvx.asDiagonal() * q.transpose();
    vv = q * dvv.asDiagonal() * q.transpose();
  }
  Eigen::MatrixXd e(n, n);
  ExpInto(a, e);
  auto off = [](const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
    return (got - want).norm() / want.norm();
  };
  const double tol = ExpBalances() ? 2e-12 : 2e-11;
  EXPECT_LT(off(e.topLeftCorner(m, m), xx), tol);
  EXPECT_LT(off(e.topRightCorner(m, m), xv), tol);
  EXPECT_LT(off(e.bottomLeftCorner(m, m), vx), tol);
  EXPECT_LT(off(e.bottomRightCorner(m, m), vv), tol);
}

TEST(MatrixExponential, SmallMatricesAndNonFiniteInput) {
  Eigen::MatrixXd a(2, 2), e(2, 2);
  a << 0, -1, 1, 0;  // a rotation by 1 rad
  ExpInto(a, e);
  EXPECT_NEAR(e(0, 0), std::cos(1.0), 1e-15);
  EXPECT_NEAR(e(1, 0), std::sin(1.0), 1e-15);
  Eigen::MatrixXd big = Eigen::MatrixXd::Identity(40, 40), out(40, 40);
  big(3, 5) = std::numeric_limits<double>::quiet_NaN();
  ExpInto(big, out);
  EXPECT_FALSE(out.allFinite());  // reported as non-finite, not as a wrong finite number
}

}  // namespace
}  // namespace ltp::internal
