#pragma once
// Gragg–Bulirsch–Stoer extrapolation stepper with Deuflhard's order and step control: the
// algorithm of Boost.Odeint's bulirsch_stoer (same stage sequence 2, 4, 6, …, polynomial
// extrapolation, error norm, step factors and order windows), written for Eigen column vectors
// so that a step allocates nothing. Boost's stepper builds two std::vectors in every try_step
// and that, with its per-step bookkeeping, was 40 % of a small system's integration in a
// stability map (docs/speed-notes.md, "Bulirsch–Stoer without allocation"). The test
// BulirschStoer.TakesBoostsStepsAndValues checks that this class takes Boost's steps.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ltp::internal {

template <class State>
class BulirschStoer {
 public:
  // Boost's k_max: stage counts 2 … 18, extrapolation to order 2·8.
  static constexpr int kMaxStage = 8;

  /// `states`: the length of State (used for dynamic-size vectors only).
  BulirschStoer(double abs_tol, double rel_tol, Eigen::Index states)
      : abs_tol_(abs_tol), rel_tol_(rel_tol) {
    for (int i = 0; i <= kMaxStage; ++i) {
      stages_[i] = 2 * (i + 1);
      cost_[i] = (i == 0 ? 0 : cost_[i - 1]) + stages_[i];
      facmin_[i] = std::pow(kStepFac3, 1.0 / (2 * i + 1));
      for (int k = 0; k < i; ++k) {
        const double r = static_cast<double>(stages_[i]) / stages_[k];
        coeff_[i][k] = 1.0 / (r * r - 1.0);
      }
    }
    if constexpr (State::SizeAtCompileTime == Eigen::Dynamic) {
      for (State* v : {&dxdt_, &out_, &x0_, &x1_, &d_, &err_}) v->resize(states);
      for (State& v : table_) v.resize(states);
    }
    reset();
  }

  /// After an accepted step, e = T_kk − T_k,k−1 at the new t (the controller's error estimate)
  /// and the factor s with T_k−1,k−1 − T_kk = s·e: s e is how far the previous row's best
  /// value (order 2k − 2 instead of 2k) lands from the accepted one. From the last
  /// Aitken–Neville update, T_kk = (1 + c) T_k,k−1 − c T_k−1,k−1 with c = 1/(r² − 1) and
  /// r = n_k / n_0 = k + 1: s = −(1 + c)/c = −r².
  const State& local_error() const { return err_; }
  double previous_row_scale() const {
    const double r = static_cast<double>(stages_[accepted_k_]) / stages_[0];
    return -r * r;
  }

  /// Forget the order and step history (a jump of the right-hand side, a new piece).
  void reset() {
    first_ = true;
    last_rejected_ = false;
    k_opt_ = 4;
  }

  /// One attempt from (t, x) with step dt. On success x and t advance; either way dt becomes the
  /// controller's proposal for the next attempt. Returns whether the step was accepted.
  template <class Rhs>
  bool try_step(Rhs&& rhs, State& x, double& t, double& dt) {
    rhs(x, dxdt_, t);
    if (dt != dt_last_) reset();  // the caller changed the step: start the order search afresh
    bool reject = true;
    std::array<double, kMaxStage + 1> h_opt{}, work{};
    double new_h = dt;
    int k = 0;
    for (; k <= k_opt_ + 1; ++k) {
      if (k == 0) {
        Midpoint(rhs, x, t, dt, stages_[0], out_);
        continue;
      }
      Midpoint(rhs, x, t, dt, stages_[k], table_[k - 1]);
      Extrapolate(k);
      // The error and step size of an order below k_opt − 2 decide nothing (the order window
      // below reads the work of k_opt − 2 … k_opt + 1): Boost computes them anyway, a pow each.
      if (!first_ && k < k_opt_ - 2) continue;
      const double error = ErrorNorm(x, dt);
      h_opt[k] = OptimalStep(dt, error, k);
      work[k] = cost_[k] / h_opt[k];
      if (k == k_opt_ - 1 || first_) {  // converged before the expected order?
        if (error < 1.0) {
          reject = false;
          if (work[k] < kKFac2 * work[k - 1] || k_opt_ <= 2) {
            k_opt_ = std::min(kMaxStage - 1, std::max(2, k + 1));
            new_h = h_opt[k] * (cost_[k + 1] / cost_[k]);
          } else {
            k_opt_ = std::min(kMaxStage - 1, std::max(2, k));
            new_h = h_opt[k];
          }
          break;
        }
        if (ShouldReject(error, k) && !first_) {
          new_h = h_opt[k];
          break;
        }
      }
      if (k == k_opt_) {  // converged at the expected order?
        if (error < 1.0) {
          reject = false;
          if (work[k - 1] < kKFac2 * work[k]) {
            k_opt_ = std::max(2, k_opt_ - 1);
            new_h = h_opt[k_opt_];
          } else if (work[k] < kKFac2 * work[k - 1] && !last_rejected_) {
            k_opt_ = std::min(kMaxStage - 1, k_opt_ + 1);
            new_h = h_opt[k] * (cost_[k_opt_] / cost_[k]);
          } else {
            new_h = h_opt[k_opt_];
          }
          break;
        }
        if (ShouldReject(error, k)) {
          new_h = h_opt[k_opt_];
          break;
        }
      }
      if (k == k_opt_ + 1) {  // the last chance: one order above
        if (error < 1.0) {
          reject = false;
          if (work[k - 2] < kKFac2 * work[k - 1]) k_opt_ = std::max(2, k_opt_ - 1);
          if (work[k] < kKFac2 * work[k_opt_] && !last_rejected_)
            k_opt_ = std::min(kMaxStage - 1, k);
        }
        new_h = h_opt[k_opt_];
        break;
      }
    }
    if (!reject) {
      t += dt;
      x = out_;
      accepted_k_ = k;
    }
    if (!last_rejected_ || new_h < dt) {
      dt_last_ = new_h;
      dt = new_h;
    }
    last_rejected_ = reject;
    first_ = false;
    return !reject;
  }

