#include "truncation_tail.h"

#include <cmath>
#include <limits>

#include "ltp/core/exponent_match.h"
#include "ltp/core/fourier_fit.h"

namespace ltp::internal {

std::vector<double> TruncationTail(const PeriodicSystem& system, const Eigen::MatrixXd& mean,
                                   double cutoff,
                                   const std::vector<std::complex<double>>& exponents) {
  using cd = std::complex<double>;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> tail(exponents.size(), inf);
  const int n = system.states();
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(mean);
  if (eig.info() != Eigen::Success) return tail;
  const Eigen::MatrixXcd v = eig.eigenvectors();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(v);
  const Eigen::MatrixXcd vinv = lu.inverse();
  if (!vinv.allFinite()) return tail;
  const Eigen::VectorXcd lambda = eig.eigenvalues();
  std::vector<int> slow, fast;
  for (int i = 0; i < n; ++i) (std::abs(lambda[i]) <= cutoff ? slow : fast).push_back(i);
  if (fast.empty()) return std::vector<double>(exponents.size(), 0.0);
  FourierMatrix harmonics;
  if (const FourierMatrix* fa = system.fourier_A()) {
    harmonics = *fa;
  } else {
    FourierFitOptions o;
    o.tol = 1e-8;
    o.max_samples = 128;
    harmonics = FitFourier([&](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalA(t, out); },
                           n, n, system.period(), o)
                    .series;
  }
  const double omega = system.omega();
  Eigen::MatrixXcd vs(n, slow.size()), vf(n, fast.size()), ws(slow.size(), n), wf(fast.size(), n);
  for (size_t j = 0; j < slow.size(); ++j) {
    vs.col(j) = v.col(slow[j]);
    ws.row(j) = vinv.row(slow[j]);
  }
  for (size_t j = 0; j < fast.size(); ++j) {
    vf.col(j) = v.col(fast[j]);
    wf.row(j) = vinv.row(fast[j]);
  }
  // δλ for every slow mode of Ā; each exponent then takes its nearest one (modulo jΩp).
  Eigen::VectorXcd delta = Eigen::VectorXcd::Zero(slow.size());
  for (int m = 1; m <= harmonics.max_harmonic(); ++m)
    for (int sign : {1, -1}) {
      const int w = sign * m;
      const Eigen::MatrixXcd to_fast = wf * harmonics[w] * vs;     // Q_w[f, i]
      const Eigen::MatrixXcd from_fast = ws * harmonics[-w] * vf;  // Q_{−w}[i, f]
      for (size_t i = 0; i < slow.size(); ++i)
        for (size_t f = 0; f < fast.size(); ++f) {
          const cd gap = lambda[slow[i]] + cd(0, w * omega) - lambda[fast[f]];
          const cd product = from_fast(i, f) * to_fast(f, i);
          if (std::abs(product) == 0) continue;
          delta[i] += std::abs(gap) > 0 ? product / gap : cd(inf, 0);
        }
    }
  std::vector<cd> slow_values;
  for (int i : slow) slow_values.push_back(lambda[i]);
  const std::vector<int> nearest = MatchExponentIndices(exponents, slow_values, omega);
  for (size_t k = 0; k < exponents.size(); ++k) {
    if (nearest[k] >= 0) {
      tail[k] = std::abs(delta[nearest[k]]);
      if (!std::isfinite(tail[k])) tail[k] = inf;
    }
  }
  return tail;
}

}  // namespace ltp::internal
