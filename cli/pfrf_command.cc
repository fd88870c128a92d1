// `ltp pfrf`: partial frequency response functions H_z of one input/output channel by the
// chosen route, checked by the others on a subset of the frequencies.
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
#include "frf_args.h"
#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/htf/frequency_range.h"
#include "ltp/htf/pfrf.h"
#include "ltp/htf/pfrf_model_error.h"
#include "plot.h"
#include "progress_bar.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;

struct PfrfArgs {
  SceneArgs scene;
  std::string input = "0", output = "0";
  std::string freq;
  std::string orders =
      std::to_string(PfrfOptions{}.min_order) + ":" + std::to_string(PfrfOptions{}.max_order);
  std::string route{ToString(PfrfOptions{}.primary)};
  int check_every = PfrfOptions{}.check_every;
  int htf_harmonics = HtfOptions{}.harmonics;
  double plot_threshold = 0.01;
  std::string csv, plot;
  bool json = false;
};

void WriteCsv(const PfrfResult& r, const std::string& file) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  csv << "f_exc_hz,z,f_resp_hz,re,im,abs,phase_deg,error_estimate,checked\n"
      << std::setprecision(15);
  for (size_t i = 0; i < r.frequencies_hz.size(); ++i)
    for (int z = r.min_order; z <= r.max_order; ++z) {
      const std::complex<double> h = r.values[i][z - r.min_order];
      csv << r.frequencies_hz[i] << "," << z << "," << r.frequencies_hz[i] + z * r.fp_hz << ","
          << h.real() << "," << h.imag() << "," << std::abs(h) << ","
          << PhaseDeg(h.real(), h.imag()) << "," << r.error_estimate[i][z - r.min_order] << ","
          << (r.checked[i] ? 1 : 0) << "\n";
    }
}

void Plot(const PfrfResult& r, const std::string& title, double threshold,
          const std::string& file) {
  double global = 0;
  for (double m : r.order_max) global = std::max(global, m);
  std::ostringstream s;
  s << GnuplotTerminal(file, 1000, 560) << "set output '" << file << "'\n"
    << "set title \"Partial FRFs " << title << "  (|H_z| with max |H_z| > " << Num(threshold, 3)
    << " · max)\"\nset xlabel 'response frequency f + z f_p  [Hz]'\nset ylabel '|H_z|'\n"
    << "set logscale y\nset format y '10^{%L}'\nset grid\nset key outside right\n";
  std::vector<int> shown;
  for (int z = r.min_order; z <= r.max_order; ++z) {
    const double m = r.order_max[z - r.min_order];
    if (m > 0 && m >= threshold * global) shown.push_back(z);
  }
  for (int z : shown) {
    s << "$Z" << (z < 0 ? "m" : "p") << std::abs(z) << " << EOD\n";
    for (size_t i = 0; i < r.frequencies_hz.size(); ++i) {
      const double a = std::abs(r.values[i][z - r.min_order]);
      s << r.frequencies_hz[i] + z * r.fp_hz << " " << (a > 0 ? a : 1e-300) << "\n";
    }
    s << "EOD\n";
  }
  if (shown.empty()) {
    s << "plot NaN title 'all H_z are zero'\n";
  } else {
    s << "plot ";
    for (size_t q = 0; q < shown.size(); ++q) {
      const int z = shown[q];
      s << (q ? ", " : "") << "$Z" << (z < 0 ? "m" : "p") << std::abs(z)
        << " using 1:2 with lines lw 1.5 title 'z = " << z << "'";
    }
    s << "\n";
  }
  RunGnuplot(file, s.str());
}

// The library's options from the command line.
PfrfOptions OptionsFrom(const PfrfArgs& args, const PeriodicSystem& sys) {
  PfrfOptions o;
  o.frequencies_hz = ParseFrequencyRange(args.freq, "--freq");
  std::tie(o.min_order, o.max_order) = ParseOrderRange(args.orders, "--orders");
  o.input = ResolveChannel(args.input, sys.labels().inputs, sys.inputs(), "--input", "input");
  o.output = ResolveChannel(args.output, sys.labels().outputs, sys.outputs(), "--output", "output");
  o.check_every = args.check_every;
  o.htf.harmonics = args.htf_harmonics;
  if (!SelectPfrfRoutes(args.route, &o))
    throw InputError("--route must be auto, modal, htf, shooting, time or all, got '" + args.route +
                     "'");
  return o;
}

// The channel's names ("" where the scene has none).
struct ChannelNames {
  std::string input, output;
};

