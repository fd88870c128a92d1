#include "ltp/floquet/floquet.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <iomanip>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "analysis_progress.h"
#include "floquet_modes.h"
#include "ltp/core/diagnostic.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/core/mode_description.h"
#include "ltp/core/text.h"
#include "ltp/floquet/detail/rigid_body.h"
#include "ltp/floquet/model_error.h"
#include "ltp/floquet/periodic_eigen.h"
#include "ltp/integrate/detail/matrix_product.h"
#include "ltp/integrate/detail/modal_basis.h"
#include "ltp/integrate/detail/segment_grid.h"
#include "ltp/integrate/detail/state_balancing.h"
#include "ltp/integrate/integrator_choice.h"
#include "ltp/integrate/threads.h"
#include "modes_below.h"

namespace ltp {

namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

int NextPowerOfTwo(int x) {
  int p = 1;
  while (p < x) p *= 2;
  return p;
}

// Mode samples per period: enough to resolve the mode shapes around the branch the averaged
// system predicts (the samples are demodulated by that branch before the FFT, see
// PriorBranches), i.e. somewhat wider than A's own harmonic content; bounded so a
// discontinuous A(t) does not ask for thousands. Before demodulation the count also had to
// cover the largest frozen frequency: 256 samples (and segments) for tower-rotor instead of 64.
int AutoModeSamples(const PeriodicSystem& system) {
  int harmonics = 8;
  if (const FourierMatrix* fa = system.fourier_A())
    harmonics = fa->max_harmonic();
  else if (!system.breakpoints().empty())
    harmonics = 16;
  const double wanted = 4.0 * (harmonics + 2);
  return std::clamp(NextPowerOfTwo(static_cast<int>(std::ceil(wanted))), 32, 1024);
}

// Uniform segments to start from when the mode shapes are wanted. One per mode sample gives the
// samples directly from the periodic eigenvectors. Larger systems start from fewer segments
// (still refined wherever a factor's condition demands) and get the remaining samples by
// propagation within a segment, which stays accurate because every factor is well
// conditioned. (The rule dates from when each eigenvector cost a sparse LU of the (K·n)²
// block-cyclic matrix — 18 s for a 60-state set at K = 256; the periodic Schur route is O(K n³)
// for all modes, and whether more segments now pay has not been measured.)
constexpr int kSmallSystemStates = 24;

int ModeSegments(int samples, int states) {
  const int shrink =
      NextPowerOfTwo(std::max(1, (states + kSmallSystemStates - 1) / kSmallSystemStates));
  return std::max(std::min(samples, 8), samples / shrink);
}

}  // namespace

std::string_view ToString(MultiplierMethod method) {
  return method == MultiplierMethod::kPeriodicSchur ? "periodic-schur" : "single-shot";
}

std::string_view ToString(ErrorEstimateMethod method) {
  switch (method) {
    case ErrorEstimateMethod::kRefinedRun:
      return "refined-run";
    case ErrorEstimateMethod::kLocalErrors:
      return "local-errors";
    case ErrorEstimateMethod::kAuto:
      return "auto";
  }
  return "unknown";
}

std::optional<ErrorEstimateMethod> ParseErrorEstimateMethod(std::string_view name) {
  for (ErrorEstimateMethod m : {ErrorEstimateMethod::kRefinedRun, ErrorEstimateMethod::kLocalErrors,
                                ErrorEstimateMethod::kAuto})
    if (name == ToString(m)) return m;
  return std::nullopt;
}

std::string_view ToString(StabilityVerdict verdict) {
  switch (verdict) {
    case StabilityVerdict::kStable:
      return "stable";
    case StabilityVerdict::kMarginal:
      return "marginal";
    case StabilityVerdict::kUnstable:
      return "unstable";
    case StabilityVerdict::kFailed:
      return "failed";
  }
  return "failed";
}

StabilityVerdict ClassifyStability(bool ok, double max_real_exponent, std::optional<double> band) {
  if (!ok || std::isnan(max_real_exponent) || (band && std::isnan(*band)))
    return StabilityVerdict::kFailed;
  const double b = std::max(band.value_or(0.0), 0.0);
  if (max_real_exponent > b) return StabilityVerdict::kUnstable;
  if (max_real_exponent < -b) return StabilityVerdict::kStable;
  return StabilityVerdict::kMarginal;
}

void FloquetOptions::Validate() const {
  integrator.Validate();
  const OptionCheck check("FloquetOptions");
  if (segments < 0) check.Fail("segments", segments, "segments >= 0 (0 = automatic)");
  if (!(max_factor_condition > 10))
    check.Fail("max_factor_condition", max_factor_condition, "> 10");
  if (max_segments < 1) check.Fail("max_segments", max_segments, "max_segments >= 1");
  if (!(max_period_scale > 0))
    check.Fail("max_period_scale", max_period_scale, "max_period_scale > 0");
  if (!(max_work_seconds >= 0))
    check.Fail("max_work_seconds", max_work_seconds, "max_work_seconds >= 0 (0 = no limit)");
  if (!(announce_work_seconds >= 0))
    check.Fail("announce_work_seconds", announce_work_seconds, "announce_work_seconds >= 0");
  if (segments > max_segments)
    check.Fail("segments", segments,
               "segments <= max_segments (" + std::to_string(max_segments) + ")");
  if (initial_segments < 0 || initial_segments > max_segments)
    check.Fail("initial_segments", initial_segments,
               "0 <= initial_segments <= max_segments (" + std::to_string(max_segments) + ")");
  if (mode_samples != 0 && (mode_samples < 4 || (mode_samples & (mode_samples - 1)) != 0))
    check.Fail("mode_samples", mode_samples, "0 or a power of two >= 4");
  if (threads < 0) check.Fail("threads", threads, "threads >= 0 (0 = all cores)");
  if (!(modes_below >= 0) || !std::isfinite(modes_below))
    check.Fail("modes_below", modes_below, "a finite modes_below >= 0 (rad/s; 0 = every mode)");
  // The refined run doubles a fixed step count; past the integrators' cap it would fail after
  // the first run's work instead of before any.
  if (estimate_error && error_estimate_method != ErrorEstimateMethod::kLocalErrors &&
      integrator.steps_per_period > 50000000)
    check.Fail(
        "integrator.steps_per_period", integrator.steps_per_period,
        "<= 5e7 with the refined-run error estimate, which doubles the steps (at most 1e8 per "
        "period); or the local-error estimate, or none");
  if (error_estimate_method != ErrorEstimateMethod::kRefinedRun &&
      error_estimate_method != ErrorEstimateMethod::kLocalErrors &&
      error_estimate_method != ErrorEstimateMethod::kAuto)
    check.Fail("error_estimate_method", static_cast<int>(error_estimate_method),
               "one of the ErrorEstimateMethod values");
}

FloquetMode MakeFloquetMode(std::complex<double> log_multiplier, int branch, double period) {
  FloquetMode m;
  m.log_multiplier = log_multiplier;
  m.branch = branch;
  m.exponent = log_multiplier / period + cd(0, branch * 2 * kPi / period);
  m.frequency_hz = m.exponent.imag() / (2 * kPi);
  const double mag = std::abs(m.exponent);
  m.damping_ratio = mag > 0 ? -m.exponent.real() / mag : 0;
  return m;
}

