#include <cmath>
#include <complex>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>

#include "command.h"
#include "deflection_output.h"
#include "format.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/floquet/estimate_source.h"
#include "ltp/floquet/floquet.h"
#include "ltp/floquet/model_error.h"
#include "ltp/hill/hill.h"
#include "ltp/hill/hill_model_error.h"
#include "ltp/models/rotor.h"
#include "ltp/studies/rotor_mbc_check.h"
#include "modal_reduction_output.h"
#include "plot.h"
#include "progress_bar.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

// Defaults from the library's option structs (Python's ltp.floquet and ltp.hill have the same).
struct FloquetArgs {
  SceneArgs scene;
  FloquetOptions options;
  std::string integrator{ToString(IntegratorOptions{}.type)};
  std::string hill_solver{ToString(HillOptions{}.solver)};
  std::string segments = "auto";
  std::string multipliers = "schur";
  std::string estimate{ToString(FloquetOptions{}.error_estimate_method)};
  std::string method = "monodromy";
  std::string harmonics = "auto";
  bool json = false;
  bool keep_going = false;
  std::string modes_csv;
  std::string deflection_csv;
  std::string deflection_plot;
  std::vector<int> deflection_modes;  ///< numbered from 1, as in the table; empty: every mode
  ModeDeflectionOptions deflection;
  std::string plot;
  double modes_below_hz = 0;
};

// Turns the string options into the library's enums and counts. @throws InputError.
void ResolveOptions(FloquetArgs& args) {
  auto type = ParseIntegratorType(args.integrator);
  if (!type)
    throw InputError("unknown integrator '" + args.integrator + "' (" + IntegratorNames() + ")");
  if (!ParseHillSolver(args.hill_solver))
    throw InputError("--hill-solver must be auto, dense or structured, got '" + args.hill_solver +
                     "'");
  args.options.integrator.type = *type;
  args.options.modes_below = 2 * kPi * args.modes_below_hz;
  if (args.modes_below_hz > 0 && args.method != "monodromy")
    throw InputError(
        "--modes-below works with --method monodromy (Hill's route analyses every "
        "mode)");
  if (args.segments == "auto") {
    args.options.segments = 0;
  } else {
    try {
      size_t used = 0;
      args.options.segments = std::stoi(args.segments, &used);
      if (used != args.segments.size() || args.options.segments < 1)
        throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw InputError("--segments must be a positive integer or 'auto', got '" + args.segments +
                       "'");
    }
  }
  if (args.method != "monodromy" && args.method != "hill" && args.method != "both")
    throw InputError("--method must be monodromy, hill or both, got '" + args.method + "'");
  // The mode shapes and the plot come from the monodromy route; Hill alone would skip them.
  if (args.method == "hill" && (!args.modes_csv.empty() || !args.plot.empty() ||
                                !args.deflection_csv.empty() || !args.deflection_plot.empty()))
    throw InputError(std::string(!args.modes_csv.empty()         ? "--modes-csv"
                                 : !args.deflection_csv.empty()  ? "--deflection-csv"
                                 : !args.deflection_plot.empty() ? "--deflection-plot"
                                                                 : "--plot") +
                     " needs the monodromy route: use --method monodromy or both");
  if (!args.deflection_modes.empty() && args.deflection_csv.empty() && args.deflection_plot.empty())
    throw InputError(
        "--deflection-mode chooses the modes of --deflection-csv or --deflection-plot: give one "
        "of them too");
  args.deflection.Validate();
  if (args.harmonics != "auto") {
    try {
      size_t used = 0;
      const int n = std::stoi(args.harmonics, &used);
      if (used != args.harmonics.size() || n < 1) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw InputError("--harmonics must be a positive integer or 'auto', got '" + args.harmonics +
                       "'");
    }
  }
  const auto estimate = ParseErrorEstimateMethod(args.estimate);
  if (!estimate)
    throw InputError("--estimate must be auto, refined-run or local-errors, got '" + args.estimate +
                     "'");
  args.options.error_estimate_method = *estimate;
  if (args.multipliers == "schur" || args.multipliers == "periodic-schur") {
    args.options.multipliers = MultiplierMethod::kPeriodicSchur;
  } else if (args.multipliers == "single-shot") {
    args.options.multipliers = MultiplierMethod::kSingleShot;
  } else {
    throw InputError("--multipliers must be 'schur' or 'single-shot', got '" + args.multipliers +
                     "'");
  }
}

