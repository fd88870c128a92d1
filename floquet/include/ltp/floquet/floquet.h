#pragma once
// Floquet analysis via the monodromy matrix: multipliers, exponents on the physical branch,
// periodic mode shapes and left modes, with an error estimate and the wall time.
//
// The period is split into K segments; the factors Φ_i = Φ(t_{i+1}, t_i) are integrated
// independently (in parallel) and the multipliers are the eigenvalues of Φ_K⋯Φ_1 from a
// periodic Schur decomposition, as logarithms, so exponents stay exact when multipliers leave
// the double range (ρ = e^{−1000T}). Mode shapes ξ_k(t_i) at the segment boundaries come from
// the null vectors of the block-cyclic matrix, never from propagating through the product.
#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/floquet/work_estimate.h"
#include "ltp/integrate/integrator.h"

namespace ltp {

/// Stability as a result can claim it: stable or unstable only when max Re λ lies beyond the
/// error estimate; marginal within it (conservative systems, multipliers on the unit circle,
/// stability boundaries); failed when the result's own checks failed.
enum class StabilityVerdict { kStable, kMarginal, kUnstable, kFailed };
std::string_view ToString(StabilityVerdict verdict);
/// The verdict for max Re λ with the absolute error `band` (1/s; empty = unknown, sign only).
StabilityVerdict ClassifyStability(bool ok, double max_real_exponent, std::optional<double> band);

enum class MultiplierMethod {
  kPeriodicSchur,  ///< eigenvalues of the product of segment factors (SLICOT MB03BD)
  kSingleShot,     ///< eig of the formed product Φ: loses every |ρ| below ~eps·max|ρ|
};
std::string_view ToString(MultiplierMethod method);

/// How the integration error of the exponents is estimated (FloquetOptions::estimate_error).
enum class ErrorEstimateMethod {
  /// A second run at rel_tol/100 on another grid; the numbers come from it, the difference to
  /// the first run is the estimate. Any integrator; about 2.5 runs' work.
  kRefinedRun,
  /// Bulirsch–Stoer, Taylor series, and Magnus 4, 6 and Magnus–Filon choosing their own steps
  /// (others fall back to kRefinedRun, with a note when the integrator was named rather than
  /// chosen by `auto`): one run at rel_tol whose factors also carry how far a lower-order
  /// solution lies, and the exponents of the factors so moved compared with theirs
  /// (docs/local-error-estimate.md). Bulirsch–Stoer: each step's previous extrapolation row;
  /// about 1.1 runs' work, the numbers are the run's at rel_tol, the estimate 25–1000× their
  /// error (study median 112×). Taylor series: the order-p sums beside the reported
  /// order-(p + 4) ones on the same steps; about 1.2 runs' work, the numbers about 10³× better
  /// than the estimate, as a refined run's. Magnus: the doubling loop's pass at half the steps
  /// beside the reported one; no extra work, the numbers 2^order better than the estimate.
  kLocalErrors,
  /// The cheaper one that keeps the refined run's promise (numbers from a computation far more
  /// accurate than the one the estimate measures): kLocalErrors for Taylor series and the Magnus
  /// methods choosing their own steps, kRefinedRun for every other integrator (Bulirsch–Stoer's
  /// local errors would report the run's own numbers). FloquetResult::error_estimate_method says
  /// which ran.
  kAuto,
};
std::string_view ToString(ErrorEstimateMethod method);
/// "refined-run", "local-errors" or "auto"; nullopt otherwise.
std::optional<ErrorEstimateMethod> ParseErrorEstimateMethod(std::string_view name);

struct FloquetOptions {
  IntegratorOptions integrator;
  /// Number of segments K; 0 = automatic: at least `mode_samples`, refined where a factor's
  /// condition number exceeds `max_factor_condition` (fast growth or decay within a segment).
  int segments = 0;
  /// Automatic mode's starting grid: 0 = from `mode_samples` and the system's size; else this
  /// many uniform segments, refined as usual. A grid known from a near-identical system (the
  /// nearest-sample route's for the trigonometric one) saves the rounds that refine up to it.
  int initial_segments = 0;
  /// Largest condition number σmax/σmin accepted for one segment factor in automatic mode.
  /// A factor loses about log10(cond) digits of its smallest singular directions.
  double max_factor_condition = 1e3;
  /// Upper bound on K (automatic mode); reaching it is reported in the diagnostics.
  int max_segments = 20000;
  MultiplierMethod multipliers = MultiplierMethod::kPeriodicSchur;
  /// Equally spaced samples of the mode shapes per period (power of two, >= 4); their FFT
  /// gives the Fourier coefficients used to choose the branch. 0 = automatic (from the
  /// harmonic content of A).
  int mode_samples = 0;
  /// Estimate the exponents' integration error, by `error_estimate_method`. The refined run
  /// is at rel_tol/100 (or twice the steps) on another grid — every segment halved with modes,
  /// the boundaries moved to the midpoints without.
  bool estimate_error = true;
  ErrorEstimateMethod error_estimate_method = ErrorEstimateMethod::kAuto;
  /// Compute mode shapes, left modes and branch selection (off: multipliers only, faster).
  bool compute_modes = true;
  /// Keep the segment factors Φ_i = Φ(t_{i+1}, t_i) in the result (FloquetResult::
  /// segment_factors): the monodromy as the product it is, usable where the formed product
  /// under- or overflows. K n² numbers.
  bool keep_segment_factors = false;
  /// OpenMP threads for the segments; 0 = all cores.
  int threads = 0;
  /// Largest T · max_t ‖A(t)‖ analysed: beyond it (a = 1e200, a rotor speed of 1e-300) no
  /// integrator follows the solutions over a period in any reasonable time, and the analysis is
  /// refused up front (InputError) instead of running for hours.
  double max_period_scale = 1e10;
  /// Refuse (InputError, with the estimate) an analysis whose fewest possible evaluations
  /// (WorkEstimate::fewest_seconds) would take longer than this many CPU seconds; 0 = no limit.
  double max_work_seconds = 3600;
  /// An analysis whose typical estimate (WorkEstimate::seconds) exceeds this many CPU seconds
  /// says so up front: a diagnostic, and `on_long_work` (the CLI prints it) before the work.
  double announce_work_seconds = 10;
  std::function<void(const WorkEstimate&)> on_long_work;
  /// For a progress bar: the phase integrating ("run", "refined run", "mode shapes"; prefixed
  /// for the other models of sampled data) and the fraction of its period done, at most every
  /// half percent; one call at a time, possibly from a worker thread.
  std::function<void(std::string_view phase, double fraction)> on_progress;
  /// Analyse only the modes whose eigenvalue of the mean Ā = (1/T)∫A dt has modulus at most
  /// this (rad/s); 0 = every mode. The system is projected on Ā's invariant subspace of those
  /// modes, analysed, and measured against the projection with kModesBelowCheck times the
  /// cut-off (further when that adds fewer than a quarter of the modes kept): the change is
  /// added to each exponent's estimate. What a Campbell diagram or a
  /// verdict on the slow modes needs, at a cost set by the cut-off instead of the stiffest
  /// mode (docs/model-sizes.md, "Modes below a frequency"). FloquetResult::reduction says what
  /// was left out.
  double modes_below = 0;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// `sink` with `prefix` before every phase name (an empty sink stays empty): the progress of
/// one analysis inside a larger job ("other model 1 of 2: run").
std::function<void(std::string_view, double)> PrefixedProgress(
    std::function<void(std::string_view, double)> sink, std::string prefix);

/// The second cut-off of a reduced analysis, as a multiple of FloquetOptions::modes_below.
inline constexpr double kModesBelowCheck = 2;

/// What an analysis of the modes below a cut-off (FloquetOptions::modes_below) kept and left out.
struct ModalReduction {
  double cutoff = 0;        ///< rad/s: the modes of Ā with |λ| ≤ cutoff were analysed
  int kept = 0;             ///< states of the reduced system (= the modes reported)
  double check_cutoff = 0;  ///< rad/s: the cut-off of the analysis the numbers come from
  int check_kept = 0;       ///< its states
  /// Largest distance (1/s, modulo jΩp) between an exponent at `cutoff` and at
  /// `check_cutoff`: what the truncation moves; in every exponent's estimate.
  double truncation_change = 0;
  /// Largest second-order effect (1/s) of the modes beyond `check_cutoff` on an exponent
  /// through the periodic part (+inf at a resonance); twice each exponent's own is in its
  /// estimate.
  double tail = 0;
  /// Eigenvalues of Ā (1/s) of the modes left out, and max_t ‖A(t) − Ā‖_F in the balanced
  /// states: how far the periodic part may move their exponents from these (an estimate, not a
  /// bound: ill-conditioned eigenvectors move further). The verdict is `stable` only when
  /// max Re of them plus this stays below 0.
  std::vector<std::complex<double>> dropped;
  double periodic_part = 0;
};

struct FloquetMode {
  std::complex<double> exponent;        ///< λ on the chosen branch (1/s)
  std::complex<double> log_multiplier;  ///< log ρ = log|ρ| + j arg ρ, arg in (−π, π]
  int branch = 0;                       ///< m in λ = Log(ρ)/T + j m Ωp
  double frequency_hz = 0;              ///< Im λ / 2π
  double damping_ratio = 0;             ///< −Re λ / |λ| (0 when λ = 0)
  double central_weight = 0;  ///< fraction of ξ's Fourier energy on harmonic 0 (chosen branch)
  /// Distance of the energy centroid from the nearest branch tie (0.5 = unambiguous, 0 = tie:
  /// e.g. a negative real multiplier, whose exponent sits on the strip edge).
  double branch_margin = 0;
  double eigvec_residual = 0;  ///< cyclic residual of the periodic eigenvector
  /// This exponent's own error estimate (1/s): its integration error (the difference to the
  /// refined run, or of the carried local errors) plus its round-off floor. The verdict asks
  /// each exponent for its own; FloquetResult::error_estimate is the largest of each part.
  /// Empty when no estimate was asked for.
  std::optional<double> error_estimate;
  /// The free rotation of a state in SystemLabels::rigid_body_states: exponent 0 in theory
  /// (its distance from 0 is the model's error), left out of max_real_exponent and stable.
  bool rigid_body = false;
  /// The share of the mode's motion in the system's whirl planes (SystemLabels::whirl_pairs)
  /// that turns with the rotor: 1 forward, 0 backward whirl (ltp/core/whirl.h). Empty without
  /// whirl pairs or mode shapes; NaN when the mode does not move in those planes.
  std::optional<double> forward_whirl;
};

/// The exponents λ of `modes`, in their order (FloquetResult::modes, HillResult::modes).
std::vector<std::complex<double>> Exponents(const std::vector<FloquetMode>& modes);

/// How a Floquet analysis ended; ok is true exactly for kCompleted.
enum class Termination {
  kNotRun,              ///< AnalyzeFloquet was not called
  kCompleted,           ///< every step ran and the result passed its checks
  kIntegrationFailed,   ///< the state transition over the period failed
  kEigenvaluesFailed,   ///< no eigenvalues of the monodromy (every fallback failed)
  kChecksFailed,        ///< the result failed its own checks (Liouville, the two cut-offs)
  kNoModesBelowCutoff,  ///< FloquetOptions::modes_below left no mode to analyse
};

/// A stable name of `t` ("checks_failed").
std::string_view ToString(Termination t);

struct FloquetResult {
  /// false: the integration failed, or the result failed its own checks (Liouville beyond the
  /// error estimate); modes are kept when they were computed, see diagnostics.
  bool ok = false;
  /// Why the analysis ended as it did; set with `failure` by Fail, or kCompleted with ok.
  Termination termination = Termination::kNotRun;
  /// Why ok is false, one sentence (also among the diagnostics); empty when ok.
  std::string failure;
  int states = 0;
  double period = 0;
  IntegratorType integrator = IntegratorType::kAuto;  ///< the one used (auto resolved)
  MultiplierMethod multiplier_method = MultiplierMethod::kPeriodicSchur;
  /// The estimate's method actually used (never kAuto; kLocalErrors falls back to kRefinedRun
  /// for integrators that carry no local errors).
  ErrorEstimateMethod error_estimate_method = ErrorEstimateMethod::kRefinedRun;
  int segments = 0;  ///< K actually used
  /// A starting grid, FloquetOptions::initial_segments, for a similar system: K of the grid the
  /// first run chose (the error estimate's refined run re-cuts it into `segments`), halved while
  /// its factors' conditions say merged pairs would still be within the limit.
  int grid_segments = 0;
  std::vector<double> segment_times;  ///< t_0 = 0 < t_1 < … < t_K = T
  std::vector<FloquetMode> modes;     ///< sorted by frequency (|Im λ|), then Re λ
  double max_real_exponent = 0;       ///< max Re λ (1/s), rigid-body modes excluded
  double max_log_abs_multiplier = 0;  ///< max log|ρ| = T · max Re λ
  bool stable = false;                ///< verdict == kStable
  StabilityVerdict verdict = StabilityVerdict::kFailed;
  /// Estimated absolute error of every exponent, max over modes (1/s): the difference to a
  /// second run at a tighter tolerance, plus the round-off floor. Empty when not asked for.
  std::optional<double> error_estimate;
  /// For a model built from samples: the part of error_estimate that is the model's own error —
  /// how far the exponents move when the same samples are interpolated the other way
  /// (IncludeModelError, ltp/floquet/model_error.h; docs/sampled-models.md). Empty otherwise.
  std::optional<double> model_error;
  /// |Σ log|ρ_k| − ∫_0^T tr A dt| / max(1, |∫ tr A|) (Liouville: det Φ = exp ∫ tr A). Empty
  /// when the analysis stopped before its multipliers.
  std::optional<double> liouville_residual;
  /// 2-norm condition number of the normalised mode matrix Ξ(t), the best of up to 16 sample
  /// times (a shape may be tiny at one t; a defective Ξ is ill-conditioned at every t); large
  /// = (near-)defective; +inf when no shape could be computed. Empty without mode shapes.
  /// Measured in the balanced states when the analysis rescaled them (see diagnostics).
  std::optional<double> mode_condition;
  /// Monodromy Φ(T, 0) as the formed product (entries may under/overflow for stiff systems).
  /// States whose units spread A's scales beyond 2¹⁰ are analysed in balanced states
  /// (powers of two, exact); monodromy and mode shapes are given back in the system's states.
  Eigen::MatrixXd monodromy;
  /// With FloquetOptions::keep_segment_factors: Φ(t_{i+1}, t_i) over segment i of
  /// `segment_times`, in the system's states (Φ = the product, last factor leftmost); of the
  /// reduced system when `reduction` is set. Empty otherwise.
  std::vector<Eigen::MatrixXd> segment_factors;
  /// Periodic mode shapes at `sample_times` (uniform, t_s = s T/S): column k of
  /// mode_samples[s] is ξ_k(t_s) on mode k's chosen branch.
  std::vector<double> sample_times;
  std::vector<Eigen::MatrixXcd> mode_samples;
  /// What carries each mode: its shape ξ_k(0) in the system's state names, blade states as
  /// multiblade families (ltp/core/mode_description.h), e.g. "zeta cyclic 78%, x 22%". Empty
  /// without mode shapes.
  std::vector<std::string> mode_descriptions;
  /// Fourier coefficients of the mode shapes: mode_fourier[v + H] (n × n) holds ξ_{k,v} in
  /// column k, harmonics v = −H..H.
  std::vector<Eigen::MatrixXcd> mode_fourier;
  int mode_harmonics = 0;  ///< H
  /// Set when only the modes below FloquetOptions::modes_below were analysed: `modes` then
  /// holds those (shapes n × reduction->kept), `monodromy` is their part U Φ_r Wᵀ (rank
  /// `kept`) and max_real_exponent is over them.
  std::optional<ModalReduction> reduction;
  long rhs_evals = 0;  ///< evaluations of A(t)Φ; kTaylor: products A_j Φ_k of the series
  double elapsed_s = 0;
  std::vector<Diagnostic> diagnostics;

