#pragma once
// Partial frequency response functions H_z(ω) of a linear T-periodic system (docs/conventions.md,
// "Partial FRF"): for u(t) = U e^{jωt} the steady-state output is
//   y(t) = Σ_z Y_z e^{j(ω + zΩp)t},   Y_z = H_z(ω) U,
// with H_z indexed by the *excitation* frequency ω. Four independent routes:
//   modal     one Floquet decomposition, then H_z(ω) = Σ_{u+v=z} Ĉ_v (j(ω+uΩp)I − Λ)⁻¹ B̂_u + D_z
//             (paper eq. 42–46); cheap per frequency;
//   htf       truncated harmonic transfer function (Wereley), one banded solve per frequency;
//   shooting  exact periodic steady state y(0) = (I − Φ e^{−jωT})⁻¹ y_p(T), no truncation of A;
//   time      integration from rest until the transient has decayed, then projection of the
//             response on e^{j(ω+zΩp)t} over whole periods (paper eq. 47).
// The sweep runs a primary route on every frequency and check routes on a subset; their
// disagreement (and the HTF truncation check N vs N+Δ) is the error estimate of every point.
#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"
#include "ltp/htf/route_reason.h"
#include "ltp/integrate/integrator.h"

namespace ltp {

namespace internal {
class ShiftedHessenbergSolver;
}

enum class PfrfRoute {
  kModal,
  kHtf,
  kShooting,
  kTime,
  /// Primary: modal (the Floquet decomposition is computed anyway, so every frequency costs a
  /// few complex products) unless the modal model reports itself unreliable; then htf for
  /// smooth A(t), shooting when A(t) jumps. Checks: htf for smooth A(t), shooting when it
  /// jumps (the HTF converges algebraically there: 2e-7 at N = 64 on Meissner, study).
  kAuto,
};
std::string_view ToString(PfrfRoute route);
std::optional<PfrfRoute> ParsePfrfRoute(std::string_view name);

/// H_z for z = min_order..max_order (index z − min_order), each outputs × inputs.
using PartialFrfs = std::vector<Eigen::MatrixXcd>;

// --- Route 1: Floquet modal ------------------------------------------------------------------

struct ModalOptions {
  /// Uniform samples of C(t)Ξ(t) and Ξ(t)⁻¹B(t) are refined ×2 or ×4 (new ones propagated from
  /// the existing mode samples over the fine grid) until the Fourier amplitude in the upper
  /// half of the harmonics is below tail_tol relative to the largest one, per mode, or at the
  /// noise level of the samples (within 10× of integrator.rel_tol, or no longer shrinking).
  double tail_tol = 1e-12;
  int max_samples = 4096;  ///< power of two
  /// The route counts as reliable only if the final tail is below this (systems with jumps
  /// decay algebraically and may stop short of tail_tol while still being accurate).
  double max_tail = 1e-8;
  IntegratorOptions integrator;  ///< for propagating new samples
  /// Above this condition number of the mode matrix Ξ (FloquetResult::mode_condition, and
  /// max_t cond Ξ(t) over the samples) the model says so in its diagnostics. Information, not
  /// a verdict: near a defective monodromy (a stability boundary) the exponents carry
  /// ~cond × their integration error, but modes of different scales reach 1e4 harmlessly;
  /// the sweep's cross-check against another route decides (PfrfRoute::kAuto).
  double max_condition = 1e4;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// The precomputed Floquet-modal form of the transfer behaviour; evaluation is cheap.
struct ModalModel {
  int states = 0, inputs = 0, outputs = 0;
  double period = 0, omega_p = 0;
  std::vector<std::complex<double>> exponents;  ///< λ_k (the branches given)
  int harmonics = 0;                            ///< V: Ĉ_v, B̂_u, D_w kept for |v| <= V
  std::vector<Eigen::MatrixXcd> c_hat;          ///< Ĉ_v (outputs × states), index v + V
  std::vector<Eigen::MatrixXcd> b_hat;          ///< B̂_u (states × inputs), index u + V
  std::vector<Eigen::MatrixXcd> d_hat;          ///< D_w (outputs × inputs), index w + V
  int samples = 0;                              ///< uniform samples per period finally used
  double tail = 0;  ///< worst relative Fourier amplitude in the upper half (per mode)
  /// The tail reached the noise level of the integrated mode samples (within 10× of their
  /// integration tolerance, or it stopped shrinking when the samples were doubled); harmonics
  /// below it were dropped.
  bool noise_floor = false;
  double condition = 0;  ///< max(mode_condition, max_t cond Ξ(t)); information only
  /// The Floquet analysis succeeded and tail <= max_tail. A sweep with route auto can still
  /// find the model wrong by its cross-check (PfrfResult::modal_cross_check_failed).
  bool reliable = false;
  long rhs_evals = 0;
  double elapsed_s = 0;  ///< building the model (the Floquet analysis not included)
  std::vector<Diagnostic> diagnostics;