double MaxDeviation(const RouteRun& run) {
  double worst = 0;
  for (double d : run.deviation) worst = std::max(worst, d);
  return worst;
}

json PfrfJson(const PfrfResult& r, const LoadedScene& l, const PfrfOptions& o,
              const ChannelNames& names) {
  json routes = json::array(), res = json::array(), points = json::array(), exps = json::array();
  for (const RouteRun& run : r.routes)
    routes.push_back({{"route", std::string(ToString(run.route))},
                      {"points", run.points.size()},
                      {"failures", run.failures},
                      {"max_deviation_from_primary", JsonNumber(MaxDeviation(run))},
                      {"setup_s", run.setup_s},
                      {"elapsed_s", run.elapsed_s},
                      {"diagnostics", Texts(run.diagnostics)}});
  for (const Resonance& p : r.resonances)
    res.push_back({{"z", p.order},
                   {"f_exc_hz", p.f_exc_hz},
                   {"f_resp_hz", p.f_resp_hz},
                   {"abs", JsonNumber(p.magnitude)},
                   {"mode", p.mode ? json(*p.mode + 1) : json(nullptr)},
                   {"harmonic", p.harmonic},
                   {"mode_line_hz", JsonNumber(p.mode_line_hz)},
                   {"share", JsonNumber(p.share)}});
  for (size_t i = 0; i < r.frequencies_hz.size(); ++i)
    for (int z = r.min_order; z <= r.max_order; ++z) {
      const auto h = r.values[i][z - r.min_order];
      points.push_back({{"f_exc_hz", r.frequencies_hz[i]},
                        {"z", z},
                        {"f_resp_hz", r.frequencies_hz[i] + z * r.fp_hz},
                        {"re", JsonNumber(h.real())},
                        {"im", JsonNumber(h.imag())},
                        {"error_estimate", JsonNumber(r.error_estimate[i][z - r.min_order])},
                        {"checked", static_cast<bool>(r.checked[i])}});
    }
  for (const auto& m : r.floquet.modes)
    exps.push_back({{"re", JsonNumber(m.exponent.real())},
                    {"im", JsonNumber(m.exponent.imag())},
                    {"frequency_hz", JsonNumber(m.frequency_hz)}});
  return {{"scene", l.scene.name},
          {"parameters", ParametersJson(l.parameters)},
          {"input", o.input},
          {"input_name", names.input},
          {"output", o.output},
          {"output_name", names.output},
          {"period", r.period},
          {"fp_hz", r.fp_hz},
          {"orders", {r.min_order, r.max_order}},
          {"primary_route", std::string(ToString(r.routes.front().route))},
          {"route_choice", r.route_choice},
          {"route_reason", std::string(CodeName(r.route_reason))},
          {"check_every", o.check_every},
          {"routes", routes},
          {"max_disagreement", JsonNumber(r.max_disagreement)},
          {"max_relative_disagreement", JsonNumber(r.max_relative_disagreement)},
          {"htf_harmonics", r.htf_harmonics},
          {"htf_truncation_change", JsonNumber(r.htf_truncation_change)},
          {"modal_reliable", r.modal ? json(r.modal->reliable) : json(nullptr)},
          {"modal_condition", r.modal ? JsonNumber(r.modal->condition) : json(nullptr)},
          {"settle_time", JsonNumber(r.settle_time)},
          {"model_error", JsonNumber(r.model_error)},
          {"floquet_exponents", exps},
          {"stable", r.floquet.stable},
          {"verdict", ToString(r.floquet.verdict)},
          {"resonances", res},
          {"values", points},
          {"elapsed_s", r.elapsed_s},
          {"ok", r.ok},
          {"failure", r.failure},
          {"diagnostics", Texts(r.diagnostics)}};
}

