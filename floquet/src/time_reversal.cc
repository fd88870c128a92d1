#include "time_reversal.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace ltp::internal {

namespace {

// How a nonzero entry couples states i and j: alike or opposite in sign.
constexpr std::uint8_t kAlike = 1, kOpposite = 2;

// The blocks X_0 = A_0 − μI, C_1, S_1, …, C_H, S_H read in place from the flat real series,
// optionally seen through the shear S = I + L (L = −μ I in the lower-left block, L² = 0):
// S X S⁻¹ = X + L X − X L − L X L.
struct ShiftedSeries {
  const double* series;
  int n, harmonics;
  double mu;
  bool shear = false;

  double X(int b, int i, int j) const {
    const double x = series[static_cast<size_t>(b) * n * n + i + static_cast<size_t>(j) * n];
    return b == 0 && i == j ? x - mu : x;
  }
  double operator()(int b, int i, int j) const {
    if (!shear) return X(b, i, j);
    const int m = n / 2;
    double x = X(b, i, j);
    if (i >= m) x -= mu * X(b, i - m, j);
    if (j < m) x += mu * X(b, i, j + m);
    if (i >= m && j < m) x -= mu * mu * X(b, i - m, j + m);
    return x;
  }
};

// The signature D = diag(±1) with D X_0 D = −X_0, D C_w D = −C_w, D S_w D = S_w, or nullopt:
// a two-colouring of the graph whose edges are the entries above `zero`.
std::optional<Eigen::VectorXd> Signature(const ShiftedSeries& x, double zero) {
  const int n = x.n;
  std::vector<std::uint8_t> relation(static_cast<size_t>(n) * n, 0);
  for (int b = 0; b < 2 * x.harmonics + 1; ++b) {
    const std::uint8_t kind = b > 0 && b % 2 == 0 ? kAlike : kOpposite;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (!(std::abs(x(b, i, j)) > zero)) continue;
        if (i == j && kind == kOpposite) return std::nullopt;  // e.g. damping
        relation[i + static_cast<size_t>(j) * n] |= kind;
        relation[j + static_cast<size_t>(i) * n] |= kind;
      }
  }
  Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
  std::vector<int> stack;
  for (int s = 0; s < n; ++s) {
    if (r[s] != 0) continue;
    r[s] = 1;
    stack.push_back(s);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (int j = 0; j < n; ++j) {
        const std::uint8_t rel = relation[i + static_cast<size_t>(j) * n];
        if (rel == 0) continue;
        if (rel == (kAlike | kOpposite)) return std::nullopt;
        const double want = rel == kAlike ? r[i] : -r[i];
        if (r[j] == 0) {
          r[j] = want;
          stack.push_back(j);
        } else if (r[j] != want) {
          return std::nullopt;
        }
      }
    }
  }
  return r;
}

// A_0 = [[0, I], [·, ·]] and zero top rows in every harmonic: a second-order system's A.
bool SecondOrderForm(const double* series, int n, int harmonics, double zero) {
  if (n % 2 != 0) return false;
  const int m = n / 2;
  for (int b = 0; b < 2 * harmonics + 1; ++b)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < m; ++i) {
        const double identity = b == 0 && j == i + m ? 1 : 0;
        if (!(std::abs(series[static_cast<size_t>(b) * n * n + i + static_cast<size_t>(j) * n] -
                       identity) <= zero))
          return false;
      }
  return true;
}

// ∫_0^{T/2} tr A(t) dt from the real series: the cosines integrate to 0 over half a period,
// sin wΩt to (1 − cos wπ)/(wΩ).
double HalfPeriodTraceIntegral(const PeriodicSystem& system) {
  int harmonics = 0;
  const double* series = system.RealSeriesA(&harmonics);
  const int n = system.states();
  const auto trace = [&](int b) {
    return Eigen::Map<const Eigen::MatrixXd>(series + static_cast<size_t>(b) * n * n, n, n).trace();
  };
  double integral = trace(0) * system.period() / 2;
  for (int w = 1; w <= harmonics; w += 2) integral += trace(2 * w) * 2 / (w * system.omega());
  return integral;
}

}  // namespace