std::vector<int> ModeDisplayOrder(const std::vector<FloquetMode>& modes) {
  std::vector<int> order(modes.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const double fa = std::abs(modes[a].exponent.imag()), fb = std::abs(modes[b].exponent.imag());
    if (std::abs(fa - fb) > 1e-9 * (1 + fa)) return fa < fb;
    if (modes[a].exponent.imag() != modes[b].exponent.imag())
      return modes[a].exponent.imag() > modes[b].exponent.imag();
    return modes[a].exponent.real() > modes[b].exponent.real();
  });
  return order;
}

Eigen::MatrixXd MeanOfA(const PeriodicSystem& system) {
  const double T = system.period();
  const int n = system.states();
  if (const FourierMatrix* fa = system.fourier_A()) return (*fa)[0].real();
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(n, n);
  if (system.form() == PeriodicSystem::Form::kPiecewiseConstant) {
    const auto& times = system.sample_times();
    for (size_t k = 0; k < times.size(); ++k) {
      const double end = k + 1 < times.size() ? times[k + 1] : times.front() + T;
      sum += (end - times[k]) / T * system.samples()[k].A;
    }
    return sum;
  }
  // 10-point Gauss–Legendre on each of 16 panels of every smooth piece.
  static const double x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244,
                              0.8650633666889845, 0.9739065285171717};
  static const double w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820,
                              0.1494513491505806, 0.0666713443086881};
  std::vector<double> cuts = {0.0};
  for (double b : system.breakpoints())
    if (b > 0) cuts.push_back(b);
  cuts.push_back(T);
  Eigen::MatrixXd a(n, n);
  for (size_t p = 0; p + 1 < cuts.size(); ++p) {
    const int panels = 16;
    const double h = (cuts[p + 1] - cuts[p]) / panels;
    for (int q = 0; q < panels; ++q) {
      const double mid = cuts[p] + (q + 0.5) * h;
      for (int i = 0; i < 5; ++i)
        for (double sgn : {-1.0, 1.0}) {
          system.EvalA(mid + sgn * x[i] * h / 2, a);
          sum += w[i] * h / 2 / T * a;
        }
    }
  }
  return sum;
}

double IntegralOfTrace(const PeriodicSystem& system) {
  return system.period() * MeanOfA(system).trace();
}

Eigen::MatrixXcd FloquetResult::ModeMatrix(double t) const {
  Eigen::MatrixXcd xi = Eigen::MatrixXcd::Zero(states, states);
  const double omega = 2 * kPi / period;
  for (int v = -mode_harmonics; v <= mode_harmonics; ++v)
    xi += mode_fourier[v + mode_harmonics] * std::polar(1.0, v * omega * t);
  return xi;
}

std::vector<std::complex<double>> Exponents(const std::vector<FloquetMode>& modes) {
  std::vector<std::complex<double>> a;
  a.reserve(modes.size());
  for (const FloquetMode& m : modes) a.push_back(m.exponent);
  return a;
}

Eigen::MatrixXcd FloquetResult::LeftModes(double t) const {
  const Eigen::MatrixXcd xi = ModeMatrix(t);
  return xi.completeOrthogonalDecomposition().pseudoInverse();
}

std::string_view ToString(Termination t) {
  switch (t) {
    case Termination::kNotRun:
      return "not_run";
    case Termination::kCompleted:
      return "completed";
    case Termination::kIntegrationFailed:
      return "integration_failed";
    case Termination::kEigenvaluesFailed:
      return "eigenvalues_failed";
    case Termination::kChecksFailed:
      return "checks_failed";
    case Termination::kNoModesBelowCutoff:
      return "no_modes_below_cutoff";
  }
  return "unknown";
}

void FloquetResult::Fail(Termination why, std::string sentence) {
  ok = false;
  termination = why;
  failure = std::move(sentence);
}

void FloquetResult::Complete() {
  ok = true;
  termination = Termination::kCompleted;
  failure.clear();
}

std::string FloquetResult::BriefReport() const {
  std::ostringstream s;
  s << (ok ? "" : "FAILED: ") << "K = " << segments << ", max Re λ = " << max_real_exponent
    << " 1/s (" << ToString(verdict) << "), ";
  if (error_estimate)
    s << "error ≈ " << *error_estimate;
  else
    s << "error not estimated";
  s << ", " << elapsed_s << " s";
  return s.str();
}

// T · max ‖A(t)‖ over 16 samples: the number of e-folds or radians a solution can move through
// in one period, i.e. the work any integrator has to do. Returns it. @throws InputError beyond
// the limit.
double CheckPeriodScale(const PeriodicSystem& system, double limit) {
  const int n = system.states();
  if (n == 0) return 0;
  Eigen::MatrixXd a(n, n);
  double largest = 0;
  for (int s = 0; s < 16; ++s) {
    system.EvalA((s + 0.5) / 16 * system.period(), a);
    largest = std::max(largest, a.stableNorm());  // no overflow for entries of 1e200
  }
  const double scale = system.period() * largest;
  if (!(scale <= limit)) {
    std::ostringstream s;
    s << "T · max ‖A(t)‖ = " << scale << " (T = " << system.period()
      << " s): following the solutions "
      << "over one period would take at least that many steps, beyond the limit "
      << "FloquetOptions::max_period_scale = " << limit
      << " (coefficients or period out of scale?)";
    throw InputError(s.str());
  }
  return scale;
}

// The cost before the work (work_estimate.h): refused when even the fewest evaluations any run
// needs would exceed FloquetOptions::max_work_seconds, announced when the typical estimate
// exceeds announce_work_seconds. A job whose upper bound is below both is not weighed further
// (no eigenvalues of A(t) for the traits). `traits` are measured here when needed.
void WeighTheWork(const PeriodicSystem& system, std::optional<SystemTraits>& traits,
                  const FloquetOptions& options, double period_scale, int segments,
                  FloquetResult& r) {
  if (system.states() == 0) return;
  const double pieces = static_cast<double>(system.breakpoints().size()) + 1;
  const double per_evaluation = SecondsPerEvaluation(system);
  // Beyond the integration: periodic Schur, its vectors and the mode samples on the K factors,
  // about 100 n×n products (≤ evaluations) each — what a large model spends most in when A(t)
  // is cheap to integrate (400 states, 16 factors: 15 of 18.5 s).
  constexpr double kLinearAlgebraPerSegment = 100;
  const double linear_algebra = kLinearAlgebraPerSegment * std::max(segments, 1);
  // Fixed steps set the count themselves, whatever the system (3 nodes, 3.5 passes at most).
  const double most = (std::max(MostEvaluations(period_scale, pieces, segments, options.integrator),
                                10.5 * options.integrator.steps_per_period) +
                       linear_algebra) *
                      per_evaluation;
  const double limit = options.max_work_seconds > 0 ? options.max_work_seconds : HUGE_VAL;
  if (most <= std::min(limit, options.announce_work_seconds)) return;
  if (!traits) traits = MeasureSystemTraits(system);
  IntegratorOptions weighed = options.integrator;  // the estimate's passes count too
  weighed.carry_local_errors =
      options.estimate_error && options.error_estimate_method == ErrorEstimateMethod::kLocalErrors;
  WorkEstimate w = EstimateFloquetWork(*traits, weighed, pieces, segments, per_evaluation);
  if (w.fewest_seconds() > limit) {
    std::ostringstream s;
    s.precision(3);
    s << "this analysis would take at least " << w.fewest_seconds() << " CPU s (about "
      << w.seconds() << " s typically; " << w.basis
      << "), beyond FloquetOptions::max_work_seconds = " << limit
      << " (ltp: --max-work SECONDS; 0 = no limit); check the period and the coefficients' "
         "units, or model fewer fast modes";
    throw InputError(s.str());
  }
  // The announcement counts the linear algebra too (as evaluation-equivalents); the refusal
  // above does not need it.
  w.evaluations += linear_algebra;
  w.basis +=
      ", and periodic Schur with the mode samples on " + std::to_string(segments) + " factors";
  if (w.seconds() > options.announce_work_seconds) {
    std::ostringstream s;
    s.precision(2);
    s << "work estimate before the analysis: about " << w.seconds() << " CPU s (" << w.evaluations
      << " evaluations; " << w.basis << ")";
    r.diagnostics.push_back({DiagnosticCode::kWorkEstimate, Severity::kNote, s.str()});
    if (options.on_long_work) options.on_long_work(w);
  }
}