 private:
  // Modified midpoint rule over [t, t + dt] in `stages` substeps, from x with x'(t) = dxdt_.
  template <class Rhs>
  void Midpoint(Rhs& rhs, const State& x, double t, double dt, int stages, State& out) {
    const double h = dt / stages, h2 = 2 * h;
    double th = t + h;
    x0_ = x;
    x1_ = x + h * dxdt_;
    rhs(x1_, d_, th);
    for (int i = 1; i != stages; ++i) {
      x0_.swap(x1_);
      x1_ = x1_ + h2 * d_;  // x1 ← x0 + 2h·d, x0 ← the old x1
      th += h;
      rhs(x1_, d_, th);
    }
    out = 0.5 * x0_ + 0.5 * x1_ + (0.5 * h) * d_;
  }

  // Aitken–Neville extrapolation to h → 0 of the k + 1 midpoint results in table_ and out_.
  void Extrapolate(int k) {
    for (int j = k - 1; j > 0; --j)
      table_[j - 1] = (1.0 + coeff_[k][j]) * table_[j] - coeff_[k][j] * table_[j - 1];
    out_ = (1.0 + coeff_[k][0]) * table_[0] - coeff_[k][0] * out_;
  }

  // max_i |out − table_0|_i / (abs_tol + rel_tol (|x_i| + |dt| |x'_i|)), Boost's error norm.
  double ErrorNorm(const State& x, double dt) {
    err_ = out_ - table_[0];
    const double adt = std::abs(dt);
    double error = 0;
    for (Eigen::Index i = 0; i < err_.size(); ++i)
      error =
          std::max(error, std::abs(err_[i]) /
                              (abs_tol_ + rel_tol_ * (std::abs(x[i]) + adt * std::abs(dxdt_[i]))));
    return error;
  }

  double OptimalStep(double h, double error, int k) const {
    const double facmin = facmin_[k];
    if (error == 0.0) return h * (1.0 / facmin);
    const double fac = kStepFac2 / std::pow(error / kStepFac1, 1.0 / (2 * k + 1));
    return h * std::max(facmin / kStepFac4, std::min(1.0 / facmin, fac));
  }

  bool ShouldReject(double error, int k) const {
    if (k == k_opt_ - 1) {
      const double d =
          static_cast<double>(stages_[k_opt_] * stages_[k_opt_ + 1] / (stages_[0] * stages_[0]));
      return error > d * d;
    }
    if (k == k_opt_) {
      const double d = static_cast<double>(stages_[k_opt_] / stages_[0]);
      return error > d * d;
    }
    return error > 1.0;
  }

  static constexpr double kStepFac1 = 0.65, kStepFac2 = 0.94, kStepFac3 = 0.02, kStepFac4 = 4.0;
  static constexpr double kKFac2 = 0.9;
  double abs_tol_, rel_tol_;
  std::array<int, kMaxStage + 1> stages_{};
  std::array<double, kMaxStage + 1> cost_{}, facmin_{};
  std::array<std::array<double, kMaxStage + 1>, kMaxStage + 1> coeff_{};
  std::array<State, kMaxStage> table_;
  State dxdt_, out_, x0_, x1_, d_, err_;
  bool first_ = true, last_rejected_ = false;
  int k_opt_ = 4;
  int accepted_k_ = 1;
  double dt_last_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace ltp::internal