json ModesJson(const std::vector<FloquetMode>& modes, json* multipliers, json* extra) {
  json exps = json::array();
  *multipliers = json::array();
  *extra = json::array();
  for (const FloquetMode& m : modes) {
    exps.push_back(
        {{"re", JsonNumber(m.exponent.real())},
         {"im", JsonNumber(m.exponent.imag())},
         {"frequency_hz", JsonNumber(m.frequency_hz)},
         {"damping_ratio", JsonNumber(m.damping_ratio)},
         {"error_estimate", m.error_estimate ? JsonNumber(*m.error_estimate) : json(nullptr)}});
    const double mag = ExpClamped(m.log_multiplier.real());
    multipliers->push_back({{"re", JsonNumber(mag * std::cos(m.log_multiplier.imag()))},
                            {"im", JsonNumber(mag * std::sin(m.log_multiplier.imag()))},
                            {"log_abs", JsonNumber(m.log_multiplier.real())},
                            {"arg", JsonNumber(m.log_multiplier.imag())}});
    extra->push_back({{"branch", m.branch},
                      {"rigid_body", m.rigid_body},
                      {"central_weight", JsonNumber(m.central_weight)},
                      {"branch_margin", JsonNumber(m.branch_margin)},
                      {"eigenvector_residual", JsonNumber(m.eigvec_residual)}});
    if (m.forward_whirl) extra->back()["forward_whirl"] = JsonNumber(*m.forward_whirl);
  }
  return exps;
}

// What an analysis of the modes below a cut-off left out (null for a full analysis).
json MonodromyJson(const LoadedScene& l, const FloquetArgs& args, const FloquetResult& r) {
  json mults, modes;
  json exps = ModesJson(r.modes, &mults, &modes);
  for (size_t k = 0; k < r.mode_descriptions.size() && k < modes.size(); ++k)
    modes[k]["description"] = r.mode_descriptions[k];
  return {{"scene", l.scene.name},
          {"parameters", ParametersJson(l.parameters)},
          {"states", r.states},
          {"period", r.period},
          {"method", "monodromy"},
          {"integrator", std::string(ToString(r.integrator))},
          {"tolerance", args.options.integrator.rel_tol},
          {"multiplier_method", std::string(ToString(r.multiplier_method))},
          {"segments", r.segments},
          {"branch_rule", "energy centroid of the periodic mode shape on harmonic 0"},
          {"exponents", exps},
          {"multipliers", mults},
          {"modes", modes},
          {"max_real_exponent", JsonNumber(r.max_real_exponent)},
          {"max_log_abs_multiplier", JsonNumber(r.max_log_abs_multiplier)},
          {"stable", r.stable},
          {"verdict", ToString(r.verdict)},
          {"error_estimate", JsonNumber(r.error_estimate)},
          {"error_estimate_method", ToString(r.error_estimate_method)},
          {"estimate_source", EstimateSource(r.error_estimate_method, r.integrator)},
          {"model_error", r.model_error ? JsonNumber(*r.model_error) : json(nullptr)},
          {"modes_below", ReductionJson(r.reduction)},
          {"liouville_residual", JsonNumber(r.liouville_residual)},
          {"mode_condition", JsonNumber(r.mode_condition)},
          {"rhs_evals", r.rhs_evals},
          {"elapsed_s", r.elapsed_s},
          {"ok", r.ok},
          {"failure", r.failure},
          {"diagnostics", Texts(r.diagnostics)}};
}