  /// Ξ(t) from the Fourier coefficients of the mode shapes (spectral interpolation).
  Eigen::MatrixXcd ModeMatrix(double t) const;
  /// Left modes: rows of Ξ(t)⁻¹ — the pseudo-inverse, so a singular Ξ (see mode_condition)
  /// gives a result, not an exception.
  Eigen::MatrixXcd LeftModes(double t) const;
  /// One line: K, max Re λ, stability, error, time.
  std::string BriefReport() const;
  /// Marks the result failed: ok false, `termination` and `failure` set together.
  void Fail(Termination why, std::string sentence);
  /// Marks the result usable: ok, kCompleted, no failure.
  void Complete();
};

/// Floquet analysis of the homogeneous part x' = A(t) x. Never throws for numerical trouble
/// (see ok and diagnostics); throws InputError for invalid options.
FloquetResult AnalyzeFloquet(const PeriodicSystem& system, const FloquetOptions& options = {});

/// The mode of the multiplier log ρ (arg in (−π, π]) on branch m: exponent λ = log ρ / T + j m Ωp,
/// frequency Im λ / 2π, damping ratio −Re λ / |λ| (0 when λ = 0). Every route builds its modes
/// here; the shape-related fields (central_weight, branch_margin, …) are left at their defaults.
FloquetMode MakeFloquetMode(std::complex<double> log_multiplier, int branch, double period);

/// The order in which both routes (monodromy and Hill) report modes: by |Im λ|, positive
/// frequency first, then by Re λ descending. Returns indices into `modes`.
std::vector<int> ModeDisplayOrder(const std::vector<FloquetMode>& modes);

/// Ā = (1/T) ∫_0^T A(t) dt, by the rules of IntegralOfTrace.
Eigen::MatrixXd MeanOfA(const PeriodicSystem& system);

/// ∫_0^T tr A(t) dt: exact for Fourier and piecewise-constant systems, Gauss–Legendre on the
/// smooth pieces between breakpoints otherwise.
double IntegralOfTrace(const PeriodicSystem& system);

}  // namespace ltp