namespace {

// Step 1: the starting grid: one segment per mode sample (fewer for large systems), refined
// automatically unless the user fixed K.
internal::SegmentGridOptions GridOptionsFor(const FloquetOptions& options, int samples, int n,
                                            bool constant) {
  internal::SegmentGridOptions grid;
  grid.integrator = options.integrator;
  grid.integrator.carry_local_errors =
      options.estimate_error && options.error_estimate_method == ErrorEstimateMethod::kLocalErrors;
  // With carried local errors there is no refined run to put the mode samples on grid
  // points, so the run itself starts from one segment per sample (80-state FE rotor: the
  // shapes' propagation within 8 segments cost more than the run).
  const bool one_run = grid.integrator.carry_local_errors;
  // A constant A: one segment unless its factor's condition
  // asks for more; the samples then cost an exponential each, where more segments would each
  // add their share of the periodic eigenvectors (a 400-state A = 0: 23 s → under a second).
  grid.uniform_segments = options.segments > 0           ? options.segments
                          : options.initial_segments > 0 ? options.initial_segments
                          : constant                     ? 1
                          : one_run                      ? samples
                                                         : ModeSegments(samples, n);
  grid.refine = options.segments == 0;
  grid.max_factor_condition = options.max_factor_condition;
  grid.max_segments = options.max_segments;
  grid.threads = ThreadsFor(options.threads);
  return grid;
}

// A starting grid for a similar system (FloquetResult::grid_segments): the grid's K halved
// while merged pairs of factors would still be within the condition limit by the bound
// cond(Φ_b Φ_a) ≤ cond Φ_b · cond Φ_a. A grid cut finer only to put the mode samples on grid
// points then starts the other models of a sampled set (no modes) at what their factors, which
// grow alike, need (250-state turbine set: K = 32 for 32 samples with every factor's condition
// below 6.9 in the mean's modes; the other models start at 16, and their periodic Schur forms
// halve: the whole call 11.3–12.0 → 10.2–10.3 s of CPU side by side, docs/model-sizes.md).
int StartingGrid(const internal::SegmentGrid& grid, double max_condition) {
  int k = static_cast<int>(grid.factors.size());
  double condition = std::max(grid.worst_condition, 1.0);
  while (k > 1 && k % 2 == 0 && condition * condition <= max_condition) {
    k /= 2;
    condition *= condition;
  }
  return k;
}

// Fewest segments whose factors stay well conditioned: the study's K panel found more
// segments only cost time once every factor is below the limit, and fewer lose the small
// multipliers (stiff.yaml: K = 1 overflows, K = 4 is off by 327 1/s).
std::string DescribeSegmentChoice(const internal::SegmentGrid& grid, const FloquetOptions& options,
                                  bool in_modes) {
  const int k = static_cast<int>(grid.times.size()) - 1;
  // Which measure judged the factors (docs/model-sizes.md, "Segments in the mean's modes").
  const char* measure = in_modes ? " in the mean's modes" : "";
  std::ostringstream s;
  s << "segments auto → K = " << k
    << (!options.estimate_error || !grid.local_error_effects.empty() ? ""
        : options.compute_modes
            ? " (halved again in the refined run that gives the numbers)"
            : " (moved by half a segment in the refined run that gives the numbers)")
    << ": ";
  if (k == grid.initial_segments)
    s << "the " << grid.initial_segments
      << (grid.initial_segments == 1 ? " segment" : " uniform segments")
      << " already keep every factor's condition below " << options.max_factor_condition << measure
      << " (worst " << std::setprecision(3) << grid.worst_condition << ")";
  else
    s << "refined from " << grid.initial_segments
      << " where factors grew or decayed beyond condition " << options.max_factor_condition
      << measure << " (worst now " << std::setprecision(3) << grid.worst_condition << ")";
  return s.str();
}

// Φ_{end−1} ⋯ Φ_begin (begin < end), each factor plus `added`'s matrix of the same index when
// given (the local errors' effects); its products through BLAS for large n (Eigen's own were
// 55 ms for the 32 factors of a 250-state monodromy, BLAS 20 ms).
Eigen::MatrixXd ProductOfFactors(const std::vector<Eigen::MatrixXd>& factors, size_t begin,
                                 size_t end, const std::vector<Eigen::MatrixXd>* added = nullptr) {
  Eigen::MatrixXd product = factors[begin], sum, next(product.rows(), product.cols());
  if (added) product += (*added)[begin];
  for (size_t j = begin + 1; j < end; ++j) {
    if (added) sum = factors[j] + (*added)[j];
    const Eigen::MatrixXd& factor = added ? sum : factors[j];  // a reference, not a copy
    internal::MultiplyInto(factor, product, next);
    product.swap(next);
  }
  return product;
}

// The factors (plus `added`, as ProductOfFactors) multiplied in consecutive groups of `r`
// (Φ_{r−1}⋯Φ_0 first; a shorter last group when r does not divide K).
std::vector<Eigen::MatrixXd> GroupedFactors(const std::vector<Eigen::MatrixXd>& factors, int r,
                                            const std::vector<Eigen::MatrixXd>* added = nullptr) {
  std::vector<Eigen::MatrixXd> groups;
  const size_t step = static_cast<size_t>(std::max(r, 1));
  for (size_t i = 0; i < factors.size(); i += step)
    groups.push_back(ProductOfFactors(factors, i, std::min(factors.size(), i + step), added));
  return groups;
}

// Step 2: the multipliers as logarithms. Periodic Schur (SLICOT MB03BD) rarely fails to
// converge (INFO > 0: nearly triple multipliers of isotropic rotors); a failed analysis would
// then cost the user the whole result, so it falls back: first the same method on the product
// regrouped into pairs (another problem for the iteration, equally accurate while the pairs'
// condition stays moderate), then the eigenvalues of the formed product (single shot), whose
// lost accuracy the error estimate then carries (SingleShotError). `note` says which was used.
LogEigenvalues MultiplierLogs(const internal::SegmentGrid& grid, MultiplierMethod method, int n,
                              std::string* note = nullptr, bool* single_shot = nullptr) {
  auto formed = [&] {
    return SingleShotLogEigenvalues(grid.factors.empty()
                                        ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, n))
                                        : ProductOfFactors(grid.factors, 0, grid.factors.size()));
  };
  if (single_shot) *single_shot = method == MultiplierMethod::kSingleShot;
  if (method == MultiplierMethod::kSingleShot) return formed();
  LogEigenvalues eig = PeriodicSchurLogEigenvalues(grid.factors);
  if (eig.ok) return eig;
  const std::string first = eig.message;
  if (grid.factors.size() >= 2) {
    const std::vector<Eigen::MatrixXd> pairs = GroupedFactors(grid.factors, 2);
    eig = PeriodicSchurLogEigenvalues(pairs);
    if (eig.ok) {
      if (note)
        *note = first + "; the multipliers are from periodic Schur of the product regrouped into " +
                std::to_string(pairs.size()) + " factors instead";
      return eig;
    }
  }
  eig = formed();
  if (eig.ok) {
    if (single_shot) *single_shot = true;
    if (note)
      *note = first +
              "; the multipliers are the eigenvalues of the formed product (single shot) "
              "instead: each carries the error eps·max|ρ|/|ρ_k| in the estimate";
  }
  return eig;
}

