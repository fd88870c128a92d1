// Work–precision study: for each scene, every method over its accuracy knob — the
// monodromy integrators × tolerance or step count (automatic segments), the segment count K,
// Hill's truncation N (dense and structured), Koopman–Hill, and the partial-FRF routes — with the
// error against a near-machine-precision reference computed by a *different* method, and the
// median CPU and wall time of repeated runs. Writes a CSV, one gnuplot script per scene (error
// against CPU time, one line per method), the honesty figures of ltp's own error estimates and
// the generated failure map (Markdown).
//
//   build/benchmarks/work_precision_benchmark --out out/work-precision [--quick] [--scenes a,b]
//   scripts/work-precision     (runs this, then gnuplot → OUT_DIR/work-precision-*.svg; into
//                               docs/ with --update-docs)
//
// Timing: threads = 1 for the segments (OPENBLAS_NUM_THREADS=1 is set by the script), so
// CPU time ≈ wall time when the machine is idle; CPU time is what the charts show because the
// machine is shared. Library code is untouched by this program: everything goes through the
// public API with the options a user would set.
#include <Eigen/Eigenvalues>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/floquet/model_error.h"
#include "ltp/htf/pfrf.h"
#include "ltp/htf/pfrf_model_error.h"
#include "ltp/models/scene.h"
#include "ltp/models/scene_input.h"
#include "ltp/studies/stability_boundary.h"
#include "support/failure_map.h"
#include "support/isotropic_rotor_lin.h"
#include "support/sweep.h"
#include "support/systems.h"
#include "support/work_precision_common.h"

