// Diagonal balancing of a periodic system's states (state_balancing.h).
#include "ltp/integrate/detail/state_balancing.h"

#include <lapacke.h>

#include <cmath>

namespace ltp::internal {

namespace {

template <class Matrix>
double BalancedFrobenius(const Matrix& x, const Eigen::VectorXd& scale) {
  double sum = 0;
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    for (Eigen::Index i = 0; i < x.rows(); ++i) sum += std::norm(x(i, j) * (scale[j] / scale[i]));
  return std::sqrt(sum);
}

}  // namespace

Eigen::MatrixXd MagnitudeOfA(const PeriodicSystem& system) {
  const int n = system.states();
  Eigen::MatrixXd magnitude = Eigen::MatrixXd::Zero(n, n);
  if (const FourierMatrix* fa = system.fourier_A()) {
    for (int w = -fa->max_harmonic(); w <= fa->max_harmonic(); ++w)
      magnitude += (*fa)[w].cwiseAbs();
    return magnitude;
  }
  constexpr int kSamples = 16;
  Eigen::MatrixXd a(n, n);
  for (int s = 0; s < kSamples; ++s) {
    system.EvalA((s + 0.5) * system.period() / kSamples, a);
    magnitude += a.cwiseAbs();
  }
  return magnitude;
}

Eigen::VectorXd BalancingScales(Eigen::MatrixXd magnitude) {
  const int n = static_cast<int>(magnitude.rows());
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  if (n == 0 || !magnitude.allFinite()) return scale;
  lapack_int ilo = 0, ihi = 0;
  if (LAPACKE_dgebal(LAPACK_COL_MAJOR, 'S', n, magnitude.data(), n, &ilo, &ihi, scale.data()) != 0)
    return Eigen::VectorXd::Ones(n);
  return scale;
}

double BalancedNorm(const Eigen::MatrixXd& x, const Eigen::VectorXd& scale) {
  return BalancedFrobenius(x, scale);
}

double BalancedNorm(const Eigen::MatrixXcd& x, const Eigen::VectorXd& scale) {
  return BalancedFrobenius(x, scale);
}

Eigen::VectorXd StateBalancing(const PeriodicSystem& system) {
  if (system.states() == 0) return {};
  const Eigen::VectorXd scale = BalancingScales(MagnitudeOfA(system));
  if (!(scale.maxCoeff() > kBalanceSpread * scale.minCoeff())) return {};
  return scale;
}

}  // namespace ltp::internal