// The error single-shot multipliers add: the formed product carries a backward error of about
// n·eps·max|ρ|, which moves log ρ_k by κ_k n eps max|ρ|/|ρ_k|; beyond 1/2 the exponent is
// undetermined (+inf). One value per exponent.
std::vector<double> SingleShotErrors(const std::vector<cd>& log_rho,
                                     const std::vector<double>& kappa, double period) {
  const int n = static_cast<int>(log_rho.size());
  double top = -std::numeric_limits<double>::infinity();
  for (const cd& l : log_rho) top = std::max(top, l.real());
  std::vector<double> errors(n);
  for (int k = 0; k < n; ++k) {
    const double relative = 16 * n * std::numeric_limits<double>::epsilon() * kappa[k] *
                            std::exp(std::min(top - log_rho[k].real(), 700.0));
    errors[k] = relative < 0.5 ? relative / period : std::numeric_limits<double>::infinity();
  }
  return errors;
}

// The refined run's grid options: the run's, reporting progress as its own phase.
internal::SegmentGridOptions RefinedRunOptions(internal::SegmentGridOptions o,
                                               const internal::AnalysisProgress& progress) {
  o.integrator.on_advance = progress.Phase("refined run");
  return o;
}

// Step 3, the error estimate: a second run on a different grid at a 100× tighter tolerance
// (twice the fixed steps). A different grid matters: on short segments an adaptive method may
// take the same single step at both tolerances, and a same-grid comparison would then see no
// difference at all. With modes every segment is halved (the mode samples stay on grid
// points); without, the boundaries move to the segments' midpoints: K + 1 segments instead of
// 2K, each integrated differently (200-state OpenFAST set: 13.3 → 10.3 s, estimates as large,
// errors 0.006–0.12 of them). The reported numbers come from this better run (grid and eig are
// replaced), so the difference bounds their error with a wide margin.
// Returns each exponent's integration error, in the order of the new `eig` (∞ when the
// reference run failed).
std::vector<double> RefineForErrorEstimate(const PeriodicSystem& system,
                                           const FloquetOptions& options,
                                           internal::SegmentGridOptions fine, int mode_samples,
                                           internal::SegmentGrid& grid, LogEigenvalues& eig,
                                           FloquetResult& r) {
  fine.refine = false;
  fine.integrator.carry_local_errors = false;  // a fallback from kLocalErrors: nothing to carry
  fine.fixed_times.clear();
  fine.fixed_times.push_back(grid.times.front());
  for (size_t i = 0; i + 1 < grid.times.size(); ++i) {
    if (options.compute_modes && i > 0) fine.fixed_times.push_back(grid.times[i]);
    fine.fixed_times.push_back(0.5 * (grid.times[i] + grid.times[i + 1]));
  }
  fine.fixed_times.push_back(grid.times.back());
  // The mode samples on grid points too: their shapes then come from the periodic eigenvectors
  // at the grid points, not from a further integration within segments (FE rotor, 120 states:
  // 21.5 → 10.7 s). Not for exact exponentials, where a sample costs a few matrix exponentials
  // and the extra segments' share of the periodic eigenvectors is the larger cost (a constant
  // 400-state A: 16 s with the samples propagated, 42 s on the grid).
  const double T = system.period();
  if (fine.integrator.type == IntegratorType::kExpm) mode_samples = 0;
  for (int s = 1; s < mode_samples; ++s) fine.fixed_times.push_back(T * s / mode_samples);
  std::sort(fine.fixed_times.begin(), fine.fixed_times.end());
  fine.fixed_times.erase(std::unique(fine.fixed_times.begin(), fine.fixed_times.end(),
                                     [T](double a, double b) { return b - a <= 1e-12 * T; }),
                         fine.fixed_times.end());
  IntegratorOptions run = fine.integrator;  // the run's integrator (resolved), its tolerances
  run.rel_tol = options.integrator.rel_tol;
  run.abs_tol = options.integrator.abs_tol;
  fine.integrator = RefinedIntegratorOptions(run);
  internal::SegmentGrid reference = internal::ComputeSegmentGrid(system, fine);
  r.rhs_evals += reference.rhs_evals;
  LogEigenvalues ref_eig = reference.ok
                               ? MultiplierLogs(reference, options.multipliers, system.states())
                               : LogEigenvalues{};
  if (!ref_eig.ok) {
    r.diagnostics.push_back({DiagnosticCode::kErrorEstimateFailed, Severity::kWarning,
                             "error estimate: the refined reference run failed; results are "
                             "from the first run and their error is unknown"});
    return std::vector<double>(eig.log_values.size(), std::numeric_limits<double>::infinity());
  }
  std::vector<double> errors = MatchExponents(ref_eig.log_values, eig.log_values, 2 * kPi);
  for (double& e : errors) e /= system.period();
  grid = std::move(reference);
  eig = std::move(ref_eig);
  return errors;
}

// Step 2 for an analysis whose mode shapes will come from this grid (no refined run replaces
// it): the factors' periodic Schur form with its vectors, whose diagonal gives the multipliers
// as well — one periodic QZ instead of an eigenvalue-only one and then the same with vectors
// (250-state turbine set: the eigenvalue-only QZ took 0.27 s beside the form's 0.66 s). Empty
// otherwise, or when the QZ did not converge: MultiplierLogs and its fallbacks then take over.
// `factors` are `grid`'s, or those in the groups FactorsPerForm allows: the vectors inside a
// group then come from the grid's factors (SchurPeriodicEigenvectors).
std::optional<PeriodicSchurForm> FormForTheShapes(const internal::SegmentGrid& grid,
                                                  const std::vector<Eigen::MatrixXd>& factors,
                                                  const FloquetOptions& options, int n) {
  const bool final_grid = !options.estimate_error || !grid.local_error_effects.empty();
  if (!options.compute_modes || n == 0 || !final_grid ||
      options.multipliers != MultiplierMethod::kPeriodicSchur)
    return std::nullopt;
  PeriodicSchurForm form = PeriodicSchurDecomposition(factors);
  if (!form.ok) return std::nullopt;
  return form;
}