  /// H_z(ω) for z = min_order..max_order.
  PartialFrfs Evaluate(double omega, int min_order, int max_order) const;
  /// H_z(s) at a complex frequency s (jω on the frequency axis): the same sum with
  /// (s + juΩp − λ_k)⁻¹ — the harmonic transfer function's continuation off the axis.
  PartialFrfs EvaluateAt(std::complex<double> s, int min_order, int max_order) const;
  /// The term of mode k, harmonic pair (u, v = z − u): [Ĉ_v]_{o,k} [B̂_u]_{k,i} / (j(ω+uΩp) − λ_k).
  std::complex<double> Term(double omega, int k, int u, int v, int output, int input) const;
};

/// One input–output channel of a modal model, gathered once into contiguous arrays: what a
/// PFRF sweep evaluates, at 1/(outputs·inputs) of the work of the full matrices, as one small
/// complex matrix–vector product per harmonic u.
class ModalChannel {
 public:
  ModalChannel(const ModalModel& model, int output, int input);
  /// H_z(ω), z = min_order..max_order.
  std::vector<std::complex<double>> Evaluate(double omega, int min_order, int max_order) const;

 private:
  using RowMajor =
      Eigen::Matrix<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  int harmonics_ = 0;
  double omega_p_ = 0;
  Eigen::ArrayXd decay_;                 ///< −Re λ_k
  Eigen::ArrayXd frequency_;             ///< Im λ_k
  RowMajor b_;                           ///< row u + V: [B̂_u]_{k,input} over k
  RowMajor c_;                           ///< row v + V: [Ĉ_v]_{output,k} over k
  std::vector<std::complex<double>> d_;  ///< [D_w]_{output,input}, index w + V
};

/// Builds the modal model from a Floquet decomposition (with modes) of `system`.
/// @throws InputError when the system has no inputs or outputs, `floquet` has no mode samples
/// or belongs to another system (state count or period differ), or options are invalid.
ModalModel BuildModalModel(const PeriodicSystem& system, const FloquetResult& floquet,
                           const ModalOptions& options = {});

// --- Route 2: truncated harmonic transfer function -------------------------------------------

struct HtfOptions {
  /// Truncation N (harmonics −N..N of the state); 0 = automatic: from max(2·max|z|, max|z| +
  /// min(H_A, 8), 8) grown ×1.5 until the N vs N+Δ change at the probe frequencies is below `tol`.
  int harmonics = 0;
  /// Δ of the truncation check (0 = automatic: max(2, N/4)).
  int delta = 0;
  double tol = 1e-11;       ///< relative truncation target of the automatic choice
  int max_harmonics = 128;  ///< upper bound of the automatic choice
  /// Largest Hill matrix (rows) that HtfSolver::PrepareSweep reduces densely (4096: 256 MB).
  int max_dense_size = 4096;
  FourierFitOptions fourier;  ///< for systems not in Fourier form
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// Harmonic transfer function: block system (jωI + 𝒩 − 𝒜) X = ℬ solved as banded
/// (LAPACK zgbtrf/zgbtrs, bandwidth (min(H_A, N) + 1)n − 1), H_z = [𝒞 X]_z + D_z. Systems
/// with jumps (algebraic Fourier decay) converge slowly in N: the truncation check says so.
class HtfSolver {
 public:
  /// @throws InputError (no inputs/outputs, bad options).
  HtfSolver(const PeriodicSystem& system, const HtfOptions& options = {});

