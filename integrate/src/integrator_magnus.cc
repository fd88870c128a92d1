// Fixed-step exponential integrators: Φ ← exp(Ω_k) Φ per step, with Ω_k from
//   kMagnus4: 2 Gauss–Legendre nodes, 4th order;
//   kMagnus6: 3 Gauss–Legendre nodes, 6th order;
//   kExpm:    A held at the step midpoint (exponential midpoint rule, 2nd order) — or, for a
//             piecewise-constant system, one exact exp(A_k Δt_k) per held piece.
// Magnus methods are exact for constant A and stay stable for stiff A (the exponential
// absorbs the stiffness), at the price of one n×n expm per step.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "integrator_internal.h"
#include "ltp/integrate/detail/matrix_exponential.h"
#include "ltp/integrate/detail/matrix_product.h"

namespace ltp::internal {

long StepsOnPiece(int steps_per_period, double length, double period) {
  // The relative slack keeps a whole number of steps from rounding up to one more.
  const double exact = steps_per_period * (length / period);
  return std::max(1L, static_cast<long>(std::ceil(exact * (1 - 1e-12))));
}

namespace {

// exp(Ω) of the last few generators seen by this thread. A held-sample system has a handful
// of distinct matrices, and its segment grid, error-estimate rerun and mode samples cut the
// period into pieces of a few distinct lengths, so the same h·A_k recurs across the many
// transitions of one analysis; so does h·Ā for an A(t) constant to round-off (a sampled
// isotropic rotor in multi-blade coordinates: 250 states, 1 000 exponentials of ~10 products
// each were 40 % of the analysis). Each exponential is ~20 n³ flops, a comparison n².
// Exact to round-off: a generator within kSameGenerator·max|Ω| of a kept one, entry by entry,
// has an exponential closer to the kept one than scaling and squaring's own rounding, about
// ε‖Ω‖ relative (Higham 2005).
constexpr double kSameGenerator = 4 * std::numeric_limits<double>::epsilon();

bool SameGenerator(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tolerance) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (!(std::abs(a.data()[k] - b.data()[k]) <= tolerance)) return false;
  return true;
}

class ExponentialMemo {
 public:
  const Eigen::MatrixXd& Exp(const Eigen::MatrixXd& omega) {
    const double tolerance = kSameGenerator * omega.cwiseAbs().maxCoeff();
    for (const Entry& e : entries_)
      if (SameGenerator(omega, e.omega, tolerance)) return e.exp;
    Entry& e = entries_[next_];
    next_ = (next_ + 1) % entries_.size();
    e.omega = omega;
    e.exp.resize(omega.rows(), omega.cols());
    ExpInto(omega, e.exp);
    return e.exp;
  }

 private:
  struct Entry {
    Eigen::MatrixXd omega, exp;
  };
  std::array<Entry, 16> entries_;
  size_t next_ = 0;
};

// Larger generators are not kept (16 entries of 2 n² doubles: 10 MB per thread at n = 256).
constexpr int kMemoStates = 256;

// e^Ω: from this thread's memo up to kMemoStates states, else formed into `scratch`.
const Eigen::MatrixXd& Exponential(const Eigen::MatrixXd& omega, Eigen::MatrixXd& scratch) {
  if (omega.rows() <= kMemoStates) {
    thread_local ExponentialMemo memo;
    return memo.Exp(omega);
  }
  ExpInto(omega, scratch);
  return scratch;
}

}  // namespace

FixedStepIntegrator::FixedStepIntegrator(const PeriodicSystem& system, IntegratorType type)
    : system_(system), type_(type) {
  const int n = system.states();
  for (Eigen::MatrixXd* m :
       {&a1_, &a2_, &a3_, &b2_, &b3_, &omega_, &comm_, &tmp_, &step_, &phi_, &next_})
    m->resize(n, n);
}

