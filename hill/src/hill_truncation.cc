// Truncation error of Hill's method: the decay of A's Fourier coefficients, the a-priori
// Koopman–Hill bound, and the convergence study over N.
//
// Bound (F. Bayer, R. I. Leine, "Explicit error bounds and guaranteed convergence of the
// Koopman-Hill projection stability method for linear time-periodic dynamics",
// arXiv:2503.21318): if ||A_w|| <= a e^{−b|w|} with b > ln 2, then
//   ||Φ(t) − C e^{H_N t} W|| <= (2 e^{−b})^N e^{4a|t|}.
// (Other versions print the factor as e^{4at} − 1; the larger one is used here.) For a finite
// series every b is admissible with a(b) = max_w ||A_w|| e^{b|w|}; b is chosen to minimise the
// bound at the N analysed. Frobenius norms (>= the 2-norm) keep a conservative.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>

#include "hill_internal.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/hill/hill.h"
#include "ltp/hill/hill_solver_choice.h"
#include "ltp/integrate/integrator_choice.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
constexpr double kLn2 = std::numbers::ln2;
// For a finite series the bound keeps improving with b; beyond this it is far below round-off.
constexpr double kMaxB = 40;

// log of the bound for a given b, or +inf when b is not admissible.
double LogBound(const std::vector<double>& norms, double b, int N, double T) {
  double a = 0;
  for (size_t w = 0; w < norms.size(); ++w)
    if (norms[w] > 0) a = std::max(a, norms[w] * std::exp(b * static_cast<double>(w)));
  return N * (kLn2 - b) + 4 * a * T;
}

struct Envelope {
  double a = 0, b = 0, log_bound = std::numeric_limits<double>::infinity();
};

Envelope BestEnvelope(const std::vector<double>& norms, double b_max, int N, double T) {
  Envelope best;
  if (!(b_max > kLn2)) return best;
  // Log-spaced grid over b − ln2, then a local refinement around the best point.
  const int kGrid = 400;
  const double lo = std::log(1e-4), hi = std::log(b_max - kLn2);
  double best_b = 0;
  for (int i = 0; i <= kGrid; ++i) {
    const double b = kLn2 + std::exp(lo + (hi - lo) * i / kGrid);
    const double l = LogBound(norms, b, N, T);
    if (l < best.log_bound) {
      best.log_bound = l;
      best_b = b;
    }
  }
  best.b = best_b;
  for (size_t w = 0; w < norms.size(); ++w)
    if (norms[w] > 0)
      best.a = std::max(best.a, norms[w] * std::exp(best_b * static_cast<double>(w)));
  return best;
}

struct Line {
  double alpha = 0, beta = 0, rss = 0;
};
Line FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  Line l;
  l.beta = sxx > 0 ? sxy / sxx : 0;
  l.alpha = my - l.beta * mx;
  for (size_t i = 0; i < x.size(); ++i) l.rss += std::pow(y[i] - l.alpha - l.beta * x[i], 2);
  return l;
}

