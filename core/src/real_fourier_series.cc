#include "ltp/core/real_fourier_series.h"

#include <cmath>

namespace ltp {

RealFourierSeries::RealFourierSeries(const FourierMatrix& m) : rows_(m.rows()), cols_(m.cols()) {
  if (rows_ == 0 || cols_ == 0) return;  // nothing to evaluate (a system without inputs)
  // Trailing zero harmonics cost evaluations and change nothing.
  int top = m.max_harmonic();
  while (top > 0 && m[top].isZero(0) && m[-top].isZero(0)) --top;
  harmonics_ = top;
  const Eigen::Index size = static_cast<Eigen::Index>(rows_) * cols_;
  blocks_.resize(static_cast<size_t>(size) * (2 * top + 1));
  Eigen::Map<Eigen::MatrixXd>(blocks_.data(), rows_, cols_) = m[0].real();
  for (int w = 1; w <= top; ++w) {
    double* at = blocks_.data() + size * (2 * w - 1);
    Eigen::Map<Eigen::MatrixXd>(at, rows_, cols_) = m[w].real() + m[-w].real();
    Eigen::Map<Eigen::MatrixXd>(at + size, rows_, cols_) = m[-w].imag() - m[w].imag();
  }
}

void RealFourierSeries::Evaluate(double t, double omega_p, Eigen::Ref<Eigen::MatrixXd> out) const {
  using Block = Eigen::Map<const Eigen::MatrixXd>;
  const Eigen::Index size = static_cast<Eigen::Index>(rows_) * cols_;
  out = Block(blocks_.data(), rows_, cols_);
  if (harmonics_ == 0) return;
  const double c1 = std::cos(omega_p * t), s1 = std::sin(omega_p * t);
  double c = c1, s = s1;
  for (int w = 1; w <= harmonics_; ++w) {
    const double* cw = blocks_.data() + size * (2 * w - 1);
    out.noalias() += c * Block(cw, rows_, cols_) + s * Block(cw + size, rows_, cols_);
    const double next_c = c * c1 - s * s1;
    s = s * c1 + c * s1;
    c = next_c;
  }
}

}  // namespace ltp