void FixedStepIntegrator::StepGenerator(double t, double h) {
  switch (type_) {
    case IntegratorType::kMagnus4: {
      // Ω = h/2 (A1 + A2) + (√3/12) h² [A2, A1], nodes c = 1/2 ∓ √3/6 (Iserles–Nørsett).
      const double d = std::sqrt(3.0) / 6;
      system_.EvalA(t + (0.5 - d) * h, a1_);
      system_.EvalA(t + (0.5 + d) * h, a2_);
      rhs_evals_ += 2;
      MultiplyInto(a2_, a1_, comm_);
      MultiplyInto(a1_, a2_, tmp_);
      comm_ -= tmp_;
      omega_ = (0.5 * h) * (a1_ + a2_) + (std::sqrt(3.0) / 12 * h * h) * comm_;
      break;
    }
    case IntegratorType::kMagnus6: {
      // Blanes, Casas & Ros, BIT 40 (2000); Blanes, Casas, Oteo & Ros, Phys. Rep. 470 (2009),
      // eq. (257): nodes c = 1/2 − √15/10, 1/2, 1/2 + √15/10 and
      //   B1 = h A2,  B2 = (√15 h/3)(A3 − A1),  B3 = (10 h/3)(A3 − 2 A2 + A1),
      //   Ω = B1 + B3/12 + (1/240) [−20 B1 − B3 + [B1, B2],  B2 − (1/60) [B1, 2 B3 + [B1, B2]]].
      // Verified by the order test in integrator_test.cc (observed order ≈ 6).
      const double d = std::sqrt(15.0) / 10;
      system_.EvalA(t + (0.5 - d) * h, a1_);
      system_.EvalA(t + 0.5 * h, a2_);
      system_.EvalA(t + (0.5 + d) * h, a3_);
      rhs_evals_ += 3;
      b2_ = (std::sqrt(15.0) * h / 3) * (a3_ - a1_);
      b3_ = (10 * h / 3) * (a3_ - 2 * a2_ + a1_);
      a2_ *= h;                       // B1
      MultiplyInto(a2_, b2_, comm_);  // [B1, B2]
      MultiplyInto(b2_, a2_, step_);
      comm_ -= step_;
      // Right operand R = B2 − (1/60) [B1, 2 B3 + [B1, B2]], into step_.
      tmp_ = 2 * b3_ + comm_;
      MultiplyInto(a2_, tmp_, step_);
      MultiplyInto(tmp_, a2_, omega_);
      step_ -= omega_;
      step_ = b2_ - step_ / 60;
      // Left operand L = −20 B1 − B3 + [B1, B2], into tmp_; then Ω.
      tmp_ = comm_ - 20 * a2_ - b3_;
      MultiplyInto(tmp_, step_, omega_);
      MultiplyInto(step_, tmp_, a1_);  // a1_ is free again
      omega_ -= a1_;
      omega_ = a2_ + b3_ / 12 + omega_ / 240;
      break;
    }
    default: {  // kExpm: exponential midpoint rule
      system_.EvalA(t + 0.5 * h, a1_);
      ++rhs_evals_;
      omega_ = h * a1_;
      break;
    }
  }
}

Eigen::MatrixXd FixedStepIntegrator::Run(const std::vector<double>& points, int steps_per_period,
                                         long refine) {
  phi_.setIdentity();
  last_pass_steps_ = 0;
  const double period = system_.period();
  for (size_t p = 0; p + 1 < points.size(); ++p) {
    const double a = points[p], length = points[p + 1] - a;
    const long steps = refine * StepsOnPiece(steps_per_period, length, period);
    const double h = length / steps;
    for (long k = 0; k < steps; ++k) {
      StepGenerator(a + k * h, h);  // a + k h, not a running sum: no drift over many steps
      MultiplyInto(Exponential(omega_, step_), phi_, next_);
      phi_.swap(next_);
    }
    last_pass_steps_ += steps;
  }
  steps_ += last_pass_steps_;
  return phi_;
}

Eigen::MatrixXd FixedStepIntegrator::RunPiecewiseConstant(const std::vector<double>& points) {
  phi_.setIdentity();
  for (size_t p = 0; p + 1 < points.size(); ++p) {
    const double a = points[p], b = points[p + 1];
    system_.EvalA(0.5 * (a + b), a1_);  // the held sample (the midpoint avoids the jump times)
    ++rhs_evals_;
    omega_ = (b - a) * a1_;
    MultiplyInto(Exponential(omega_, step_), phi_, next_);
    phi_.swap(next_);
    ++steps_;
  }
  return phi_;
}

}  // namespace ltp::internal