  /// Chooses N automatically (when options.harmonics == 0) for these orders, probing at the
  /// given excitation frequencies (rad/s). Returns the N chosen.
  int ChooseTruncation(int min_order, int max_order, const std::vector<double>& probe_omegas);
  /// Prepares `frequencies` evaluations at each truncation N of `truncations` (empty: the
  /// current one): where that pays and the matrix has at most options.max_dense_size rows,
  /// the Hill matrix is reduced once to Hessenberg form (the truncations in parallel) and
  /// Evaluate at that N costs O(size²) per frequency instead of a banded factorization
  /// (docs/speed-notes.md, "HTF sweeps"). Returns whether every one was reduced.
  /// Not thread-safe; Evaluate stays safe to call concurrently afterwards.
  bool PrepareSweep(int frequencies, const std::vector<int>& truncations = {});
  /// H_z(ω) at truncation N (0 = the current one). Never throws for a singular matrix: the
  /// entries are then NaN.
  PartialFrfs Evaluate(double omega, int min_order, int max_order, int harmonics = 0) const;
  /// H_z(s) at a complex frequency s ((sI + 𝒩 − 𝒜) X = ℬ; s = jω on the frequency axis).
  PartialFrfs EvaluateAt(std::complex<double> s, int min_order, int max_order,
                         int harmonics = 0) const;

  int harmonics() const { return harmonics_; }
  int delta() const;
  int coefficient_harmonics() const { return ha_; }  ///< H_A used (after capping)
  double fourier_tail() const { return fourier_tail_; }
  /// The Fourier coefficients of A, B, C, D (exact for a Fourier-form system, else the fit).
  const SystemFourier& coefficients() const { return fourier_; }
  /// The automatic truncation reached its target (always true for a fixed N).
  bool truncation_converged() const { return truncation_converged_; }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  int n_ = 0, m_ = 0, p_ = 0;
  bool truncation_converged_ = true;
  double omega_p_ = 0;
  HtfOptions options_;
  int harmonics_ = 0, ha_ = 0;
  double fourier_tail_ = 0;
  SystemFourier fourier_;
  std::vector<Diagnostic> diagnostics_;
  std::map<int, std::shared_ptr<const internal::ShiftedHessenbergSolver>> reduced_;  ///< by N

  PartialFrfs EvaluateBanded(std::complex<double> s, int min_order, int max_order, int N) const;
  bool PaysToReduce(int frequencies, int N) const;
  std::shared_ptr<const internal::ShiftedHessenbergSolver> Reduce(int N) const;
  Eigen::MatrixXcd HillRhs(int N) const;
};

// --- Routes 3 and 4: shooting and time simulation --------------------------------------------

struct ShootingOptions {
  /// Tolerances of the Runge–Kutta–Fehlberg 7(8) integration of the forced ODE.
  double rel_tol = 1e-12;
  double abs_tol = 1e-15;
  /// Uniform samples per period for the FFT of the periodic response (power of two);
  /// 0 = automatic: doubled until the upper half of the spectrum is below sample_tol.
  int samples = 0;
  double sample_tol = 1e-12;
  int max_samples = 8192;
  long max_steps = 5'000'000;
  /// Monodromy / Φ(t_s, 0) integration.
  IntegratorOptions integrator;
  // Time route only:
  /// The transient is taken as decayed when cond(Ξ)·e^{max Re λ · t} <= settle_tol.
  double settle_tol = 1e-9;
  /// Whole periods of the record projected on e^{j(ω+zΩp)t} (after settling).
  int record_periods = 4;
  /// Refuse (mark failed) when the settling time exceeds this many periods.
  double max_settle_periods = 1e5;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// Integrates the complex forced ODE y' = (A − jωI) y + B (all inputs at once) on the real
/// 2n-dimensional form, restarting at breakpoints and landing on the samples.
class ForcedResponseSolver {
 public:
  /// @throws InputError (no inputs/outputs, bad options).
  ForcedResponseSolver(const PeriodicSystem& system, const ShootingOptions& options = {});

