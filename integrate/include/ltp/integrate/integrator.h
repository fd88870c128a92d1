#pragma once
// State-transition matrices Φ(t1, t0) of x' = A(t) x, all n columns integrated together
// (Φ' = A(t) Φ as one n×n matrix ODE), by one of several integrators behind one interface.
#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ltp/core/periodic_system.h"

namespace ltp {

enum class IntegratorType {
  kDopri5,  ///< adaptive Dormand–Prince 5(4), Boost.Odeint; smooth non-stiff A(t)
  kRkf78,   ///< adaptive Runge–Kutta–Fehlberg 7(8), Boost.Odeint; tight tolerances
  /// Bulirsch–Stoer extrapolation with adaptive order (Boost.Odeint's algorithm, in an
  /// allocation-free copy that takes the same steps): the cheapest per digit for smooth
  /// systems at tight tolerances (stability maps); no jumps inside pieces
  kBulirschStoer,
  kCvodeBdf,    ///< SUNDIALS CVODE, BDF (stiff), Newton with an exact block preconditioner
  kCvodeAdams,  ///< SUNDIALS CVODE, Adams–Moulton (non-stiff, cheap per step)
  kMagnus4,     ///< fixed-step 4th-order Magnus, 2 Gauss–Legendre nodes + expm
  kMagnus6,     ///< fixed-step 6th-order Magnus, 3 Gauss–Legendre nodes + expm
  kExpm,        ///< product of matrix exponentials: exact for piecewise-constant systems
  /// Taylor series of order ≈ −ln(rel_tol) from the exact derivatives of a Fourier-form A(t)
  /// (docs/taylor-integrator.md): a few long steps per period, the cheapest for small smooth
  /// Fourier systems at tight tolerances (stability maps). Fourier-form systems only.
  kTaylor,
  /// Fixed-step Magnus in the interaction picture of the period mean Ā = VΛV⁻¹, its first two
  /// terms integrated exactly (Filon): the error follows h‖A(t) − Ā‖, not the fastest mode of Ā
  /// (docs/magnus-filon.md). Fourier-form systems whose Ā has a well-conditioned eigenbasis.
  kMagnusFilon,
  /// The study's cheapest for the system at hand (ltp/integrate/integrator_choice.h); analyses
  /// report the integrator actually used and why.
  kAuto,
};

std::string_view ToString(IntegratorType type);
std::optional<IntegratorType> ParseIntegratorType(std::string_view name);
/// Every concrete integrator (not kAuto).
std::vector<IntegratorType> AllIntegrators();
/// "auto, dopri5, rkf78, …": every name ParseIntegratorType takes, for error messages.
std::string IntegratorNames();

struct IntegratorOptions {
  /// The library's default is the CLI's: the study's cheapest integrator for the system.
  IntegratorType type = IntegratorType::kAuto;
  /// Relative tolerance of the adaptive methods, and the target of automatic step selection
  /// for the fixed-step ones. Tight by default: Floquet exponents inherit this error.
  double rel_tol = 1e-10;
  /// Absolute tolerance per entry of Φ (Φ(t0,t0) = I, so entries are O(1) at the start).
  double abs_tol = 1e-13;
  /// Fixed-step methods (Magnus, expm on non-piecewise-constant systems): steps per period.
  /// 0 = automatic: doubled until two successive results agree to rel_tol.
  int steps_per_period = 0;
  /// Upper bound on steps per integration (adaptive methods) before giving up.
  long max_steps = 2'000'000;
  /// Bulirsch–Stoer: also carry every accepted step's local error (the previous row's best
  /// extrapolant, two orders lower, minus the accepted value) to the end of each transition, to
  /// first order: TransitionResult::local_error_effect. One n×n LU per step.
  /// Taylor series: also keep the product of the steps' order-p sums beside the reported one of
  /// order p + 4 on the same steps (about 1.2 runs' work). Fixed-step methods whose steps are
  /// chosen by doubling (steps_per_period = 0): the last coarse pass beside the reported one
  /// (no extra work). Ignored by the other methods.
  bool carry_local_errors = false;
  /// For progress reports: called with the time each accepted step advanced (adaptive
  /// methods) or each transition spanned (the others), possibly from several threads at once,
  /// so it must be thread-safe. Empty: nothing is called.
  std::function<void(double)> on_advance = nullptr;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// The options of the reference run an error estimate compares with: a hundredth of both
/// tolerances (rel_tol at least 1e-15) and twice a fixed step count, so that a fixed-step method
/// takes other steps too.
IntegratorOptions RefinedIntegratorOptions(const IntegratorOptions& options);

struct TransitionResult {
  Eigen::MatrixXd phi;  ///< Φ(t1, t0), n×n
  bool ok = false;      ///< false: integrator failed; `message` says why
  std::string message;
  long steps = 0;  ///< accepted steps (fixed-step: steps taken)
  /// Evaluations of A(t) (products A(t)Φ); kTaylor: the n × n products of its series
  /// (TaylorSeriesShape::ProductsPerOrder per order), each the arithmetic of an evaluation's.
  long rhs_evals = 0;
  int steps_per_period = 0;  ///< fixed-step methods: the resolution used (after auto choice)
  /// Fixed-step auto: ||Φ_N − Φ_{N/2}|| / ||Φ||; empty for other integrators.
  std::optional<double> error_estimate;
  /// With IntegratorOptions::carry_local_errors: δΦ, what a solution held only to the tolerance
  /// may be off by (docs/local-error-estimate.md). Bulirsch–Stoer: how far Φ moves to first
  /// order had every step kept its previous row's extrapolant, Σ_i Φ(t1, t_i) l_i over the
  /// steps' local error estimates l_i. Taylor series: the product of the order-p sums minus
  /// `phi`, the product of the order-(p + 4) sums on the same steps. Fixed steps chosen by
  /// doubling: the pass at half the steps minus `phi`. Empty otherwise.
  Eigen::MatrixXd local_error_effect;
};

/// Φ(t1, t0) for t1 >= t0. Integration restarts at every breakpoint of the system inside
/// (t0, t1) (and at its periodic copies), so discontinuous A(t) keeps full order.
/// Never throws for numerical trouble (see TransitionResult::ok); throws InputError for bad
/// options or t1 < t0.
TransitionResult StateTransition(const PeriodicSystem& system, double t0, double t1,
                                 const IntegratorOptions& options = {});

/// Φ(t_{i+1}, t_i) for every consecutive pair of `times` (strictly increasing): result i is
/// the factor over [t_i, t_{i+1}]. One pass of the integrator: the adaptive methods keep
/// their step size (and order) across the t_i, which only restart the matrix at I, and start
/// afresh only at breakpoints of the system — many short factors cost about what one
/// integration over the whole span costs. Fewer results than intervals, the last with
/// ok = false, when the integration failed. Throws InputError for bad options or times.
std::vector<TransitionResult> ConsecutiveTransitions(const PeriodicSystem& system,
                                                     const std::vector<double>& times,
                                                     const IntegratorOptions& options = {});

/// Φ over each of `intervals` (sorted, non-overlapping [t0, t1]) on up to `threads` cores:
/// runs of touching intervals (one's t1 is the next one's t0) are chains that one
/// ConsecutiveTransitions pass covers, cut into about 2 × threads jobs. One result per
/// interval, in order; an interval after a failure in its pass (or in a pass that threw, e.g.
/// for bad times) gets ok = false and a message. Throws InputError only for bad options.
std::vector<TransitionResult> IntervalTransitions(
    const PeriodicSystem& system, const std::vector<std::pair<double, double>>& intervals,
    const IntegratorOptions& options, int threads);

}  // namespace ltp