namespace {

using namespace ltp;
using namespace ltp::wp;
constexpr double kPi = std::numbers::pi;

struct Row {
  std::string scene, panel, method, knob_name;
  double knob = 0;
  bool ok = false;
  double error_abs = kInf, error_rel = kInf;
  Timing t;
  double estimate = -1;        ///< ltp's error estimate (estimate run), -1 = none offered
  double estimate_error = -1;  ///< true error of the numbers the estimate run reported
  /// Below this (absolute) the true error is not measurable: the reference's own uncertainty
  /// (disagreement of two independent references) or 1e-14 of the scale.
  double floor = 0;
  std::string note;
};

struct Config {
  std::string out = "out/work-precision";
  bool quick = false;
  std::set<std::string> scenes;
  int repeats = 5;
  double budget_s = 0.15;  ///< per point: repeats stop once this much wall time is spent
};

struct StudyScene {
  std::string name, title;
  PeriodicSystem sys = test::Mathieu(1, 0);  // placeholder: PeriodicSystem has no default
  /// Reference exponents for the monodromy methods (closed form, or Hill) and for Hill's
  /// methods (closed form, or the monodromy route): never the method being measured.
  std::vector<cd> ref_for_mono, ref_for_hill;
  std::string ref_mono_source, ref_hill_source;
  double reference_agreement = -1;  ///< |Hill ref − monodromy ref| when both were computed
  double scale = 1;                 ///< max(1, max |λ|) on the physical branch
  int max_dense_size = 900, max_koopman_size = 400, max_structured_n = 256;
  // PFRF
  bool pfrf = false;
  std::vector<double> freqs_hz;
  bool time_route = false;
};

std::string Fmt(double x) {
  std::ostringstream s;
  s << std::setprecision(6) << x;
  return s.str();
}

FloquetOptions MonoOptions(IntegratorType type) {
  FloquetOptions o;
  o.integrator.type = type;
  o.estimate_error = false;
  o.compute_modes = false;
  o.threads = 1;
  return o;
}

// --- references --------------------------------------------------------------------------

std::vector<cd> MonoReference(const PeriodicSystem& s, double tol) {
  FloquetOptions o = MonoOptions(IntegratorType::kRkf78);
  o.integrator.rel_tol = tol;
  o.integrator.abs_tol = tol * 1e-3;
  o.compute_modes = true;  // physical branch, for the scale
  const FloquetResult r = AnalyzeFloquet(s, o);
  if (!r.ok) throw std::runtime_error("monodromy reference failed on " + r.BriefReport());
  return Exponents(r.modes);
}

std::vector<cd> HillReference(const PeriodicSystem& s, int n, const std::vector<cd>& shifts) {
  HillOptions o;
  o.harmonics = n;
  o.solver = HillSolver::kStructured;
  o.expected = shifts;  // shifts only say where to look; the eigenvalues are Hill's own
  o.koopman_check = false;
  o.delta_harmonics = -1;
  o.fourier.tol = 1e-15;
  const HillResult h = AnalyzeHill(s, o);
  if (!h.ok) throw std::runtime_error("Hill reference failed: " + h.BriefReport());
  return Exponents(h.modes);
}

double Scale(const std::vector<cd>& e) {
  double m = 1;
  for (const cd& x : e) m = std::max(m, std::abs(x));
  return m;
}

// A scene whose exponents are known in closed form: both method families measured against them.
StudyScene ClosedFormScene(const std::string& name, const std::string& title, PeriodicSystem sys,
                           std::vector<cd> exact, const std::string& source) {
  StudyScene sc;
  sc.name = name;
  sc.title = title;
  sc.sys = std::move(sys);
  sc.ref_for_mono = sc.ref_for_hill = std::move(exact);
  sc.ref_mono_source = sc.ref_hill_source = source;
  sc.scale = Scale(sc.ref_for_mono);
  return sc;
}

// A scene without a closed form: the monodromy methods are measured against Hill at
// `hill_harmonics` (structured, FFT fit to 1e-15), Hill's against rkf78 at `mono_tol`; their
// agreement is the floor below which no error is measurable.
StudyScene CrossReferencedScene(const std::string& name, const std::string& title,
                                PeriodicSystem sys, double mono_tol, int hill_harmonics) {
  StudyScene sc;
  sc.name = name;
  sc.title = title;
  sc.sys = std::move(sys);
  const auto mono = MonoReference(sc.sys, mono_tol);
  const auto hill = HillReference(sc.sys, hill_harmonics, mono);
  sc.ref_for_mono = hill;
  sc.ref_mono_source = "Hill structured N = " + std::to_string(hill_harmonics) +
                       " (FFT fit to 1e-15 when not in Fourier form)";
  sc.ref_for_hill = mono;
  sc.ref_hill_source = "monodromy rkf78 rel tol " + Fmt(mono_tol);
  sc.reference_agreement = ExponentError(hill, mono, sc.sys.omega());
  sc.scale = Scale(mono);
  return sc;
}

std::vector<StudyScene> MakeScenes(const Config& cfg) {
  std::vector<StudyScene> scenes;
  auto want = [&](const std::string& n) { return cfg.scenes.empty() || cfg.scenes.count(n); };
  if (want("mathieu")) {
    // Two independent near-exact references: rkf78 at 1e-14 and Hill N = 40 (exact Fourier
    // coefficients, error ~e^{-6.4 N}, i.e. at round-off from N ≈ 6).
    StudyScene sc = CrossReferencedScene(
        "mathieu", "Mathieu a=1.5, q=0.5, c=0.05 (n = 2, smooth, stable)",
        LoadScene("mathieu").Build({{"a", "1.5"}, {"q", "0.5"}, {"c", "0.05"}}), 1e-14, 40);
    sc.pfrf = true;
    sc.time_route = true;
    sc.freqs_hz = {0.05, 0.13, 0.21, 0.29, 0.37, 0.45, 0.53};
    scenes.push_back(std::move(sc));
  }
  if (want("meissner")) {
    // Closed form: Φ = E₊(π/2) E₋(π) E₊(π/2) (tests/support/systems.h), eigenvalues of a 2×2.
    const Eigen::Matrix2d phi = test::MeissnerMonodromy(2, 0.5, 0.05);
    std::vector<cd> exact;
    for (int k = 0; k < 2; ++k) exact.push_back(std::log(cd(phi.eigenvalues()(k))) / (2 * kPi));
    StudyScene sc =
        ClosedFormScene("meissner", "Meissner a=2, b=0.5, c=0.05 (n = 2, jumps)",
                        LoadScene("meissner").Build({{"a", "2"}, {"b", "0.5"}, {"c", "0.05"}}),
                        exact, "closed-form monodromy (product of 3 matrix exponentials)");
    sc.scale =
        Scale(MonoReference(sc.sys, 1e-13));  // |λ| on the physical branch, not the principal log
    sc.pfrf = true;
    sc.time_route = true;
    sc.freqs_hz = {0.03, 0.11, 0.19, 0.27, 0.35, 0.43};
    sc.max_dense_size = 700;
    scenes.push_back(std::move(sc));
  }
  if (want("stiff")) {
    // Upper triangular: the exponents are the period averages of the diagonal (closed form).
    scenes.push_back(
        ClosedFormScene("stiff", "stiff.yaml: exponents -800, 150, -3 (ρ = e^{-5027}, e^{942})",
                        LoadScene(std::string(LTP_SOURCE_DIR) + "/tests/data/stiff.yaml").Build(),
                        {cd(-800, 0), cd(150, 0), cd(-3, 0)},
                        "closed form (triangular: averages of the diagonal)"));
  }
  if (want("stiff-coupled")) {
    // stiff.yaml is triangular, which makes Magnus exact at any step count; this one has the
    // same exponents' range but every state coupled (tests/support/systems.h: Lyapunov-
    // reducible, exponents exactly diag Λ), so each method has to earn its accuracy.
    StudyScene sc = ClosedFormScene(
        "stiff-coupled",
        "stiff, coupled: R(t) Λ R(t)ᵀ + Ṙ Rᵀ, exponents -800, 150, -3, -0.5 (n = 4)",
        test::Reducible4(Eigen::Vector4d(-800, 150, -3, -0.5)),
        {cd(-800, 0), cd(150, 0), cd(-3, 0), cd(-0.5, 0)},
        "closed form (Lyapunov-reducible: diag Λ)");
    sc.max_dense_size = 400;
    sc.max_structured_n = 64;
    scenes.push_back(std::move(sc));
  }
  if (want("reducible")) {
    // The honesty issue's case: Hill's truncation edge produced a spurious pair with a tiny
    // estimate here (exact exponents l1, l2; tests/support/systems.h).
    StudyScene sc = ClosedFormScene(
        "reducible", "reducible R(t + e sin t), exponents 120, -120.5 (n = 2, ρ = e^{754})",
        test::ReducibleRotation(120, -120.5, 0.5), {cd(120, 0), cd(-120.5, 0)},
        "closed form (Lyapunov-reducible: l1, l2)");
    sc.scale = Scale(MonoReference(sc.sys, 1e-13));  // |λ| on the physical branch
    scenes.push_back(std::move(sc));
  }
  if (want("poisson")) {
    // Harmonics r^|w| (Poisson kernel, r = 0.9): Hill's estimate fell just short here.
    // References: Hill at N = 360 (0.9^360 ≈ 3e-17) and rkf78 at 1e-14.
    scenes.push_back(CrossReferencedScene(
        "poisson", "Poisson kernel a=0.8, b=0.2, r=0.9, c=0.02 (n = 2, ‖A_w‖ ~ 0.9^|w|)",
        test::PoissonKernel(0.8, 0.2, 0.9, 0.02), 1e-14, 360));
  }
  if (want("rotor")) {
    StudyScene sc = CrossReferencedScene("rotor", "rotor, 2 blades (n = 8, time-function form)",
                                         LoadScene("rotor").Build({{"blades", "2"}}), 1e-14, 48);
    sc.pfrf = true;
    sc.freqs_hz = {0.02, 0.05, 0.08, 0.11, 0.14, 0.2};
    scenes.push_back(std::move(sc));
  }
  if (want("tower-rotor")) {
    StudyScene sc =
        CrossReferencedScene("tower-rotor", "tower-rotor (n = 22, the reference paper system)",
                             LoadScene("tower-rotor").Build(), 1e-13, 64);
    sc.max_dense_size = 800;
    sc.max_koopman_size = 500;
    sc.max_structured_n = 128;
    sc.pfrf = true;
    sc.freqs_hz = {10, 60, 95, 130, 170, 240};
    scenes.push_back(std::move(sc));
  }
  return scenes;
}

// --- Floquet exponent methods ------------------------------------------------------------------

Row NewRow(const StudyScene& sc, const std::string& method, const std::string& knob_name,
           double knob, const std::string& panel = "exponents") {
  Row row;
  row.scene = sc.name;
  row.panel = panel;
  row.method = method;
  row.knob_name = knob_name;
  row.knob = knob;
  return row;
}

void Finish(Row& row, const StudyScene& sc) {
  row.error_rel = row.error_abs / sc.scale;
  // Two references agreeing to d pin the truth down to about d (the worse one's error, known
  // to a factor ~2): below 2d a measured error says nothing.
  row.floor = std::max(2 * sc.reference_agreement, 1e-14 * sc.scale);
  if (!std::isfinite(row.error_abs)) row.ok = false;
}

void RunMonodromy(const StudyScene& sc, const Config& cfg, std::vector<Row>& rows) {
  const PeriodicSystem& s = sc.sys;
  struct Line {
    IntegratorType type;
    bool fixed;
  };
  // `auto` last: the automatic choice (ltp/integrate/integrator_choice.h) drawn over the lines it
  // chooses from, so the chart shows whether it follows their lower envelope.
  const std::vector<Line> lines = {
      {IntegratorType::kDopri5, false},        {IntegratorType::kRkf78, false},
      {IntegratorType::kBulirschStoer, false}, {IntegratorType::kCvodeBdf, false},
      {IntegratorType::kCvodeAdams, false},    {IntegratorType::kMagnus4, true},
      {IntegratorType::kMagnus6, true},        {IntegratorType::kTaylor, false},
      {IntegratorType::kAuto, false}};
  for (const Line& line : lines) {
    // Taylor series need A(t) as a Fourier series (docs/taylor-integrator.md).
    if (line.type == IntegratorType::kTaylor && s.RealSeriesA(nullptr) == nullptr) continue;
    const int points = cfg.quick ? 3 : (line.fixed ? 5 : 6);
    for (int i = 0; i < points; ++i) {
      Row row = NewRow(sc, std::string(ToString(line.type)), "", 0);
      FloquetOptions o = MonoOptions(line.type);
      if (line.fixed) {
        o.integrator.steps_per_period = 16 << (cfg.quick ? 3 * i : 2 * i);
        row.knob_name = "steps_per_period";
        row.knob = o.integrator.steps_per_period;
      } else {
        o.integrator.rel_tol = std::pow(10.0, -3.0 - (cfg.quick ? 4 * i : 2 * i));
        o.integrator.abs_tol = o.integrator.rel_tol * 1e-3;
        row.knob_name = "rel_tol";
        row.knob = o.integrator.rel_tol;
      }
      FloquetResult r;
      row.t = TimeIt([&] { r = AnalyzeFloquet(s, o); }, cfg.repeats, cfg.budget_s);
      row.ok = r.ok;
      row.error_abs = r.ok ? ExponentError(Exponents(r.modes), sc.ref_for_mono, s.omega()) : kInf;
      if (!r.ok) row.note = r.diagnostics.empty() ? "not ok" : r.diagnostics.front().text;
      if (line.type == IntegratorType::kAuto)
        row.note = "picked " + std::string(ToString(r.integrator));
      // The analysis a user gets (modes, branch, error estimate by the refined run): honesty.
      // Its refined run is 100× tighter and computes the modes on K ≥ 32 segments, so it is
      // skipped where one plain run already took over 0.3 s (the study has to fit in 10 min).
      if (row.t.wall_s < 0.3) {
        FloquetOptions e = o;
        e.estimate_error = true;
        e.compute_modes = true;
        const FloquetResult re = AnalyzeFloquet(s, e);
        row.estimate = re.ok ? re.error_estimate.value_or(-1) : -1;
        row.estimate_error =
            re.ok ? ExponentError(Exponents(re.modes), sc.ref_for_mono, s.omega()) : kInf;
        // The other estimate of Bulirsch–Stoer and Taylor series, their carried local errors
        // (one run): honesty only, in its own panel, so the chart's lines stay the plain runs.
        if (line.type == IntegratorType::kBulirschStoer || line.type == IntegratorType::kTaylor) {
          e.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
          const FloquetResult rl = AnalyzeFloquet(s, e);
          Row local = NewRow(sc, std::string(ToString(line.type)) + ", local-errors estimate",
                             row.knob_name, row.knob, "local-errors-honesty");
          local.ok = rl.ok;
          local.estimate = rl.ok ? rl.error_estimate.value_or(-1) : -1;
          local.estimate_error =
              rl.ok ? ExponentError(Exponents(rl.modes), sc.ref_for_mono, s.omega()) : kInf;
          local.error_abs = local.estimate_error;
          Finish(local, sc);
          rows.push_back(local);
        }
      }
      Finish(row, sc);
      rows.push_back(row);
      std::cerr << "  " << sc.name << " " << row.method << " " << row.knob_name << "=" << row.knob
                << " err " << Fmt(row.error_rel) << " cpu " << Fmt(row.t.cpu_s) << " s\n";
      if (row.t.wall_s > 1) break;  // the remaining points would be slower still
    }
  }
  // The segment count K at fixed integrator and tolerance (rkf78, 1e-12): where K matters.
  for (int k : {1, 4, 16, 64, 256}) {
    if (cfg.quick && k > 4) break;
    Row row = NewRow(sc, "rkf78 1e-12 over K segments", "segments", k);
    FloquetOptions o = MonoOptions(IntegratorType::kRkf78);
    o.integrator.rel_tol = 1e-12;
    o.integrator.abs_tol = 1e-15;
    o.segments = k;
    FloquetResult r;
    row.t = TimeIt([&] { r = AnalyzeFloquet(s, o); }, cfg.repeats, cfg.budget_s);
    row.ok = r.ok;
    row.error_abs = r.ok ? ExponentError(Exponents(r.modes), sc.ref_for_mono, s.omega()) : kInf;
    if (!r.ok) row.note = r.diagnostics.empty() ? "not ok" : r.diagnostics.front().text;
    FloquetOptions e = o;
    e.estimate_error = true;
    e.compute_modes = true;
    const FloquetResult re = AnalyzeFloquet(s, e);
    row.estimate = re.ok ? re.error_estimate.value_or(-1) : -1;
    row.estimate_error =
        re.ok ? ExponentError(Exponents(re.modes), sc.ref_for_mono, s.omega()) : kInf;
    if (re.ok && !re.diagnostics.empty() && row.note.empty())
      row.note = re.diagnostics.front().text;
    Finish(row, sc);
    rows.push_back(row);
  }
}

std::vector<int> HillTruncations(const Config& cfg) {
  if (cfg.quick) return {2, 8, 16};
  return {1, 2, 4, 8, 12, 16, 24, 32, 48, 64, 128, 256};
}

// Hill at fixed truncations N, dense and structured: one timed solve, and the estimate of what
// `ltp floquet --method hill --harmonics N` reports.
void RunHillTruncations(const StudyScene& sc, const Config& cfg, std::vector<Row>& rows) {
  const PeriodicSystem& s = sc.sys;
  const int n = s.states();
  const std::vector<int> ns = HillTruncations(cfg);
  for (HillSolver solver : {HillSolver::kDense, HillSolver::kStructured}) {
    for (int N : ns) {
      const int size = (2 * N + 1) * n;
      if (solver == HillSolver::kDense && size > sc.max_dense_size) break;
      if (solver == HillSolver::kStructured && N > sc.max_structured_n) break;
      Row row = NewRow(sc, std::string("hill ") + std::string(ToString(solver)), "harmonics", N);
      HillOptions o;
      o.harmonics = N;
      o.solver = solver;
      o.delta_harmonics = -1;  // timed run: one solve, as in a sweep
      o.koopman_check = false;
      o.structured_fallback = false;  // time the structured solver itself
      HillResult h;
      try {
        row.t = TimeIt([&] { h = AnalyzeHill(s, o); }, cfg.repeats, cfg.budget_s);
      } catch (const Error& e) {
        row.note = e.what();
      }
      row.ok = h.ok;
      row.error_abs = h.ok ? ExponentError(Exponents(h.modes), sc.ref_for_hill, s.omega()) : kInf;
      if (!h.ok && row.note.empty())
        row.note = h.diagnostics.empty() ? "not ok" : h.diagnostics.front().text;
      // What `ltp floquet --method hill --harmonics N` reports (N vs N+Δ, Koopman–Hill).
      HillOptions e;
      e.harmonics = N;
      e.solver = solver;
      // The Koopman–Hill check is a dense expm of the Hill matrix: ~40 s at 2000 rows. Above
      // 600 rows the study relies on the N vs N+Δ estimate alone (ltp does so above 2500).
      e.koopman_max_size = 600;
      try {
        const HillResult he = AnalyzeHill(s, e);
        row.estimate = he.ok ? HillEstimate(he) : -1;
        row.estimate_error =
            he.ok ? ExponentError(Exponents(he.modes), sc.ref_for_hill, s.omega()) : kInf;
      } catch (const Error& ex) {
        row.estimate = -1;
      }
      Finish(row, sc);
      rows.push_back(row);
      std::cerr << "  " << sc.name << " " << row.method << " N=" << N << " err "
                << Fmt(row.error_rel) << " cpu " << Fmt(row.t.cpu_s) << " s\n";
      if (row.t.wall_s > 3) break;
    }
  }
}

// What `ltp floquet --method hill` does by default: N doubled until N vs N+Δ meets the
// tolerance, the solver chosen per N (HillSolver::kAuto); timed whole, estimate included.
void RunHillAuto(const StudyScene& sc, const Config& cfg, std::vector<Row>& rows) {
  const PeriodicSystem& s = sc.sys;
  for (double tol : cfg.quick ? std::vector<double>{1e-6} : std::vector<double>{1e-5, 1e-10}) {
    Row row = NewRow(sc, "hill auto (N and solver)", "tol", tol);
    HillOptions o;
    o.solver = HillSolver::kAuto;
    o.harmonics = kHillAutoStartHarmonics;  // where `ltp floquet --harmonics auto` starts
    HillResult h;
    try {
      row.t = TimeIt([&] { h = AnalyzeHillAuto(s, o, tol, sc.max_structured_n); }, cfg.repeats,
                     cfg.budget_s);
    } catch (const Error& e) {
      row.note = e.what();
    }
    row.ok = h.ok;
    row.error_abs = h.ok ? ExponentError(Exponents(h.modes), sc.ref_for_hill, s.omega()) : kInf;
    row.estimate = h.ok ? HillEstimate(h) : -1;
    row.estimate_error = h.ok ? row.error_abs : -1;
    if (row.note.empty())
      row.note = "picked N = " + std::to_string(h.harmonics) + " " + h.SolverDescription();
    Finish(row, sc);
    rows.push_back(row);
    std::cerr << "  " << sc.name << " " << row.method << " tol=" << tol << " err "
              << Fmt(row.error_rel) << " cpu " << Fmt(row.t.cpu_s) << " s (" << row.note << ")\n";
    if (row.t.wall_s > 3) break;
  }
}

// Koopman–Hill: Φ(T) ≈ C expm(H_N T) W, then eig; no selection among Hill eigenvalues.
void RunKoopmanHill(const StudyScene& sc, const Config& cfg, std::vector<Row>& rows) {
  const PeriodicSystem& s = sc.sys;
  const int n = s.states();
  for (int N : HillTruncations(cfg)) {
    const int size = (2 * N + 1) * n;
    if (size > sc.max_koopman_size) break;
    Row row = NewRow(sc, "koopman-hill", "harmonics", N);
    std::vector<cd> exps;
    bool finite = true;
    row.t = TimeIt(
        [&] {
          FourierMatrix A = s.fourier_A() ? *s.fourier_A() : ToFourier(s).A.series;
          const Eigen::MatrixXcd phi = KoopmanHillTransition(A, s.omega(), N, s.period());
          finite = phi.allFinite();
          exps.clear();
          if (!finite) return;
          Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(phi, false);
          for (int k = 0; k < es.eigenvalues().size(); ++k)
            exps.push_back(std::log(es.eigenvalues()(k)) / s.period());
        },
        cfg.repeats, cfg.budget_s);
    row.ok = finite;
    row.error_abs = finite ? ExponentError(exps, sc.ref_for_hill, s.omega()) : kInf;
    if (!finite) row.note = "expm(H T) not finite (multipliers beyond the double range)";
    Finish(row, sc);
    rows.push_back(row);
  }
}

void RunHill(const StudyScene& sc, const Config& cfg, std::vector<Row>& rows) {
  RunHillTruncations(sc, cfg, rows);
  RunHillAuto(sc, cfg, rows);
  RunKoopmanHill(sc, cfg, rows);
}

// --- partial FRFs ---------------------------------------------------------------------------

constexpr int kMinOrder = -2, kMaxOrder = 2;

using Values = std::vector<PartialFrfs>;  // per frequency

double FrfError(const Values& got, const Values& ref, double* scale_out = nullptr) {
  double scale = 0, err = 0;
  for (size_t f = 0; f < ref.size(); ++f)
    for (size_t z = 0; z < ref[f].size(); ++z)
      scale = std::max(scale, ref[f][z].cwiseAbs().maxCoeff());
  for (size_t f = 0; f < ref.size(); ++f) {
    if (f >= got.size()) return kInf;
    for (size_t z = 0; z < ref[f].size(); ++z) {
      const double d = (got[f][z] - ref[f][z]).cwiseAbs().maxCoeff();
      if (!std::isfinite(d)) return kInf;
      err = std::max(err, d);
    }
  }
  if (scale_out) *scale_out = scale;
  return err;
}

Values ShootingValues(const PeriodicSystem& s, const std::vector<double>& fhz, double tol,
                      bool* ok) {
  ShootingOptions so;
  so.rel_tol = tol;
  so.abs_tol = tol * 1e-3;
  so.integrator.type = IntegratorType::kRkf78;
  so.integrator.rel_tol = std::max(tol, 1e-14);
  so.integrator.abs_tol = so.integrator.rel_tol * 1e-3;
  ForcedResponseSolver solver(s, so);
  Values v;
  *ok = true;
  for (double f : fhz) {
    bool pt = true;
    v.push_back(solver.Shooting(2 * kPi * f, kMinOrder, kMaxOrder, &pt));
    *ok = *ok && pt;
  }
  return v;
}

Values ModalValues(const PeriodicSystem& s, const std::vector<double>& fhz, double tol, bool* ok,
                   double* condition = nullptr) {
  FloquetOptions fo = MonoOptions(IntegratorType::kRkf78);
  fo.integrator.rel_tol = tol;
  fo.integrator.abs_tol = tol * 1e-3;
  fo.compute_modes = true;
  const FloquetResult fl = AnalyzeFloquet(s, fo);
  *ok = fl.ok;
  if (!fl.ok) return {};
  ModalOptions mo;
  mo.integrator = fo.integrator;
  const ModalModel model = BuildModalModel(s, fl, mo);
  if (condition) *condition = model.condition;
  Values v;
  for (double f : fhz) v.push_back(model.Evaluate(2 * kPi * f, kMinOrder, kMaxOrder));
  return v;
}

// The partial-FRF panel of one scene: each route over its knob, measured against a reference by
// another route.
class PfrfStudy {
 public:
  PfrfStudy(const StudyScene& sc, const Config& cfg, std::vector<Row>& rows)
      : sc_(sc), s_(sc.sys), fhz_(sc.freqs_hz), cfg_(cfg), rows_(rows) {}

