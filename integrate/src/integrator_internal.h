#pragma once
// Internal pieces of StateTransition (integrator.h): the restart grid, and one routine per
// integrator family. Every routine takes the restart points t_0 < … < t_m of [t0, t1] (the
// interval cut at every breakpoint copy) and returns Φ(t_m, t_0) with its counters; the
// dispatcher in integrator.cc validates input, checks finiteness and runs the automatic
// step-size loop of the fixed-step methods.
#include <Eigen/Dense>
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"

namespace ltp::internal {

/// t0, every copy b + kT of a system breakpoint strictly inside (t0, t1), t1 — sorted, with
/// points closer than a few ulps merged (a sliver piece would only add round-off).
std::vector<double> RestartPoints(const PeriodicSystem& system, double t0, double t1);

/// Initial step for an adaptive method of the given order on a piece of length `length`:
/// the step whose local error error_constant·(h·||A||)^(order+1) is about rel_tol.
double InitialStep(double norm_a, double length, double rel_tol, int order, double error_constant);

/// 1/(p+1)!: the local error constant of an order-p one-step method on x' = Ax, the Taylor
/// remainder of e^{hA}. With it the first step is 2.6× (p = 4) to 4.1× (p = 8) longer than with
/// 1, which the step controller otherwise ramps up to over several steps.
double TaylorErrorConstant(int order);

/// Where to evaluate A(t) while integrating the smooth piece [a, b]: t moved a few ulps
/// inside the piece. A(t) exactly at a breakpoint is ambiguous — sign(cos t) at the double
/// nearest π/2 is +1, the value of the *previous* piece — and methods whose first stage sits at
/// the piece start (rkf78, CVODE's initial derivative) would otherwise integrate the wrong
/// side of the jump.
class PieceWindow {
 public:
  PieceWindow() = default;
  PieceWindow(double a, double b);
  double operator()(double t) const { return std::clamp(t, lo_, hi_); }

 private:
  double lo_ = 0, hi_ = 0;
};

/// "state transition is not finite (overflow?)" — one wording for every integrator.
inline constexpr const char* kNotFiniteMessage = "state transition is not finite (overflow?)";

/// One smooth stretch [t0, t1] of an integration. `restart`: A(t) may jump at t0 (or it is the
/// first piece), so adaptive steppers start afresh; `output`: a transition factor ends at t1.
struct Piece {
  double t0 = 0, t1 = 0;
  bool restart = true;
  bool output = true;
};

/// The pieces of Φ(t_{i+1}, t_i) for consecutive `times`: each interval cut at the breakpoint
/// copies inside it (restart pieces); an interval starting on a breakpoint restarts too.
std::vector<Piece> TransitionPieces(const PeriodicSystem& system, const std::vector<double>& times);

/// kDopri5 / kRkf78 via Boost.Odeint steppers, kBulirschStoer via bulirsch_stoer.h: one
/// result per output piece (fewer, the last not ok, when the integration failed); max_steps
/// bounds the attempted steps over all pieces.
std::vector<TransitionResult> OdeintTransitions(const PeriodicSystem& system,
                                                const std::vector<Piece>& pieces,
                                                const IntegratorOptions& options);

/// What a Taylor-series step exploits in a Fourier-form A(t) (integrator_taylor.cc).
struct TaylorSeriesShape {
  int harmonics = 0;  ///< H: A(t) = A₀ + Σ_{w ≤ H} cos wΩt C_w + sin wΩt S_w
  /// A = [0 D; A₂₁ A₂₂] with D diagonal (the identity or its balanced scaling) and every
  /// harmonic in the lower rows: only the lower rows of a term need products.
  bool second_order = false;
  bool constant_damping = false;   ///< second order, and the harmonics leave A₂₂ alone
  Eigen::VectorXd upper_diagonal;  ///< D (second order only)
  /// Products of n × n matrices per order of the series: 1 + 2H; (1 + 2H)/2 in second-order
  /// form; (1 + H)/2 with constant damping.
  double ProductsPerOrder() const;
};
/// The shape of A(t)'s series; nullopt when A(t) is not a Fourier series.
std::optional<TaylorSeriesShape> ShapeOfSeries(const PeriodicSystem& system);

/// kTaylor (integrator_taylor.cc) for a Fourier-form system: Φ(t_{i+1}, t_i) for consecutive
/// `times`, one result each (fewer, the last not ok, when a step failed); max_steps bounds the
/// steps over all intervals.
std::vector<TransitionResult> TaylorTransitions(const PeriodicSystem& system,
                                                const std::vector<double>& times,
                                                const IntegratorOptions& options);

/// kCvodeBdf / kCvodeAdams via SUNDIALS CVODE on the n² vector vec(Φ).
TransitionResult CvodeTransition(const PeriodicSystem& system, const std::vector<double>& points,
                                 const IntegratorOptions& options);

/// Steps a fixed-step method takes on a piece of length `length`:
/// max(1, ceil(steps_per_period · length / period)).
long StepsOnPiece(int steps_per_period, double length, double period);

/// Fixed-step exponential integrators (Magnus 4/6, exponential midpoint rule) with their
/// workspace allocated once and reused over the passes of the automatic resolution loop.
class FixedStepIntegrator {
 public:
  /// `type` must be kMagnus4, kMagnus6 or kExpm.
  FixedStepIntegrator(const PeriodicSystem& system, IntegratorType type);

