// 2-norm condition numbers σmax/σmin from the singular values alone (LAPACK gesdd, JOBZ = 'N'):
// several times faster than a Jacobi SVD for the 20–60-state matrices the analyses meet.
#pragma once

#include <Eigen/Dense>

namespace ltp::internal {

/// σmax/σmin; +inf for a singular, empty-column or non-finite matrix; 1 for an empty one.
double ConditionNumber(const Eigen::MatrixXd& m);
double ConditionNumber(const Eigen::MatrixXcd& m);

}  // namespace ltp::internal
