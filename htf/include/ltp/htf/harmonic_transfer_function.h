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
// The transmission zeros of a square system (Zeros) are the generalized eigenvalues of the
// truncated harmonic Rosenbrock pencil, checked where it applies by the Floquet exponents of the
// zero dynamics (docs/htf-operator.md, "Zeros").
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/core/diagnostic.h"
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
  std::vector<Diagnostic> diagnostics;
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
  std::vector<Diagnostic> diagnostics;
};

/// The routes to the transmission zeros (docs/htf-operator.md, "Zeros").
enum class ZeroRoute {
  /// Generalized eigenvalues of the truncated harmonic pencil [[𝒜 − 𝒩 − sI, 𝓑], [𝒞, 𝒟]]
  /// (LAPACK zggev), converged from N to N + Δ.
  kHill,
  /// Floquet exponents of the zero dynamics x' = (A − B D⁻¹ C) x: D(t) invertible for all t.
  kZeroDynamics,
  /// Floquet exponents of x' = (A − B (CB)⁻¹ (CA + C')) x without the m exponents 0 of the
  /// directions that C(t) sees: D = 0 with C(t)B(t) invertible for all t (relative degree one).
  kRelativeDegreeOne,
};
std::string_view ToString(ZeroRoute route);

struct ZerosOptions {
  /// Truncation N of the pencil (harmonics −N…N); 0 = automatic: from the Hill route's N (or
  /// the largest that fits max_pencil_size), grown to N + Δ until every zero moves by less than
  /// tol · max(|z|, Ωp) from N to N + Δ.
  int harmonics = 0;
  /// Δ of the truncation check (0 = automatic: max(2, N/2)).
  int delta = 0;
  double tol = 1e-9;
  int max_harmonics = 64;
  /// Largest pencil solved (rows (2N+1)(n+m), dense complex QZ with eigenvectors: work ~ rows³;
  /// the limit keeps one solve to about a minute on a 2-core machine, docs/htf-operator.md).
  int max_pencil_size = 1500;
  /// Run the check route where it applies (D(t) invertible, or D = 0 with C(t)B(t) invertible).
  bool check = true;
  /// The check route's Floquet analysis of the zero dynamics (mode shapes are computed).
  FloquetOptions floquet;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// One transmission zero: u = e^{zt} p_u(t), x = e^{zt} p_x(t) with p_u, p_x T-periodic give
/// y ≡ 0. Defined modulo jΩp.
struct TransmissionZero {
  /// In the fundamental strip −Ωp/2 < Im z <= Ωp/2: the reported route's value (the Hill
  /// route's at N + Δ, or the check route's when its estimates are the smaller ones).
  std::complex<double> value;
  /// The member z + jmΩp of the family whose direction (p_x, p_u) has its Fourier energy
  /// centred on harmonic 0 (an LTI system in rotating coordinates: its G(s)'s own zero).
  std::complex<double> centred;
  /// The Hill route's value at N + Δ (on the centred branch), whichever route is reported.
  std::complex<double> hill_value;
  /// Energy centroid of that direction over the harmonics (|centroid| <= 1/2 but for ties).
  double centroid = 0;
  /// |z(N) − z(N + Δ)| modulo jΩp (1/s), times (N + Δ)/Δ when a coefficient's Fourier series
  /// decays algebraically; +inf when the zero has no partner at the other truncation.
  double truncation_change = 0;
  /// Absolute (1/s): the reported route's own estimate (truncation_change, or the check route's),
  /// or the disagreement between the routes beyond the other route's estimate, if larger.
  double error_estimate = 0;
  /// The check route's matching exponent (its own branch) and estimate; empty without a check.
  std::optional<std::complex<double>> check_value;
  std::optional<double> check_error_estimate;
};

struct TransmissionZeros {
  /// Where a check route applies: both routes found the same number of zeros and each agrees
  /// within the estimates (the Hill route's truncation need not have met tol then: the check
  /// route's values are reported). Without one: the Hill route's truncation converged.
  bool ok = false;
  std::string failure;  ///< why ok is false; empty when ok
  /// By |Im centred| (positive first), then Re descending. Empty: no finite zeros.
  std::vector<TransmissionZero> zeros;
  /// Whose values are reported: kHill, or the check route when its largest estimate is the
  /// smaller (as H2Norm reports its better route).
  ZeroRoute route = ZeroRoute::kHill;
  /// Empty when no check route applies or it was switched off (diagnostics say why).
  std::optional<ZeroRoute> check_route;
  /// Every zero the check route found (its exponents, its branches), in its order.
  std::vector<std::complex<double>> check_zeros;
  int harmonics = 0;    ///< N
  int delta = 0;        ///< Δ (the reported values are at N + Δ)
  int pencil_size = 0;  ///< rows of the pencil at N + Δ
  /// Generalized eigenvalues at N + Δ taken as infinite (|s| beyond 1e4 × the pencil's norm).
  int infinite_eigenvalues = 0;
  /// Finite eigenvalues at N + Δ not centred on harmonic 0 (other members of the families,
  /// and eigenvalues of the truncation edge).
  int uncentred_eigenvalues = 0;
  double elapsed_s = 0;
  std::vector<Diagnostic> diagnostics;
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
  /// The transmission zeros of a square system (inputs = outputs), by the Hill route and,
  /// where it applies, the zero dynamics' Floquet exponents.
  /// @throws InputError for a non-square system or invalid options.
  TransmissionZeros Zeros(const ZerosOptions& options = {}) const;

  const PeriodicSystem& system() const { return system_; }
  const FloquetResult& floquet() const { return floquet_; }
  /// Empty when the Floquet analysis failed (the modal route then gives NaN).
  const std::optional<ModalModel>& modal() const { return modal_; }
  int hill_harmonics() const { return hill_.harmonics(); }
  /// The Fourier coefficients of A, B, C, D that the Hill route uses.
  const SystemFourier& coefficients() const { return hill_.coefficients(); }
  /// The modal model is reliable and the Hill route's truncation converged.
  bool ok() const;
  std::vector<Diagnostic> diagnostics() const;

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
/// The zero dynamics of a system with D(t) invertible: x' = (A − B D⁻¹ C) x.
PeriodicSystem ZeroDynamicsSystem(const PeriodicSystem& system);
/// The closed loop u = −(CB)⁻¹(CA + C') x of a system with D = 0 and C(t)B(t) invertible:
/// x' = (A − B (CB)⁻¹ (CA + C')) x, which keeps C x constant; `c_dot` is C'(t).
PeriodicSystem RelativeDegreeOneSystem(const PeriodicSystem& system, const FourierMatrix& c_dot);
/// The truncated harmonic Rosenbrock pencil at N: M = [[𝒜 − 𝒩, 𝓑], [𝒞, 𝒟]] (Hill's matrix and
/// the block-Toeplitz harmonic matrices of B, C, D), the zeros being where M − sE is singular,
/// E = diag(I, 0). Rows and columns: the state's harmonics −N…N, then the input's (output's).
Eigen::MatrixXcd HarmonicPencil(const SystemFourier& coefficients, double omega, int harmonics);
}  // namespace internal

}  // namespace ltp
