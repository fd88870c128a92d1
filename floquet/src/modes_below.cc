#include "modes_below.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "floquet_modes.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/exponent_match.h"
#include "ltp/core/mode_description.h"
#include "ltp/floquet/detail/rigid_body.h"
#include "ltp/floquet/model_error.h"
#include "ltp/integrate/detail/state_balancing.h"
#include "spectral_split.h"
#include "truncation_tail.h"

namespace ltp::internal {
namespace {

using cd = std::complex<double>;

// q' = Wᵀ A(t) U q, in the form the system has: Fourier coefficients and samples are projected
// once; a time function is projected at every evaluation.
PeriodicSystem Projected(const PeriodicSystem& s, const SpectralSplit& split) {
  const Eigen::MatrixXd wt = split.left.transpose();
  const Eigen::MatrixXd& u = split.right;
  const int k = static_cast<int>(u.cols());
  PeriodicSystem out = [&] {
    if (const FourierMatrix* fa = s.fourier_A()) {
      FourierMatrix r(k, k, fa->max_harmonic());
      for (int w = 0; w <= fa->max_harmonic(); ++w)
        r.SetHarmonic(w, wt.cast<cd>() * (*fa)[w] * u.cast<cd>());
      return PeriodicSystem::FromFourier(s.period(), r);
    }
    if (s.form() == PeriodicSystem::Form::kPiecewiseConstant) {
      std::vector<LtiSystem> samples;
      for (const LtiSystem& x : s.samples()) samples.push_back({wt * x.A * u, {}, {}, {}});
      return PeriodicSystem::FromSamples(s.period(), s.sample_times(), samples);
    }
    PeriodicSystem::Functions f;
    const int n = s.states();
    f.A = [s, wt, u, n](double t, Eigen::Ref<Eigen::MatrixXd> out) {
      thread_local Eigen::MatrixXd a;
      a.resize(n, n);
      s.EvalA(t, a);
      out.noalias() = wt * (a * u);
    };
    return PeriodicSystem::FromFunctions(s.period(), k, 0, 0, f, s.breakpoints());
  }();
  return s.rotor_speed() ? out.WithRotorSpeed(*s.rotor_speed()) : out;
}

// max_t ‖A(t) − Ā‖_F: Σ_w ‖A_w‖_F over the harmonics (a bound) for a Fourier series, else the
// largest of the samples, or of 64 times for a time function.
double PeriodicPart(const PeriodicSystem& s, const Eigen::MatrixXd& mean) {
  if (const FourierMatrix* fa = s.fourier_A()) {
    double sum = 0;
    for (int w = 1; w <= fa->max_harmonic(); ++w) sum += 2 * (*fa)[w].norm();
    return sum;
  }
  double largest = 0;
  if (s.form() == PeriodicSystem::Form::kPiecewiseConstant) {
    for (const LtiSystem& x : s.samples()) largest = std::max(largest, (x.A - mean).norm());
    return largest;
  }
  Eigen::MatrixXd a(s.states(), s.states());
  for (int i = 0; i < 64; ++i) {
    s.EvalA((i + 0.5) * s.period() / 64, a);
    largest = std::max(largest, (a - mean).norm());
  }
  return largest;
}

// The reduced result's shapes in the given states: x = S U q for the columns `keep`.
Eigen::MatrixXcd ToStates(const Eigen::MatrixXcd& q, const Eigen::MatrixXd& u,
                          const Eigen::VectorXd& scale, const std::vector<int>& keep) {
  Eigen::MatrixXcd picked(q.rows(), keep.size());
  for (size_t j = 0; j < keep.size(); ++j) picked.col(j) = q.col(keep[j]);
  Eigen::MatrixXcd x = u.cast<cd>() * picked;
  if (scale.size()) x = scale.cast<cd>().asDiagonal() * x;
  return x;
}

// The left eigenvectors (rows) in the given states of the modes `keep` of the reduced shapes
// q (complete, square): for x = S U q, q = Wᵀ S⁻¹ x, so a row ℓ of q⁻¹ acts on x as ℓ Wᵀ S⁻¹.
Eigen::MatrixXcd LeftToStates(const Eigen::MatrixXcd& q, const Eigen::MatrixXd& w,
                              const Eigen::VectorXd& scale, const std::vector<int>& keep) {
  const Eigen::MatrixXcd inverse = LeftEigenvectors(q);
  if (inverse.size() == 0) return {};
  Eigen::MatrixXcd picked(keep.size(), inverse.cols());
  for (size_t j = 0; j < keep.size(); ++j) picked.row(j) = inverse.row(keep[j]);
  Eigen::MatrixXcd x = picked * w.transpose().cast<cd>();
  if (scale.size()) x = x * scale.cwiseInverse().cast<cd>().asDiagonal();
  return x;
}

std::string Hz(double rad_per_s) {
  std::ostringstream s;
  s << rad_per_s / (2 * std::numbers::pi) << " Hz";
  return s.str();
}

FloquetOptions Unreduced(const FloquetOptions& options, int states, bool shapes) {
  FloquetOptions o = options;
  o.modes_below = 0;
  o.compute_modes = options.compute_modes && shapes;
  o.estimate_error = options.estimate_error && shapes;  // the first run: exponents only
  o.on_progress = PrefixedProgress(options.on_progress,
                                   "modes below (" + std::to_string(states) + " states): ");
  return o;
}

// The verdict on the kept modes (each exponent with its own estimate), made `marginal` when the
// modes left out might reach Re λ ≥ 0.
void Classify(const ModalReduction& m, FloquetResult& r) {
  r.max_real_exponent = MaxRealExponent(r.modes);
  r.max_log_abs_multiplier = r.max_real_exponent * r.period;
  const std::optional<double> band =
      r.error_estimate
          ? std::optional<double>(PerModeBand(r.modes, r.max_real_exponent, *r.error_estimate))
          : std::nullopt;
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, band);
  double reach = -std::numeric_limits<double>::infinity();
  for (const cd& l : m.dropped) reach = std::max(reach, l.real() + m.periodic_part);
  if (r.verdict == StabilityVerdict::kStable && reach >= 0) {
    r.verdict = StabilityVerdict::kMarginal;
    std::ostringstream s;
    s << "stability undecided (marginal): the modes below the cut-off are stable, but those "
         "left out have mean eigenvalues up to Re λ = "
      << reach - m.periodic_part << " 1/s, and the periodic part (" << m.periodic_part
      << ") may move them past 0 — raise the cut-off or analyse every mode";
    r.diagnostics.push_back({DiagnosticCode::kStabilityMarginal, Severity::kWarning, s.str()});
  }
  r.stable = r.verdict == StabilityVerdict::kStable;
}

// The check's cut-off: twice the cut-off, and past at least the next quarter of the kept
// count (two at least) of the modes left out, nearest first — the check must add modes to
// measure anything.
double CheckCutoff(const SpectralSplit& low, double cutoff) {
  std::vector<double> beyond;
  for (const cd& l : low.dropped) beyond.push_back(std::abs(l));
  std::sort(beyond.begin(), beyond.end());
  const size_t added = std::max<size_t>(2, (low.kept.size() + 3) / 4);
  double check = kModesBelowCheck * cutoff;
  if (!beyond.empty()) check = std::max(check, beyond[std::min(added, beyond.size()) - 1]);
  return check;
}

// The reported modes: the larger projection's (`numbers`) matched to the smaller one's
// (`first`), each estimate grown by its change plus `floor`; `columns` gets each one's column
// in `numbers`' shapes. Returns the largest change (+inf when a mode found no match).
double MergeMatched(const FloquetResult& first, const FloquetResult& numbers, double omega,
                    double floor, std::vector<FloquetMode>& modes, std::vector<int>& columns) {
  std::vector<cd> a, b;
  for (const FloquetMode& x : first.modes) a.push_back(x.exponent);
  for (const FloquetMode& x : numbers.modes) b.push_back(x.exponent);
  const std::vector<int> match = MatchExponentIndices(a, b, omega);
  double largest = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (match[i] < 0) return std::numeric_limits<double>::infinity();
    const double change = ExponentDistance(a[i], b[match[i]], omega) + floor;
    largest = std::max(largest, change);
    FloquetMode mode = numbers.modes[match[i]];
    if (mode.error_estimate) *mode.error_estimate += change;
    mode.rigid_body = false;  // flagged again from the shapes in the given states
    modes.push_back(mode);
    columns.push_back(match[i]);
  }
  return largest;
}

