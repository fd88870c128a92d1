#include "ltp/integrate/detail/modal_basis.h"

#include <vector>

#ifndef LTP_EIGEN_ONLY
#include <lapacke.h>
#endif

#include "ltp/integrate/detail/condition_number.h"

namespace ltp::internal {

namespace {

// W with dgeev (which balances, transforms back and gives each eigenvector unit norm) or, in the
// sanitizer build, Eigen's pseudo-eigenvectors with each real vector and each complex pair's
// (a, b) scaled to unit norm together (separate scales would make D's 2×2 blocks non-normal).
std::optional<Eigen::MatrixXd> Eigenvectors(const Eigen::MatrixXd& a) {
  const Eigen::Index n = a.rows();
#ifndef LTP_EIGEN_ONLY
  const auto m = static_cast<lapack_int>(n);
  Eigen::MatrixXd work = a, w(n, n);
  std::vector<double> re(n), im(n);
  if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', m, work.data(), m, re.data(), im.data(), nullptr, 1,
                    w.data(), m) != 0)
    return std::nullopt;
  return w;
#else
  Eigen::EigenSolver<Eigen::MatrixXd> es(a);
  if (es.info() != Eigen::Success) return std::nullopt;
  Eigen::MatrixXd w = es.pseudoEigenvectors();
  const Eigen::VectorXcd& lambda = es.eigenvalues();
  for (Eigen::Index j = 0; j < n;) {
    const Eigen::Index width = lambda(j).imag() != 0 && j + 1 < n ? 2 : 1;
    const double norm = w.middleCols(j, width).norm();
    if (norm > 0) w.middleCols(j, width) /= norm;
    j += width;
  }
  return w;
#endif
}

}  // namespace

std::optional<Eigen::MatrixXd> RealModalBasis(const Eigen::MatrixXd& a, double max_condition) {
  if (a.rows() == 0 || a.cols() != a.rows() || !a.allFinite()) return std::nullopt;
  std::optional<Eigen::MatrixXd> w = Eigenvectors(a);
  if (!w || !w->allFinite() || !(ConditionNumber(*w) <= max_condition)) return std::nullopt;
  return w;
}

}  // namespace ltp::internal
