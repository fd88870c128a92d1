// The mean's real modal basis and the segment grid that measures factor conditions in it.
#include "ltp/integrate/detail/modal_basis.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_system.h"
#include "ltp/integrate/detail/segment_grid.h"

namespace ltp::internal {
namespace {

// A (a + jb) = λ_j (a + jb) for a complex pair's columns a, b (and A w = λ w for a real one), and
// the eigenvalues alone are the same set: against Eigen's own eigensolver on the same matrix (the
// plain build's are LAPACK's dgeev, an independent implementation; the sanitizer build's are
// Eigen's, so there the decomposition's relation is the check).
TEST(RealEigenDecomposition, PairsAreAPlusJBAndTheEigenvaluesMatchAnotherSolver) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  const Eigen::MatrixXd a = Eigen::MatrixXd::NullaryExpr(30, 30, [&] { return g(rng); });
  const auto basis = RealEigenDecomposition(a);
  ASSERT_TRUE(basis.has_value());
  int pairs = 0;
  for (Eigen::Index j = 0; j < a.rows(); ++j) {
    const std::complex<double> lambda = basis->eigenvalues(j);
    Eigen::VectorXcd v = basis->w.col(j).cast<std::complex<double>>();
    if (lambda.imag() != 0) {
      ASSERT_GT(lambda.imag(), 0) << "the pair's first has Im > 0";
      ASSERT_EQ(basis->eigenvalues(j + 1), std::conj(lambda));
      v += std::complex<double>(0, 1) * basis->w.col(j + 1);
      ++pairs;
    }
    EXPECT_LT((a * v - lambda * v).norm(), 1e-12 * a.norm() * v.norm()) << j;
    EXPECT_EQ(ComplexEigenvectors(*basis).col(j), v) << j;
    if (lambda.imag() != 0) ++j;
  }
  EXPECT_GT(pairs, 3);
  // Coefficients in the complex eigenbasis: V c = x for a complex x.
  const Eigen::MatrixXcd x =
      Eigen::MatrixXcd::NullaryExpr(30, 4, [&] { return std::complex<double>(g(rng), g(rng)); });
  const Eigen::MatrixXcd c = EigenbasisCoefficients(*basis, x);
  EXPECT_LT((ComplexEigenvectors(*basis) * c - x).norm(), 1e-11 * x.norm());
  const auto values = RealEigenvalues(a);
  ASSERT_TRUE(values.has_value());
  const Eigen::VectorXcd reference = Eigen::EigenSolver<Eigen::MatrixXd>(a, false).eigenvalues();
  for (Eigen::Index i = 0; i < reference.size(); ++i) {
    double nearest = INFINITY, nearest_in_basis = INFINITY;
    for (Eigen::Index j = 0; j < values->size(); ++j) {
      nearest = std::min(nearest, std::abs((*values)(j)-reference(i)));
      nearest_in_basis = std::min(nearest_in_basis, std::abs(basis->eigenvalues(j) - reference(i)));
    }
    EXPECT_LT(nearest, 1e-12 * a.norm()) << reference(i);
    EXPECT_LT(nearest_in_basis, 1e-12 * a.norm()) << reference(i);
  }
  EXPECT_FALSE(RealEigenvalues(Eigen::MatrixXd::Constant(2, 2, NAN)).has_value());
  EXPECT_FALSE(RealEigenDecomposition(Eigen::MatrixXd(2, 3)).has_value());
}

// W⁻¹ A W is block diagonal: real eigenvalues in 1 × 1 blocks, complex pairs in 2 × 2 ones.
TEST(RealModalBasis, TakesAIntoRealBlockDiagonalForm) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  const Eigen::MatrixXd a = Eigen::MatrixXd::NullaryExpr(9, 9, [&] { return g(rng); });
  const auto w = RealModalBasis(a, 1e7);
  ASSERT_TRUE(w.has_value());
  const Eigen::MatrixXd d = w->lu().solve(a * *w);
  int pairs = 0;
  for (Eigen::Index j = 0; j < d.cols();) {
    // A 2 × 2 block starts where the subdiagonal entry is not round-off.
    const int width = j + 1 < d.cols() && std::abs(d(j + 1, j)) > 1e-8 * a.norm() ? 2 : 1;
    pairs += width == 2;
    for (Eigen::Index i = 0; i < d.rows(); ++i) {
      if (i < j || i >= j + width) {
        EXPECT_LT(std::abs(d(i, j)), 1e-12 * a.norm()) << i << "," << j;
      }
    }
    j += width;
  }
  EXPECT_GT(pairs, 0);  // a random 9 × 9 has complex pairs: the 2 × 2 case is exercised
  // A Jordan block has no eigenbasis.
  Eigen::Matrix2d jordan;
  jordan << 0.5, 1, 0, 0.5;
  EXPECT_FALSE(RealModalBasis(jordan, 1e7).has_value());
}

// Two oscillators of 1 and 30 000 rad/s mixed by a rotation of their coordinates, decaying at
// 0.02 and 0.5 1/s, over one second: in the states [x; x'] no diagonal scaling balances both
// frequencies at once, so a factor of one second has condition 3.5e4 and the grid splits
// the period; in the modes it is e^{0.48 h}, and one segment is enough.
TEST(SegmentGrid, FactorConditionsInTheMeansModesFollowTheRatesNotTheStates) {
  const double c = std::cos(0.6), s = std::sin(0.6);
  Eigen::Matrix2d rotation;
  rotation << c, -s, s, c;
  const Eigen::Matrix2d stiffness =
      rotation * Eigen::Vector2d(1, 9e8).asDiagonal() * rotation.transpose();
  const Eigen::Matrix2d damping =
      rotation * Eigen::Vector2d(0.04, 1).asDiagonal() * rotation.transpose();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 4);
  a.topRightCorner(2, 2).setIdentity();
  a.bottomLeftCorner(2, 2) = -stiffness;
  a.bottomRightCorner(2, 2) = -damping;
  const PeriodicSystem system = PeriodicSystem::FromFourier(1.0, FourierMatrix::Constant(a));
  SegmentGridOptions o;
  o.integrator.type = IntegratorType::kMagnus6;
  o.integrator.rel_tol = 1e-12;
  const SegmentGrid states = ComputeSegmentGrid(system, o);
  o.modal_basis = RealModalBasis(a, 1e7);
  ASSERT_TRUE(o.modal_basis.has_value());
  const SegmentGrid modes = ComputeSegmentGrid(system, o);
  ASSERT_TRUE(states.ok && modes.ok);
  EXPECT_GT(states.factors.size(), 1u) << states.worst_condition;
  EXPECT_EQ(modes.factors.size(), 1u);
  EXPECT_LT(modes.worst_condition, 1.01 * std::exp(0.48));
  // The one factor is e^{A} (scipy's expm and a 50-digit mpmath expm agree with Eigen's to
  // 3e-12). The states' nine factors are each e^{A h} to 7e-9 (the exponential's own
  // conditioning, ε‖hA‖), but their formed product is off by 2e-2: the non-normality that
  // made the grid split also amplifies the factors' errors in the product.
  const Eigen::MatrixXd exact = a.exp();
  EXPECT_LT((modes.factors[0] - exact).norm(), 1e-11 * exact.norm());
}

}  // namespace
}  // namespace ltp::internal
