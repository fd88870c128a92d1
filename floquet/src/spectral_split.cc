#include "spectral_split.h"

#include <lapacke.h>

#include <algorithm>
#include <cmath>

namespace ltp::internal {

RealSchurForm SchurOfMean(const Eigen::MatrixXd& mean) {
  RealSchurForm f;
  const lapack_int n = static_cast<lapack_int>(mean.rows());
  if (n == 0 || !mean.allFinite()) return f;
  f.t = mean;
  f.q.resize(n, n);
  Eigen::VectorXd wr(n), wi(n);
  lapack_int sdim = 0;
  f.ok = LAPACKE_dgees(LAPACK_COL_MAJOR, 'V', 'N', nullptr, n, f.t.data(), n, &sdim, wr.data(),
                       wi.data(), f.q.data(), n) == 0;
  return f;
}

SpectralSplit SplitAtModulus(const RealSchurForm& schur, double cutoff) {
  SpectralSplit s;
  if (!schur.ok) return s;
  const lapack_int n = static_cast<lapack_int>(schur.t.rows());
  // The kept eigenvalues moved to the leading block (a conjugate pair has one modulus, so both
  // of it are selected or neither).
  Eigen::MatrixXd t = schur.t, q = schur.q;
  Eigen::VectorXd wr(n), wi(n);
  for (lapack_int i = 0; i < n; ++i) {  // the eigenvalues of T's 1×1 and 2×2 diagonal blocks
    wr[i] = t(i, i);
    wi[i] = 0;
    if (i + 1 < n && t(i + 1, i) != 0) {
      const double im = std::sqrt(std::abs(t(i + 1, i))) * std::sqrt(std::abs(t(i, i + 1)));
      wr[i + 1] = t(i + 1, i + 1);
      wi[i] = im;
      wi[i + 1] = -im;
      ++i;
    }
  }
  std::vector<lapack_logical> select(n);
  for (lapack_int i = 0; i < n; ++i) select[i] = std::hypot(wr[i], wi[i]) <= cutoff;
  lapack_int k = 0, info = 0;
  double cond = 0, sep = 0;
  // The workspace is given: LAPACKE's own query crashes OpenBLAS's dtrsen for job 'N'.
  const lapack_int lwork = std::max<lapack_int>(1, n * n), liwork = lwork;
  std::vector<double> work(lwork);
  std::vector<lapack_int> iwork(liwork);
  LAPACK_dtrsen("N", "V", select.data(), &n, t.data(), &n, q.data(), &n, wr.data(), wi.data(), &k,
                &cond, &sep, work.data(), &lwork, iwork.data(), &liwork, &info);
  if (info != 0) return s;
  for (lapack_int i = 0; i < n; ++i) (i < k ? s.kept : s.dropped).emplace_back(wr[i], wi[i]);
  // T₁₁X − XT₂₂ = −T₁₂ block-diagonalises T: the left basis is Wᵀ = [I, −X] Qᵀ.
  const lapack_int m = n - k;
  Eigen::MatrixXd x = -t.block(0, k, k, m);
  double scale = 1;
  if (k > 0 && m > 0 &&
      LAPACKE_dtrsyl(LAPACK_COL_MAJOR, 'N', 'N', -1, k, m, t.data(), n, t.data() + k * n + k, n,
                     x.data(), k, &scale) < 0)
    return s;
  if (scale != 1 && scale > 0) x /= scale;  // scale < 1 only to avoid overflow
  s.right = q.leftCols(k);
  s.left = q.leftCols(k) - q.rightCols(m) * x.transpose();
  s.coupling = x.size() ? x.cwiseAbs().maxCoeff() : 0.0;
  s.ok = s.left.allFinite();
  return s;
}

}  // namespace ltp::internal