  /// One pass over the restart points; each piece gets
  /// refine · max(1, ceil(steps_per_period · length / T)) equal steps. The automatic loop
  /// doubles `refine`, which doubles the steps on *every* piece — with steps_per_period
  /// doubled instead, pieces shorter than T/steps_per_period would keep their single step
  /// and two passes could agree without having converged. Adds to the counters.
  Eigen::MatrixXd Run(const std::vector<double>& points, int steps_per_period, long refine = 1);
  /// Steps taken by the last Run.
  long last_pass_steps() const { return last_pass_steps_; }

  /// Exact product of exp(A_k Δt_k) over the held pieces of a piecewise-constant system.
  Eigen::MatrixXd RunPiecewiseConstant(const std::vector<double>& points);

  long steps() const { return steps_; }
  long rhs_evals() const { return rhs_evals_; }

 private:
  // Ω for one step [t, t + h] of the configured method; A evaluated into the workspace.
  void StepGenerator(double t, double h);

  const PeriodicSystem& system_;
  IntegratorType type_;
  Eigen::MatrixXd a1_, a2_, a3_, b2_, b3_, omega_, comm_, tmp_, step_, phi_, next_;
  long steps_ = 0;
  long rhs_evals_ = 0;
  long last_pass_steps_ = 0;
};

/// kMagnusFilon (integrator_magnus_filon.cc): fixed steps of Magnus in the interaction picture
/// of the period mean Ā = VΛV⁻¹, with exact exponential integrals, for a Fourier-form A(t). The
/// same interface as FixedStepIntegrator for the automatic resolution loop.
class MagnusFilonIntegrator {
 public:
  struct Split;
  explicit MagnusFilonIntegrator(const PeriodicSystem& system);

  /// Empty when the method applies to the system; else why not (then Run must not be called).
  const std::string& unsuitable() const;
  /// As FixedStepIntegrator::Run; pieces also take at least the steps that keep
  /// h·(max Re λ − min Re λ) ≤ 2 (the interaction picture's factors stay O(1)).
  Eigen::MatrixXd Run(const std::vector<double>& points, int steps_per_period, long refine = 1);
  long last_pass_steps() const { return last_pass_steps_; }
  long steps() const { return steps_; }
  /// Real n×n products of arithmetic, 20 per step (no A(t) is evaluated).
  long rhs_evals() const { return rhs_evals_; }

 private:
  const PeriodicSystem& system_;
  std::shared_ptr<Split> split_;
  long steps_ = 0;
  long rhs_evals_ = 0;
  long last_pass_steps_ = 0;
};

}  // namespace ltp::internal