  void Run(std::ostream& log) {
    References(log);
    const std::vector<double> tols =
        cfg_.quick ? std::vector<double>{1e-5, 1e-10} : std::vector<double>{1e-4, 1e-8, 1e-12};
    ModalLine(tols);
    HtfLine();
    ShootingLine(tols);
    if (sc_.time_route) TimeLine();
    SweepLines();
    SweepHonesty();
  }

 private:
  // References: shooting (no Fourier truncation, rkf78 at 1e-13) for modal / htf / time; the
  // modal route at 1e-13 for shooting itself. Their agreement is printed.
  void References(std::ostream& log) {
    bool ok1 = false, ok2 = false;
    ref_shoot_ = ShootingValues(s_, fhz_, 1e-13, &ok1);
    ref_modal_ = ModalValues(s_, fhz_, 1e-13, &ok2);
    agree_ = FrfError(ref_modal_, ref_shoot_, &hscale_);
    log << sc_.name << ": PFRF references shooting (rkf78 1e-13) vs modal (rkf78 1e-13) agree to "
        << Fmt(agree_ / hscale_) << " relative (max |H_z| " << Fmt(hscale_) << ")\n";
    // For the peers (benchmarks/peers/pfrf_stepsine_scipy.py): the reference values themselves.
    std::ofstream ref(cfg_.out + "/pfrf_reference.csv", std::ios::app);  // header: main()
    ref << std::setprecision(17);
    for (size_t f = 0; f < fhz_.size(); ++f)
      for (int z = kMinOrder; z <= kMaxOrder; ++z) {
        const cd h = ref_shoot_[f][z - kMinOrder](0, 0);
        ref << sc_.name << "," << fhz_[f] << "," << z << "," << h.real() << "," << h.imag() << ","
            << agree_ / hscale_ << "\n";
      }
  }

