#include "condition_number.h"

#include <Eigen/SVD>
#include <limits>

namespace ltp::internal {

namespace {

template <typename Matrix>
double FromSingularValues(const Matrix& m) {
  if (m.size() == 0) return 1;
  if (!m.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::BDCSVD<Matrix> svd(m);  // singular values only
  const Eigen::VectorXd& s = svd.singularValues();
  if (s.size() == 0 || !s.allFinite()) return std::numeric_limits<double>::infinity();
  const double lo = s.minCoeff(), hi = s.maxCoeff();
  return lo > 0 ? hi / lo : std::numeric_limits<double>::infinity();
}

}  // namespace

double ConditionNumber(const Eigen::MatrixXd& m) { return FromSingularValues(m); }
double ConditionNumber(const Eigen::MatrixXcd& m) { return FromSingularValues(m); }

}  // namespace ltp::internal