  /// Shooting: exact periodic steady state, then FFT of C y + D. `ok` false (NaN entries) when
  /// the integration failed or I − Φ e^{−jωT} is singular.
  PartialFrfs Shooting(double omega, int min_order, int max_order, bool* ok = nullptr);
  /// Step-sine simulation from rest (complex input e^{jωt}, i.e. a cos and a sin run):
  /// `settle_time` (s) from the slowest Floquet exponent, then projection over whole periods.
  PartialFrfs TimeSimulation(double omega, int min_order, int max_order, double settle_time,
                             bool* ok = nullptr);

  /// Settling time cond·e^{max Re λ t} = settle_tol; +inf when max Re λ >= 0.
  static double SettlingTime(const FloquetResult& floquet, double settle_tol);

  int samples() const { return samples_; }
  /// Largest upper-half amplitude ratio of the response spectra so far (sampling check).
  double sample_tail() const { return sample_tail_; }
  long rhs_evals() const { return rhs_evals_; }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  // y_p from y(t0) over [t0, t0 + periods·T], writing the samples of the last period (S per
  // period) into `out` (samples × (n·m) complex, column-major per sample). Returns false on
  // failure.
  bool Integrate(double omega, const Eigen::MatrixXcd& y0, double t0, int periods,
                 std::vector<Eigen::MatrixXcd>* last_period, Eigen::MatrixXcd* end_state,
                 std::vector<Eigen::MatrixXcd>* average);
  void PrepareTransitions();
  PartialFrfs Project(const std::vector<Eigen::MatrixXcd>& y, double omega, int min_order,
                      int max_order, double* tail) const;

