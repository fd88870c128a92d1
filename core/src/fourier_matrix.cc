#include "ltp/core/fourier_matrix.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "ltp/core/error.h"

namespace ltp {

FourierMatrix::FourierMatrix(int rows, int cols, int max_harmonic)
    : rows_(rows), cols_(cols), max_harmonic_(max_harmonic) {
  if (rows < 0 || cols < 0 || max_harmonic < 0)
    throw InputError("FourierMatrix: negative size or harmonic count");
  coeffs_.assign(2 * max_harmonic + 1, Eigen::MatrixXcd::Zero(rows, cols));
}

FourierMatrix FourierMatrix::Constant(const Eigen::MatrixXd& m) {
  FourierMatrix f(static_cast<int>(m.rows()), static_cast<int>(m.cols()), 0);
  f.coeffs_[0] = m.cast<std::complex<double>>();
  return f;
}

Eigen::MatrixXcd FourierMatrix::coefficient(int w) const {
  if (std::abs(w) > max_harmonic_) return Eigen::MatrixXcd::Zero(rows_, cols_);
  return coeffs_[w + max_harmonic_];
}

Eigen::MatrixXcd& FourierMatrix::operator[](int w) {
  if (std::abs(w) > max_harmonic_)
    throw InputError("FourierMatrix: harmonic " + std::to_string(w) + " outside ±" +
                     std::to_string(max_harmonic_));
  return coeffs_[w + max_harmonic_];
}

const Eigen::MatrixXcd& FourierMatrix::operator[](int w) const {
  if (std::abs(w) > max_harmonic_)
    throw InputError("FourierMatrix: harmonic " + std::to_string(w) + " outside ±" +
                     std::to_string(max_harmonic_));
  return coeffs_[w + max_harmonic_];
}

void FourierMatrix::SetHarmonic(int w, const Eigen::MatrixXcd& m) {
  if (w < 0) throw InputError("FourierMatrix::SetHarmonic: w must be >= 0");
  if (m.rows() != rows_ || m.cols() != cols_)
    throw InputError("FourierMatrix::SetHarmonic: coefficient has the wrong size");
  (*this)[w] = m;
  if (w == 0) {
    (*this)[0] = m.real().cast<std::complex<double>>();
  } else {
    (*this)[-w] = m.conjugate();
  }
}

void FourierMatrix::Evaluate(double t, double omega_p, Eigen::Ref<Eigen::MatrixXd> out) const {
  // Real part of Σ M_w e^{jwΩt} = M_0 + Σ_{w>0} 2 Re(M_w e^{jwΩt}) for a Hermitian series; we sum
  // both halves explicitly so that a slightly non-Hermitian series still evaluates to its real
  // part.
  out = coeffs_[max_harmonic_].real();
  for (int w = 1; w <= max_harmonic_; ++w) {
    const std::complex<double> e = std::polar(1.0, w * omega_p * t);
    const auto& mp = coeffs_[max_harmonic_ + w];
    const auto& mm = coeffs_[max_harmonic_ - w];
    out.noalias() += (mp.real() + mm.real()) * e.real() - (mp.imag() - mm.imag()) * e.imag();
  }
}

Eigen::MatrixXd FourierMatrix::Evaluate(double t, double omega_p) const {
  Eigen::MatrixXd out(rows_, cols_);
  Evaluate(t, omega_p, out);
  return out;
}

Eigen::MatrixXcd FourierMatrix::BlockToeplitz(int harmonics) const {
  if (harmonics < 0) throw InputError("FourierMatrix::BlockToeplitz: harmonics must be >= 0");
  const int N = harmonics, h = std::min(max_harmonic_, 2 * N);
  Eigen::MatrixXcd t = Eigen::MatrixXcd::Zero((2 * N + 1) * rows_, (2 * N + 1) * cols_);
  if (coeffs_.empty()) return t;
  for (int v = -N; v <= N; ++v)
    for (int u = std::max(-N, v - h); u <= std::min(N, v + h); ++u)
      t.block((v + N) * rows_, (u + N) * cols_, rows_, cols_) = coeffs_[v - u + max_harmonic_];
  return t;
}

double FourierMatrix::HermitianDefect() const {
  double d = coeffs_.empty() ? 0.0 : coeffs_[max_harmonic_].imag().norm();
  for (int w = 1; w <= max_harmonic_; ++w)
    d = std::max(d, (coeffs_[max_harmonic_ + w] - coeffs_[max_harmonic_ - w].conjugate()).norm());
  return d;
}

std::vector<double> FourierMatrix::HarmonicNorms() const {
  std::vector<double> n;
  n.reserve(coeffs_.size());
  for (const auto& c : coeffs_) n.push_back(c.norm());
  return n;
}

}  // namespace ltp