// The routes, their agreement and the decomposition behind them.
void PrintRoutes(const PfrfResult& r, const PfrfOptions& o) {
  std::cout << "  route       points  failures   max |Δ| vs primary    setup [ms]    total [ms]\n";
  for (const RouteRun& run : r.routes)
    std::cout << "  " << std::left << std::setw(10) << ToString(run.route) << std::right
              << std::setw(8) << run.points.size() << std::setw(10) << run.failures
              << (&run == &r.routes.front() ? std::string(21, ' ') + "(primary)"
                                            : Num(MaxDeviation(run), 3, 21))
              << Num(run.setup_s * 1e3, 4, 14) << Num(run.elapsed_s * 1e3, 4, 14) << "\n";
  std::cout << "\n  max disagreement between routes " << Num(r.max_disagreement, 3) << " ("
            << Num(r.max_relative_disagreement, 3) << " of max |H_z|), checked on every "
            << o.check_every << "th frequency";
  if (r.model_error)
    std::cout << "\n  sampling error of the model (the other interpolations of its samples) "
              << Num(*r.model_error, 3) << ", in every estimate";
  if (r.htf_harmonics > 0)
    std::cout << "\n  htf truncation N = " << r.htf_harmonics << ", change against N + Δ "
              << Num(r.htf_truncation_change, 3);
  if (r.modal)
    std::cout << "\n  modal: " << r.modal->samples << " samples/period, V = " << r.modal->harmonics
              << " harmonics, cond Ξ = " << Num(r.modal->condition, 3) << ", "
              << (r.modal->reliable ? "reliable" : "UNRELIABLE") << ", built in "
              << Num(r.modal->elapsed_s * 1e3, 3) << " ms";
  std::cout << "\n  Floquet: max Re λ = " << Num(r.floquet.max_real_exponent, 6) << " 1/s ("
            << ToString(r.floquet.verdict) << "), " << Num(r.floquet.elapsed_s * 1e3, 3) << " ms\n";
}

// max |H_z| per order; every value when there are few; the resonances.
void PrintValues(const PfrfResult& r, bool csv_written) {
  const auto& f = r.frequencies_hz;
  std::cout << "\n  order z   max |H_z|\n";
  for (int z = r.min_order; z <= r.max_order; ++z)
    std::cout << std::setw(9) << z << Num(r.order_max[z - r.min_order], 4, 12) << "\n";
  if (f.size() <= 12) {
    std::cout << "\n   f_exc [Hz]    z   f_resp [Hz]          Re H_z          Im H_z           "
                 "|H_z|   phase [°]     error est.\n";
    for (size_t i = 0; i < f.size(); ++i)
      for (int z = r.min_order; z <= r.max_order; ++z) {
        const auto h = r.values[i][z - r.min_order];
        std::cout << Num(f[i], 6, 13) << std::setw(5) << z << Num(f[i] + z * r.fp_hz, 6, 14)
                  << Num(h.real(), 8, 16) << Num(h.imag(), 8, 16) << Num(std::abs(h), 6, 16)
                  << Num(PhaseDeg(h.real(), h.imag()), 5, 12)
                  << Num(r.error_estimate[i][z - r.min_order], 2, 15) << "\n";
      }
  } else if (!csv_written) {
    std::cout << "\n  (" << f.size() * (r.max_order - r.min_order + 1)
              << " values: write them with --csv FILE, or --json)\n";
  }
  if (r.resonances.empty()) return;
  std::cout << "\n  resonances (peaks of |H_z|; mode k and harmonic v of the resonant modal term, "
               "line f_k + v fp)\n    z    f_exc [Hz]   f_resp [Hz]         |H_z|   mode  v   line "
               "[Hz]   share\n";
  for (const Resonance& p : r.resonances)
    std::cout << std::setw(5) << p.order << Num(p.f_exc_hz, 6, 14) << Num(p.f_resp_hz, 6, 14)
              << Num(p.magnitude, 4, 14) << std::setw(7)
              << (p.mode ? std::to_string(*p.mode + 1) : "?") << std::setw(3) << p.harmonic
              << Num(p.mode_line_hz, 6, 12) << Num(p.share, 2, 8) << "\n";
}

// The notes of the sweep and its routes; one repeated for many frequencies is printed once,
// with its count.
void PrintNotes(const PfrfResult& r) {
  std::vector<std::string> diags = Texts(r.diagnostics);
  for (const RouteRun& run : r.routes)
    for (const Diagnostic& d : run.diagnostics) diags.push_back(d.text);
  if (diags.empty()) return;
  std::vector<std::pair<std::string, int>> unique;
  for (const auto& d : diags) {
    auto it =
        std::find_if(unique.begin(), unique.end(), [&](const auto& u) { return u.first == d; });
    if (it == unique.end())
      unique.emplace_back(d, 1);
    else
      ++it->second;
  }
  std::cout << "\n  notes:\n";
  for (const auto& [d, count] : unique)
    std::cout << "    - " << d << (count > 1 ? " (" + std::to_string(count) + " points)" : "")
              << "\n";
}