// Twice the modes beyond the check's second-order effect (truncation_tail.h) in each
// estimate: the change between two truncations alone misses a slowly converging tail (a
// finite-element shaft whose stiffness asymmetry couples every mode: 7.6e-4 between 12 and 16
// states against a true 0.05). Returns the largest effect.
double AddTail(const PeriodicSystem& system, const Eigen::MatrixXd& mean, double cutoff,
               std::vector<FloquetMode>& modes) {
  std::vector<cd> reported;
  for (const FloquetMode& mode : modes) reported.push_back(mode.exponent);
  const std::vector<double> tail = TruncationTail(system, mean, cutoff, reported);
  double largest = 0;
  for (size_t k = 0; k < modes.size(); ++k) {
    largest = std::max(largest, tail[k]);
    if (modes[k].error_estimate) *modes[k].error_estimate += 2 * tail[k];
  }
  return largest;
}

// Grid, checks and shapes of the analysis the numbers come from, the shapes and monodromy in
// the given states (x = S U q), the modes in display order with their descriptions and the
// rigid-body flag.
void TakeFromProjection(const FloquetResult& numbers, const SpectralSplit& used,
                        const Eigen::VectorXd& scale, const SystemLabels& labels,
                        std::vector<FloquetMode> modes, const std::vector<int>& columns,
                        FloquetResult& r) {
  std::vector<int> kept_columns;
  for (int i : ModeDisplayOrder(modes)) {
    r.modes.push_back(modes[i]);
    kept_columns.push_back(columns[i]);
  }
  r.integrator = numbers.integrator;
  r.multiplier_method = numbers.multiplier_method;
  r.error_estimate_method = numbers.error_estimate_method;
  r.segments = numbers.segments;
  r.grid_segments = numbers.grid_segments;
  r.segment_times = numbers.segment_times;
  r.liouville_residual = numbers.liouville_residual;
  r.mode_condition = numbers.mode_condition;
  r.mode_harmonics = numbers.mode_harmonics;
  r.sample_times = numbers.sample_times;
  for (const auto& q : numbers.mode_samples)
    r.mode_samples.push_back(ToStates(q, used.right, scale, kept_columns));
  for (const auto& q : numbers.mode_fourier)
    r.mode_fourier.push_back(ToStates(q, used.right, scale, kept_columns));
  r.monodromy = used.right * numbers.monodromy * used.left.transpose();
  if (scale.size())
    r.monodromy = scale.asDiagonal() * r.monodromy * scale.cwiseInverse().asDiagonal();
  if (!r.mode_samples.empty())
    r.mode_descriptions =
        DescribeModes(labels, r.mode_samples.front(),
                      LeftToStates(numbers.mode_samples.front(), used.left, scale, kept_columns));
  for (std::string& line : FlagRigidBodyModes(
           labels, r.mode_samples.empty() ? Eigen::MatrixXcd() : r.mode_samples.front(), r.modes))
    r.diagnostics.push_back({DiagnosticCode::kRigidBodyMode, Severity::kNote, std::move(line)});
}