std::optional<TimeReversal> FindTimeReversal(const PeriodicSystem& system) {
  int harmonics = 0;
  const double* series = system.RealSeriesA(&harmonics);
  const int n = system.states();
  if (series == nullptr || n == 0) return std::nullopt;
  const double mu = Eigen::Map<const Eigen::MatrixXd>(series, n, n).trace() / n;
  double scale = std::abs(mu);
  for (size_t k = 0; k < static_cast<size_t>(2 * harmonics + 1) * n * n; ++k)
    scale = std::max(scale, std::abs(series[k]));
  // Entries this small are round-off of the shift and shear (terms X, μX, μ²X), not couplings.
  const double zero =
      16 * std::numeric_limits<double>::epsilon() * scale * (1 + std::abs(mu)) * (1 + std::abs(mu));
  ShiftedSeries x{series, n, harmonics, mu};
  if (const auto d = Signature(x, zero)) return TimeReversal{d->asDiagonal(), mu};
  // A scalar-damped second-order system: S (A − μI) S⁻¹ has no damping left, R = S⁻¹ D S.
  if (mu == 0 || !SecondOrderForm(series, n, harmonics, zero)) return std::nullopt;
  x.shear = true;
  const auto d = Signature(x, zero);
  if (!d) return std::nullopt;
  const int m = n / 2;
  Eigen::MatrixXd shear = Eigen::MatrixXd::Identity(n, n), unshear = shear;
  shear.bottomLeftCorner(m, m).diagonal().setConstant(-mu);
  unshear.bottomLeftCorner(m, m).diagonal().setConstant(mu);
  return TimeReversal{unshear * d->asDiagonal() * shear, mu};
}

TransitionResult MonodromyFromHalfPeriod(const PeriodicSystem& system, const TimeReversal& reversal,
                                         const IntegratorOptions& integrator) {
  const double T = system.period();
  TransitionResult half = StateTransition(system, 0, 0.5 * T, integrator);
  if (!half.ok) return half;
  const double growth = std::exp(reversal.rate * T);
  // Φh is about as ill-conditioned as the largest multiplier is large, and an inverse formed
  // from it loses that factor of accuracy; it is kept only while that rounding (ε·cond Φh,
  // relative to the largest multiplier) stays below a hundredth of the tolerance.
  const double eps = std::numeric_limits<double>::epsilon(), allowed = 1e-2 * integrator.rel_tol;
  if (half.phi.rows() == 2) {
    // adj Φh / det Φh with the adjugate exact. det Φh as ad − bc makes det Φ(T) exact (a
    // stable pair stays on its circle) but cancels by (|ad| + |bc|) / |ad − bc|; beyond the
    // allowance Liouville's det Φh = exp ∫ tr A instead.
    const Eigen::Matrix2d h = half.phi, r = reversal.involution;
    Eigen::Matrix2d adjugate;
    adjugate << h(1, 1), -h(0, 1), -h(1, 0), h(0, 0);
    const double ad = h(0, 0) * h(1, 1), bc = h(0, 1) * h(1, 0);
    const double det = eps * (std::abs(ad) + std::abs(bc)) <= allowed * std::abs(ad - bc)
                           ? ad - bc
                           : std::exp(HalfPeriodTraceIntegral(system));
    half.phi = growth / det * (r * adjugate * r * h);
    return half;
  }
  // Larger systems: an LU solve within the allowance, else the full period.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(half.phi);
  if (!(eps <= allowed * lu.rcond())) return StateTransition(system, 0, T, integrator);
  const Eigen::MatrixXd& r = reversal.involution;
  half.phi = growth * (r * lu.solve(r * half.phi));
  return half;
}

}  // namespace ltp::internal