void PrintPfrf(const PfrfResult& r, const LoadedScene& l, const PfrfOptions& o,
               const ChannelNames& names, bool csv_written) {
  const auto& f = r.frequencies_hz;
  std::cout << "Partial FRFs of " << l.scene.name;
  if (!l.parameters.empty()) std::cout << " (" << ParameterList(l.parameters) << ")";
  std::cout << "\n  output " << o.output << (names.output.empty() ? "" : " (" + names.output + ")")
            << " / input " << o.input << (names.input.empty() ? "" : " (" + names.input + ")")
            << ", " << l.system.states() << " states, T = " << Num(r.period, 10)
            << " s, fp = " << Num(r.fp_hz, 8) << " Hz\n  " << f.size() << " excitation frequencies "
            << Num(f.front(), 6) << " … " << Num(f.back(), 6) << " Hz, orders z = " << r.min_order
            << " … " << r.max_order
            << "  (H_z indexed by the excitation frequency; response at f + z fp)\n\n";
  PrintRoutes(r, o);
  PrintValues(r, csv_written);
  PrintNotes(r);
  std::cout << "\n  total " << Num(r.elapsed_s, 4) << " s\n";
}

int RunPfrf(PfrfArgs& args) {
  if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);  // reject a bad extension up front
  if (args.freq.empty()) throw InputError("--freq F0:F1:DF is required");
  LoadedScene l = LoadSceneArgs(args.scene);
  const PeriodicSystem& sys = l.system;
  if (sys.inputs() < 1 || sys.outputs() < 1)
    throw InputError("scene '" + l.scene.name + "' has no inputs or no outputs: no FRF to compute");
  PfrfOptions o = OptionsFrom(args, sys);
  ProgressBar progress("pfrf");
  o.progress = [&progress](int done, int total) { progress.Update(done, total, "frequencies"); };
  PfrfResult r = ComputePartialFrf(sys, o);
  IncludeModelError(l.model_alternatives, o, r);  // sampled (.lin) models: their sampling error
  ChannelNames names;
  if (o.input < static_cast<int>(sys.labels().inputs.size()))
    names.input = sys.labels().inputs[o.input];
  if (o.output < static_cast<int>(sys.labels().outputs.size()))
    names.output = sys.labels().outputs[o.output];
  if (!args.csv.empty()) WriteCsv(r, args.csv);
  if (!args.plot.empty())
    Plot(r,
         GnuplotEscape(l.scene.name + " " +
                       (names.output.empty() ? std::to_string(o.output) : names.output) + "/" +
                       (names.input.empty() ? std::to_string(o.input) : names.input)),
         args.plot_threshold, args.plot);
  if (args.json)
    std::cout << PfrfJson(r, l, o, names).dump(2) << "\n";
  else
    PrintPfrf(r, l, o, names, !args.csv.empty());
  if (!r.ok) SetFailureFrom("partial FRFs", r.failure);
  return r.ok ? 0 : 1;
}

}  // namespace

Command AddPfrfCommand(CLI::App& app) {
  static PfrfArgs args;
  args = PfrfArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand(
      "pfrf",
      "Partial frequency response functions H_z(ω) by independent routes, with error estimates");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--input", args.input, "input channel: index from 0 or name")
      ->capture_default_str();
  cmd->add_option("--output", args.output, "output channel: index from 0 or name")
      ->capture_default_str();
  cmd->add_option("--freq", args.freq, "excitation frequencies F0:F1:DF in Hz (F:F:DF = one)")
      ->required();
  cmd->add_option("--orders", args.orders, "orders z, ZMIN:ZMAX")->capture_default_str();
  cmd->add_option(
         "--route", args.route,
         "auto | modal | htf | shooting | time | all (primary route; auto: modal unless it "
         "reports itself unreliable, checked by htf, or by shooting when A(t) jumps; all: "
         "modal checked by the other three)")
      ->capture_default_str();
  cmd->add_option("--check-every", args.check_every,
                  "run the check routes on every k-th frequency (1 = all)")
      ->capture_default_str()
      ->check(NumberAboveZero());
  cmd->add_option("--htf-harmonics", args.htf_harmonics, "HTF truncation N (0 = automatic)")
      ->capture_default_str()
      ->check(NumberAboveZero(true));
  cmd->add_option("--plot-threshold", args.plot_threshold,
                  "plot the orders with max |H_z| above this fraction of the largest")
      ->capture_default_str();
  cmd->add_option("--csv", args.csv, "write every H_z to CSV");
  cmd->add_option("--plot", args.plot,
                  "draw |H_z| against the response frequency (FILE.svg or .png)");
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  return {cmd, [] { return RunPfrf(args); }};
}

}  // namespace ltp::cli