// How many consecutive factors of an automatic grid the multipliers' periodic Schur form takes
// as one: those StartingGrid merges, whose products stay within the condition limit. The grid
// was cut finer only to put the mode samples on grid points, and a form's cost is linear in its
// factors (250-state turbine set: K = 32 in groups of 2, the whole call 0.89× side by side).
// A group is as well conditioned as a factor of a grid refined without samples, so the
// round-off floor's model holds for it too; vectors inside it that lose more than the cyclic
// residual allows go to the inverse iteration. 1 for a grid the user gave.
int FactorsPerForm(const internal::SegmentGrid& grid,
                   const internal::SegmentGridOptions& grid_options, double max_condition) {
  if (!grid_options.refine) return 1;
  return static_cast<int>(grid.factors.size()) / StartingGrid(grid, max_condition);
}

// The eigenvalues of the factors moved by their carried local errors, Φ_i + δΦ_i — the period
// integrated as a run held only to the tolerance would be (Bulirsch–Stoer one extrapolation
// order lower, to first order; Taylor series at order p; the Magnus methods at half the steps)
// — grouped as the multipliers' form was (`group`, FactorsPerForm). They do not depend on that
// form, so the analysis finds them beside it on another thread.
LogEigenvalues MovedFactorLogs(const internal::SegmentGrid& grid, MultiplierMethod method,
                               int group, int n) {
  internal::SegmentGrid moved;
  moved.factors = GroupedFactors(grid.factors, group, &grid.local_error_effects);
  return MultiplierLogs(moved, method, n);
}

// Step 3 when the integrator carried its local errors: the exponents of the moved factors
// (MovedFactorLogs) against the factors' own (docs/local-error-estimate.md). Returns each
// exponent's difference (∞ when the moved factors' eigenvalues failed).
std::vector<double> LocalErrorEstimate(const LogEigenvalues& eig, const LogEigenvalues& moved_eig,
                                       double period, FloquetResult& r) {
  if (!moved_eig.ok) {
    r.diagnostics.push_back(
        {DiagnosticCode::kErrorEstimateFailed, Severity::kWarning,
         "error estimate: the eigenvalues of the factors moved by their local errors failed; "
         "the error is unknown"});
    return std::vector<double>(eig.log_values.size(), std::numeric_limits<double>::infinity());
  }
  std::vector<double> errors = MatchExponents(eig.log_values, moved_eig.log_values, 2 * kPi);
  for (double& e : errors) e /= period;
  return errors;
}

// Near-ties of the branch choice, one line per kind with the modes' numbers (a rotor at three
// azimuths has twenty negative real multipliers).
void ReportBranchTies(FloquetResult& r) {
  std::vector<int> strip_edge, ambiguous;
  double smallest_margin = 1;
  for (size_t k = 0; k < r.modes.size(); ++k) {
    const FloquetMode& m = r.modes[k];
    if (!(m.branch_margin < 0.05) || !std::isfinite(m.eigvec_residual)) continue;
    if (std::abs(std::abs(m.log_multiplier.imag()) - kPi) < 1e-6) {
      strip_edge.push_back(static_cast<int>(k) + 1);
    } else {
      ambiguous.push_back(static_cast<int>(k) + 1);
      smallest_margin = std::min(smallest_margin, m.branch_margin);
    }
  }
  auto modes = [](const std::vector<int>& list) {
    std::ostringstream s;
    s << (list.size() == 1 ? "mode " : "modes ");
    for (size_t i = 0; i < list.size(); ++i) s << (i ? ", " : "") << list[i];
    return s.str();
  };
  if (!strip_edge.empty())
    r.diagnostics.push_back({DiagnosticCode::kBranchOnStripEdge, Severity::kNote,
                             modes(strip_edge) + ": negative real multiplier" +
                                 (strip_edge.size() > 1 ? "s" : "") +
                                 ", so the exponent sits on the strip edge: Im λ = +Ωp/2 and −Ωp/2 "
                                 "(mod Ωp) describe the "
                                 "same solution; the non-negative one is reported"});
  if (!ambiguous.empty()) {
    std::ostringstream s;
    s << modes(ambiguous) << ": branch ambiguous (margin down to " << smallest_margin
      << "): the mode shape's Fourier energy is split between two neighbouring harmonics; the "
         "smaller non-negative frequency was taken";
    r.diagnostics.push_back({DiagnosticCode::kBranchAmbiguous, Severity::kNote, s.str()});
  }
}

// Step 5: modes ordered by |frequency|, positive first, then by Re λ; samples and Fourier
// coefficients permuted alike; near-ties of the branch choice reported.
void StoreOrderedModes(const PeriodicSystem& system, const std::vector<FloquetMode>& modes,
                       bool with_shapes, FloquetResult& r) {
  const int n = static_cast<int>(modes.size());
  const std::vector<int> order = ModeDisplayOrder(modes);
  for (int k : order) r.modes.push_back(modes[k]);
  if (with_shapes) ReportBranchTies(r);
  if (r.mode_samples.empty()) return;
  auto permute = [&](Eigen::MatrixXcd& m) {
    Eigen::MatrixXcd p(m.rows(), m.cols());
    for (int j = 0; j < n; ++j) p.col(j) = m.col(order[j]);
    m = p;
  };
  for (auto& m : r.mode_samples) permute(m);
  for (auto& m : r.mode_fourier) permute(m);
  r.mode_descriptions = DescribeModeShapes(system.labels(), r.mode_samples.front());
  internal::AssignWhirl(system, r);
}

// Round-off floor of each exponent (1/s): every factor carries a backward error of a few eps,
// K + n of them accumulate; an eigenvalue moves by κ_k times that, or by its square root when
// the eigenvalue is defective (κ = ∞), and every exponent by backward · max|log ρ| / T. Every
// step of a fixed-step method is a product of its own that no error control sees: S of them,
// each off by up to n eps, add up like a random walk, n √S (Magnus 4 at 4096 steps per period
// on tower-rotor: the difference to the refined run, 1.1e-7, had fallen below the true error,
// 1.55e-7; the worst case, S n eps, over-estimates the study's errors 10–10⁴×).
std::vector<double> RoundOffFloors(const std::vector<cd>& log_rho, const std::vector<double>& kappa,
                                   int segments, long fixed_steps, double period) {
  const int n = static_cast<int>(log_rho.size());
  const double steps_term = n * std::sqrt(static_cast<double>(fixed_steps));
  const double backward = 16 * std::numeric_limits<double>::epsilon() * (segments + n + steps_term);
  double max_abs_log = 0;
  for (const cd& l : log_rho)
    if (std::isfinite(l.real())) max_abs_log = std::max(max_abs_log, std::abs(l));
  std::vector<double> floors(n);
  for (int k = 0; k < n; ++k)
    floors[k] =
        std::max(std::min(kappa[k] * backward, 2 * std::sqrt(backward)), backward * max_abs_log) /
        period;
  return floors;
}