  void Add(Row row, const Values& v, const Values& ref) {
    row.error_abs = row.ok ? FrfError(v, ref) : kInf;
    row.error_rel = row.error_abs / hscale_;
    if (!std::isfinite(row.error_abs)) row.ok = false;
    rows_.push_back(row);
    std::cerr << "  " << sc_.name << " pfrf " << row.method << " " << row.knob_name << "="
              << row.knob << " err " << Fmt(row.error_rel) << " cpu " << Fmt(row.t.cpu_s) << " s\n";
  }

  void ModalLine(const std::vector<double>& tols) {
    for (double tol : tols) {
      Row row = NewRow(sc_, "modal (Floquet rkf78)", "rel_tol", tol, "pfrf");
      Values v;
      row.t = TimeIt([&] { v = ModalValues(s_, fhz_, tol, &row.ok); }, cfg_.repeats, cfg_.budget_s);
      Add(row, v, ref_shoot_);
    }
  }

  void HtfLine() {
    for (int N : cfg_.quick ? std::vector<int>{4, 16} : std::vector<int>{2, 4, 8, 16, 32, 64}) {
      Row row = NewRow(sc_, "htf (banded)", "harmonics", N, "pfrf");
      Values v;
      row.ok = true;
      row.t = TimeIt(
          [&] {
            HtfOptions ho;
            ho.harmonics = N;
            HtfSolver htf(s_, ho);
            v.clear();
            for (double f : fhz_) v.push_back(htf.Evaluate(2 * kPi * f, kMinOrder, kMaxOrder));
          },
          cfg_.repeats, cfg_.budget_s);
      Add(row, v, ref_shoot_);
      if (row.t.wall_s > 3) break;
    }
  }