json HillJson(const LoadedScene& l, const HillResult& h) {
  json mults, modes;
  json exps = ModesJson(h.modes, &mults, &modes);
  double margin = 1;
  for (size_t k = 0; k < h.info.size(); ++k) {
    modes[k]["selection_margin"] = JsonNumber(h.info[k].selection_margin);
    modes[k]["tail_weight"] = JsonNumber(h.info[k].tail_weight);
    margin = std::min(margin, h.info[k].selection_margin);
  }
  return {{"scene", l.scene.name},
          {"parameters", ParametersJson(l.parameters)},
          {"states", h.states},
          {"period", h.period},
          {"method", "hill"},
          {"harmonics", h.harmonics},
          {"matrix_size", h.matrix_size},
          {"solver", h.SolverDescription()},
          {"selection_rule", h.selection_rule},
          {"exponents", exps},
          {"multipliers", mults},
          {"modes", modes},
          {"selection_margin", JsonNumber(margin)},
          {"max_real_exponent", JsonNumber(h.max_real_exponent)},
          {"stable", h.stable},
          {"verdict", ToString(h.verdict)},
          {"truncation_estimate", JsonNumber(h.truncation_estimate)},
          {"apriori_bound", JsonNumber(h.apriori_bound)},
          {"koopman_discrepancy", JsonNumber(h.koopman_discrepancy)},
          {"coefficient_decay",
           {{"kind", std::string(ToString(h.decay.kind))}, {"rate", JsonNumber(h.decay.rate)}}},
          {"error_estimate", JsonNumber(h.error_estimate)},
          {"model_error", h.model_error ? JsonNumber(*h.model_error) : json(nullptr)},
          {"fourier_fit_error", JsonNumber(h.fourier_fit_error)},
          {"tolerance_met", h.tolerance_met ? json(*h.tolerance_met) : json(nullptr)},
          {"elapsed_s", h.elapsed_s},
          {"ok", h.ok},
          {"failure", h.failure},
          {"diagnostics", Texts(h.diagnostics)}};
}

// "; forward whirl 97%" (the share turning with the rotor, or against it when that is larger).
std::string WhirlText(const FloquetMode& m) {
  if (!m.forward_whirl || !std::isfinite(*m.forward_whirl)) return "";
  const double f = *m.forward_whirl;
  return f >= 0.5 ? "; forward whirl " + Num(100 * f, 3) + "%"
                  : "; backward whirl " + Num(100 * (1 - f), 3) + "%";
}

void PrintModeTable(const std::vector<FloquetMode>& modes,
                    const std::vector<std::string>& descriptions = {}) {
  std::cout << "\n  mode      Re λ [1/s]    Im λ [rad/s]     freq [Hz]   damping ζ       log|ρ|    "
               "arg ρ [rad]  branch"
            << (descriptions.empty() ? "" : "   carried by (participation at t = 0)") << "\n";
  for (size_t k = 0; k < modes.size(); ++k) {
    const FloquetMode& m = modes[k];
    std::cout << "  " << std::setw(4) << k + 1 << Num(m.exponent.real(), 7, 15)
              << Num(m.exponent.imag(), 7, 16) << Num(m.frequency_hz, 6, 14)
              << Num(m.damping_ratio, 4, 12) << Num(m.log_multiplier.real(), 6, 13)
              << Num(m.log_multiplier.imag(), 6, 15) << std::setw(8) << m.branch
              << (k < descriptions.size() ? "   " + descriptions[k] : std::string()) << WhirlText(m)
              << (m.rigid_body ? "  rigid body" : "") << "\n";
  }
}

// The headline: stable / unstable only beyond the error estimate.
std::string VerdictText(StabilityVerdict verdict) {
  switch (verdict) {
    case StabilityVerdict::kStable:
      return "STABLE";
    case StabilityVerdict::kUnstable:
      return "UNSTABLE";
    case StabilityVerdict::kMarginal:
      return "MARGINAL (|max Re λ| within the error estimate: undecided)";
    case StabilityVerdict::kFailed:
      return "NOT DECIDED: the result failed its own checks";
  }
  return "?";
}

void PrintDiagnostics(const std::vector<Diagnostic>& diagnostics) {
  if (diagnostics.empty()) return;
  std::cout << "  diagnostics:\n";
  for (const Diagnostic& d : diagnostics) std::cout << "    - " << d.text << "\n";
}

