// kTaylor: Taylor-series steps of Φ' = A(t) Φ for systems whose A(t) is a trigonometric
// polynomial (the Fourier form). There every derivative of A at a step's start is exact and
// cheap — harmonic w contributes (wΩ)^j/j! times its cos/sin turned by jπ/2 — so the series of Φ
// follows from the recurrence Φ_{k+1} = Σ_j A_j Φ_{k−j} / (k + 1) without evaluating A anywhere
// else, and one step of order p ≈ −ln(tol) spans what Bulirsch–Stoer covers in many
// (docs/taylor-integrator.md: the order and step rule, and what they cost).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "integrator_internal.h"

namespace ltp::internal {

namespace {

template <int N>
class TaylorSeriesStepper {
 public:
  using Matrix = Eigen::Matrix<double, N, N>;

  TaylorSeriesStepper(const PeriodicSystem& system, const IntegratorOptions& options)
      : n_(system.states()),
        order_(TaylorOrder(options.rel_tol)),
        omega_(system.omega()),
        rel_tol_(options.rel_tol),
        abs_tol_(options.abs_tol) {
    series_ = system.RealSeriesA(&harmonics_);
    a_.assign(static_cast<size_t>(order_) + 1, Matrix::Zero(n_, n_));
    phi_.assign(static_cast<size_t>(order_) + 1, Matrix::Zero(n_, n_));
    a_[0] = Block(0);
    second_order_ = SecondOrderForm();
    constant_damping_ = second_order_ && ConstantLowerRight();
  }

  /// Φ(t1, t0) into `result` (steps and products added); false when a step's series is not
  /// finite (overflow) or the step budget `steps_left` runs out.
  bool Transition(double t0, double t1, TransitionResult& result, long& steps_left) {
    Matrix phi = Matrix::Identity(n_, n_);
    double t = t0;
    while (t < t1) {
      if (steps_left-- <= 0) {
        result.message = "Taylor series: more than max_steps steps";
        return false;
      }
      SeriesOfA(t);
      const double tol = abs_tol_ + rel_tol_ * phi.cwiseAbs().maxCoeff();
      // Steps that cannot reach t1 skip the check for an early end (on n = 2 it costs about a
      // quarter of the step).
      const bool may_end = t1 - t <= full_step_;
      const int order = SeriesOfPhi(phi, tol, may_end ? t1 - t : 0);
      double h = t1 - t;  // reached early: the series' last terms at t1 are within tol
      if (order == order_) {
        full_step_ = StepLength(tol, order);
        h = std::min(h, full_step_);
      }
      if (!(h > 0) || !std::isfinite(h)) {
        result.message = kNotFiniteMessage;
        return false;
      }
      // Horner: Φ(t + h) = Σ_k Φ_k h^k.
      phi = phi_[static_cast<size_t>(order)];
      for (int k = order - 1; k >= 0; --k) phi = phi_[static_cast<size_t>(k)] + h * phi;
      t = h == t1 - t ? t1 : t + h;
      ++result.steps;
      result.rhs_evals += static_cast<long>(order) * (order + 1) / 2;
    }
    result.phi = phi;
    return true;
  }

 private:
  // The lowest order an interval's end may be reached with (fewer terms than this say
  // little about the tail).
  static constexpr int kMinOrder = 4;

  // The order from the tolerance: a step of order p is p²/2 products and, for coefficients
  // decaying like (ωh)^k/k!, spans h ∝ p tol^{1/p}, so the work per unit time ∝ p tol^{−1/p}
  // is least at p = −ln tol (23 at 1e-10). Clamped to where the series stays cheap.
  static int TaylorOrder(double rel_tol) {
    return std::clamp(static_cast<int>(std::ceil(-std::log(rel_tol))), 8, 36);
  }

  Eigen::Map<const Matrix> Block(int b) const {
    return Eigen::Map<const Matrix>(series_ + static_cast<size_t>(b) * n_ * n_, n_, n_);
  }