  void ShootingLine(const std::vector<double>& tols) {
    for (double tol : tols) {
      Row row = NewRow(sc_, "shooting (rkf78)", "rel_tol", tol, "pfrf");
      Values v;
      row.t =
          TimeIt([&] { v = ShootingValues(s_, fhz_, tol, &row.ok); }, cfg_.repeats, cfg_.budget_s);
      Add(row, v, ref_modal_);
      if (row.t.wall_s > 5) break;
    }
  }

  void TimeLine() {
    FloquetOptions fo = MonoOptions(IntegratorType::kRkf78);
    fo.compute_modes = true;
    const FloquetResult fl = AnalyzeFloquet(s_, fo);
    for (double settle :
         cfg_.quick ? std::vector<double>{1e-4} : std::vector<double>{1e-3, 1e-6, 1e-9}) {
      Row row = NewRow(sc_, "time (step-sine)", "settle_tol", settle, "pfrf");
      Values v;
      row.t = TimeIt(
          [&] {
            ShootingOptions so;
            so.settle_tol = settle;
            so.rel_tol = std::min(1e-6, settle * 1e-2);
            so.abs_tol = so.rel_tol * 1e-3;
            ForcedResponseSolver solver(s_, so);
            const double ts = ForcedResponseSolver::SettlingTime(fl, settle);
            v.clear();
            row.ok = true;
            for (double f : fhz_) {
              bool pt = true;
              v.push_back(solver.TimeSimulation(2 * kPi * f, kMinOrder, kMaxOrder, ts, &pt));
              row.ok = row.ok && pt;
            }
          },
          1, cfg_.budget_s);
      Add(row, v, ref_shoot_);
    }
  }

  // `ltp pfrf`'s options: route `route`, integrator auto.
  PfrfOptions SweepOptions(PfrfRoute route, double tol) const {
    PfrfOptions po;
    po.frequencies_hz = fhz_;
    po.min_order = kMinOrder;
    po.max_order = kMaxOrder;
    po.primary = route;
    po.floquet.integrator.type = IntegratorType::kAuto;
    po.floquet.integrator.rel_tol = tol;
    po.modal.integrator.type = IntegratorType::kAuto;
    return po;
  }

  // The sweep `ltp pfrf` runs by default (route auto, integrator auto, a check every 10th
  // frequency) beside the same sweep with each route forced (`--route R`; its check chosen as
  // auto would): the Floquet decomposition, the checks and the resonance attribution are in
  // every one of them. A sweep reports one channel: compared on channel (0, 0).
  void SweepLines() {
    Values ref_channel;
    for (const PartialFrfs& h : ref_shoot_) {
      ref_channel.emplace_back();
      for (const auto& m : h) ref_channel.back().push_back(m.block(0, 0, 1, 1));
    }
    const double tol = 1e-10;
    for (const PfrfRoute route :
         {PfrfRoute::kAuto, PfrfRoute::kModal, PfrfRoute::kHtf, PfrfRoute::kShooting}) {
      const std::string method = route == PfrfRoute::kAuto
                                     ? "ltp pfrf auto (default)"
                                     : "ltp pfrf --route " + std::string(ToString(route));
      Row row = NewRow(sc_, method, "rel_tol", tol, "pfrf");
      PfrfResult pr;
      row.t = TimeIt([&] { pr = ComputePartialFrf(s_, SweepOptions(route, tol)); }, cfg_.repeats,
                     cfg_.budget_s);
      row.ok = pr.ok;
      Values v;
      for (size_t f = 0; f < fhz_.size(); ++f) {
        PartialFrfs h(kMaxOrder - kMinOrder + 1, Eigen::MatrixXcd::Zero(1, 1));
        for (int z = kMinOrder; z <= kMaxOrder; ++z)
          h[z - kMinOrder](0, 0) = pr.values[f][z - kMinOrder];
        v.push_back(h);
      }
      // The routes as they ran (primary first), not parsed from the route_choice sentence.
      row.note = "picked " + std::string(ToString(pr.routes.front().route));
      for (size_t k = 1; k < pr.routes.size(); ++k)
        row.note += (k == 1 ? " checked by " : ", ") + std::string(ToString(pr.routes[k].route));
      Add(row, v, ref_channel);
    }
  }

  // Honesty of the sweep a user runs (`ltp pfrf`: automatic route and checks), here with a
  // check at every frequency so every value has its own estimate.
  void SweepHonesty() {
    PfrfOptions po = SweepOptions(PfrfRoute::kAuto, PfrfOptions{}.floquet.integrator.rel_tol);
    po.check_every = 1;
    const PfrfResult pr = ComputePartialFrf(s_, po);
    for (size_t f = 0; f < fhz_.size(); ++f) {
      for (int z = kMinOrder; z <= kMaxOrder; ++z) {
        Row row = NewRow(sc_, "ltp pfrf default (auto route + checks)", "freq_hz,order",
                         fhz_[f] + 1e-3 * z /* informative only */, "pfrf-honesty");
        row.ok = pr.ok;
        const cd got = pr.values[f][z - kMinOrder];
        const cd ref = ref_shoot_[f][z - kMinOrder](po.output, po.input);
        row.estimate_error = std::abs(got - ref);
        row.estimate = pr.error_estimate[f][z - kMinOrder];
        row.floor = std::max(2 * agree_, 1e-14 * hscale_);  // as Finish()
        row.error_abs = row.estimate_error;
        row.error_rel = row.error_abs / hscale_;
        row.t = {pr.elapsed_s, pr.elapsed_s, 1};
        rows_.push_back(row);
      }
    }
  }