// Step 6b: max Re λ, the error estimate (the largest integration error plus the largest
// round-off floor: a bound on every exponent), the Liouville check and the verdict, which asks
// it of each exponent with its own estimate (FloquetMode::error_estimate).
void SummariseAndCheck(const PeriodicSystem& system, const std::vector<cd>& log_rho,
                       double integration_error, double floor, const FloquetOptions& options,
                       FloquetResult& r) {
  const int n = r.states;
  const double T = r.period;
  r.max_real_exponent = internal::MaxRealExponent(r.modes);
  r.max_log_abs_multiplier = r.max_real_exponent * T;
  double sum_log_abs = 0;
  for (const cd& l : log_rho) sum_log_abs += l.real();
  const double trace_integral = IntegralOfTrace(system);
  r.liouville_residual =
      std::abs(sum_log_abs - trace_integral) / std::max(1.0, std::abs(trace_integral));
  if (options.estimate_error) r.error_estimate = integration_error + floor;
  // Liouville: Σ log|ρ_k| = ∫ tr A exactly, and every exponent is within the estimate, so the
  // sum is within n·T·estimate of it. Beyond that some exponents are wrong — e.g. forced
  // settings: one segment with single-shot multipliers loses every |ρ| below eps·max|ρ| — and
  // the result is not ok. Without an estimate only a gross failure can be told from the
  // integration's own error: the allowance is then 1e4 × the tolerance (at least 1e-6),
  // relative.
  const double gross =
      std::max(1e-6, 1e4 * options.integrator.rel_tol) * std::max(1.0, std::abs(trace_integral));
  const double liouville_allowance =
      options.estimate_error
          ? std::max(n * T * *r.error_estimate, 1e-6 * std::max(1.0, std::abs(trace_integral)))
          : gross;
  if (std::abs(sum_log_abs - trace_integral) <= liouville_allowance) {
    r.Complete();
  } else {
    std::ostringstream s;
    s << "Liouville check failed: Σ log|ρ| = " << sum_log_abs
      << " but ∫ tr A dt = " << trace_integral << ", beyond what the error estimate allows ("
      << liouville_allowance
      << "): some exponents are wrong (too few segments, single-shot multipliers or too loose a "
         "tolerance for this system; the automatic settings avoid this)";
    r.Fail(Termination::kChecksFailed, s.str());
    r.diagnostics.push_back({DiagnosticCode::kLiouvilleCheckFailed, Severity::kFailure, s.str()});
  }
  std::optional<double> band = r.error_estimate;
  if (r.error_estimate) band = PerModeBand(r.modes, r.max_real_exponent, *r.error_estimate);
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, band);
  r.stable = r.verdict == StabilityVerdict::kStable;
  if (r.verdict == StabilityVerdict::kMarginal && r.error_estimate)
    r.diagnostics.push_back({DiagnosticCode::kStabilityMarginal, Severity::kWarning,
                             "stability undecided (marginal): |max Re λ| is within the error "
                             "estimate (a conservative system, or one on a stability boundary)"});
  const bool decided_by_own_estimates =
      r.error_estimate && r.verdict != StabilityVerdict::kMarginal &&
      r.verdict != StabilityVerdict::kFailed &&
      ClassifyStability(r.ok, r.max_real_exponent, r.error_estimate) == StabilityVerdict::kMarginal;
  if (decided_by_own_estimates) {
    std::ostringstream s;
    s << "verdict: max Re λ is within ±" << *band
      << " 1/s — each exponent with its own estimate; the largest, " << *r.error_estimate
      << " 1/s, belongs to exponents far from the stability boundary";
    r.diagnostics.push_back({DiagnosticCode::kVerdictPerModeBand, Severity::kNote, s.str()});
  }
}

}  // namespace

