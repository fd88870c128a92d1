#pragma once
// Hill's method: Floquet exponents as eigenvalues of the truncated Hill matrix
//   block (v,u) = A_{v−u} − j v Ωp δ_vu I,   v, u = −N..N,   size (2N+1)n   (docs/conventions.md),
// whose spectrum approximates λ_k + j m Ωp for every k and m. Only n eigenvalues are the
// physical ones: they are selected by where the eigenvector's energy sits over the harmonic
// blocks (centred on block 0), with a selection margin, a tail weight and a truncation error
// estimate for each. A Koopman–Hill projection Φ(T) ≈ C expm(H_N T) W gives the multipliers
// without any selection, as an independent cross-check.
//
// Two solvers: dense (LAPACK zgeev: full spectrum, cost ~ N³) and structured (banded
// shift-invert Arnoldi around the expected exponents: only the n physical ones, cost ~ N).
#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"

namespace ltp {

enum class HillSolver {
  kDense,       ///< all (2N+1)n eigenpairs by LAPACK zgeev
  kStructured,  ///< banded LU (zgbtrf) + shift-invert Arnoldi around the expected exponents
  /// Chosen per N by the work–precision study's rule (ChooseHillSolver in hill_solver_choice.h);
  /// the result's diagnostics say which and why.
  kAuto,
};
std::string_view ToString(HillSolver solver);
std::optional<HillSolver> ParseHillSolver(std::string_view name);

/// How the n physical eigenvalues are picked among the (2N+1)n.
enum class HillSelectionRule {
  /// Energy centroid of the eigenvector over the blocks closest to block 0 (|centroid| < 1/2
  /// passes). Same rule as the monodromy route's branch choice, so both report the same branch.
  kCentroid,
  /// Largest energy fraction on the central block (block 0 must be the heaviest to pass).
  kCentralWeight,
  /// Fundamental strip |Im λ| <= Ωp/2 (the textbook rule, for comparison: it ignores the
  /// eigenvector and is wrong whenever a mode's frequency exceeds Ωp/2).
  kStrip,
};
std::string_view ToString(HillSelectionRule rule);
std::optional<HillSelectionRule> ParseHillSelectionRule(std::string_view name);

struct HillOptions {
  /// Truncation N: harmonics −N..N.
  int harmonics = 16;
  HillSolver solver = HillSolver::kAuto;  ///< the CLI's default too
  HillSelectionRule selection = HillSelectionRule::kCentroid;
  /// A selection margin below this flags the choice as a tie between λ and λ ± jΩp (margins
  /// are in [0, 1]). A tie never needs resolving: both are the same exponent modulo jΩp (a
  /// negative real multiplier puts it on the strip edge ±Ωp/2); the member with the larger
  /// Im λ is reported, as the monodromy route does (docs/hill-method.md).
  double ambiguity_threshold = 0.05;
  /// Truncation error estimate from a second solve at N + Δ (0 = automatic: max(2, ⌈N/2⌉);
  /// -1 = no second solve).
  int delta_harmonics = 0;
  /// Koopman–Hill cross-check (needs a dense expm of the Hill matrix; skipped above
  /// `koopman_max_size`) and the a-priori bound that uses its eigenvectors.
  bool koopman_check = true;
  int koopman_max_size = 2500;
  /// Structured solver: expected exponents used as shifts (e.g. from AnalyzeFloquet).
  /// Empty = eigenvalues of A_0 (the averaged system).
  std::vector<std::complex<double>> expected;
  /// Structured solver: fall back to the dense one (when it fits in memory) if fewer than n
  /// exponents were found.
  bool structured_fallback = true;
  /// Fourier fit of A(t) for systems not given in Fourier form.
  FourierFitOptions fourier;
  /// Largest dense Hill matrix accepted (bytes); larger → ResourceError.
  double max_dense_bytes = 2.0 * 1024 * 1024 * 1024;
  /// HillConvergenceStudy reports progress as (work done, total work) after each solve, the
  /// work of a truncation counted as its matrix size cubed (what a dense solve costs).
  std::function<void(double done, double total)> progress;
  /// Cost before the work. Dense solver: the eigen-solves at N and N + Δ and the Koopman–Hill
  /// expm cost about 4 complex n×n-product equivalents per m³ (m = n(2N+1), calibrated on
  /// Mathieu, m = 402…1602: 1.3–78 s). Structured solver: one banded shift-invert run per
  /// state, about 9e3 product-cubes per row·n² over both truncations (calibrated on Mathieu
  /// and tower-rotor, 2–194 s; the rotor takes a sixth). The product is timed on this machine at
  /// the start. A solve whose estimate exceeds 3 × max_work_seconds (0 = no limit) is refused
  /// before it starts (and a structured result is not replaced by a dense one that would be); one
  /// above announce_work_seconds calls on_long_work first (seconds() is the estimate, basis says
  /// what decided it) and says so in the diagnostics.
  double max_work_seconds = 3600;
  double announce_work_seconds = 10;
  std::function<void(const WorkEstimate&)> on_long_work;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

/// What the selection says about one physical eigenvalue (parallel to HillResult::modes).
struct HillModeInfo {
  /// Energy centroid of the eigenvector over the blocks (0 = centred on harmonic 0).
  double centroid = 0;
  /// Score gap between the chosen eigenvalue and the runner-up of its jΩp-shift family under
  /// the selection rule, in [0, 1]: 1 = clean, 0 = tie. Centroid rule: |c_runner| − |c_winner|
  /// (ideal 1 − 2|c|); central-weight rule: difference of central-block weights; strip rule:
  /// 1 − 2|Im λ|/Ωp.
  double selection_margin = 0;
  /// Fraction of the eigenvector's energy on the outermost blocks ±N: large = truncation too
  /// small for this mode.
  double tail_weight = 0;
  /// |λ_N − λ_{N+Δ}| modulo jΩp (1/s); empty when not computed.
  std::optional<double> truncation_change;
  /// Relative eigen-residual ||H x − λ x|| / (||H|| ||x||).
  double residual = 0;
  bool passed = false;     ///< met the rule's pass condition (see HillSelectionRule)
  bool ambiguous = false;  ///< selection_margin < ambiguity_threshold (a tie: see HillOptions)
};

/// ||A_w|| <= a e^{−b|w|} envelope of the Fourier coefficients of A (Frobenius norms), or an
/// algebraic decay ~ |w|^{−p} for which no exponential envelope exists.
struct HillDecay {
  FourierDecay kind = FourierDecay::kFinite;
  int harmonics = 0;        ///< H: largest harmonic of A used
  double fourier_tail = 0;  ///< relative norm of the dropped harmonics of A (0 when exact)
  /// Fitted rate: b of ||A_w|| ~ e^{−b|w|} (exponential; caps the envelope's b) or p of
  /// ||A_w|| ~ |w|^{−p} (algebraic: no exponential envelope, no a-priori bound); 0 = finite.
  double rate = 0;
  double a = 0, b = 0;        ///< envelope a e^{−b|w|} minimising the bound at the N analysed
  std::vector<double> norms;  ///< ||A_w||_F, w = 0..H
};

struct HillResult {
  /// false: the solver failed, fewer than n exponents were found, or the selected ones failed
  /// the Liouville check (then modes are kept for inspection and error_estimate is +inf).
  bool ok = false;
  /// Why ok is false, one sentence (also among the diagnostics); empty when ok.
  std::string failure;
  int states = 0;
  int harmonics = 0;                       ///< N actually used
  int matrix_size = 0;                     ///< (2N+1)n
  double period = 0;                       ///< T of the system
  HillSolver solver = HillSolver::kDense;  ///< the one that produced the exponents
  /// The structured solver found fewer than n exponents (or failed the Liouville check) and
  /// the dense one gave them.
  bool dense_fallback = false;
  /// The rule that chose the physical exponents; selection_rule is its name, ToString(selection).
  HillSelectionRule selection = HillSelectionRule::kCentroid;
  std::string selection_rule;
  /// The n physical exponents (same struct and order as AnalyzeFloquet: by |frequency|,
  /// positive first, then Re λ). branch_margin = 0.5 − |centroid|.
  std::vector<FloquetMode> modes;
  std::vector<HillModeInfo> info;  ///< parallel to modes
  /// Periodic mode shapes at t = 0, ξ_k(0) = Σ_w v_w (the eigenvector's blocks summed), one
  /// column per mode in modes' order (n × n; empty when no exponents were found).
  Eigen::MatrixXcd mode_shapes;
  /// The Hill matrix's eigenvectors of the selected eigenvalues, one column per mode in modes'
  /// order ((2N+1)n × n, blocks v = −N..N of n rows each; unit 2-norm): H_N v_k ≈ λ_k v_k.
  /// For a tie reported as λ + jΩp (see HillOptions::ambiguity_threshold) the eigenvector of
  /// the eigenvalue found, λ, shifted down one block (exact but for the truncation edge).
  Eigen::MatrixXcd eigenvectors;
  double max_real_exponent = 0;
  bool stable = false;  ///< verdict == kStable
  StabilityVerdict verdict = StabilityVerdict::kFailed;

