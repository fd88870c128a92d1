#include "ltp/integrate/detail/modal_basis.h"

#include <utility>
#include <vector>

#ifndef LTP_EIGEN_ONLY
#include <lapacke.h>
#endif

#include "ltp/integrate/detail/condition_number.h"

namespace ltp::internal {

// W with dgeev (which balances, transforms back and gives each eigenvector unit norm) or, in the
// sanitizer build, Eigen's pseudo-eigenvectors with each real vector and each complex pair's
// (a, b) scaled to unit norm together (separate scales would make D's 2×2 blocks non-normal).
std::optional<RealEigenbasis> RealEigenDecomposition(const Eigen::MatrixXd& a) {
  if (a.rows() == 0 || a.cols() != a.rows() || !a.allFinite()) return std::nullopt;
  const Eigen::Index n = a.rows();
  RealEigenbasis out;
#ifndef LTP_EIGEN_ONLY
  const auto m = static_cast<lapack_int>(n);
  Eigen::MatrixXd work = a;
  out.w.resize(n, n);
  std::vector<double> re(n), im(n);
  if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', m, work.data(), m, re.data(), im.data(), nullptr, 1,
                    out.w.data(), m) != 0)
    return std::nullopt;
  out.eigenvalues.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) out.eigenvalues(j) = {re[j], im[j]};
#else
  Eigen::EigenSolver<Eigen::MatrixXd> es(a);
  if (es.info() != Eigen::Success) return std::nullopt;
  out.w = es.pseudoEigenvectors();
  out.eigenvalues = es.eigenvalues();
  for (Eigen::Index j = 0; j < n;) {
    const Eigen::Index width = out.eigenvalues(j).imag() != 0 && j + 1 < n ? 2 : 1;
    const double norm = out.w.middleCols(j, width).norm();
    if (norm > 0) out.w.middleCols(j, width) /= norm;
    j += width;
  }
#endif
  if (!out.w.allFinite()) return std::nullopt;
  return out;
}

Eigen::MatrixXcd ComplexEigenvectors(const RealEigenbasis& basis) {
  const Eigen::Index n = basis.w.rows();
  Eigen::MatrixXcd v = basis.w.cast<std::complex<double>>();
  for (Eigen::Index j = 0; j + 1 < n; ++j) {
    if (basis.eigenvalues(j).imag() == 0) continue;
    v.col(j) = basis.w.col(j) + std::complex<double>(0, 1) * basis.w.col(j + 1);
    v.col(j + 1) = v.col(j).conjugate();
    ++j;
  }
  return v;
}

Eigen::MatrixXcd EigenbasisCoefficients(const RealEigenbasis& basis, const Eigen::MatrixXcd& x) {
  const std::complex<double> i(0, 1);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(basis.w);
  Eigen::MatrixXcd c = lu.solve(x.real()).cast<std::complex<double>>();
  c += i * lu.solve(x.imag()).cast<std::complex<double>>();
  for (Eigen::Index j = 0; j + 1 < c.rows(); ++j) {
    if (basis.eigenvalues(j).imag() == 0) continue;
    const Eigen::RowVectorXcd a = c.row(j), b = c.row(j + 1);
    c.row(j) = 0.5 * (a - i * b);
    c.row(j + 1) = 0.5 * (a + i * b);
    ++j;
  }
  return c;
}

std::optional<Eigen::VectorXcd> RealEigenvalues(const Eigen::MatrixXd& a) {
  if (a.rows() == 0 || a.cols() != a.rows() || !a.allFinite()) return std::nullopt;
#ifndef LTP_EIGEN_ONLY
  const auto m = static_cast<lapack_int>(a.rows());
  Eigen::MatrixXd work = a;
  std::vector<double> re(a.rows()), im(a.rows());
  if (LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', m, work.data(), m, re.data(), im.data(), nullptr, 1,
                    nullptr, 1) != 0)
    return std::nullopt;
  Eigen::VectorXcd values(a.rows());
  for (Eigen::Index j = 0; j < a.rows(); ++j) values(j) = {re[j], im[j]};
  return values;
#else
  Eigen::EigenSolver<Eigen::MatrixXd> es(a, /*computeEigenvectors=*/false);
  if (es.info() != Eigen::Success) return std::nullopt;
  return Eigen::VectorXcd(es.eigenvalues());
#endif
}

std::optional<Eigen::MatrixXd> RealModalBasis(const Eigen::MatrixXd& a, double max_condition) {
  std::optional<RealEigenbasis> basis = RealEigenDecomposition(a);
  if (!basis || !(ConditionNumber(basis->w) <= max_condition)) return std::nullopt;
  return std::move(basis->w);
}

}  // namespace ltp::internal