std::string SummaryLine(const ModalReduction& m, int states, bool checked, double decoupling) {
  std::ostringstream s;
  s << "modes below " << Hz(m.cutoff) << " (|λ| ≤ " << m.cutoff
    << " rad/s of the mean A): " << m.kept << " of " << states << " states analysed";
  if (checked)
    s << ", the numbers from the projection at " << Hz(m.check_cutoff) << " (" << m.check_kept
      << " states); between the two the exponents move by at most " << m.truncation_change
      << " 1/s, and the modes beyond the second by about " << m.tail
      << " (second order in the periodic part): both, the latter twice, added to each "
         "estimate (docs/model-sizes.md)";
  else
    s << "; what the modes left out change is not measured (no error estimate asked for)";
  if (decoupling > 1e6)
    s << "; the cut-off separates eigenvalues of the mean that are close (decoupling " << decoupling
      << ")";
  return s.str();
}

FloquetResult Failed(std::string why, const PeriodicSystem& system,
                     std::chrono::steady_clock::time_point start) {
  FloquetResult r;
  r.states = system.states();
  r.period = system.period();
  r.Fail(Termination::kNoModesBelowCutoff, std::move(why));
  r.diagnostics.push_back({DiagnosticCode::kNoModesBelowCutoff, Severity::kFailure, r.failure});
  r.elapsed_s = SecondsSince(start);
  return r;
}

}  // namespace