  // Truncation error (exponents, 1/s).
  int delta_harmonics = 0;  ///< Δ of the N vs N+Δ estimate (0: not computed)
  /// max_k |λ_k(N) − λ_k(N+Δ)| (mod jΩp); empty when not computed.
  std::optional<double> truncation_estimate;
  /// A-priori bound on the exponent error: Bayer–Leine bound on ||Φ(T) − C e^{H_N T} W||,
  /// carried to the multipliers by Bauer–Fike and added to the Hill vs Koopman–Hill gap.
  /// +inf when not available (algebraic decay, bound not yet below |ρ|, no Koopman check).
  double apriori_bound = std::numeric_limits<double>::infinity();
  /// Bound on ||Φ(T) − C e^{H_N T} W||_2 (truncation, plus the expm round-off when the
  /// Koopman–Hill check ran).
  double apriori_phi_bound = std::numeric_limits<double>::infinity();
  HillDecay decay;
  /// Error of the exponents due to the FFT fit of A(t) (1/s), whatever N: the change when the
  /// fit uses half the samples (aliasing of a discontinuous A(t) falls like 1/S or faster, so
  /// the change is at least the error). 0 for Fourier-form systems and converged fits.
  double fourier_fit_error = 0;
  /// How A(t) was fitted (harmonics, samples, tail, decay), one sentence; empty when A(t) was a
  /// Fourier series. Also the first diagnostic.
  std::string fourier_fit;
  /// AnalyzeHillAuto only: whether the truncation met the requested tolerance (false: it
  /// stopped at the memory or harmonics limit, or early because the observed convergence rate
  /// or the Fourier fit of A could not reach it; the diagnostics say which). Empty for a fixed N.
  std::optional<bool> tolerance_met;
  /// The error estimate reported for every exponent (1/s): the N vs N+Δ change (pre-asymptotic,
  /// with the eigenvectors at the truncation edge: change/(1 − q) from a third solve at N+2Δ,
  /// +inf when the changes do not shrink), at least the Liouville deficit |Σ Re λ − mean tr A|
  /// (+inf when that check fails), the Koopman–Hill gap where it exceeds that projection's own
  /// bound (a suspect selection), plus the round-off floor of the eigen-residuals and
  /// fourier_fit_error; the Koopman–Hill gap alone when there is no N+Δ run; +inf when neither
  /// check ran; empty when no exponents were found.
  std::optional<double> error_estimate;
  /// For a model built from samples: the part of error_estimate that is the model's own error
  /// (IncludeModelError, ltp/floquet/model_error.h). Empty otherwise.
  std::optional<double> model_error;