void PrintMonodromy(const FloquetArgs& args, const FloquetResult& r) {
  std::cout << "  monodromy by " << ToString(r.integrator)
            << (args.integrator == "auto" ? " (picked by --integrator auto; " : " (") << "rel tol "
            << args.options.integrator.rel_tol << ") over K = " << r.segments
            << " segments; multipliers by " << ToString(r.multiplier_method) << "\n";
  if (r.modes.empty()) {
    std::cout << "\n  FAILED\n";
    PrintDiagnostics(r.diagnostics);
    return;
  }
  if (!r.ok)
    std::cout << "\n  FAILED its own checks (see diagnostics): the exponents below are wrong\n";
  PrintModeTable(r.modes, r.mode_descriptions);
  if (r.reduction) PrintReduction(*r.reduction, r.states);
  std::cout << "\n  max Re λ = " << Num(r.max_real_exponent, 8) << " 1/s  →  "
            << VerdictText(r.verdict) << "   (max log|ρ| = " << Num(r.max_log_abs_multiplier, 8)
            << ")\n"
            << "  error estimate " << Num(r.error_estimate, 2) << " 1/s on every exponent\n  ("
            << EstimateSource(r.error_estimate_method, r.integrator) << ")\n";
  if (r.model_error)
    std::cout << "  of which the model's sampling error is " << Num(*r.model_error, 2)
              << " 1/s (other models of the same samples; docs/sampled-models.md)\n";
  std::cout << "  Liouville residual " << Num(r.liouville_residual, 2) << ", cond(Ξ) "
            << Num(r.mode_condition, 3) << ", " << r.rhs_evals
            << (r.integrator == IntegratorType::kTaylor ? " products of A's and Φ's series, "
                                                        : " evaluations of A(t), ")
            << Num(r.elapsed_s * 1e3, 3) << " ms\n"
            << "  branch: Im λ chosen so each periodic mode shape's Fourier energy is centred on "
               "harmonic 0\n";
  PrintDiagnostics(r.diagnostics);
}

void PrintHill(const HillResult& h) {
  std::cout << "  Hill's method: N = " << h.harmonics << " harmonics (matrix " << h.matrix_size
            << "×" << h.matrix_size << ", " << h.SolverDescription() << " solver, "
            << h.selection_rule << " selection)\n";
  if (h.modes.empty()) {
    std::cout << "\n  FAILED\n";
    PrintDiagnostics(h.diagnostics);
    return;
  }
  if (!h.ok)
    std::cout << "\n  FAILED its own checks (see diagnostics): the exponents below are wrong\n";
  PrintModeTable(h.modes);
  std::cout << "\n  max Re λ = " << Num(h.max_real_exponent, 8) << " 1/s  →  "
            << VerdictText(h.verdict) << "\n"
            << "  truncation estimate (N vs N+" << h.delta_harmonics << ") "
            << Num(h.truncation_estimate, 2) << " 1/s, Koopman–Hill disagreement "
            << Num(h.koopman_discrepancy, 2) << ", a-priori bound " << Num(h.apriori_bound, 2)
            << "\n  coefficients of A: " << ToString(h.decay.kind) << " decay";
  if (h.decay.kind == FourierDecay::kExponential)
    std::cout << " (rate " << Num(h.decay.rate, 3) << ")";
  if (h.decay.kind == FourierDecay::kAlgebraic)
    std::cout << " (|A_w| ~ |w|^-" << Num(h.decay.rate, 3) << ")";
  std::cout << ", " << Num(h.elapsed_s * 1e3, 3) << " ms\n"
            << "  error estimate " << Num(h.error_estimate, 2) << " 1/s on every exponent";
  if (h.fourier_fit_error > 0)
    std::cout << " (of which the Fourier fit of A: " << Num(h.fourier_fit_error, 2) << ")";
  std::cout << "\n";
  if (h.model_error)
    std::cout << "  of which the model's sampling error is " << Num(*h.model_error, 2)
              << " 1/s (other models of the same samples; docs/sampled-models.md)\n";
  if (h.tolerance_met && !*h.tolerance_met)
    std::cout
        << "  tolerance NOT reached (see diagnostics): the estimate is what this N delivers\n";
  PrintDiagnostics(h.diagnostics);
}

// Largest distance between the two routes' exponents, matched one-to-one modulo jΩp.
double Disagreement(const std::vector<FloquetMode>& a, const std::vector<FloquetMode>& b,
                    double omega) {
  std::vector<std::complex<double>> x, y;
  for (const FloquetMode& m : a) x.push_back(m.exponent);
  for (const FloquetMode& m : b) y.push_back(m.exponent);
  return MaxExponentMismatch(x, y, omega);
}

json MbcCheckJson(const std::optional<RotorMbcCheck>& check) {
  if (!check) return nullptr;
  if (!check->applicable) return {{"applicable", false}, {"reason", check->reason}};
  return {{"applicable", true},
          {"blades", check->blades},
          {"max_difference", JsonNumber(check->max_difference)}};
}