FloquetResult AnalyzeModesBelow(const PeriodicSystem& given, const FloquetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // Split in balanced states: an orthonormal basis of metres and radians against N/m would
  // weigh the subspace by the units.
  const Eigen::VectorXd scale = StateBalancing(given);
  const PeriodicSystem system = scale.size() ? given.WithStateScaling(scale) : given;
  const Eigen::MatrixXd mean = MeanOfA(system);
  ModalReduction m;
  m.cutoff = options.modes_below;
  const RealSchurForm schur = SchurOfMean(mean);  // one Schur form, reordered for each split
  const SpectralSplit low = SplitAtModulus(schur, m.cutoff);
  m.check_cutoff = CheckCutoff(low, m.cutoff);
  const SpectralSplit check = SplitAtModulus(schur, m.check_cutoff);
  if (!low.ok || !check.ok)
    return Failed("the mean of A(t) has no Schur form (non-finite entries)", system, start);
  if (low.kept.empty())
    return Failed("no mode of the mean A(t) has |λ| ≤ " + std::to_string(m.cutoff) + " rad/s (" +
                      Hz(m.cutoff) + "): raise the cut-off",
                  system, start);
  if (low.dropped.empty()) {  // nothing to leave out: the ordinary analysis
    FloquetOptions every = options;
    every.modes_below = 0;
    FloquetResult full = AnalyzeFloquet(given, every);
    full.diagnostics.insert(
        full.diagnostics.begin(),
        {DiagnosticCode::kAllModesBelowCutoff, Severity::kNote,
         "every mode of the mean A(t) is below " + Hz(m.cutoff) + ": all analysed, none left out"});
    full.elapsed_s = SecondsSince(start);
    return full;
  }
  m.kept = static_cast<int>(low.kept.size());
  m.check_kept = static_cast<int>(check.kept.size());
  m.dropped = low.dropped;
  m.periodic_part = PeriodicPart(system, mean);
  // Without an estimate there is nothing to check: one projection, at the cut-off.
  const bool checked = options.estimate_error;
  if (!checked) {
    m.check_cutoff = m.cutoff;
    m.check_kept = m.kept;
  }
  const SpectralSplit& used = checked ? check : low;
  const FloquetResult first =
      checked ? AnalyzeFloquet(Projected(system, low), Unreduced(options, m.kept, false))
              : FloquetResult{};
  const FloquetResult numbers =
      AnalyzeFloquet(Projected(system, used), Unreduced(options, m.check_kept, true));
  // The projection's own round-off: Schur form and Sylvester solve are backward stable, so the
  // reduced matrices are those of an Ā moved by a few ε‖Ā‖, amplified by the decoupling.
  const double projection_floor = 16 * std::numeric_limits<double>::epsilon() * mean.norm() *
                                  (1 + std::max(low.coupling, check.coupling));
  std::vector<FloquetMode> modes;
  std::vector<int> columns;
  m.truncation_change = MergeMatched(checked ? first : numbers, numbers, system.omega(),
                                     projection_floor, modes, columns);
  if (checked && std::isfinite(m.truncation_change))
    m.tail = AddTail(system, mean, m.check_cutoff, modes);
  FloquetResult r;
  r.states = system.states();
  r.period = system.period();
  if (checked && !first.ok)
    r.Fail(first.termination, "the analysis at the cut-off failed: " + first.failure);
  else if (!numbers.ok)
    r.Fail(numbers.termination, numbers.failure);
  else if (!std::isfinite(m.truncation_change))
    r.Fail(Termination::kChecksFailed, "the analyses at the two cut-offs found different modes");
  else
    r.Complete();
  TakeFromProjection(numbers, used, scale, given.labels(), std::move(modes), columns, r);
  AssignWhirl(given, r);
  if (numbers.error_estimate) {
    double largest = 0;
    for (const FloquetMode& mode : r.modes) largest = std::max(largest, *mode.error_estimate);
    r.error_estimate =
        std::max(largest, *numbers.error_estimate + m.truncation_change + 2 * m.tail);
  }
  r.diagnostics.push_back({DiagnosticCode::kModesBelowSummary, Severity::kNote,
                           SummaryLine(m, r.states, checked, low.coupling)});
  r.diagnostics.insert(r.diagnostics.end(), numbers.diagnostics.begin(), numbers.diagnostics.end());
  if (!r.failure.empty() && r.failure != numbers.failure)
    r.diagnostics.push_back({DiagnosticCode::kCutoffsDisagree, Severity::kFailure, r.failure});
  r.rhs_evals = first.rhs_evals + numbers.rhs_evals;
  r.reduction = m;
  Classify(m, r);
  r.elapsed_s = SecondsSince(start);
  return r;
}

}  // namespace ltp::internal