  const StudyScene& sc_;
  const PeriodicSystem& s_;
  const std::vector<double>& fhz_;
  const Config& cfg_;
  std::vector<Row>& rows_;
  Values ref_shoot_, ref_modal_;
  double agree_ = 0, hscale_ = 0;
};

void RunPfrf(const StudyScene& sc, const Config& cfg, std::vector<Row>& rows, std::ostream& log) {
  PfrfStudy(sc, cfg, rows).Run(log);
}

// --- honesty on sampled models and chart boundaries ------------------------------------------

// A point of the honesty table that is not on a work–precision line.
Row HonestyPoint(const std::string& scene, const std::string& method, const std::string& knob_name,
                 double knob, double estimate, double error, double floor) {
  Row row;
  row.scene = scene;
  row.panel = "honesty";
  row.method = method;
  row.knob_name = knob_name;
  row.knob = knob;
  row.ok = std::isfinite(error);
  row.estimate = estimate;
  row.estimate_error = row.error_abs = error;
  row.floor = floor;
  return row;
}

// Generated rotating-frame `.lin` sets (tests/support/isotropic_rotor_lin.h) with a 1P gravity
// term, analysed as `ltp floquet DIR` and `ltp pfrf DIR` analyse them (sampling error included).
// References: the trigonometric route in blade coordinates, exact because A(ψ) there holds
// harmonics 0 and ±1 only (3 and 9 azimuths agree, their distance is the floor), and for H_z
// the default route at 9 azimuths (exact: the multi-blade model holds harmonics 0 and ±3).
void RunSampledHonesty(const Config& cfg, std::vector<Row>& rows) {
  const double gravity = 0.4;
  auto load = [&](int azimuths, bool channels, const std::vector<std::string>& set) {
    auto model =
        test::MakeIsotropicRotorLin(channels ? 2 : 4, channels ? 2 : 4,
                                    test::EvenAzimuths(azimuths), 1.0, channels ? 5 : 3, gravity);
    if (channels) test::AddBladeChannels(model);
    const std::string dir = test::WriteLinDirectory(
        model.files, cfg.out + "/lin-" + std::to_string(azimuths) + (channels ? "-io" : ""));
    return LoadSceneInput({dir}, set);
  };
  FloquetOptions tight;
  tight.integrator.rel_tol = 1e-13;
  const FloquetResult ref3 = AnalyzeFloquet(load(3, false, {"mbc=0"}).system, tight);
  const FloquetResult ref9 = AnalyzeFloquet(load(9, false, {"mbc=0"}).system, tight);
  const double omega = 1.0;  // the generated rotor's speed
  const double floor =
      std::max(2 * ExponentError(Exponents(ref9.modes), Exponents(ref3.modes), omega), 1e-13);
  const std::vector<std::pair<std::string, std::vector<std::string>>> routes = {
      {"default (trigonometric, multi-blade)", {}},
      {"held samples", {"trig=0"}},
      {"held, blade coordinates", {"trig=0", "mbc=0"}}};
  for (int K : {3, 5, 8}) {
    for (const auto& [name, set] : routes) {
      const LoadedScene l = load(K, false, set);
      FloquetResult r = AnalyzeFloquet(l.system);
      IncludeModelError(l.model_alternatives, FloquetOptions{}, r);
      const double error =
          r.ok ? ExponentError(Exponents(r.modes), Exponents(ref3.modes), omega) : kInf;
      Row row = HonestyPoint("sampled", "ltp floquet on .lin (sampling error included)", "azimuths",
                             K, r.error_estimate.value_or(-1), error, floor);
      row.note = name;
      rows.push_back(row);
      std::cerr << "  sampled K=" << K << " " << name << " err " << Fmt(error) << " estimate "
                << Fmt(row.estimate) << "\n";
    }
  }
  PfrfOptions po;
  for (double f = 0.05; f < 0.7; f += 0.05) po.frequencies_hz.push_back(f);
  po.min_order = -1;
  po.max_order = 1;
  for (int output : {0, 1}) {
    po.output = output;
    const PfrfResult ref = ComputePartialFrf(load(9, true, {}).system, po);
    const LoadedScene l = load(3, true, {});
    PfrfResult r = ComputePartialFrf(l.system, po);
    IncludeModelError(l.model_alternatives, po, r);
    double peak = 0;
    for (double m : ref.order_max) peak = std::max(peak, m);
    for (size_t i = 0; i < r.values.size(); ++i)
      for (size_t z = 0; z < r.values[i].size(); ++z)
        rows.push_back(HonestyPoint("sampled", "ltp pfrf on .lin (sampling error included)",
                                    "freq_hz", po.frequencies_hz[i], r.error_estimate[i][z],
                                    std::abs(r.values[i][z] - ref.values[i][z]),
                                    std::max(2 * ref.error_estimate[i][z], 1e-14 * peak)));
  }
}

// The refined stability boundaries of the undamped Meissner map over the honesty issue's grid
// (a = −1…6, b = 0…3, step 0.025), each against the nearest root of |tr Φ| − 2 on its line
// (closed-form monodromy, bisected to round-off): is the boundary within its bracket?
void RunBoundaryHonesty(std::vector<Row>& rows) {
  const Scene scene = LoadScene("meissner");
  const ParameterMap base = scene.Resolve({{"c", "0"}});
  const SweepGrid grid =
      MakeSweepGrid(scene, {SweepAxis::Parse("a=-1:6:0.025"), SweepAxis::Parse("b=0:3:0.025")});
  SweepOptions o;
  o.modes = false;
  const std::vector<SweepPoint> points = test::SweepAll(scene, base, grid, o);
  BoundaryOptions b;
  b.max_lines = 0;
  int refined = 0;
  for (const BoundaryPoint& p : RefineBoundaryPoints(scene, base, grid, points, o, b)) {
    if (!p.estimate.refined) continue;
    ++refined;
    const double a = p.values[0], bb = p.values[1], x0 = p.values[p.axis];
    auto indicator = [&](double x) {
      const Eigen::Matrix2d phi =
          p.axis == 0 ? test::MeissnerMonodromy(x, bb) : test::MeissnerMonodromy(a, x);
      return std::abs(phi.trace()) - 2;
    };
    // The nearest sign change within a grid step, bisected; a tangent root (a tongue's tip on
    // the b = 0 axis, where |tr Φ| − 2 touches 0 from above) is the sample nearest zero, known
    // to a cell.
    double truth = kInf, floor = 1e-13, smallest = kInf, at_smallest = kInf;
    const int cells = 400;
    for (int i = 0; i < cells; ++i) {
      double lo = x0 - 0.025 + 0.05 * i / cells, hi = lo + 0.05 / cells;
      double flo = indicator(lo);
      if (std::abs(flo) < smallest) {
        smallest = std::abs(flo);
        at_smallest = lo;
      }
      if ((flo < 0) == (indicator(hi) < 0)) continue;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(lo)); ++it) {
        const double mid = 0.5 * (lo + hi), fm = indicator(mid);
        if ((fm < 0) == (flo < 0)) {
          lo = mid;
          flo = fm;
        } else {
          hi = mid;
        }
      }
      if (std::abs(0.5 * (lo + hi) - x0) < std::abs(truth - x0)) truth = 0.5 * (lo + hi);
    }
    if (!std::isfinite(truth) && smallest < 1e-10) {
      truth = at_smallest;
      floor = 0.05 / cells;
    }
    rows.push_back(HonestyPoint("meissner-map", "chart boundary bracket (Meissner c = 0 map)",
                                p.axis == 0 ? "a" : "b", x0, p.estimate.bracket,
                                std::abs(truth - x0), floor));
  }
  std::cerr << "  meissner-map: " << refined << " refined boundary points\n";
}

