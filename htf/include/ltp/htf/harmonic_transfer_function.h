#pragma once
// The harmonic transfer function as an operator (Wereley), MIMO and at any complex s, with its
// H∞ and H2 norms (docs/htf-operator.md). For an input u(t) = Σ_u U_u e^{(s + juΩp)t} the
// steady-state output is y(t) = Σ_v Y_v e^{(s + jvΩp)t} with
//   Y_v = Σ_u 𝓗_{v,u}(s) U_u,   𝓗_{v,u}(s) = H_{v−u}(s + juΩp),
// where H_z are the partial transfer functions of ltp/htf/pfrf.h continued off the frequency
// axis. Two routes give every value: the Floquet modal form (one decomposition, then sums of
// modal terms) and the truncated Hill system (sI + 𝒩 − 𝒜) X = ℬ, solved as banded. The norms
// are each computed by two routes that share nothing but the system:
//   H∞  a search over frequency of σmax of the operator's sections (a lower bound: a section is
//       a compression of the operator), and a bisection on γ with the periodic Hamiltonian
//       system, whose Floquet exponents reach the imaginary axis exactly when γ <= ‖G‖∞;
//   H2  the Floquet modal form integrated in closed form over frequency (Parseval), and the
//       periodic solution of the Lyapunov differential equation P' = AP + PAᵀ + BBᵀ,
//       ‖G‖₂² = (1/T) ∫_0^T tr(C P Cᵀ) dt.
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"
#include "ltp/htf/pfrf.h"

namespace ltp {

/// How an operator value is computed.
enum class OperatorRoute {
  kModal,  ///< the Floquet modal form (ModalModel)
  kHill,   ///< the truncated Hill system, banded (HtfSolver)
};
std::string_view ToString(OperatorRoute route);
std::optional<OperatorRoute> ParseOperatorRoute(std::string_view name);

struct HtfOperatorOptions {
  /// The decomposition behind the modal route (mode shapes are always computed).
  FloquetOptions floquet;
  ModalOptions modal;
  /// The Hill route; its truncation is chosen for orders −probe_orders…probe_orders.
  HtfOptions hill;
  int probe_orders = 4;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct NormOptions {
  /// Relative accuracy asked of each route; the routes must agree to about this.
  double rel_tol = 1e-8;
  /// H∞ frequency search: uniform points over one fundamental interval [0, Ωp/2] (besides the
  /// modes' own frequencies), and the largest operator section tried (harmonics −K…K).
  int grid_points = 64;
  int max_section_harmonics = 64;
  /// H∞ bisection: integrator tolerance of the Hamiltonian systems' Floquet analyses.
  double hamiltonian_rel_tol = 1e-11;
  int max_bisections = 80;
  /// H2 Lyapunov route: the augmented system has n² + 2 states; above this many system states
  /// the route is skipped (the modal value is then unchecked, and says so).
  int max_lyapunov_states = 12;
  /// OpenMP threads for the frequency search; 0 = all cores.
  int threads = 0;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// ‖G‖∞: the L2-induced gain of the periodic system, sup over s = jθ of σmax(𝓗(s)).
struct HinfNorm {
  /// Both routes ran and agree within the estimate. An unstable system is ok with value +inf.
  bool ok = false;
  std::string failure;  ///< why ok is false; empty when ok
  double value = 0;     ///< the Hamiltonian bracket's midpoint (+inf: unstable system)
  /// Absolute: the half-width of the bracket plus the routes' disagreement.
  double error_estimate = 0;
  /// The Hamiltonian system has exponents on the imaginary axis at `lower` and none at `upper`.
  double lower = 0, upper = 0;
  int hamiltonian_analyses = 0;
  /// The frequency search: max σmax over the sections searched, where it peaks (rad/s, the
  /// excitation frequency s = jθ), and the section (harmonics −K…K) it converged at.
  double search_value = 0;
  double peak_omega = 0;
  int section_harmonics = 0;
  int search_points = 0;
  double elapsed_s = 0;
  std::vector<std::string> diagnostics;
};

/// ‖G‖₂: ((1/T) ∫_0^T ∫_0^∞ ‖g(t + τ, t)‖_F² dτ dt)^{1/2}, g the impulse response.
struct H2Norm {
  /// The routes ran (or the modal one alone, said in diagnostics) and agree within the
  /// estimate. +inf for an unstable system or one with a direct feedthrough D ≠ 0 (ok).
  bool ok = false;
  std::string failure;
  /// The value of the route with the smaller own estimate (the modal one when the Lyapunov
  /// route was skipped).
  double value = 0;
  /// Absolute: the chosen route's own estimate, or the disagreement beyond the other route's
  /// estimate when that is larger.
  double error_estimate = 0;
  double modal_value = 0;
  std::optional<double> lyapunov_value;  ///< empty when the route was skipped
  double elapsed_s = 0;
  std::vector<std::string> diagnostics;
};

/// The harmonic transfer function of one system: set up once (a Floquet decomposition and the
/// Hill route's truncation), then evaluated anywhere. Evaluation is const and thread-safe.
class HarmonicTransferFunction {
 public:
  /// @throws InputError when the system has no inputs or outputs or options are invalid.
  explicit HarmonicTransferFunction(const PeriodicSystem& system,
                                    const HtfOperatorOptions& options = {});

  /// H_z(s) for z = min_order…max_order, each outputs × inputs.
  PartialFrfs Partial(std::complex<double> s, int min_order, int max_order,
                      OperatorRoute route = OperatorRoute::kModal) const;
  /// The section of the operator with input and output harmonics −K…K: block (v, u) (outputs ×
  /// inputs, v and u from −K) is 𝓗_{v,u}(s) = H_{v−u}(s + juΩp).
  Eigen::MatrixXcd Section(std::complex<double> s, int harmonics,
                           OperatorRoute route = OperatorRoute::kModal) const;

  HinfNorm Hinf(const NormOptions& options = {}) const;
  H2Norm H2(const NormOptions& options = {}) const;

  const PeriodicSystem& system() const { return system_; }
  const FloquetResult& floquet() const { return floquet_; }
  /// Empty when the Floquet analysis failed (the modal route then gives NaN).
  const std::optional<ModalModel>& modal() const { return modal_; }
  int hill_harmonics() const { return hill_.harmonics(); }
  /// The modal model is reliable and the Hill route's truncation converged.
  bool ok() const;
  std::vector<std::string> diagnostics() const;

 private:
  PeriodicSystem system_;
  HtfOperatorOptions options_;
  FloquetResult floquet_;
  std::optional<ModalModel> modal_;
  HtfSolver hill_;
};

namespace internal {
/// max_t σmax(D(t)) on 64 samples of the period: the H∞ norm's floor, and 0 exactly when the
/// system has no feedthrough (its H2 norm is finite only then).
double MaxFeedthrough(const PeriodicSystem& system);
/// The periodic Hamiltonian system of the bounded-real test at level γ > max_t σmax(D(t)):
/// with R = γ²I − DᵀD, [[A + BR⁻¹DᵀC, BR⁻¹Bᵀ], [−Cᵀ(I + DR⁻¹Dᵀ)C, −(A + BR⁻¹DᵀC)ᵀ]].
PeriodicSystem HamiltonianSystem(const PeriodicSystem& system, double gamma);
/// The Lyapunov differential equation as a linear system of n² + 2 states [vec P; J; 1]:
/// P' = AP + PAᵀ + BBᵀ·1, J' = tr(C P Cᵀ).
PeriodicSystem LyapunovSystem(const PeriodicSystem& system);
}  // namespace internal

}  // namespace ltp