  // Koopman–Hill cross-check (sorting-free).
  std::vector<std::complex<double>> koopman_log_multipliers;  ///< log eig(C e^{H T} W)
  /// max_k |λ_k,Hill − log ρ_k,KH / T| (mod jΩp); empty when the check was skipped.
  std::optional<double> koopman_discrepancy;

  /// All eigenvalues of the Hill matrix (dense solver) or those found (structured).
  std::vector<std::complex<double>> eigenvalues;
  double elapsed_s = 0;
  std::vector<Diagnostic> diagnostics;

  /// One line: N, size, max Re λ, error estimates, time.
  std::string BriefReport() const;
  /// "dense", "structured", or "structured→dense" after a fallback.
  std::string SolverDescription() const;
};

/// Hill analysis of x' = A(t) x. Fourier-form systems use their exact coefficients; others are
/// fitted by FFT first (the fit's tail and decay are reported). Never throws for numerical
/// trouble (see ok, diagnostics).
/// @throws InputError for invalid options; ResourceError when the truncation would not fit.
HillResult AnalyzeHill(const PeriodicSystem& system, const HillOptions& options = {});

/// Convergence study over N = 1 .. max_harmonics (every N up to 10, then roughly ×1.25).
struct HillStudyRow {
  int harmonics = 0;
  int matrix_size = 0;
  /// Per physical exponent (in the order of HillStudy::reference): |λ_Hill − λ_ref| modulo jΩp
  /// of the analysed period; empty without a reference.
  std::vector<double> errors;
  std::optional<double> max_error;  ///< max of errors; empty without a reference
  /// The exponents at this N (1/s), Hill's branch, one column per mode in the order of the
  /// analysis at max_harmonics (the last row is its exponents): with a reference, Hill's match
  /// of each reference exponent (so the errors above are these modulo jΩp); without, Hill's
  /// match of each exponent of the last row. NaN where none matched.
  std::vector<std::complex<double>> exponents;
  double apriori_bound = 0;                   ///< HillResult::apriori_bound
  std::optional<double> truncation_estimate;  ///< N vs N+Δ (HillResult::truncation_estimate)
  /// HillResult::error_estimate at this N: what the analysis reports as its error bound.
  std::optional<double> error_estimate;
  double selection_margin = 0;  ///< min over modes
  double tail_weight = 0;       ///< max over modes
  bool ambiguous = false;
  double elapsed_s = 0;
};

/// How the error of Hill's exponents falls with the truncation N.
enum class HillConvergence {
  kExponential,  ///< error ~ e^{−rate N}
  kAlgebraic,    ///< error ~ N^{−rate}
};
/// "exponential", "algebraic", "" for nullopt (not fitted): the words of the CLI's and
/// Python's output.
std::string_view ToString(std::optional<HillConvergence> convergence);

struct HillStudy {
  std::vector<HillStudyRow> rows;
  HillDecay decay;  ///< of A's coefficients
  /// Fitted convergence law of the error (of the N vs N+Δ estimate without a reference);
  /// nullopt: too few points above round-off (then rate = 0).
  std::optional<HillConvergence> rate_kind;
  double rate = 0;
  /// The reference exponents used, in the order of the rows' exponents (the analysis at
  /// max_harmonics; reference exponents Hill did not match last).
  std::vector<std::complex<double>> reference;
  double elapsed_s = 0;
  std::vector<Diagnostic> diagnostics;
};

/// `options.harmonics` is overridden per row. With a reference (the monodromy route), errors
/// are measured against its exponents modulo jΩp.
/// @throws InputError for max_harmonics < 1 or invalid options.
HillStudy HillConvergenceStudy(const PeriodicSystem& system, int max_harmonics,
                               const FloquetResult& reference, HillOptions options = {});
HillStudy HillConvergenceStudy(const PeriodicSystem& system, int max_harmonics,
                               HillOptions options = {});

/// The study as `ltp hill` and Python's `ltp.hill_study` run it: the reference (when asked
/// for) from the monodromy route at rel_tol kHillStudyReferenceTol, left out if that run
/// fails; the rows up to `max_harmonics`; and the full analysis at N = max_harmonics.
struct HillStudyRun {
  HillStudy study;
  HillResult last;  ///< AnalyzeHill at N = max_harmonics
  /// last's diagnostics, then the study's that last does not already have.
  std::vector<Diagnostic> diagnostics;
};
inline constexpr int kHillStudyMaxHarmonics = 32;
inline constexpr double kHillStudyReferenceTol = 1e-12;
/// @throws InputError for max_harmonics < 1 or invalid options.
HillStudyRun RunHillStudy(const PeriodicSystem& system, int max_harmonics,
                          const HillOptions& options, bool reference);

// --- Building blocks (also used by tests and benchmarks) ------------------------------------

/// Dense Hill matrix of the Fourier series A with fundamental `omega` and truncation N.
/// @throws ResourceError when it would exceed `max_bytes`.
Eigen::MatrixXcd HillMatrix(const FourierMatrix& A, double omega, int harmonics,
                            double max_bytes = 2.0 * 1024 * 1024 * 1024);

/// The Hill matrix of `system` at truncation N as AnalyzeHill builds it: from A's exact Fourier
/// coefficients, or from the FFT fit of A(t) that AnalyzeHill makes (options.fourier) for a
/// system in another form. Block (v,u) = A_{v−u} − j v Ωp δ_vu I, v, u = −N..N.
/// @throws InputError for harmonics < 0; ResourceError beyond options.max_dense_bytes.
Eigen::MatrixXcd HillMatrix(const PeriodicSystem& system, int harmonics,
                            const HillOptions& options = {});

/// Koopman–Hill projection Φ(t) ≈ C expm(H_N t) W (C picks block 0, W stacks identities).
Eigen::MatrixXcd KoopmanHillTransition(const FourierMatrix& A, double omega, int harmonics,
                                       double t);

/// Decay of A's coefficients and the envelope a e^{−b|w|} (b chosen for truncation N).
HillDecay FitHillDecay(const FourierMatrix& A, const FourierFit* fit, int harmonics, double period);

/// Bayer–Leine bound (2e^{−b})^N e^{4aT} on ||Φ(T) − C e^{H_N T} W|| for the envelope in
/// `decay` (b > ln 2); +inf for algebraic decay.
double KoopmanHillBound(const HillDecay& decay, int harmonics, double period);

/// Hill analysis with the truncation chosen automatically: N = start, 2·start, … until the
/// N vs N+Δ estimate is below `tol` · max(1, max|λ|), the matrix would exceed the memory
/// limit, or N reaches `max_harmonics`. The result says which N was used; not reaching `tol`
/// is a diagnostic, not an error.
HillResult AnalyzeHillAuto(const PeriodicSystem& system, HillOptions options, double tol,
                           int max_harmonics = 256);

/// What `harmonics = auto` means for Hill's method in the CLI (`ltp floquet --method hill`)
/// and in Python (`ltp.hill`): AnalyzeHillAuto from N = kHillAutoStartHarmonics to the
/// tolerance HillAutoTolerance(rel_tol) of the analysis' relative tolerance. `options.harmonics`
/// is replaced by the start.
HillResult AnalyzeHillToTolerance(const PeriodicSystem& system, HillOptions options,
                                  double rel_tol);
/// Doubled from here: smooth scenes converge by N = 8–16 (study).
inline constexpr int kHillAutoStartHarmonics = 4;
/// max(rel_tol, 1e-12): below 1e-12 the N vs N+Δ estimate meets the round-off of the eigensolve.
double HillAutoTolerance(double rel_tol);

}  // namespace ltp