// N = 1..10, then about ×1.25 (16, 20, 24, 32, 40, 48, 64, ...), always ending at max.
std::vector<int> StudyHarmonics(int max_harmonics) {
  std::vector<int> out;
  for (int N = 1; N <= std::min(10, max_harmonics); ++N) out.push_back(N);
  for (int p = 8; p <= max_harmonics; p *= 2)
    for (int f : {4, 5, 6}) {
      const int N = p * f / 4;
      if (N > 10 && N <= max_harmonics && N != out.back()) out.push_back(N);
    }
  if (out.back() != max_harmonics) out.push_back(max_harmonics);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// The whole study weighed before its first solve: the sum of its truncations' estimates, each
// with the solver it will use, refused beyond max_work_seconds and announced beyond
// announce_work_seconds (a note in `notes` and on_long_work). Returns each truncation's
// estimated seconds (the progress's weights).
std::vector<double> WeighTheStudy(const PeriodicSystem& system, const std::vector<int>& rows,
                                  const HillOptions& options, std::vector<Diagnostic>& notes) {
  const int n = system.states();
  std::vector<double> seconds;
  if (n * (2.0 * rows.back() + 1) < 300) {  // well under a second: weights by size³ only
    for (int N : rows) seconds.push_back(std::pow(n * (2.0 * N + 1), 3));
    return seconds;
  }
  const double per_cube = hill_internal::ComplexProductSecondsPerCube();
  std::optional<SystemTraits> traits;
  WorkEstimate total;
  total.seconds_per_evaluation = 1;  // the counts below are seconds
  std::set<HillSolver> solvers;
  std::string largest;
  for (int N : rows) {
    HillOptions o = options;
    o.harmonics = N;
    if (o.solver == HillSolver::kAuto) {
      if (!traits) traits = MeasureSystemTraits(system);
      const FourierMatrix* fa = system.fourier_A();
      o.solver = ChooseHillSolver(*traits, N, fa ? fa->max_harmonic() : N).solver;
    }
    solvers.insert(o.solver);
    const WorkEstimate w = hill_internal::HillWork(n, N, o, per_cube);
    seconds.push_back(w.seconds());
    largest = w.basis;
    total.evaluations += w.seconds();
    total.fewest_evaluations += w.fewest_seconds();
  }
  std::ostringstream basis;
  basis << rows.size() << " truncations (N = " << rows.front() << "…" << rows.back() << " by the "
        << (solvers.size() > 1                       ? "dense and structured solvers"
            : *solvers.begin() == HillSolver::kDense ? "dense solver"
                                                     : "structured solver")
        << ", each with its check at N + Δ; the largest: " << largest << ")";
  total.basis = basis.str();
  hill_internal::WeighHillWork(total,
                               "the convergence study up to N = " + std::to_string(rows.back()),
                               options, "study fewer harmonics (--max-harmonics)", notes);
  return seconds;
}

}  // namespace

namespace {

// Exact coefficients given by the user (Fourier form): a short series is "finite"; a long one
// (≥ 8 harmonics) may still be the truncation of an algebraically decaying series (a
// discontinuous A(t) written as its Fourier series). Fit log||A_w|| against w and against
// log w over the significant harmonics and keep the better fit.
FourierDecay ClassifyGivenCoefficients(const std::vector<double>& norms, double* rate) {
  *rate = 0;
  const double top = *std::max_element(norms.begin(), norms.end());
  std::vector<double> w, y;
  for (size_t k = 1; k < norms.size(); ++k)
    if (norms[k] > 1e-13 * top) {
      w.push_back(static_cast<double>(k));
      y.push_back(std::log(norms[k]));
    }
  if (w.size() < 8) return FourierDecay::kFinite;
  auto fit = [&](const std::vector<double>& x, double* slope) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      sx += x[i];
      sy += y[i];
      sxx += x[i] * x[i];
      sxy += x[i] * y[i];
    }
    *slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    const double icpt = (sy - *slope * sx) / n;
    double res = 0;
    for (size_t i = 0; i < x.size(); ++i) res += std::pow(y[i] - icpt - *slope * x[i], 2);
    return res;
  };
  std::vector<double> logw(w.size());
  for (size_t i = 0; i < w.size(); ++i) logw[i] = std::log(w[i]);
  double b = 0, p = 0;
  const double res_exp = fit(w, &b), res_alg = fit(logw, &p);
  if (res_alg < res_exp) {
    *rate = -p;
    return FourierDecay::kAlgebraic;
  }
  *rate = -b;
  return FourierDecay::kExponential;
}

}  // namespace

HillDecay FitHillDecay(const FourierMatrix& A, const FourierFit* fit, int harmonics,
                       double period) {
  HillDecay d;
  d.harmonics = A.max_harmonic();
  d.norms.resize(A.max_harmonic() + 1);
  for (int w = 0; w <= A.max_harmonic(); ++w) d.norms[w] = std::max(A[w].norm(), A[-w].norm());
  if (fit) {
    d.kind = fit->decay;
    d.rate = fit->decay_rate;
    d.fourier_tail = fit->tail;
  } else {
    d.kind = ClassifyGivenCoefficients(d.norms, &d.rate);
  }
  const double b_max = d.kind == FourierDecay::kFinite        ? kMaxB
                       : d.kind == FourierDecay::kExponential ? d.rate
                                                              : 0;
  const Envelope e = BestEnvelope(d.norms, b_max, harmonics, period);
  d.a = e.a;
  d.b = e.b;
  return d;
}