void PrintMbcCheck(const std::optional<RotorMbcCheck>& check) {
  if (!check) return;
  if (!check->applicable) {
    std::cout << "  MBC cross-check: not applicable — " << check->reason << "\n";
    return;
  }
  std::cout << "  MBC cross-check (" << check->blades
            << " blades): the Floquet exponents equal the eigenvalues of the constant "
               "multi-blade-coordinate system modulo jΩ to "
            << Num(check->max_difference, 2) << " 1/s\n";
}

// Hill's route beside (or instead of) the monodromy route; a successful monodromy run gives the
// structured solver its shifts. `r` is null when the monodromy route did not run.
HillResult RunHillRoute(const LoadedScene& l, const FloquetArgs& args, const FloquetResult* r) {
  HillOptions ho;
  ho.solver = *ParseHillSolver(args.hill_solver);
  ho.max_work_seconds = args.options.max_work_seconds;
  ho.on_long_work = [](const WorkEstimate& w) {
    std::cerr << "ltp floquet: Hill's method: " << WorkAhead(w.seconds()) << " (" << w.basis
              << ")\n";
  };
  if (r && r->ok) {  // shifts for the structured solver from the monodromy route
    for (const auto& m : r->modes) ho.expected.push_back(m.exponent);
  }
  HillResult h;
  if (args.harmonics == "auto") {
    h = AnalyzeHillToTolerance(l.system, ho, args.options.integrator.rel_tol);
  } else {
    ho.harmonics = std::stoi(args.harmonics);
    h = AnalyzeHill(l.system, ho);
  }
  IncludeModelError(l.model_alternatives, args.options, h);  // as for the monodromy route
  return h;
}

// --modes-csv: the periodic mode shapes ξ_k(t) at the sample times, one row per time; columns
// re_mode1_x, im_mode1_x: by mode number (as in the table) and state name.
void WriteModesCsv(const FloquetResult& r, const SystemLabels& labels, const std::string& file) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  csv << "t";
  const int modes = static_cast<int>(r.modes.size());  // fewer than states with --modes-below
  for (int k = 0; k < modes; ++k)
    for (int i = 0; i < r.states; ++i) {
      const std::string state = i < static_cast<int>(labels.states.size())
                                    ? labels.states[static_cast<size_t>(i)]
                                    : "x" + std::to_string(i + 1);
      const std::string column = "_mode" + std::to_string(k + 1) + "_" + state;
      csv << "," << CsvText("re" + column) << "," << CsvText("im" + column);
    }
  csv << "\n" << std::setprecision(12);
  for (size_t s = 0; s < r.mode_samples.size(); ++s) {
    csv << r.sample_times[s];
    for (int k = 0; k < modes; ++k)
      for (int i = 0; i < r.states; ++i)
        csv << "," << r.mode_samples[s](i, k).real() << "," << r.mode_samples[s](i, k).imag();
    csv << "\n";
  }
}

// --deflection-csv and --deflection-plot: the chosen modes' deflected structure over a period
// (scenes that draw one).
void WriteDeflection(const LoadedScene& l, const FloquetArgs& args, const FloquetResult& r) {
  if (!l.scene.geometry)
    throw InputError(
        std::string(args.deflection_csv.empty() ? "--deflection-plot" : "--deflection-csv") +
        ": scene '" + l.scene.name +
        "' has no structure to draw (tower-rotor has one); --modes-csv writes "
        "the mode shapes of any scene");
  std::vector<int> modes;
  for (int k : args.deflection_modes) modes.push_back(k - 1);
  const ModeDeflections d = DeflectModes(l.scene.geometry(l.parameters), r, modes, args.deflection);
  if (!args.deflection_csv.empty()) WriteDeflectionCsv(args.deflection_csv, d);
  if (!args.deflection_plot.empty()) PlotDeflection(args.deflection_plot, d);
}

