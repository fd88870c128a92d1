// `ltp hill`: convergence study of Hill's method over the truncation N, against the
// monodromy route, with the a-priori bound and the analysis' own error estimate per row.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "command.h"
#include "format.h"
#include "ltp/core/error.h"
#include "ltp/floquet/floquet.h"
#include "ltp/hill/hill.h"
#include "plot.h"
#include "progress_bar.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

struct HillArgs {
  SceneArgs scene;
  int max_harmonics = kHillStudyMaxHarmonics;
  std::string solver{ToString(HillOptions{}.solver)};
  std::string selection{ToString(HillOptions{}.selection)};
  double max_work = HillOptions{}.max_work_seconds;
  bool no_reference = false;
  bool json = false;
  std::string csv;
  std::string plot;
};

std::string RateText(const HillStudy& s) {
  std::ostringstream t;
  if (s.rate_kind == HillConvergence::kExponential)
    t << "error ∝ e^{-" << Num(s.rate, 3) << " N}";
  else if (s.rate_kind == HillConvergence::kAlgebraic)
    t << "error ∝ N^{-" << Num(s.rate, 3) << "}";
  else
    t << "rate not fitted";
  return t.str();
}

void WriteCsv(const HillStudy& s, const std::string& file) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  const size_t k = s.rows.empty() ? 0 : s.rows.front().errors.size();
  csv << "harmonics,matrix_size,max_error,apriori_bound,truncation_estimate,error_estimate,"
         "selection_margin,tail_weight,ambiguous,elapsed_s";
  for (size_t i = 0; i < k; ++i) csv << ",error_" << i;
  csv << "\n" << std::setprecision(12);
  for (const HillStudyRow& r : s.rows) {
    csv << r.harmonics << "," << r.matrix_size << "," << CsvNumber(r.max_error) << ","
        << r.apriori_bound << "," << CsvNumber(r.truncation_estimate) << ","
        << CsvNumber(r.error_estimate) << "," << r.selection_margin << "," << r.tail_weight << ","
        << r.ambiguous << "," << r.elapsed_s;
    for (double e : r.errors) csv << "," << e;
    csv << "\n";
  }
}

void Plot(const HillStudy& s, const std::string& title, const std::string& file) {
  // Zero or infinite values cannot sit on a log axis: gnuplot skips NaN points.
  auto val = [](std::optional<double> x) {
    return x && std::isfinite(*x) && *x > 0 ? Num(*x, 6) : std::string("NaN");
  };
  std::ostringstream g;
  g << GnuplotTerminal(file, 900, 560) << "set output '" << file << "'\n$D << EOD\n";
  for (const HillStudyRow& r : s.rows)
    g << r.harmonics << " " << val(r.max_error) << " " << val(r.apriori_bound) << " "
      << val(r.error_estimate) << "\n";
  g << "EOD\n"
    << "set title \"Hill convergence: " << title << "  (" << RateText(s) << ")\"\n"
    << "set xlabel 'harmonics N'\nset ylabel 'exponent error  [1/s]'\n"
    << "set logscale y\nset format y '10^{%L}'\nset grid\nset key top right\n";
  if (s.rate_kind == HillConvergence::kAlgebraic) g << "set logscale x\n";
  g << "plot $D using 1:2 with linespoints pt 7 lc rgb '#1f77b4' title 'error vs monodromy', "
       "$D using 1:3 with linespoints pt 5 dt 2 lc rgb '#d62728' title 'a-priori bound', "
       "$D using 1:4 with linespoints pt 9 dt 3 lc rgb '#2ca02c' title 'error estimate'\n";
  RunGnuplot(file, g.str());
}

// Turns the string options into the library's enums; checks the truncation. @throws InputError.
HillOptions ResolveOptions(const HillArgs& args) {
  HillOptions options;
  const auto solver = ParseHillSolver(args.solver);
  if (!solver)
    throw InputError("--solver must be 'auto', 'dense' or 'structured', got '" + args.solver + "'");
  options.solver = *solver;
  const auto rule = ParseHillSelectionRule(args.selection);
  if (!rule)
    throw InputError("--selection must be 'centroid', 'central-weight' or 'strip', got '" +
                     args.selection + "'");
  options.selection = *rule;
  options.max_work_seconds = args.max_work;
  // The whole study is weighed before its first solve; a long one says so on stderr.
  options.on_long_work = [](const WorkEstimate& w) {
    std::cerr << "ltp hill: " << WorkAhead(w.seconds()) << " (" << w.basis << ")\n";
  };
  if (args.max_harmonics < 1) throw InputError("--max-harmonics must be >= 1");
  return options;
}