double KoopmanHillBound(const HillDecay& decay, int harmonics, double period) {
  if (decay.kind == FourierDecay::kAlgebraic) return std::numeric_limits<double>::infinity();
  const double b_max = decay.kind == FourierDecay::kFinite ? kMaxB : decay.rate;
  const Envelope e = BestEnvelope(decay.norms, b_max, harmonics, period);
  return e.log_bound > 700 ? std::numeric_limits<double>::infinity() : std::exp(e.log_bound);
}

namespace {

// The modes' columns in the order of the analysis at max_harmonics (HillStudyRun::last), so
// that the last row is its exponents mode by mode: modes of equal |frequency| (a 2:1
// resonance's pair) are ordered by round-off, differently by each analysis and each route.
// Without a reference, every row is matched to those exponents (modulo jΩp; Hill's branch at
// that N kept, NaN where none matched); with one, the reference's order is permuted.
void OrderColumnsLike(const std::vector<cd>& final_order, bool have_ref, double omega_p,
                      HillStudy& study) {
  if (!have_ref) {
    for (HillStudyRow& row : study.rows) {
      const std::vector<int> match = MatchExponentIndices(final_order, row.exponents, omega_p);
      std::vector<cd> ordered;
      for (int m : match)
        ordered.push_back(m < 0 ? cd(std::numeric_limits<double>::quiet_NaN(), 0.0)
                                : row.exponents[static_cast<size_t>(m)]);
      row.exponents = std::move(ordered);
    }
  } else if (!study.rows.empty()) {
    const std::vector<cd>& matched = study.rows.back().exponents;  // values of final_order
    std::vector<size_t> order;
    std::vector<bool> taken(matched.size(), false);
    for (const cd& e : final_order)
      for (size_t i = 0; i < matched.size(); ++i)
        if (!taken[i] && matched[i] == e) {
          order.push_back(i);
          taken[i] = true;
          break;
        }
    for (size_t i = 0; i < matched.size(); ++i)  // reference exponents Hill did not match
      if (!taken[i]) order.push_back(i);
    auto permuted = [&order](const auto& v) {
      std::decay_t<decltype(v)> out;
      for (size_t i : order) out.push_back(v[i]);
      return out;
    };
    study.reference = permuted(study.reference);
    for (HillStudyRow& row : study.rows) {
      row.exponents = permuted(row.exponents);
      row.errors = permuted(row.errors);
    }
  }
}

// Fail up front (not after hours of smaller truncations) when the largest one cannot fit.
void CheckLargestTruncationFits(const PeriodicSystem& system, int max_harmonics,
                                const HillOptions& options) {
  const int largest = max_harmonics + std::max(options.delta_harmonics, (max_harmonics + 1) / 2);
  const HillSolver largest_solver =
      options.solver == HillSolver::kAuto
          ? ChooseHillSolver(MeasureSystemTraits(system), largest,
                             system.fourier_A() ? system.fourier_A()->max_harmonic() : largest)
                .solver
          : options.solver;
  if (largest_solver == HillSolver::kDense)
    hill_internal::CheckDenseMemory(system.states(), largest, options.max_dense_bytes);
  else if (const FourierMatrix* fa = system.fourier_A())
    hill_internal::CheckBandMemory(system.states(), hill_internal::BlockBandwidth(*fa, largest),
                                   largest);
}

std::vector<cd> ExponentsOf(const HillResult& r) {
  std::vector<cd> v;
  for (const FloquetMode& m : r.modes) v.push_back(m.exponent);
  return v;
}

// The study's row for the analysis `r` at N; with a reference, its exponents matched to it.
HillStudyRow RowOf(const HillResult& r, int N, const std::vector<cd>& reference) {
  const double omega = 2 * std::numbers::pi / r.period;
  HillStudyRow row;
  row.harmonics = N;
  row.matrix_size = r.matrix_size;
  row.apriori_bound = r.apriori_bound;
  row.elapsed_s = r.elapsed_s;
  row.selection_margin = 1;
  for (const HillModeInfo& i : r.info) {
    row.selection_margin = std::min(row.selection_margin, i.selection_margin);
    row.tail_weight = std::max(row.tail_weight, i.tail_weight);
    row.ambiguous = row.ambiguous || i.ambiguous;
  }
  row.truncation_estimate = r.truncation_estimate;
  row.error_estimate = r.error_estimate;
  row.exponents = ExponentsOf(r);
  if (!reference.empty()) {
    // One matching gives both: Hill's exponent for each reference one and its distance.
    const std::vector<int> match = MatchExponentIndices(reference, row.exponents, omega);
    std::vector<cd> matched;
    for (size_t k = 0; k < match.size(); ++k) {
      const bool none = match[k] < 0;
      matched.push_back(none ? cd(std::numeric_limits<double>::quiet_NaN(), 0.0)
                             : row.exponents[static_cast<size_t>(match[k])]);
      row.errors.push_back(none ? std::numeric_limits<double>::infinity()
                                : ExponentDistance(reference[k], matched.back(), omega));
    }
    row.exponents = std::move(matched);
    double worst = 0;
    for (double e : row.errors) worst = std::max(worst, e);
    row.max_error = worst;
  }
  return row;
}

// One full analysis per N in `rows` (`work` their weights for the progress), a row each in
// `study`. Returns the exponents of the analysis at max_harmonics, in its order; `last` (when
// given) receives that analysis.
std::vector<cd> AnalyzeTruncations(const PeriodicSystem& system, const std::vector<int>& rows,
                                   const std::vector<double>& work, const HillOptions& options,
                                   HillStudy* study, HillResult* last) {
  double total_work = 0, done_work = 0;
  for (double w : work) total_work += w;
  std::vector<cd> final_order;
  for (size_t i = 0; i < rows.size(); ++i) {
    const int N = rows[i];
    HillOptions o = options;
    o.harmonics = N;
    o.progress = nullptr;
    HillResult r = AnalyzeHill(system, o);
    done_work += work[i];
    if (options.progress) options.progress(done_work, total_work);
    if (study->rows.empty()) {
      study->decay = r.decay;
      if (!r.fourier_fit.empty())
        study->diagnostics.push_back(
            {DiagnosticCode::kFourierFitted, Severity::kNote, r.fourier_fit});
    }
    study->rows.push_back(RowOf(r, N, study->reference));
    if (N == rows.back()) final_order = ExponentsOf(r);
    if (last && N == rows.back()) *last = std::move(r);
  }
  return final_order;
}

// Convergence law from the points clearly above round-off: exponential or algebraic in N,
// whichever line fits log error better.
void FitConvergenceLaw(bool have_ref, HillStudy* study) {
  double scale = 1;
  for (const cd& l : study->reference) scale = std::max(scale, std::abs(l));
  std::vector<double> n_lin, n_log, y;
  for (const HillStudyRow& row : study->rows) {
    const std::optional<double> e = have_ref ? row.max_error : row.truncation_estimate;
    if (e && *e > 1e-12 * scale && std::isfinite(*e)) {
      n_lin.push_back(row.harmonics);
      n_log.push_back(std::log(static_cast<double>(row.harmonics)));
      y.push_back(std::log(*e));
    }
  }
  if (y.size() < 3) {
    study->diagnostics.push_back({DiagnosticCode::kConvergenceRateUnknown, Severity::kNote,
                                  "too few points above round-off to fit a convergence rate"});
    return;
  }
  const Line ex = FitLine(n_lin, y), al = FitLine(n_log, y);
  if (ex.rss <= al.rss) {
    study->rate_kind = HillConvergence::kExponential;
    study->rate = -ex.beta;
  } else {
    study->rate_kind = HillConvergence::kAlgebraic;
    study->rate = -al.beta;
  }
  if (!(study->rate > 0)) {  // no law of convergence: the error does not fall with N
    study->rate_kind.reset();
    study->rate = 0;
    study->diagnostics.push_back(
        {DiagnosticCode::kConvergenceRateUnknown, Severity::kWarning,
         "the error does not fall with N over the truncations above round-off: no convergence "
         "rate (the selected eigenvalues are not converging; see the rows)"});
  }
}

// HillConvergenceStudy; `last` (when given) receives the analysis at max_harmonics, the
// study's last row, so a caller that wants its modes need not solve it again.
HillStudy StudyTruncations(const PeriodicSystem& system, int max_harmonics,
                           const FloquetResult& reference, HillOptions options, HillResult* last) {
  const auto start = std::chrono::steady_clock::now();
  options.Validate();
  if (max_harmonics < 1)
    OptionCheck("HillConvergenceStudy").Fail("max_harmonics", max_harmonics, "max_harmonics >= 1");
  CheckLargestTruncationFits(system, max_harmonics, options);
  HillStudy study;
  for (const FloquetMode& m : reference.modes) study.reference.push_back(m.exponent);
  const bool have_ref = !study.reference.empty();

  // One full analysis per N: each row reports the estimate AnalyzeHill reports at that N (the
  // N vs N+Δ change with its tail factor, the edge and Liouville checks), not a bare change.
  const std::vector<int> rows = StudyHarmonics(max_harmonics);
  const std::vector<double> work = WeighTheStudy(system, rows, options, study.diagnostics);
  // The study was weighed as a whole: its solves neither announce nor refuse one by one.
  options.announce_work_seconds = std::numeric_limits<double>::infinity();
  options.on_long_work = nullptr;
  options.max_work_seconds = 0;
  const std::vector<cd> final_order = AnalyzeTruncations(system, rows, work, options, &study, last);

  OrderColumnsLike(final_order, have_ref, system.omega(), study);
  FitConvergenceLaw(have_ref, &study);
  if (study.decay.kind == FourierDecay::kAlgebraic) {
    std::ostringstream s;
    s << "A(t) is discontinuous (coefficients decay like |w|^-" << study.decay.rate
      << "): expect algebraic convergence of the exponents, and no exponential a-priori bound";
    study.diagnostics.push_back(
        {DiagnosticCode::kDiscontinuousCoefficients, Severity::kNote, s.str()});
  }
  study.elapsed_s = SecondsSince(start);
  return study;
}

}  // namespace