  // A = [0 I; A₂₁ A₂₂] with every harmonic zero in the upper rows: the upper half of each
  // Φ_{k+1} is the lower half of Φ_k / (k + 1), and only the lower rows need products.
  bool SecondOrderForm() const {
    if (n_ % 2 != 0) return false;
    const int h = n_ / 2;
    const Matrix a0 = Block(0);
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < h; ++i)
        if (a0(i, j) != (j == i + h ? 1.0 : 0.0)) return false;
    for (int b = 1; b <= 2 * harmonics_; ++b)
      if (!Block(b).topRows(h).isZero(0)) return false;
    return true;
  }

  // Second-order form whose harmonics leave A₂₂ alone (constant damping, e.g. Mathieu, the
  // Jeffcott rotor): for j ≥ 1 lower(A_j) Φ = A₂₁,j · upper(Φ), half the products.
  bool ConstantLowerRight() const {
    const int h = n_ / 2;
    for (int b = 1; b <= 2 * harmonics_; ++b)
      if (!Block(b).bottomRightCorner(h, h).isZero(0)) return false;
    return true;
  }

  // A_j = A^(j)(t)/j!, j = 0 … p: the mean block A₀ (j = 0 only) plus every harmonic's j-th
  // derivative.
  void SeriesOfA(double t) {
    a_[0] = Block(0);
    for (int j = 1; j <= order_; ++j) a_[static_cast<size_t>(j)].setZero();
    if (harmonics_ == 0) return;
    const double c1 = std::cos(omega_ * t), s1 = std::sin(omega_ * t);
    double c = c1, s = s1;
    for (int w = 1; w <= harmonics_; ++w) {
      const auto cw = Block(2 * w - 1), sw = Block(2 * w);
      double scale = 1;       // (wΩ)^j / j!
      double cj = c, sj = s;  // cos and sin of wΩt + jπ/2
      for (int j = 0; j <= order_; ++j) {
        a_[static_cast<size_t>(j)] += (scale * cj) * cw + (scale * sj) * sw;
        const double turned = -sj;
        sj = cj;
        cj = turned;
        scale *= w * omega_ / (j + 1);
      }
      const double next_c = c * c1 - s * s1;
      s = s * c1 + c * s1;
      c = next_c;
    }
  }

  // Φ_0 = Φ, Φ_{k+1} = Σ_{j ≤ k} A_j Φ_{k−j} / (k + 1), up to the order; returns the order
  // computed. With left > 0, stops early when the series already reaches the end of the
  // interval, `left` ahead, within the tolerance — the last step of an interval, short
  // segments.
  int SeriesOfPhi(const Matrix& phi, double tol, double left) {
    phi_[0] = phi;
    double power = 1;                                            // left^(k+1)
    double last_term = std::numeric_limits<double>::infinity();  // ‖Φ_k‖ left^k
    for (int k = 0; k < order_; ++k) {
      Matrix& next = phi_[static_cast<size_t>(k) + 1];
      const double inv = 1.0 / (k + 1);
      if (second_order_) {
        SecondOrderTerm(k, inv, next);
      } else {
        next.noalias() = a_[0] * phi_[static_cast<size_t>(k)];
        for (int j = 1; j <= k; ++j)
          next.noalias() += a_[static_cast<size_t>(j)] * phi_[static_cast<size_t>(k - j)];
        next *= inv;
      }
      if (left == 0) continue;
      power *= left;
      const double term = phi_[static_cast<size_t>(k) + 1].cwiseAbs().maxCoeff() * power;
      if (k + 1 >= kMinOrder && term <= tol && last_term <= tol) return k + 1;
      last_term = term;
    }
    return order_;
  }

