// 2-norm condition numbers σmax/σmin from the singular values alone (LAPACK's gesvd without U
// and V; Eigen's BDCSVD in the sanitizer build, see condition_number.cc).
#pragma once

#include <Eigen/Dense>

namespace ltp::internal {

/// σmax/σmin; +inf for a singular, empty-column or non-finite matrix; 1 for an empty one.
double ConditionNumber(const Eigen::MatrixXd& m);
double ConditionNumber(const Eigen::MatrixXcd& m);

}  // namespace ltp::internal
