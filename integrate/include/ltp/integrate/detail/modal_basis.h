// The real eigenvector basis of a constant matrix, in which the segment grid measures the
// condition of factors made by integrators whose error is a backward error of each step's
// generator (docs/model-sizes.md, "Segments in the mean's modes").
#pragma once

#include <Eigen/Dense>
#include <optional>

namespace ltp::internal {

/// A real matrix's eigenvalues with its real eigenvector basis W, A W = W D: a real eigenvalue's
/// unit eigenvector, a complex pair's v = a + jb (for eigenvalues(j), Im > 0; the conjugate
/// follows) as the columns a, b (LAPACK dgeev, balanced).
struct RealEigenbasis {
  Eigen::VectorXcd eigenvalues;
  Eigen::MatrixXd w;
};
/// Empty when A is not square and finite or the eigensolver fails.
std::optional<RealEigenbasis> RealEigenDecomposition(const Eigen::MatrixXd& a);

/// The complex eigenvectors V of the basis, in its order: a pair's columns a, b become
/// v = a + jb and v̄ = a − jb.
Eigen::MatrixXcd ComplexEigenvectors(const RealEigenbasis& basis);

/// V⁻¹ x without forming V: W⁻¹ x by a real LU, then a pair's rows c_a, c_b become
/// ½(c_a − j c_b) (for v) and ½(c_a + j c_b) (for v̄), since x = c_a a + c_b b.
Eigen::MatrixXcd EigenbasisCoefficients(const RealEigenbasis& basis, const Eigen::MatrixXcd& x);

/// A real matrix's eigenvalues alone (LAPACK dgeev without vectors: at 250 states a tenth of
/// Eigen's complex eigensolver); empty when A is not square and finite or the solver fails.
std::optional<Eigen::VectorXcd> RealEigenvalues(const Eigen::MatrixXd& a);

/// RealEigenDecomposition's W (D real block diagonal); empty when that is, or when W's 2-norm
/// condition exceeds `max_condition` (a (near-)defective A, whose modes' scales are not its
/// factors').
std::optional<Eigen::MatrixXd> RealModalBasis(const Eigen::MatrixXd& a, double max_condition);

}  // namespace ltp::internal