  // Φ_{k+1} = (1/(k+1)) [Φ_k's lower half; Σ_j lower(A_j) Φ_{k−j}]: fixed-size halves for
  // fixed N (a dynamic block would send the tiny products through Eigen's general kernel).
  void SecondOrderTerm(int k, double inv, Matrix& next) const {
    if constexpr (N != Eigen::Dynamic && N % 2 == 0) {
      constexpr int h = N / 2;
      Eigen::Matrix<double, h, N> lower =
          a_[0].template bottomRows<h>() * phi_[static_cast<size_t>(k)];
      if (constant_damping_) {
        for (int j = 1; j <= k; ++j)
          lower.noalias() += a_[static_cast<size_t>(j)].template bottomLeftCorner<h, h>() *
                             phi_[static_cast<size_t>(k - j)].template topRows<h>();
      } else {
        for (int j = 1; j <= k; ++j)
          lower.noalias() += a_[static_cast<size_t>(j)].template bottomRows<h>() *
                             phi_[static_cast<size_t>(k - j)];
      }
      next.template bottomRows<h>() = inv * lower;
      next.template topRows<h>() = inv * phi_[static_cast<size_t>(k)].template bottomRows<h>();
    } else {
      const int h = n_ / 2;
      auto lower = next.bottomRows(h);
      lower.noalias() = a_[0].bottomRows(h) * phi_[static_cast<size_t>(k)];
      for (int j = 1; j <= k; ++j)
        lower.noalias() +=
            a_[static_cast<size_t>(j)].bottomRows(h) * phi_[static_cast<size_t>(k - j)];
      lower *= inv;
      next.topRows(h) = inv * phi_[static_cast<size_t>(k)].bottomRows(h);
    }
  }

  // The longest h whose last two terms ‖Φ_k‖ h^k (k = p − 1, p) are within `tol` (the
  // tolerance at Φ's size): two terms, because one coefficient alone can vanish by symmetry
  // (Jorba and Zou 2005).
  double StepLength(double tol, int order) const {
    double h = std::numeric_limits<double>::infinity();
    for (int k : {order - 1, order}) {
      const double size = phi_[static_cast<size_t>(k)].cwiseAbs().maxCoeff();
      if (!std::isfinite(size)) return std::numeric_limits<double>::quiet_NaN();
      if (size > 0) h = std::min(h, std::pow(tol / size, 1.0 / k));
    }
    return h;
  }

  int n_;
  int order_;
  double omega_, rel_tol_, abs_tol_;
  const double* series_ = nullptr;
  int harmonics_ = 0;
  bool second_order_ = false;
  bool constant_damping_ = false;  // second order, harmonics only in A₂₁
  std::vector<Matrix> a_, phi_;    // the series of A(t) and of Φ at the step's start
  // The last step taken at the full order: a shorter interval end may be reached early.
  double full_step_ = std::numeric_limits<double>::infinity();
};

template <int N>
std::vector<TransitionResult> RunTaylor(const PeriodicSystem& system,
                                        const std::vector<double>& times,
                                        const IntegratorOptions& options) {
  TaylorSeriesStepper<N> stepper(system, options);
  std::vector<TransitionResult> results;
  long steps_left = options.max_steps;
  for (size_t i = 0; i + 1 < times.size(); ++i) {
    TransitionResult r;
    r.ok = stepper.Transition(times[i], times[i + 1], r, steps_left);
    if (r.ok && !r.phi.allFinite()) {
      r.ok = false;
      r.message = kNotFiniteMessage;
    }
    results.push_back(std::move(r));
    if (!results.back().ok) break;
  }
  return results;
}

}  // namespace

std::vector<TransitionResult> TaylorTransitions(const PeriodicSystem& system,
                                                const std::vector<double>& times,
                                                const IntegratorOptions& options) {
  switch (system.states()) {
    case 2:
      return RunTaylor<2>(system, times, options);
    case 4:
      return RunTaylor<4>(system, times, options);
    default:
      return RunTaylor<Eigen::Dynamic>(system, times, options);
  }
}

}  // namespace ltp::internal
