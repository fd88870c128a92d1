#include "shifted_hessenberg.h"

#include <lapacke.h>

#include <algorithm>
#include <complex>
#include <vector>

namespace ltp::internal {

namespace {
using cd = std::complex<double>;
lapack_complex_double* Lapack(cd* p) { return reinterpret_cast<lapack_complex_double*>(p); }
}  // namespace

ShiftedHessenbergSolver::ShiftedHessenbergSolver(Eigen::MatrixXcd h, const Eigen::MatrixXcd& b,
                                                 const Eigen::MatrixXcd& g) {
  const lapack_int n = static_cast<lapack_int>(h.rows());
  if (n == 0 || h.cols() != n || b.rows() != n || g.cols() != n) return;
  // Scaling only ('S'): no permutation, so the reduction spans all of H (ilo = 1, ihi = n).
  lapack_int ilo = 1, ihi = n;
  Eigen::VectorXd scale(n);
  if (LAPACKE_zgebal(LAPACK_COL_MAJOR, 'S', n, Lapack(h.data()), n, &ilo, &ihi, scale.data()) != 0)
    return;
  std::vector<cd> tau(static_cast<size_t>(std::max<lapack_int>(n - 1, 1)));
  if (LAPACKE_zgehrd(LAPACK_COL_MAJOR, n, ilo, ihi, Lapack(h.data()), n, Lapack(tau.data())) != 0)
    return;
  qb_ = scale.cwiseInverse().asDiagonal() * b;
  gq_ = g * scale.asDiagonal();
  const lapack_int m = static_cast<lapack_int>(b.cols()), r = static_cast<lapack_int>(g.rows());
  if (m > 0 && LAPACKE_zunmhr(LAPACK_COL_MAJOR, 'L', 'C', n, m, ilo, ihi, Lapack(h.data()), n,
                              Lapack(tau.data()), Lapack(qb_.data()), n) != 0)
    return;
  if (r > 0 && LAPACKE_zunmhr(LAPACK_COL_MAJOR, 'R', 'N', r, n, ilo, ihi, Lapack(h.data()), n,
                              Lapack(tau.data()), Lapack(gq_.data()), r) != 0)
    return;
  hessenberg_ = h;  // by rows; below the subdiagonal zgehrd left reflectors, never read
  ok_ = true;
}

bool ShiftedHessenbergSolver::Solve(cd s, int first, int count, Eigen::MatrixXcd& out) const {
  if (!ok_) return false;
  const int n = size(), m = static_cast<int>(qb_.cols());
  const cd shift = s;
  // Forward elimination keeps one working row w: at step k it is row k of the partly reduced
  // matrix. Only w and row k + 1 of jωI + 𝐻 have an entry in column k; the larger one there is
  // the pivot and becomes row k of U, the other minus l × pivot the next w. One pass per step
  // reads the row of 𝐻 and writes the row of U; w stays in cache.
  thread_local std::vector<cd> u, ub, work, wb;
  u.resize(static_cast<size_t>(n) * n);
  ub.resize(static_cast<size_t>(n) * m);
  work.assign(hessenberg_.row(0).data(), hessenberg_.row(0).data() + n);
  work[0] += shift;
  wb.assign(m, cd(0));
  for (int j = 0; j < m; ++j) wb[j] = qb_(0, j);
  for (int k = 0; k + 1 < n; ++k) {
    const cd* h = hessenberg_.row(k + 1).data();
    const cd below = h[k];
    const bool swap = std::abs(below) > std::abs(work[k]);
    const cd pivot = swap ? below : work[k];
    if (pivot == cd(0)) return false;
    const cd l = (swap ? work[k] : below) / pivot;
    cd* urow = u.data() + static_cast<size_t>(k) * n;
    urow[k] = pivot;
    // Column k + 1 (where row k + 1 carries the shift) first, then the rest in real
    // arithmetic: std::complex products carry NaN checks that keep the loop scalar.
    {
      const cd row = h[k + 1] + shift, wk = work[k + 1];
      urow[k + 1] = swap ? row : wk;
      work[k + 1] = swap ? wk - l * row : row - l * wk;
    }
    const double lr = l.real(), li = l.imag();
    auto* w = reinterpret_cast<double*>(work.data());
    auto* ur = reinterpret_cast<double*>(urow);
    const auto* hr = reinterpret_cast<const double*>(h);
    if (swap) {  // pivot = row k + 1, new w = w − l·row
      for (int c = 2 * (k + 2); c < 2 * n; c += 2) {
        const double pr = hr[c], pi = hr[c + 1];
        ur[c] = pr;
        ur[c + 1] = pi;
        w[c] -= lr * pr - li * pi;
        w[c + 1] -= lr * pi + li * pr;
      }
    } else {  // pivot = w, new w = row − l·w
      for (int c = 2 * (k + 2); c < 2 * n; c += 2) {
        const double pr = w[c], pi = w[c + 1];
        ur[c] = pr;
        ur[c + 1] = pi;
        w[c] = hr[c] - (lr * pr - li * pi);
        w[c + 1] = hr[c + 1] - (lr * pi + li * pr);
      }
    }
    for (int j = 0; j < m; ++j) {
      const cd row_b = qb_(k + 1, j);
      const cd pb = swap ? row_b : wb[j], ob = swap ? wb[j] : row_b;
      ub[static_cast<size_t>(k) * m + j] = pb;
      wb[j] = ob - l * pb;
    }
  }
  u[static_cast<size_t>(n - 1) * n + n - 1] = work[n - 1];
  for (int j = 0; j < m; ++j) ub[static_cast<size_t>(n - 1) * m + j] = wb[j];
  // Back substitution on U, row by row (contiguous).
  Eigen::MatrixXcd y(n, m);
  for (int k = n - 1; k >= 0; --k) {
    const cd* urow = u.data() + static_cast<size_t>(k) * n;
    if (urow[k] == cd(0)) return false;
    const auto* ur = reinterpret_cast<const double*>(urow);
    for (int j = 0; j < m; ++j) {
      const auto* yr = reinterpret_cast<const double*>(y.col(j).data());
      // Four partial sums: one chain of dependent additions would bound the loop by latency.
      double sr[4] = {0, 0, 0, 0}, si[4] = {0, 0, 0, 0};
      int c = k + 1;
      for (; c + 3 < n; c += 4)
        for (int q = 0; q < 4; ++q) {
          const int e = 2 * (c + q);
          sr[q] += ur[e] * yr[e] - ur[e + 1] * yr[e + 1];
          si[q] += ur[e] * yr[e + 1] + ur[e + 1] * yr[e];
        }
      for (; c < n; ++c) {
        sr[0] += ur[2 * c] * yr[2 * c] - ur[2 * c + 1] * yr[2 * c + 1];
        si[0] += ur[2 * c] * yr[2 * c + 1] + ur[2 * c + 1] * yr[2 * c];
      }
      const cd dot((sr[0] + sr[1]) + (sr[2] + sr[3]), (si[0] + si[1]) + (si[2] + si[3]));
      y(k, j) = (ub[static_cast<size_t>(k) * m + j] - dot) / urow[k];
    }
  }
  // A few rows against a few columns: a plain product (a BLAS call costs more than it does).
  out.noalias() = gq_.middleRows(first, count).lazyProduct(y);
  return true;
}

}  // namespace ltp::internal
