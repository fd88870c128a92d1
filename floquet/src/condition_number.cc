#include "condition_number.h"

#include <lapacke.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace ltp::internal {

namespace {

double FromSingularValues(const std::vector<double>& s, lapack_int info) {
  if (info != 0 || s.empty()) return std::numeric_limits<double>::infinity();
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  return *lo > 0 ? *hi / *lo : std::numeric_limits<double>::infinity();
}

}  // namespace

double ConditionNumber(const Eigen::MatrixXd& m) {
  if (m.size() == 0) return 1;
  if (!m.allFinite()) return std::numeric_limits<double>::infinity();
  Eigen::MatrixXd a = m;  // gesdd overwrites its argument
  const lapack_int rows = static_cast<lapack_int>(a.rows()),
                   cols = static_cast<lapack_int>(a.cols());
  std::vector<double> s(static_cast<size_t>(std::min(rows, cols)));
  double unused = 0;
  const lapack_int info = LAPACKE_dgesdd(LAPACK_COL_MAJOR, 'N', rows, cols, a.data(), rows,
                                         s.data(), &unused, 1, &unused, 1);
  return FromSingularValues(s, info);
}

double ConditionNumber(const Eigen::MatrixXcd& m) {
  if (m.size() == 0) return 1;
  if (!m.allFinite()) return std::numeric_limits<double>::infinity();
  Eigen::MatrixXcd a = m;
  const lapack_int rows = static_cast<lapack_int>(a.rows()),
                   cols = static_cast<lapack_int>(a.cols());
  std::vector<double> s(static_cast<size_t>(std::min(rows, cols)));
  lapack_complex_double unused{};
  const lapack_int info = LAPACKE_zgesdd(LAPACK_COL_MAJOR, 'N', rows, cols,
                                         reinterpret_cast<lapack_complex_double*>(a.data()), rows,
                                         s.data(), &unused, 1, &unused, 1);
  return FromSingularValues(s, info);
}

}  // namespace ltp::internal