namespace {

// What the analysis runs on: the states balanced (docs/model-sizes.md), the integrator resolved.
struct Setup {
  Eigen::VectorXd scale;  ///< x = S z; empty when the given states are used
  PeriodicSystem system;  ///< in the balanced states
  FloquetOptions options;
  std::optional<SystemTraits> traits;  ///< measured when the integrator was auto
  double period_scale = 1;
  ErrorEstimateMethod requested_estimate = ErrorEstimateMethod::kAuto;  ///< before resolution
};

// Bulirsch–Stoer and Taylor series carry their steps' local errors; Magnus 4, 6 and Magnus–Filon
// keep the doubling loop's coarse pass when they choose their steps (docs/local-error-estimate.md).
bool CarriesLocalErrors(const IntegratorOptions& integrator) {
  switch (integrator.type) {
    case IntegratorType::kBulirschStoer:
    case IntegratorType::kTaylor:
      return true;
    case IntegratorType::kMagnus4:
    case IntegratorType::kMagnus6:
    case IntegratorType::kMagnusFilon:
      return integrator.steps_per_period == 0;
    default:
      return false;
  }
}

// `auto`: the carried local errors where the numbers they leave are still far more accurate
// than the estimate (Taylor series' order p + 4, the Magnus methods' finer pass), else the
// refined run (ErrorEstimateMethod::kAuto).
ErrorEstimateMethod ResolveEstimateMethod(ErrorEstimateMethod requested,
                                          const IntegratorOptions& integrator) {
  if (requested != ErrorEstimateMethod::kAuto) return requested;
  return integrator.type != IntegratorType::kBulirschStoer && CarriesLocalErrors(integrator)
             ? ErrorEstimateMethod::kLocalErrors
             : ErrorEstimateMethod::kRefinedRun;
}

// States in units far apart (a finite-element rotor's metres and radians, stiffness entries of
// 1e9 N/m) are rescaled by powers of two before anything is measured or integrated; shapes and
// monodromy are scaled back at the end. Says so, and which integrator auto chose, in r.
Setup Prepare(const PeriodicSystem& given, const FloquetOptions& requested, FloquetResult& r) {
  const Eigen::VectorXd scale = internal::StateBalancing(given);
  Setup s{scale, scale.size() ? given.WithStateScaling(scale) : given, requested, {}, 1};
  s.period_scale = CheckPeriodScale(s.system, requested.max_period_scale);
  if (scale.size()) {
    std::ostringstream d;
    d << "states rescaled by powers of two from 2^" << std::lround(std::log2(scale.minCoeff()))
      << " to 2^" << std::lround(std::log2(scale.maxCoeff()))
      << " (diagonal balancing of A, exact) for the integration; results are in the given states";
    r.diagnostics.push_back({DiagnosticCode::kStatesBalanced, Severity::kNote, d.str()});
  }
  std::string choice;
  if (requested.integrator.type == IntegratorType::kAuto) s.traits = MeasureSystemTraits(s.system);
  s.options.integrator =
      ResolveIntegrator(s.system, requested.integrator, &choice, s.traits ? &*s.traits : nullptr);
  if (!choice.empty())
    r.diagnostics.push_back(
        {DiagnosticCode::kIntegratorChosen, Severity::kNote,
         "integrator auto → " + std::string(ToString(s.options.integrator.type)) + ": " + choice});
  s.requested_estimate = requested.error_estimate_method;
  s.options.error_estimate_method =
      ResolveEstimateMethod(requested.error_estimate_method, s.options.integrator);
  r.states = s.system.states();
  r.period = s.system.period();
  r.integrator = s.options.integrator.type;
  r.multiplier_method = s.options.multipliers;
  return s;
}

// Integrators whose error is a backward error of each step's generator: Magnus 4/6, Magnus–Filon
// and products of exponentials (the truncated series, or the exponential's rounding, is an
// error in the exponent). In the mean's modes that error sits on each mode's own scale, so their
// segments may be limited by the spread of the modes' rates instead of the states' condition
// (docs/model-sizes.md, "Segments in the mean's modes"). The basis may add at most as many
// digits as the condition limit: cond W ≤ 1e4.
std::optional<Eigen::MatrixXd> ModalBasisForTheGrid(const Setup& s) {
  switch (s.options.integrator.type) {
    case IntegratorType::kMagnus4:
    case IntegratorType::kMagnus6:
    case IntegratorType::kMagnusFilon:
    case IntegratorType::kExpm:
      return internal::RealModalBasis(MeanOfA(s.system), 1e4);
    default:
      return std::nullopt;
  }
}

// Step 3: each exponent's integration error, in eig's order — the carried local errors (the
// moved factors' eigenvalues, `moved_eig`), or a refined run whose grid and multipliers then
// replace `grid` and `eig` (zeros without an estimate).
std::vector<double> IntegrationErrors(const Setup& s,
                                      const internal::SegmentGridOptions& grid_options,
                                      const internal::AnalysisProgress& progress, int samples,
                                      const LogEigenvalues* moved_eig, internal::SegmentGrid& grid,
                                      LogEigenvalues& eig, FloquetResult& r) {
  const int n = r.states;
  const FloquetOptions& options = s.options;
  r.error_estimate_method = grid.local_error_effects.empty() ? ErrorEstimateMethod::kRefinedRun
                                                             : ErrorEstimateMethod::kLocalErrors;
  // Worth a note: local errors that were not finite, or asked of an integrator the user named
  // that carries none. Under `auto` (integrator or estimate) the estimate follows the integrator
  // chosen, and r.error_estimate_method says which.
  const bool carrier = CarriesLocalErrors(options.integrator);
  const bool asked = s.requested_estimate == ErrorEstimateMethod::kLocalErrors && !s.traits;
  if (options.estimate_error && n > 0 && (carrier || asked) &&
      options.error_estimate_method != r.error_estimate_method)
    r.diagnostics.push_back(
        {DiagnosticCode::kErrorEstimateFallback, Severity::kNote,
         carrier ? "error estimate: the carried local errors were not finite (a singular step "
                   "matrix, an overflowing series, or fixed steps that did not reach the "
                   "tolerance); the refined run instead"
                 : "error estimate: local errors are carried by Bulirsch–Stoer, Taylor series and "
                   "the Magnus methods choosing their own steps only; " +
                       std::string(ToString(options.integrator.type)) +
                       (options.integrator.steps_per_period > 0 ? " with fixed steps" : "") +
                       " gets the refined run instead"});
  if (!options.estimate_error || n == 0) return std::vector<double>(n, 0.0);
  return r.error_estimate_method == ErrorEstimateMethod::kLocalErrors
             ? LocalErrorEstimate(eig, *moved_eig, r.period, r)
             : RefineForErrorEstimate(s.system, options, RefinedRunOptions(grid_options, progress),
                                      options.compute_modes ? samples : 0, grid, eig, r);
}

// Step 4: the modes with their periodic shapes (sampled on the uniform mode grid) or, without
// shapes, on the principal branch; returns each multiplier's condition number (1 without).
std::vector<double> ComputeModes(const Setup& s, const internal::SegmentGrid& grid,
                                 const LogEigenvalues& eig, int samples, bool constant,
                                 const PeriodicSchurForm* form,
                                 const internal::AnalysisProgress& progress,
                                 std::vector<FloquetMode>& modes, FloquetResult& r) {
  const int n = r.states;
  modes.resize(n);
  for (int k = 0; k < n; ++k) modes[k] = MakeFloquetMode(eig.log_values[k], 0, r.period);
  if (!s.options.compute_modes || n == 0) {
    r.diagnostics.push_back({DiagnosticCode::kModesNotComputed, Severity::kNote,
                             "branch: principal logarithm (modes not computed)"});
    return std::vector<double>(n, 1.0);
  }
  IntegratorOptions shape_integrator = s.options.integrator;
  shape_integrator.on_advance = progress.Phase("mode shapes");
  internal::ModeShapes shapes =
      internal::ComputeModeShapes(s.system, grid, eig.log_values, samples, shape_integrator,
                                  ThreadsFor(s.options.threads), constant, form);
  r.rhs_evals += shapes.rhs_evals;
  for (auto& d : shapes.diagnostics) r.diagnostics.push_back(std::move(d));
  modes = std::move(shapes.modes);
  r.sample_times = std::move(shapes.sample_times);
  r.mode_samples = std::move(shapes.samples);
  r.mode_fourier = std::move(shapes.fourier);
  r.mode_harmonics = shapes.harmonics;
  r.mode_condition = shapes.condition;
  return std::move(shapes.kappa);
}

// Steps 5–6: the monodromy and shapes back in the given states, each exponent's own estimate
// (integration + round-off floor, + the lost accuracy of a single-shot fallback), the modes
// ordered and rigid-body ones flagged, the summary numbers and checks.
void Finish(const Setup& s, const internal::SegmentGrid& grid, const LogEigenvalues& eig,
            const std::vector<double>& kappa, bool single_shot_fallback,
            std::vector<double> integration, std::vector<FloquetMode> modes, FloquetResult& r) {
  const int n = r.states;
  const double T = r.period;
  if (s.scale.size()) {  // back to the given states: x = S z
    r.monodromy = s.scale.asDiagonal() * r.monodromy * s.scale.cwiseInverse().asDiagonal();
    for (Eigen::MatrixXd& f : r.segment_factors)
      f = s.scale.asDiagonal() * f * s.scale.cwiseInverse().asDiagonal();
    for (Eigen::MatrixXcd& m : r.mode_samples) m = s.scale.asDiagonal() * m;
    for (Eigen::MatrixXcd& m : r.mode_fourier) m = s.scale.asDiagonal() * m;
  }
  // A fallback to single shot (the user did not ask for it) carries its lost accuracy.
  if (single_shot_fallback) {
    const std::vector<double> lost = SingleShotErrors(eig.log_values, kappa, T);
    for (int k = 0; k < n; ++k) integration[k] += lost[k];
  }
  const std::vector<double> floors =
      RoundOffFloors(eig.log_values, kappa, r.segments, grid.fixed_steps, T);
  // Own estimates only from periodic Schur: single-shot multipliers below eps·max|ρ| are lost
  // to the formed product in both runs alike, so their difference says nothing of them (a
  // −2000 1/s exponent off by 213 with a difference of 146); the verdict then uses the
  // common estimate.
  if (s.options.estimate_error && s.options.multipliers == MultiplierMethod::kPeriodicSchur)
    for (int k = 0; k < n; ++k) modes[k].error_estimate = integration[k] + floors[k];
  StoreOrderedModes(s.system, modes, s.options.compute_modes, r);
  // The rigid rotation of a free angle (rigid_body.h), from the mode shapes at t = 0.
  for (std::string& line : internal::FlagRigidBodyModes(
           s.system.labels(), r.mode_samples.empty() ? Eigen::MatrixXcd() : r.mode_samples.front(),
           r.modes))
    r.diagnostics.push_back({DiagnosticCode::kRigidBodyMode, Severity::kNote, std::move(line)});
  const double largest_integration =
      n > 0 ? *std::max_element(integration.begin(), integration.end()) : 0.0;
  const double largest_floor = n > 0 ? *std::max_element(floors.begin(), floors.end()) : 0.0;
  SummariseAndCheck(s.system, eig.log_values, largest_integration, largest_floor, s.options, r);
}

}  // namespace