// --- output ---------------------------------------------------------------------------------

void WriteCsv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream f(path);
  f << "scene,panel,method,knob_name,knob,ok,error_abs,error_rel,cpu_s,wall_s,repeats,estimate,"
       "estimate_error,note\n";
  f << std::setprecision(6);
  for (const Row& r : rows) {
    std::string note = r.note;
    for (char& c : note)
      if (c == ',' || c == '\n' || c == '"') c = ';';
    f << r.scene << "," << r.panel << "," << r.method << "," << r.knob_name << "," << r.knob << ","
      << r.ok << "," << r.error_abs << "," << r.error_rel << "," << r.t.cpu_s << "," << r.t.wall_s
      << "," << r.t.repeats << "," << r.estimate << "," << r.estimate_error << "," << note << "\n";
  }
}

// One gnuplot script per scene: error (log) against CPU time (log), one line per method;
// exponents left, partial FRFs right (when the scene has inputs and outputs).
void WriteGnuplot(const StudyScene& sc, const std::vector<Row>& rows, const std::string& dir,
                  const std::string& svg) {
  const std::string dat = dir + "/" + sc.name + ".dat";
  std::ofstream d(dat);
  d << std::setprecision(6);
  std::vector<std::pair<std::string, std::string>> blocks;  // (panel, method), in order
  for (const std::string panel : {"exponents", "pfrf"}) {
    std::vector<std::string> methods;
    for (const Row& r : rows)
      if (r.scene == sc.name && r.panel == panel &&
          std::find(methods.begin(), methods.end(), r.method) == methods.end())
        methods.push_back(r.method);
    for (const auto& m : methods) {
      int written = 0;
      d << "# " << panel << " / " << m << "\n";
      for (const Row& r : rows)
        if (r.scene == sc.name && r.panel == panel && r.method == m && r.ok &&
            std::isfinite(r.error_rel)) {
          // Errors below 1e-16 relative are round-off: drawn at the floor of the chart.
          d << r.t.cpu_s << " " << std::max(r.error_rel, 1e-16) << " " << r.knob << "\n";
          ++written;
        }
      if (!written) d << "nan nan nan\n";
      d << "\n\n";
      blocks.push_back({panel, m});
    }
  }
  const bool two = sc.pfrf;
  std::ofstream g(dir + "/" + sc.name + ".gp");
  g << "set terminal svg size " << (two ? 1200 : 640)
    << ",480 dynamic font 'sans,11' background rgb 'white'\n"
    << "set output '" << svg << "'\n"
    << "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
    << "set grid\nset key outside below maxrows 4 font ',9'\n"
    << "set xlabel 'CPU time per analysis [s] (median)'\n";
  if (two) g << "set multiplot layout 1,2 title '" << sc.title << "'\n";
  int idx = 0;
  for (const std::string panel : {"exponents", "pfrf"}) {
    std::vector<std::string> cmds;
    for (size_t i = 0; i < blocks.size(); ++i) {
      if (blocks[i].first != panel) continue;
      cmds.push_back("'" + dat + "' index " + std::to_string(i) +
                     " using 1:2 with linespoints pt " + std::to_string(idx % 13 + 1) +
                     " lw 1.5 title '" + blocks[i].second + "'");
      ++idx;
    }
    if (cmds.empty()) continue;
    if (panel == "exponents") {
      g << "set title '" << (two ? "Floquet exponents" : sc.title) << "'\n"
        << "set ylabel 'max exponent error / max(1, max|λ|)'\n";
    } else {
      g << "set title 'partial FRFs H_z, z = -2..2, " << sc.freqs_hz.size() << " frequencies'\n"
        << "set ylabel 'max |H_z - H_z,ref| / max |H_z,ref|'\n";
    }
    g << "plot ";
    for (size_t i = 0; i < cmds.size(); ++i) g << (i ? ", \\\n     " : "") << cmds[i];
    g << "\n";
  }
  if (two) g << "unset multiplot\n";
}

std::string Fmt3(double x) {
  std::ostringstream s;
  s << std::setprecision(3) << x;
  return s.str();
}

void Honesty(const std::vector<Row>& rows, std::ostream& out) {
  // Every point with an estimate: under-estimate when estimate < true error. Over-estimation
  // factor = estimate / max(true error, round-off floor 1e-15·scale-free) on points above the
  // floor: below ~1e-14 the "true error" is itself round-off of the reference.
  struct Acc {
    int points = 0, under = 0, none = 0, at_floor = 0;
    std::vector<double> factors;
    std::vector<std::string> worst;
  };
  std::map<std::string, Acc> by;
  for (const Row& r : rows) {
    if (r.estimate_error < 0) continue;
    const std::string key = r.panel == "pfrf-honesty" ? "partial FRF (ltp pfrf default)" : r.method;
    Acc& a = by[key];
    if (r.estimate < 0 || !std::isfinite(r.estimate_error)) {
      ++a.none;
      continue;
    }
    ++a.points;
    if (r.estimate_error <= r.floor) {
      ++a.at_floor;  // the true error is below what the reference can resolve
      continue;
    }
    // The true error is only known to within the reference's own uncertainty (the floor):
    // an under-estimate is one that falls short of the measured error by more than that.
    if (r.estimate < r.estimate_error - r.floor) {
      ++a.under;
      std::ostringstream w;
      w << r.scene << " " << r.knob_name << "=" << r.knob << ": estimate " << Fmt(r.estimate)
        << " < error " << Fmt(r.estimate_error);
      a.worst.push_back(w.str());
    } else if (r.estimate_error > 0) {
      a.factors.push_back(r.estimate / r.estimate_error);
    }
  }
  out << "| method | points | under-estimates | median over-estimation | error at the reference "
         "floor | "
         "no estimate / failed |\n"
      << "|---|---|---|---|---|---|\n";
  int total = 0, under = 0, measurable = 0;
  std::vector<double> all;
  for (const auto& [k, a] : by) {
    total += a.points;
    under += a.under;
    measurable += a.points - a.at_floor;
    all.insert(all.end(), a.factors.begin(), a.factors.end());
    out << "| " << k << " | " << a.points << " | " << a.under << " ("
        << Fmt3(a.points > a.at_floor ? 100.0 * a.under / (a.points - a.at_floor) : 0) << " %) | "
        << (a.factors.empty() ? std::string("—") : Fmt3(Median(a.factors)) + "×") << " | "
        << a.at_floor << " | " << a.none << " |\n";
  }
  out << "| **all** | " << total << " | " << under << " ("
      << Fmt3(measurable ? 100.0 * under / measurable : 0) << " %) | "
      << (all.empty() ? std::string("—") : Fmt3(Median(all)) + "×") << " | | |\n\n";
  for (const auto& [k, a] : by)
    for (size_t i = 0; i < a.worst.size() && i < 6; ++i)
      out << "- under-estimate, " << k << ": " << a.worst[i] << "\n";
}

