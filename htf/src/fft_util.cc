#include "fft_util.h"

#include <unsupported/Eigen/FFT>

namespace ltp::internal {

std::vector<Eigen::MatrixXcd> SampledFourier(const std::vector<Eigen::MatrixXcd>& samples) {
  const int S = static_cast<int>(samples.size());
  const int H = S / 2 - 1;
  if (S == 0) return {};
  const Eigen::Index rows = samples[0].rows(), cols = samples[0].cols();
  std::vector<Eigen::MatrixXcd> coef(2 * H + 1, Eigen::MatrixXcd::Zero(rows, cols));
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(S), out(S);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) {
      for (int s = 0; s < S; ++s) in[s] = samples[s](i, j);
      fft.fwd(out, in);  // out[k] = Σ_s in[s] e^{−2πj ks/S}
      for (int v = -H; v <= H; ++v) coef[v + H](i, j) = out[(v + S) % S] / double(S);
    }
  return coef;
}

double UpperHalfRatio(const std::vector<Eigen::MatrixXcd>& coef) {
  const int H = static_cast<int>(coef.size()) / 2;
  double all = 0, upper = 0;
  for (int v = -H; v <= H; ++v) {
    const double norm = coef[v + H].norm();
    all = std::max(all, norm);
    if (2 * std::abs(v) > H) upper = std::max(upper, norm);
  }
  return all > 0 ? upper / all : 0.0;
}

int NextPowerOfTwo(int x) {
  int p = 1;
  while (p < x) p *= 2;
  return p;
}

}  // namespace ltp::internal