FloquetResult AnalyzeFloquet(const PeriodicSystem& given, const FloquetOptions& requested) {
  requested.Validate();
  if (requested.modes_below > 0) return internal::AnalyzeModesBelow(given, requested);
  const auto start = std::chrono::steady_clock::now();
  FloquetResult r;
  Setup s = Prepare(given, requested, r);
  FloquetOptions& options = s.options;
  const int n = r.states;

  // 1. Segment factors on a grid refined where factors grow or decay too fast.
  const int mode_samples =
      options.mode_samples > 0 ? options.mode_samples : AutoModeSamples(s.system);
  const int samples = options.compute_modes ? mode_samples : 1;
  // Without modes a small system starts from one segment. A large one starts from the grid it
  // would have with modes: one period of it is nearly always beyond the condition limit, and
  // refining from one segment costs extra rounds and ends on more segments (60-state OpenFAST
  // set: K = 48 from 1, 27 from 8).
  const int grid_samples = n > kSmallSystemStates ? mode_samples : samples;
  WeighTheWork(s.system, s.traits, options, s.period_scale, grid_samples, r);
  const internal::AnalysisProgress progress(options.on_progress, r.period);
  // A(t) the same at every t, as the integrator choice measured it (its traits: constant
  // between breakpoints and none inside the period); unknown, so false, when the user chose
  // the integrator.
  const bool constant = s.traits && s.traits->constant_pieces && !s.traits->has_jumps;
  internal::SegmentGridOptions grid_options = GridOptionsFor(options, grid_samples, n, constant);
  // Only a grid that refines measures its factors' conditions.
  if (grid_options.refine) grid_options.modal_basis = ModalBasisForTheGrid(s);
  grid_options.integrator.on_advance = progress.Phase("run");
  internal::SegmentGrid grid = internal::ComputeSegmentGrid(s.system, grid_options);
  r.rhs_evals += grid.rhs_evals;
  // One line per failing segment would flood the reader (a NaN from t > 1 on: 19 945 lines).
  for (auto& d : CollapseRepeated(grid.diagnostics)) r.diagnostics.push_back(std::move(d));
  if (options.segments == 0 && grid.ok)
    r.diagnostics.push_back(
        {DiagnosticCode::kSegmentsChosen, Severity::kNote,
         DescribeSegmentChoice(grid, options, grid_options.modal_basis.has_value())});
  if (!grid.ok) {
    r.Fail(Termination::kIntegrationFailed,
           grid.diagnostics.empty() ? "the integration of the period failed"
                                    : "integration failed: " + grid.diagnostics.front().text);
    r.elapsed_s = SecondsSince(start);
    return r;
  }
  // 2. Multipliers as logarithms; beside their form, on another thread, the eigenvalues of the
  // factors moved by their local errors (step 3): two serial periodic QZ runs that need nothing
  // of each other (250-state set: 0.1–0.3 s each, in each of its three models).
  std::string fallback;
  bool single_shot = false;
  const int group = FactorsPerForm(grid, grid_options, options.max_factor_condition);
  const MultiplierMethod method = options.multipliers;
  std::future<LogEigenvalues> moved;
  if (options.estimate_error && n > 0 && !grid.local_error_effects.empty())
    moved =
        std::async(ThreadsFor(options.threads) > 1 ? std::launch::async : std::launch::deferred,
                   [&grid, method, group, n] { return MovedFactorLogs(grid, method, group, n); });
  internal::SegmentGrid grouped;  // the factors the multipliers come from, when grouped
  if (group > 1) grouped.factors = GroupedFactors(grid.factors, group);
  const internal::SegmentGrid& multiplier_grid = group > 1 ? grouped : grid;
  std::optional<PeriodicSchurForm> form =
      FormForTheShapes(grid, multiplier_grid.factors, options, n);
  LogEigenvalues eig =
      form ? LogEigenvaluesOf(*form)
           : MultiplierLogs(multiplier_grid, options.multipliers, n, &fallback, &single_shot);
  grouped.factors.clear();  // K/group n² numbers, not held while the analysis goes on
  if (!fallback.empty()) {
    r.diagnostics.push_back({single_shot ? DiagnosticCode::kMultipliersSingleShot
                                         : DiagnosticCode::kMultipliersRegrouped,
                             single_shot ? Severity::kWarning : Severity::kNote, fallback});
    if (single_shot) {  // the refined run and the local errors use the same method
      options.multipliers = MultiplierMethod::kSingleShot;
      r.multiplier_method = MultiplierMethod::kSingleShot;
    }
  }
  if (!eig.ok) {
    r.Fail(Termination::kEigenvaluesFailed, "eigenvalues of the monodromy failed: " + eig.message);
    r.diagnostics.push_back({DiagnosticCode::kMultipliersFailed, Severity::kFailure, r.failure});
    r.elapsed_s = SecondsSince(start);
    return r;
  }
  r.grid_segments = grid_options.refine ? StartingGrid(grid, options.max_factor_condition)
                                        : static_cast<int>(grid.factors.size());
  // 3. Error estimate (after a refined run the numbers come from it). A fallback to the
  // single-shot multipliers moves the factors' eigenvalues the same way.
  std::optional<LogEigenvalues> moved_eig;
  if (moved.valid()) {
    moved_eig = moved.get();
    if (options.multipliers != method)
      moved_eig = MovedFactorLogs(grid, options.multipliers, group, n);
  }
  std::vector<double> integration = IntegrationErrors(
      s, grid_options, progress, samples, moved_eig ? &*moved_eig : nullptr, grid, eig, r);
  r.segments = static_cast<int>(grid.factors.size());
  r.segment_times = grid.times;
  r.monodromy = grid.factors.empty() ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, n))
                                     : ProductOfFactors(grid.factors, 0, grid.factors.size());
  if (options.keep_segment_factors) r.segment_factors = grid.factors;
  // 4. Modes: periodic eigenvectors at the grid points, samples on the uniform mode grid.
  std::vector<FloquetMode> modes;
  const std::vector<double> kappa =
      ComputeModes(s, grid, eig, samples, constant, form ? &*form : nullptr, progress, modes, r);
  form.reset();  // 2 K n² numbers, not held while the analysis finishes
  // 5–6. Estimates per exponent, order, rigid-body modes, summary and checks.
  Finish(s, grid, eig, kappa, single_shot && !fallback.empty(), std::move(integration),
         std::move(modes), r);
  r.elapsed_s = SecondsSince(start);
  return r;
}

std::function<void(std::string_view, double)> PrefixedProgress(
    std::function<void(std::string_view, double)> sink, std::string prefix) {
  if (!sink) return {};
  return [sink = std::move(sink), prefix = std::move(prefix)](std::string_view phase, double f) {
    sink(prefix + std::string(phase), f);
  };
}

}  // namespace ltp
