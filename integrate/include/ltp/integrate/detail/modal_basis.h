// The real eigenvector basis of a constant matrix, in which the segment grid measures the
// condition of factors made by integrators whose error is a backward error of each step's
// generator (docs/model-sizes.md, "Segments in the mean's modes").
#pragma once

#include <Eigen/Dense>
#include <optional>

namespace ltp::internal {

/// W with A W = W D, D real block diagonal (LAPACK dgeev: a real eigenvalue's unit eigenvector,
/// a complex pair's vector v = a ± jb as the columns a, b); empty when A is not finite, LAPACK
/// fails, or W's 2-norm condition exceeds `max_condition` (a (near-)defective A, whose modes'
/// scales are not its factors').
std::optional<Eigen::MatrixXd> RealModalBasis(const Eigen::MatrixXd& a, double max_condition);

}  // namespace ltp::internal
