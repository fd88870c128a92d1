#include "line_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/FFT>

namespace ltp::internal {

LineFit FitLines(const Eigen::VectorXd& y, const Eigen::MatrixXd& phases) {
  return LineBasis(phases, Eigen::MatrixXcd()).Fit(y);
}

LineBasis::LineBasis(const Eigen::MatrixXd& phases, const Eigen::MatrixXcd& gains)
    : lines_(phases.cols()), columns_(phases.rows(), 1 + 2 * phases.cols()) {
  columns_.col(0).setOnes();
  for (Eigen::Index l = 0; l < lines_; ++l) {
    // α Re w + β Im w = 2 Re(A w) with w = g e^{jφ} and A = (α − jβ)/2.
    Eigen::ArrayXcd w =
        phases.col(l).array().unaryExpr([](double phi) { return std::polar(1.0, phi); });
    if (gains.size() > 0) w *= gains.col(l).array();
    columns_.col(1 + 2 * l) = w.real();
    columns_.col(2 + 2 * l) = w.imag();
  }
  // Columns scaled to unit norm, so the rank decision compares directions, not sizes.
  scale_ = columns_.colwise().norm().transpose().cwiseMax(1e-300);
  columns_ = columns_ * scale_.cwiseInverse().asDiagonal();
  svd_.compute(columns_, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd_.singularValues();
  const double cut = 1e-9 * s(0);
  while (rank_ < s.size() && s(rank_) > cut) ++rank_;
}

Eigen::VectorXd LineBasis::Coefficients(const Eigen::VectorXd& projected) const {
  // Minimum-norm solution on the determined subspace.
  return svd_.matrixV().leftCols(rank_) *
         (svd_.singularValues().head(rank_).cwiseInverse().asDiagonal() * projected);
}

LineFit LineBasis::Fit(const Eigen::VectorXd& y) const {
  const Eigen::Index n = y.size(), p = 1 + 2 * lines_;
  const Eigen::VectorXd& s = svd_.singularValues();
  const Eigen::MatrixXd& V = svd_.matrixV();
  const Eigen::VectorXd coefficients = Coefficients(svd_.matrixU().leftCols(rank_).transpose() * y);
  // Covariance factors on the determined subspace.
  Eigen::VectorXd factor(p), undetermined(p);
  for (Eigen::Index i = 0; i < p; ++i) {
    factor(i) =
        (V.row(i).head(rank_).array().square() / s.head(rank_).array().square().transpose()).sum() /
        (scale_(i) * scale_(i));
    undetermined(i) = V.row(i).tail(p - rank_).squaredNorm();
  }
  LineFit fit;
  fit.dof = static_cast<long>(n - rank_);
  const double residual = (y - columns_ * coefficients).squaredNorm();
  fit.noise_variance = fit.dof > 0 ? residual / static_cast<double>(fit.dof)
                                   : std::numeric_limits<double>::quiet_NaN();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Eigen::Index l = 0; l < lines_; ++l) {
    const Eigen::Index c = 1 + 2 * l, si = 2 + 2 * l;
    const bool ok = undetermined(c) < 1e-6 && undetermined(si) < 1e-6;
    const double a = coefficients(c) / scale_(c), b = coefficients(si) / scale_(si);
    fit.determined.push_back(ok);
    fit.amplitude.push_back(ok ? std::complex<double>(a, -b) / 2.0 : std::complex<double>(nan, 0));
    fit.variance.push_back(ok ? fit.noise_variance * (factor(c) + factor(si)) / 4 : nan);
  }
  return fit;
}

std::vector<std::vector<std::complex<double>>> LineBasis::Response(
    const std::vector<RowPerturbation>& changes) const {
  std::vector<std::vector<std::complex<double>>> responses;
  for (const RowPerturbation& d : changes) {
    const Eigen::VectorXd change = Coefficients(
        svd_.matrixU().block(d.first, 0, d.values.size(), rank_).transpose() * d.values);
    std::vector<std::complex<double>> response;
    for (Eigen::Index l = 0; l < lines_; ++l)
      response.emplace_back(change(1 + 2 * l) / scale_(1 + 2 * l) / 2,
                            -change(2 + 2 * l) / scale_(2 + 2 * l) / 2);
    responses.push_back(std::move(response));
  }
  return responses;
}

FittedRate FitLineRate(const std::vector<double>& time, const Eigen::VectorXd& y,
                       const Eigen::MatrixXd& base, const std::vector<double>& multiplier,
                       double r0) {
  const Eigen::Index n = y.size(), lines = base.cols(), p = 2 + 2 * lines;
  // Centred time in the derivative column (an offset there only moves the phases' constants,
  // which the amplitudes absorb) keeps it well conditioned.
  const double mid = 0.5 * (time.front() + time.back()), L = time.back() - time.front();
  Eigen::VectorXd t(n), tc(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    t(i) = time[static_cast<size_t>(i)];
    tc(i) = (t(i) - mid) / L;
  }
  const double bin = 2 * std::acos(-1.0) / L;
  FittedRate out{r0, std::numeric_limits<double>::quiet_NaN()};
  Eigen::MatrixXd X(n, p);
  for (int it = 0; it < 50; ++it) {
    X.col(0).setOnes();
    for (Eigen::Index l = 0; l < lines; ++l) {
      const Eigen::ArrayXd phase = base.col(l).array() + multiplier[l] * out.rate * t.array();
      X.col(1 + 2 * l) = phase.cos().matrix();
      X.col(2 + 2 * l) = phase.sin().matrix();
    }
    const Eigen::VectorXd c = X.leftCols(p - 1).colPivHouseholderQr().solve(y);
    X.col(p - 1).setZero();
    for (Eigen::Index l = 0; l < lines; ++l)
      X.col(p - 1).array() +=
          multiplier[l] * tc.array() *
          (-c(1 + 2 * l) * X.col(2 + 2 * l).array() + c(2 + 2 * l) * X.col(1 + 2 * l).array());
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
    if (qr.rank() < p) break;  // no line depends on the rate (all amplitudes 0)
    const Eigen::VectorXd d = qr.solve(y);
    const double delta = std::clamp(d(p - 1) / L, -bin / 4, bin / 4);
    if (!std::isfinite(delta)) break;
    out.rate += delta;
    if (std::abs(delta) <= 1e-15 * std::abs(out.rate)) {
      const double variance = (y - X * d).squaredNorm() / static_cast<double>(n - p);
      const Eigen::MatrixXd inverse = (X.transpose() * X).inverse();
      out.standard_error = std::sqrt(variance * inverse(p - 1, p - 1)) / L;
      break;
    }
  }
  return out;
}

namespace {

// The residual of the least-squares sine at ω.
double SineResidual(const Eigen::VectorXd& t, const Eigen::VectorXd& u, double omega) {
  Eigen::MatrixXd X(t.size(), 3);
  X.col(0).setOnes();
  X.col(1) = (omega * t).array().cos();
  X.col(2) = (omega * t).array().sin();
  return (u - X * X.colPivHouseholderQr().solve(u)).squaredNorm();
}

}  // namespace

double StrongestLine(const std::vector<double>& time, const Eigen::VectorXd& u) {
  const Eigen::Index n = u.size();
  const double L = time.back() - time.front();
  const Eigen::VectorXd centred = u.array() - u.mean();
  Eigen::FFT<double> fft;
  std::vector<double> in(centred.data(), centred.data() + n);
  std::vector<std::complex<double>> out;
  fft.fwd(out, in);
  Eigen::Index best = 1;
  for (Eigen::Index k = 1; 2 * k < n; ++k)
    if (std::abs(out[static_cast<size_t>(k)]) > std::abs(out[static_cast<size_t>(best)])) best = k;
  // Bin k is k cycles over n samples, n steps of L/(n − 1).
  return 2 * std::acos(-1.0) * static_cast<double>(best) * static_cast<double>(n - 1) /
         (static_cast<double>(n) * L);
}

FittedRate FitSineFrequency(const std::vector<double>& time, const Eigen::VectorXd& u,
                            double omega0) {
  const Eigen::Index n = u.size();
  Eigen::VectorXd t(n);
  for (Eigen::Index i = 0; i < n; ++i) t(i) = time[static_cast<size_t>(i)];
  const double bin = 2 * std::acos(-1.0) / (time.back() - time.front());
  double start = omega0, best = std::numeric_limits<double>::infinity();
  for (int k = -16; k <= 16; ++k) {  // ±2 bins in eighths
    const double w = omega0 + k * bin / 8;
    const double r = w > 0 ? SineResidual(t, u, w) : best;
    if (r < best) best = r, start = w;
  }
  return FitLineRate(time, u, Eigen::MatrixXd::Zero(n, 1), {1.0}, start);
}

}  // namespace ltp::internal