HillStudy HillConvergenceStudy(const PeriodicSystem& system, int max_harmonics,
                               HillOptions options) {
  return HillConvergenceStudy(system, max_harmonics, FloquetResult{}, std::move(options));
}

HillStudy HillConvergenceStudy(const PeriodicSystem& system, int max_harmonics,
                               const FloquetResult& reference, HillOptions options) {
  return StudyTruncations(system, max_harmonics, reference, std::move(options), nullptr);
}

HillStudyRun RunHillStudy(const PeriodicSystem& system, int max_harmonics,
                          const HillOptions& options, bool reference) {
  if (max_harmonics < 1) throw InputError("max_harmonics must be >= 1");
  FloquetResult monodromy;
  if (reference) {
    FloquetOptions fo;
    fo.integrator.rel_tol = kHillStudyReferenceTol;
    monodromy = AnalyzeFloquet(system, fo);
    if (!monodromy.ok) monodromy = FloquetResult{};
  }
  HillStudyRun run;
  run.study = StudyTruncations(system, max_harmonics, monodromy, options, &run.last);
  run.diagnostics = run.last.diagnostics;
  // The study's own lines, less the kinds the last analysis said already (the fit of A).
  for (const Diagnostic& d : run.study.diagnostics)
    if (!HasCode(run.diagnostics, d.code)) run.diagnostics.push_back(d);
  return run;
}

}  // namespace ltp