  PeriodicSystem system_;
  ShootingOptions options_;
  int n_ = 0, m_ = 0, p_ = 0;
  int samples_ = 0;
  double sample_tail_ = 0;
  long rhs_evals_ = 0;
  std::vector<Eigen::MatrixXd> phi_;  ///< Φ(t_s, 0), s = 0..S (Φ(T, 0) last)
  std::vector<double> pieces_;        ///< sample times ∪ breakpoints in [0, T]
  /// Breakpoints only, with 0 and T: the grid of the periods that record nothing (settling),
  /// where landing on every sample would only cut the steps short.
  std::vector<double> jump_pieces_;
  std::vector<Diagnostic> diagnostics_;
};

// --- Sweeps ---------------------------------------------------------------------------------

struct PfrfOptions {
  std::vector<double> frequencies_hz;  ///< excitation frequencies f = ω/2π
  int min_order = -4, max_order = 4;
  int input = 0, output = 0;  ///< the channel reported
  PfrfRoute primary = PfrfRoute::kAuto;
  /// Routes run on every `check_every`-th frequency (and the last) to estimate the error.
  /// kAuto in this list: the check the automatic choice pairs with the primary.
  std::vector<PfrfRoute> checks = {PfrfRoute::kAuto};
  int check_every = 10;
  /// Resonance list: peaks of |H_z| above this fraction of the largest |H_z| of the sweep.
  double peak_threshold = 1e-3;
  int max_peaks_per_order = 8;
  FloquetOptions floquet;
  ModalOptions modal;
  HtfOptions htf;
  ShootingOptions shooting;
  /// Called after every frequency of the primary route and every check point: (done, total).
  std::function<void(int, int)> progress;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct RouteRun {
  PfrfRoute route = PfrfRoute::kModal;
  std::vector<int> points;  ///< indices into frequencies_hz where it ran
  /// values[i][z − min_order] for points[i] (the selected channel)
  std::vector<std::vector<std::complex<double>>> values;
  /// max |H_route − H_primary| over orders at each point plus own_error there (0 for the
  /// primary): a bound on the primary's error at that point
  std::vector<double> deviation;
  /// The route's own error at each point: what it measured there (the HTF's N vs N + Δ
  /// change) plus what its tolerance implies relative to the response there
  std::vector<double> own_error;
  int failures = 0;
  double setup_s = 0;    ///< one-off work (decomposition, Fourier fit, Φ samples)
  double elapsed_s = 0;  ///< setup + all points
  std::vector<Diagnostic> diagnostics;
};

struct Resonance {
  int order = 0;               ///< z
  double f_exc_hz = 0;         ///< excitation frequency of the peak
  double f_resp_hz = 0;        ///< f_exc + z fp
  double magnitude = 0;        ///< |H_z| at the peak
  std::optional<size_t> mode;  ///< Floquet mode k (index into FloquetResult::modes)
  int harmonic = 0;            ///< v: the response line f_k + v fp of that mode
  double mode_line_hz = 0;     ///< Im λ_k/2π + v fp
  double share = 0;            ///< |dominant modal term| / Σ |terms| at the peak
};

struct PfrfResult {
  bool ok = false;  ///< the primary route gave every frequency
  /// Why ok is false, one sentence (also among the diagnostics); empty when ok.
  std::string failure;
  std::vector<double> frequencies_hz;
  int min_order = 0, max_order = 0;
  int input = 0, output = 0;
  double period = 0, fp_hz = 0;
  /// values[f][z − min_order]: H_z(2π f) of the selected channel from the primary route
  std::vector<std::vector<std::complex<double>>> values;
  /// Absolute error estimate of every value: the spread of the routes at the nearest check
  /// points (and the HTF truncation change there), at least the modal tail.
  std::vector<std::vector<double>> error_estimate;
  std::vector<bool> checked;     ///< frequency f had check routes run on it
  std::vector<RouteRun> routes;  ///< primary first
  /// Why these routes: the kind, and in words (the routes and the reason, or "as requested").
  RouteReason route_reason = RouteReason::kAsRequested;
  std::string route_choice;
  /// Route auto tried the modal route first and its check found it wrong (beyond
  /// max(1e-8, 100 × the Floquet tolerance) of the largest |H_z|): the primary is then the
  /// HTF (or shooting) and the modal values are the check.
  bool modal_cross_check_failed = false;
  double max_disagreement = 0;           ///< max over check points and orders (absolute)
  double max_relative_disagreement = 0;  ///< divided by max |H_z| of the sweep
  int htf_harmonics = 0;                 ///< N, when the htf route ran
  /// max |H(N) − H(N+Δ)| at the points the htf route ran (empty when it did not).
  std::optional<double> htf_truncation_change;
  std::optional<double> settle_time;  ///< time route: settling time (s); else empty
  /// Sampled models: max |H_other − H| (absolute) over the other models of the same samples
  /// (ltp/htf/pfrf_model_error.h; part of every estimate); empty for other systems.
  std::optional<double> model_error;
  FloquetResult floquet;            ///< the decomposition (modes sorted as reported)
  std::optional<ModalModel> modal;  ///< when the modal route ran
  std::vector<double> order_max;    ///< max_f |H_z| per order
  std::vector<Resonance> resonances;
  double elapsed_s = 0;
  std::vector<Diagnostic> diagnostics;
};

/// Sets the primary and check routes from a route name, as `ltp pfrf --route` and Python's
/// `route=` take it: auto, modal, htf, shooting or time (that primary, checked by the route
/// the automatic choice pairs with it) or all (modal, checked by the other three). Returns
/// false, leaving `options` unchanged, for any other name.
bool SelectPfrfRoutes(std::string_view name, PfrfOptions* options);

/// Runs the sweep. Never throws for numerical trouble (see ok and diagnostics).
/// @throws InputError for invalid options (channel out of range, empty sweep, ...).
PfrfResult ComputePartialFrf(const PeriodicSystem& system, const PfrfOptions& options);

/// Local maxima of every |H_z| (above threshold·max), attributed to a Floquet mode and
/// harmonic by the largest modal term at the peak (nearest line when `modal` is null).
std::vector<Resonance> FindResonances(const PfrfResult& result, const ModalModel* modal,
                                      double threshold, int max_per_order);

}  // namespace ltp