// One entry per truncation N: the table of the text output, plus the exponents at that N.
json RowsJson(const HillStudy& s) {
  json rows = json::array();
  for (const HillStudyRow& r : s.rows) {
    json errs = json::array(), at_n = json::array();
    for (double e : r.errors) errs.push_back(JsonNumber(e));
    for (const std::complex<double>& l : r.exponents)
      at_n.push_back({JsonNumber(l.real()), JsonNumber(l.imag())});
    rows.push_back({{"harmonics", r.harmonics},
                    {"matrix_size", r.matrix_size},
                    {"errors", errs},
                    {"exponents", at_n},
                    {"max_error", JsonNumber(r.max_error)},
                    {"apriori_bound", JsonNumber(r.apriori_bound)},
                    {"truncation_estimate", JsonNumber(r.truncation_estimate)},
                    {"error_estimate", JsonNumber(r.error_estimate)},
                    {"selection_margin", JsonNumber(r.selection_margin)},
                    {"tail_weight", JsonNumber(r.tail_weight)},
                    {"ambiguous", r.ambiguous},
                    {"elapsed_s", r.elapsed_s}});
  }
  return rows;
}

// The exponents at the largest truncation, with how surely each was selected.
json ExponentsJson(const HillResult& last) {
  json exps = json::array();
  for (size_t k = 0; k < last.modes.size(); ++k) {
    const FloquetMode& m = last.modes[k];
    exps.push_back({{"re", JsonNumber(m.exponent.real())},
                    {"im", JsonNumber(m.exponent.imag())},
                    {"frequency_hz", JsonNumber(m.frequency_hz)},
                    {"damping_ratio", JsonNumber(m.damping_ratio)},
                    {"selection_margin", JsonNumber(last.info[k].selection_margin)},
                    {"tail_weight", JsonNumber(last.info[k].tail_weight)},
                    {"centroid", JsonNumber(last.info[k].centroid)},
                    {"ambiguous", last.info[k].ambiguous}});
  }
  return exps;
}

json StudyJson(const LoadedScene& l, const HillOptions& options, const HillStudyRun& run) {
  const HillStudy& s = run.study;
  const HillResult& last = run.last;
  json ref = json::array();
  for (const auto& e : s.reference)
    ref.push_back({{"re", JsonNumber(e.real())}, {"im", JsonNumber(e.imag())}});
  json j = {
      {"scene", l.scene.name},
      {"parameters", ParametersJson(l.parameters)},
      {"states", l.system.states()},
      {"period", l.system.period()},
      {"method", "hill"},
      {"solver", std::string(ToString(options.solver))},
      {"selection_rule", std::string(ToString(options.selection))},
      {"coefficient_decay",
       {{"kind", std::string(ToString(s.decay.kind))},
        {"rate", JsonNumber(s.decay.rate)},
        {"harmonics", s.decay.harmonics},
        {"fourier_tail", JsonNumber(s.decay.fourier_tail)}}},
      {"convergence", {{"kind", std::string(ToString(s.rate_kind))}, {"rate", JsonNumber(s.rate)}}},
      {"reference", ref},
      {"rows", RowsJson(s)},
      {"exponents", ExponentsJson(last)},
      {"koopman_discrepancy", JsonNumber(last.koopman_discrepancy)},
      {"ok", last.ok},
      {"elapsed_s", s.elapsed_s},
      {"diagnostics", Texts(last.diagnostics)}};
  // The study's own diagnostics after the last solve's, each kind once (as RunHillStudy).
  for (const Diagnostic& d : s.diagnostics)
    if (!HasCode(last.diagnostics, d.code)) j["diagnostics"].push_back(d.text);
  return j;
}

// The scene, the solver and what the Fourier coefficients of A promise, above the table.
void PrintHeader(const LoadedScene& l, const HillOptions& options, const HillStudy& s) {
  const double T = l.system.period();
  std::cout << "Hill convergence study of " << l.scene.name;
  if (!l.parameters.empty()) std::cout << " (" << ParameterList(l.parameters) << ")";
  std::cout << "\n  " << l.system.states() << " states, period T = " << Num(T, 10)
            << " s (Ωp = " << Num(2 * kPi / T, 8) << " rad/s); solver " << ToString(options.solver)
            << ", selection by " << ToString(options.selection)
            << "\n  coefficients of A: " << ToString(s.decay.kind);
  if (s.decay.kind == FourierDecay::kExponential)
    std::cout << " decay (b = " << Num(s.decay.rate, 3) << ")";
  if (s.decay.kind == FourierDecay::kAlgebraic)
    std::cout << " decay (|A_w| ~ |w|^-" << Num(s.decay.rate, 3) << ", discontinuous A(t))";
  std::cout << ", " << s.decay.harmonics << " harmonics";
  if (s.decay.fourier_tail > 0) std::cout << ", fit tail " << Num(s.decay.fourier_tail, 2);
  std::cout << "\n  reference: "
            << (!s.reference.empty() ? "monodromy route (dopri5, rel tol 1e-12), error modulo jΩp"
                                     : "none");
}

