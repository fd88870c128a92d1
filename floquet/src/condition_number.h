// 2-norm condition numbers σmax/σmin from the singular values alone (Eigen's divide-and-conquer
// SVD without U and V: the bidiagonalisation costs what LAPACK's gesdd costs for the 20–200-state
// mode matrices the analyses meet, and it runs under the sanitizers, where OpenBLAS's zgemv
// kernels read past the end of gesdd's arrays).
#pragma once

#include <Eigen/Dense>

namespace ltp::internal {

/// σmax/σmin; +inf for a singular, empty-column or non-finite matrix; 1 for an empty one.
double ConditionNumber(const Eigen::MatrixXd& m);
double ConditionNumber(const Eigen::MatrixXcd& m);

}  // namespace ltp::internal