// One route's JSON as it is, or both side by side with their disagreement.
json FloquetJson(const LoadedScene& l, const FloquetArgs& args, const FloquetResult& r,
                 const HillResult& h) {
  if (args.method == "monodromy") {
    json j = MonodromyJson(l, args, r);
    if (const json mbc =
            r.reduction ? json(nullptr) : MbcCheckJson(CheckRotorByMbc(l.scene, l.parameters, r));
        !mbc.is_null())
      j["mbc_check"] = mbc;
    return j;
  }
  if (args.method == "hill") return HillJson(l, h);
  return {
      {"scene", l.scene.name},
      {"parameters", ParametersJson(l.parameters)},
      {"method", "both"},
      {"monodromy", MonodromyJson(l, args, r)},
      {"hill", HillJson(l, h)},
      {"disagreement", JsonNumber(Disagreement(r.modes, h.modes, 2 * kPi / h.period))},
      {"combined_error_estimate", r.error_estimate && h.error_estimate
                                      ? JsonNumber(std::max(*r.error_estimate, *h.error_estimate))
                                      : nullptr}};
}

void PrintFloquet(const LoadedScene& l, const FloquetArgs& args, const FloquetResult& r,
                  const HillResult& h, bool run_mono, bool run_hill) {
  const double T = l.system.period();
  std::cout << "Floquet analysis of " << l.scene.name;
  if (!l.parameters.empty()) std::cout << " (" << ParameterList(l.parameters) << ")";
  std::cout << "\n  " << l.system.states() << " states, period T = " << Num(T, 10)
            << " s (Ωp = " << Num(2 * kPi / T, 8) << " rad/s)\n";
  if (run_mono) PrintMonodromy(args, r);
  // The cross-check compares every exponent; an analysis of the slow modes has only some.
  if (run_mono && !r.reduction) PrintMbcCheck(CheckRotorByMbc(l.scene, l.parameters, r));
  if (run_mono && run_hill) std::cout << "\n";
  if (run_hill) PrintHill(h);
  if (run_mono && run_hill)
    std::cout << "\n  the two routes disagree by "
              << Num(Disagreement(r.modes, h.modes, 2 * kPi / h.period), 3)
              << " 1/s (largest difference of matched exponents; estimates "
              << Num(r.error_estimate, 2) << " and " << Num(h.error_estimate, 2) << ")\n";
}

int RunFloquet(FloquetArgs& args) {
  if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);  // reject a bad extension up front
  ResolveOptions(args);
  LoadedScene l = LoadSceneArgs(args.scene);
  const bool run_mono = args.method != "hill", run_hill = args.method != "monodromy";
  FloquetResult r;
  HillResult h;
  // A long analysis says so before it starts (the library's estimate), on stderr.
  args.options.on_long_work = [reduced = args.modes_below_hz > 0](const WorkEstimate& w) {
    std::cerr << "ltp floquet: " << WorkAhead(w.seconds()) << " (" << Num(w.evaluations, 2)
              << " evaluations of A(t)·Φ, or their worth of linear algebra, at "
              << Num(w.seconds_per_evaluation * 1e6, 2) << " µs each)\n";
    if (!reduced)
      std::cerr << "ltp floquet: if only the slower modes matter (a Campbell diagram to a few "
                   "Hz), --modes-below HZ analyses those and says what the rest change\n";
  };
  ProgressBar progress("floquet", !args.json);  // long integrations: a bar on a terminal
  args.options.on_progress = [&progress](std::string_view phase, double fraction) {
    progress.Update(fraction, 1, {}, phase);
  };
  if (run_mono) r = AnalyzeFloquet(l.system, args.options);
  // A sampled model (.lin files): the estimate and the verdict include the sampling error.
  if (run_mono) IncludeModelError(l.model_alternatives, args.options, r);
  if (run_hill) h = RunHillRoute(l, args, run_mono ? &r : nullptr);

  progress.Clear();
  if (run_mono && !args.modes_csv.empty()) WriteModesCsv(r, l.system.labels(), args.modes_csv);
  if (run_mono && !(args.deflection_csv.empty() && args.deflection_plot.empty()))
    WriteDeflection(l, args, r);
  if (run_mono && !args.plot.empty()) PlotFloquet(r, l.scene.name, args.plot);
  const bool ok = (!run_mono || r.ok) && (!run_hill || h.ok);
  if (run_mono && !r.ok)
    SetFailureFrom("monodromy route", r.failure);
  else if (run_hill && !h.ok)
    SetFailureFrom("Hill's method", h.failure);

  if (args.json)
    std::cout << FloquetJson(l, args, r, h).dump(2) << "\n";
  else
    PrintFloquet(l, args, r, h, run_mono, run_hill);
  return ok || args.keep_going ? 0 : 1;
}

}  // namespace

