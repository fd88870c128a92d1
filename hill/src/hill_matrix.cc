// The Hill matrix H_N (dense, banded, or as an operator) and the period-doubled series.
#include <complex>
// LAPACKE with std::complex<double> arguments (same layout as Fortran COMPLEX*16).
#define lapack_complex_float std::complex<float>
#define lapack_complex_double std::complex<double>
#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hill_internal.h"
#include "ltp/core/error.h"
#include "ltp/hill/hill.h"

namespace ltp {
namespace hill_internal {

int BlockBandwidth(const FourierMatrix& A, int harmonics) {
  int h = 0;
  for (int w = 1; w <= A.max_harmonic(); ++w)
    if (A[w].norm() > 0 || A[-w].norm() > 0) h = w;
  return std::min(h, 2 * harmonics);
}

double HillNormEstimate(const FourierMatrix& A, double omega, int harmonics) {
  double s = harmonics * omega;
  const int h = std::min(A.max_harmonic(), 2 * harmonics);
  for (int w = -h; w <= h; ++w) s += A[w].norm();
  return std::max(s, 1e-300);
}

Eigen::VectorXcd HillMultiply(const FourierMatrix& A, double omega, int harmonics,
                              const Eigen::VectorXcd& x) {
  const int n = A.rows(), N = harmonics;
  const int h = BlockBandwidth(A, N);
  Eigen::VectorXcd y = Eigen::VectorXcd::Zero(x.size());
  for (int v = -N; v <= N; ++v) {
    auto yv = y.segment((v + N) * n, n);
    for (int u = std::max(-N, v - h); u <= std::min(N, v + h); ++u)
      yv.noalias() += A[v - u] * x.segment((u + N) * n, n);
    yv -= cd(0, v * omega) * x.segment((v + N) * n, n);
  }
  return y;
}

void CheckDenseMemory(int n, int harmonics, double max_bytes) {
  const double size = (2.0 * harmonics + 1) * n;
  const double bytes = size * size * sizeof(cd);
  if (bytes > max_bytes) {
    std::ostringstream s;
    s << "Hill truncation N = " << harmonics << " with n = " << n << " states needs a dense "
      << size << "×" << size << " complex matrix (" << bytes / (1024.0 * 1024 * 1024)
      << " GiB), more than the limit of " << max_bytes / (1024.0 * 1024 * 1024)
      << " GiB; lower the harmonics or use the structured solver";
    throw ResourceError(s.str());
  }
}

BandedShiftInvert::BandedShiftInvert(const FourierMatrix& A, double omega, int harmonics)
    : a_(A), omega_(omega), harmonics_(harmonics), n_(A.rows()) {
  size_ = (2 * harmonics + 1) * n_;
  kl_ = std::min((BlockBandwidth(A, harmonics) + 1) * n_ - 1, size_ - 1);
  ldab_ = 3 * kl_ + 1;  // 2 kl + ku + 1 with ku = kl (zgbtrf needs kl extra rows for fill-in)
  CheckBandMemory(n_, BlockBandwidth(A, harmonics), harmonics);
}

void CheckBandMemory(int n, int block_bandwidth, int harmonics) {
  const double size = (2.0 * harmonics + 1) * n;
  const double kl = std::min((block_bandwidth + 1.0) * n - 1, size - 1);
  const double bytes = (3 * kl + 1) * size * sizeof(cd);
  if (bytes > 2.0 * 1024 * 1024 * 1024) {
    std::ostringstream s;
    s << "Hill truncation N = " << harmonics << " with n = " << n
      << " states needs a band matrix of " << bytes / (1024.0 * 1024 * 1024)
      << " GiB, more than the limit of 2 GiB; lower the harmonics";
    throw ResourceError(s.str());
  }
}

bool BandedShiftInvert::Factor(cd shift) {
  const int N = harmonics_, n = n_, h = BlockBandwidth(a_, N), ku = kl_;
  ab_.assign(static_cast<size_t>(ldab_) * size_, cd(0));
  ipiv_.assign(size_, 0);
  auto at = [&](int i, int j) -> cd& {
    return ab_[kl_ + ku + i - j + static_cast<size_t>(j) * ldab_];
  };
  for (int v = -N; v <= N; ++v)
    for (int u = std::max(-N, v - h); u <= std::min(N, v + h); ++u) {
      const Eigen::MatrixXcd& b = a_[v - u];
      for (int c = 0; c < n; ++c)
        for (int r = 0; r < n; ++r) at((v + N) * n + r, (u + N) * n + c) = b(r, c);
    }
  for (int v = -N; v <= N; ++v)
    for (int r = 0; r < n; ++r) at((v + N) * n + r, (v + N) * n + r) -= cd(0, v * omega_) + shift;
  const lapack_int info =
      LAPACKE_zgbtrf(LAPACK_COL_MAJOR, size_, size_, kl_, ku, ab_.data(), ldab_, ipiv_.data());
  return info == 0;
}

void BandedShiftInvert::Solve(Eigen::Ref<Eigen::VectorXcd> x) const {
  LAPACKE_zgbtrs(LAPACK_COL_MAJOR, 'N', size_, kl_, kl_, 1, ab_.data(), ldab_, ipiv_.data(),
                 x.data(), size_);
}

}  // namespace hill_internal

Eigen::MatrixXcd HillMatrix(const FourierMatrix& A, double omega, int harmonics, double max_bytes) {
  if (harmonics < 0) throw InputError("HillMatrix: harmonics must be >= 0");
  const int n = A.rows(), N = harmonics;
  hill_internal::CheckDenseMemory(n, N, max_bytes);
  Eigen::MatrixXcd H = A.BlockToeplitz(N);
  for (int v = -N; v <= N; ++v)
    H.block((v + N) * n, (v + N) * n, n, n).diagonal().array() -=
        std::complex<double>(0, v * omega);
  return H;
}

}  // namespace ltp