// Does every automatic choice follow the charts? For each `auto` point: the cheapest other
// method of the same scene and panel that reached the same error (within 2×, or the floor),
// and the CPU-time ratio auto / that method (1 = auto picked the winner; < 1: auto beat every
// measured point, e.g. by choosing a resolution between the study's knob values).
void AutoChoiceTable(const std::vector<Row>& rows, std::ostream& out) {
  out << "| scene | panel | auto (knob) | picked | error | CPU | cheapest other at that error | "
         "its CPU | auto / cheapest |\n"
      << "|---|---|---|---|---|---|---|---|---|\n";
  std::vector<double> ratios;
  for (const Row& a : rows) {
    if (a.method.find("auto") == std::string::npos || !a.ok || a.panel == "pfrf-honesty") continue;
    // Auto picks within a family: integrators (`--integrator auto`), Hill (`--harmonics auto`,
    // `--hill-solver auto`), PFRF routes (`--route auto`: full sweeps of `ltp pfrf`).
    auto family = [](const Row& r) {
      if (r.panel == "pfrf") return r.method.rfind("ltp pfrf", 0) == 0 ? 2 : 3;
      return r.method.rfind("hill", 0) == 0 || r.method == "koopman-hill" ? 1 : 0;
    };
    const Row* best = nullptr;
    for (const Row& c : rows) {
      if (c.scene != a.scene || c.panel != a.panel || !c.ok ||
          c.method.find("auto") != std::string::npos || family(c) != family(a))
        continue;
      if (c.error_abs > std::max(2 * a.error_abs, a.floor)) continue;
      if (!best || c.t.cpu_s < best->t.cpu_s) best = &c;
    }
    out << "| " << a.scene << " | " << a.panel << " | " << a.method << " (" << a.knob_name << " "
        << Fmt3(a.knob) << ") | " << a.note << " | " << Fmt3(a.error_rel) << " | "
        << Fmt3(a.t.cpu_s * 1e3) << " ms | ";
    if (best) {
      const double ratio = a.t.cpu_s / best->t.cpu_s;
      ratios.push_back(ratio);
      out << best->method << " (" << best->knob_name << " " << Fmt3(best->knob) << ") | "
          << Fmt3(best->t.cpu_s * 1e3) << " ms | " << Fmt3(ratio) << " |\n";
    } else {
      out << "none reached it | — | — |\n";
    }
  }
  if (!ratios.empty())
    out << "\nMedian auto / cheapest: " << Fmt3(Median(ratios))
        << "; worst: " << Fmt3(*std::max_element(ratios.begin(), ratios.end())) << " ("
        << ratios.size() << " points).\n";
}

}  // namespace

int main(int argc, char** argv) {
  Config cfg;
  bool run_study = true, run_map = true;
  std::string only_regime;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) {
      cfg.out = argv[++i];
    } else if (a == "--failure-map-only") {
      run_study = false;
    } else if (a == "--regime" && i + 1 < argc) {
      only_regime = argv[++i];
    } else if (a == "--no-failure-map") {
      run_map = false;
    } else if (a == "--quick") {
      cfg.quick = true;
      cfg.repeats = 3;
      cfg.budget_s = 0.1;
    } else if (a == "--scenes" && i + 1 < argc) {
      std::stringstream ss(argv[++i]);
      std::string item;
      while (std::getline(ss, item, ',')) cfg.scenes.insert(item);
    } else if (a == "--repeats" && i + 1 < argc) {
      cfg.repeats = std::atoi(argv[++i]);
    } else if (a == "--help" || a == "-h") {
      std::cout
          << "usage: work_precision_benchmark [--out DIR] [--quick] [--scenes a,b,...] "
             "[--repeats R]\n"
             "       [--failure-map-only | --no-failure-map]\n"
             "scenes: mathieu meissner stiff stiff-coupled reducible poisson rotor tower-rotor, "
             "and the honesty-only sampled meissner-map; writes "
             "DIR/work_precision.csv, "
             "DIR/<scene>.gp, DIR/honesty.md, DIR/auto_choice.md, DIR/failure_map.md, "
             "DIR/references.txt,\n"
             "DIR/pfrf_reference.csv\n";
      return 0;
    } else {
      std::cerr << "work_precision_benchmark: error: unrecognized argument '" << a << "'\n";
      return 2;
    }
  }
  std::filesystem::create_directories(cfg.out);
  std::ofstream log(cfg.out + "/references.txt");
  if (run_study)  // channel (0, 0); one block per PFRF scene, appended by RunPfrf
    std::ofstream(cfg.out + "/pfrf_reference.csv")
        << "scene,freq_hz,order,re,im,reference_agreement_rel\n";
  const double t0 = WallNow();
  std::vector<Row> rows;
  std::vector<StudyScene> scenes;
  try {
    if (run_study) scenes = MakeScenes(cfg);
  } catch (const std::exception& e) {
    std::cerr << "work_precision_benchmark: error: " << e.what() << "\n";
    return 1;
  }
  for (const StudyScene& sc : scenes) {
    log << sc.name << ": " << sc.title
        << "\n  monodromy methods measured against: " << sc.ref_mono_source
        << "\n  Hill methods measured against: " << sc.ref_hill_source
        << "\n  scale max(1, max|λ|) = " << Fmt(sc.scale);
    if (sc.reference_agreement >= 0)
      log << "\n  the two references agree to " << Fmt(sc.reference_agreement) << " 1/s ("
          << Fmt(sc.reference_agreement / sc.scale) << " relative)";
    log << "\n";
    std::cerr << "scene " << sc.name << " (" << Fmt(WallNow() - t0) << " s)\n";
    RunMonodromy(sc, cfg, rows);
    RunHill(sc, cfg, rows);
    if (sc.pfrf) RunPfrf(sc, cfg, rows, log);
    WriteCsv(rows, cfg.out + "/work_precision.csv");  // after every scene: partial results survive
  }
  auto want = [&](const std::string& n) { return cfg.scenes.empty() || cfg.scenes.count(n); };
  if (run_study && want("sampled")) {
    std::cerr << "sampled .lin models (" << Fmt(WallNow() - t0) << " s)\n";
    RunSampledHonesty(cfg, rows);
  }
  if (run_study && want("meissner-map")) {
    std::cerr << "Meissner map boundaries (" << Fmt(WallNow() - t0) << " s)\n";
    RunBoundaryHonesty(rows);
  }
  WriteCsv(rows, cfg.out + "/work_precision.csv");
  for (const StudyScene& sc : scenes)
    WriteGnuplot(sc, rows, cfg.out, cfg.out + "/work-precision-" + sc.name + ".svg");
  if (run_study) {
    std::ofstream h(cfg.out + "/honesty.md");
    Honesty(rows, h);
    std::ofstream a(cfg.out + "/auto_choice.md");
    AutoChoiceTable(rows, a);
  }
  if (run_map) {
    std::ofstream m(cfg.out + "/failure_map.md");
    const auto map = RunFailureMap(cfg.quick, &std::cerr, only_regime);
    WriteFailureMap(map, m);
  }
  std::cerr << "done in " << Fmt(WallNow() - t0) << " s; results in " << cfg.out << "\n";
  return 0;
}