Command AddFloquetCommand(CLI::App& app) {
  static FloquetArgs args;
  FloquetArgs fresh;  // fresh state for each RunLtp call (the argument fuzzer makes many)
  args = std::move(fresh);
  auto* cmd = app.add_subcommand(
      "floquet", "Floquet exponents, multipliers and periodic modes via the monodromy matrix");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--integrator", args.integrator,
                  "auto | dopri5 | rkf78 | bs | cvode | cvode-adams | magnus4 | magnus6 | expm | "
                  "taylor | magnus-filon (these two: Fourier-form A(t) only) "
                  "(auto: the work-precision study's cheapest for the system; the output says "
                  "which and why)")
      ->capture_default_str();
  cmd->add_option("--hill-solver", args.hill_solver,
                  "Hill's eigensolver: auto | dense | structured (auto: per N, as the study found)")
      ->capture_default_str();
  cmd->add_option("--tol", args.options.integrator.rel_tol, "relative tolerance")
      ->capture_default_str()
      ->check(NumberAboveZero());
  cmd->add_option("--steps", args.options.integrator.steps_per_period,
                  "fixed-step methods: steps per period (0 = automatic, at most 1e8)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000000));
  cmd->add_option("--method", args.method,
                  "monodromy | hill | both (both: side by side, with their disagreement)")
      ->capture_default_str();
  cmd->add_option(
         "--harmonics", args.harmonics,
         "Hill truncation N (harmonics -N..N), or auto (doubled until N vs N+Δ agree to --tol)")
      ->capture_default_str();
  cmd->add_option("--segments", args.segments, "number of segments K, or auto")
      ->capture_default_str();
  cmd->add_option(
         "--multipliers", args.multipliers,
         "schur (periodic Schur of the segment factors) | single-shot (eig of the formed Φ)")
      ->capture_default_str();
  cmd->add_option(
         "--estimate", args.estimate,
         "auto (local-errors for Taylor series and Magnus, refined-run otherwise) | refined-run "
         "(a second run at --tol/100 gives the numbers) | local-errors (one run: " +
             std::string(kLocalErrorSources) + ")")
      ->capture_default_str();
  cmd->add_option("--mode-samples", args.options.mode_samples,
                  "samples of the mode shapes per period (power of two; 0 = automatic)")
      ->capture_default_str();
  cmd->add_option("--threads", args.options.threads, "OpenMP threads (0 = all cores)")
      ->capture_default_str();
  cmd->add_option("--modes-below", args.modes_below_hz,
                  "analyse only the modes whose eigenvalue of the mean A(t) is below this many Hz "
                  "(|λ|/2π), checked against twice the cut-off; 0 = every mode")
      ->capture_default_str()
      ->check(NumberAboveZero(true));
  cmd->add_option("--max-work", args.options.max_work_seconds,
                  "refuse an analysis estimated to need more CPU seconds than this even at its "
                  "fastest (0 = no limit)")
      ->capture_default_str()
      ->check(NumberAboveZero(true));
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  cmd->add_flag("--keep-going", args.keep_going,
                "exit 0 even when the analysis failed its own checks (the output still says so; "
                "default: exit 1)");
  cmd->add_option("--modes-csv", args.modes_csv, "write the periodic mode shapes ξ_k(t) to CSV");
  cmd->add_option("--deflection-csv", args.deflection_csv,
                  "write each mode's deflected structure over one period to CSV (scenes with a "
                  "structure: tower-rotor)");
  cmd->add_option("--deflection-plot", args.deflection_plot,
                  "draw the deflected structure of up to 4 modes chosen by --deflection-mode "
                  "(FILE.svg or FILE.png)");
  cmd->add_option("--deflection-mode", args.deflection_modes,
                  "only these modes in --deflection-csv and --deflection-plot (numbered as in "
                  "the table; repeatable)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--deflection-amplitude", args.deflection.amplitude,
                  "largest node displacement in --deflection-csv and --deflection-plot, as a "
                  "fraction of the structure's size")
      ->capture_default_str();
  cmd->add_option("--plot", args.plot,
                  "draw exponents and mode-shape spectra (FILE.svg or FILE.png)");
  return {cmd, [] { return RunFloquet(args); }};
}

}  // namespace ltp::cli