void PrintRows(const HillStudy& s) {
  std::cout << "\n\n       N   size   error vs ref  a-priori bound   estimate   margin      tail   "
               "time [ms]\n";
  for (const HillStudyRow& r : s.rows) {
    std::cout << std::setw(8) << r.harmonics << std::setw(7) << r.matrix_size
              << Num(r.max_error, 3, 15) << Num(r.apriori_bound, 3, 16)
              << Num(r.error_estimate, 3, 11) << Num(r.selection_margin, 3, 9)
              << Num(r.tail_weight, 2, 10) << Num(r.elapsed_s * 1e3, 3, 12)
              << (r.ambiguous ? "  tie λ/λ±jΩp" : "") << "\n";
  }
}

void PrintExponents(const HillResult& last, int max_harmonics) {
  std::cout << "\n  exponents at N = " << max_harmonics << ":\n"
            << "  mode       Re λ [1/s]     Im λ [rad/s]     freq [Hz]   margin   tail weight\n";
  for (size_t k = 0; k < last.modes.size(); ++k) {
    const FloquetMode& m = last.modes[k];
    std::cout << "  " << std::setw(4) << k + 1 << Num(m.exponent.real(), 9, 17)
              << Num(m.exponent.imag(), 9, 17) << Num(m.frequency_hz, 6, 14)
              << Num(last.info[k].selection_margin, 3, 9) << Num(last.info[k].tail_weight, 2, 14)
              << "\n";
  }
  std::cout << "  Koopman–Hill multipliers differ by " << Num(last.koopman_discrepancy, 2)
            << " 1/s (sorting-free cross-check)\n";
}

void PrintStudy(const LoadedScene& l, const HillOptions& options, const HillStudyRun& run,
                int max_harmonics) {
  PrintHeader(l, options, run.study);
  PrintRows(run.study);
  std::cout << "\n  convergence: " << RateText(run.study) << "\n";
  PrintExponents(run.last, max_harmonics);
  const std::vector<Diagnostic>& diags = run.diagnostics;
  if (!diags.empty()) {
    std::cout << "  diagnostics:\n";
    for (const Diagnostic& d : diags) std::cout << "    - " << d.text << "\n";
  }
}

int RunHill(HillArgs& args) {
  if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);  // reject a bad extension up front
  HillOptions options = ResolveOptions(args);
  LoadedScene l = LoadSceneArgs(args.scene);

  ProgressBar progress("hill: convergence study");  // the largest truncations take the time
  options.progress = [&progress](double done, double total) { progress.Update(done, total); };
  const HillStudyRun run = RunHillStudy(l.system, args.max_harmonics, options, !args.no_reference);

  if (!args.csv.empty()) WriteCsv(run.study, args.csv);
  if (!args.plot.empty()) Plot(run.study, l.scene.name, args.plot);
  if (args.json)
    std::cout << StudyJson(l, options, run).dump(2) << "\n";
  else
    PrintStudy(l, options, run, args.max_harmonics);
  return run.last.ok ? 0 : 1;
}

}  // namespace

Command AddHillCommand(CLI::App& app) {
  static HillArgs args;
  args = HillArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand("hill", "Hill's method: truncation convergence study");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--max-harmonics", args.max_harmonics, "largest truncation N (harmonics -N..N)")
      ->capture_default_str();
  cmd->add_option(
         "--solver", args.solver,
         "auto | dense (zgeev, full spectrum) | structured (banded shift-invert); auto: per N, "
         "as the work-precision study found")
      ->capture_default_str();
  cmd->add_option("--selection", args.selection, "centroid | central-weight | strip")
      ->capture_default_str();
  cmd->add_flag("--no-reference", args.no_reference,
                "skip the monodromy reference (no error column)");
  cmd->add_option("--max-work", args.max_work,
                  "refuse a study estimated to need more CPU seconds than this even at its "
                  "fastest (0 = no limit)")
      ->capture_default_str()
      ->check(NumberAboveZero(true));
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  cmd->add_option("--csv", args.csv, "write the study table to CSV");
  cmd->add_option("--plot", args.plot, "chart of error and estimates vs N (FILE.svg or FILE.png)");
  return {cmd, [] { return RunHill(args); }};
}

}  // namespace ltp::cli
