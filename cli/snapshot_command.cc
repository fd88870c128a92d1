// `ltp snapshot`: the FRF of the system frozen at one time or rotor angle, optionally overlaid
// with the response of the periodic system to an impulse (the summed partial FRFs, paper Fig. 6).
#include <cmath>
#include <complex>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>

#include "command.h"
#include "format.h"
#include "frf_args.h"
#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/htf/frequency_range.h"
#include "ltp/htf/snapshot.h"
#include "plot.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

struct SnapshotArgs {
  SceneArgs scene;
  std::optional<double> angle, time;
  std::string input = "0", output = "0";
  std::string freq;
  std::string orders = std::to_string(SnapshotOptions{}.min_order) + ":" +
                       std::to_string(SnapshotOptions{}.max_order);
  bool compare = false;
  std::string csv, plot;
  bool json = false;
};

void WriteCsv(const SnapshotResult& r, bool compare, const std::string& file) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  csv << "f_exc_hz,z,f_resp_hz,re,im,abs,phase_deg,error_estimate";
  if (compare) csv << ",summed_re,summed_im,summed_abs,summed_phase_deg,summed_error_estimate";
  csv << "\n" << std::setprecision(15);
  for (size_t i = 0; i < r.frequencies_hz.size(); ++i) {
    const auto h = r.snapshot[i];
    // The frozen system is time-invariant: only z = 0, computed by one LU solve (round-off).
    csv << r.frequencies_hz[i] << ",0," << r.frequencies_hz[i] << "," << h.real() << "," << h.imag()
        << "," << std::abs(h) << "," << PhaseDeg(h.real(), h.imag()) << "," << 1e-15 * std::abs(h);
    if (compare) {
      const auto g = r.summed[i];
      csv << "," << g.real() << "," << g.imag() << "," << std::abs(g) << ","
          << PhaseDeg(g.real(), g.imag()) << "," << r.summed_error[i];
    }
    csv << "\n";
  }
}

void Plot(const SnapshotResult& r, bool compare, const std::string& title,
          const std::string& file) {
  std::ostringstream s;
  s << GnuplotTerminal(file, 1000, 520) << "set output '" << file << "'\n"
    << "set title \"" << title << "\"\nset xlabel 'frequency [Hz]'\nset ylabel '|H|'\n"
    << "set logscale y\nset format y '10^{%L}'\nset grid\nset key below\n$D << EOD\n";
  for (size_t i = 0; i < r.frequencies_hz.size(); ++i) {
    const double a = std::abs(r.snapshot[i]);
    s << r.frequencies_hz[i] << " " << (std::isfinite(a) && a > 0 ? a : 1e-300);
    if (compare) s << " " << std::max(std::abs(r.summed[i]), 1e-300);
    s << "\n";
  }
  s << "EOD\nplot $D using 1:2 with lines lw 1.5 title 'snapshot FRF (frozen system)'";
  if (compare)
    s << ", $D using 1:3 with lines lw 1.5 title 'periodic system: Σ_z H_z(ω − zΩp) (impulse "
         "response)'";
  s << "\n";
  RunGnuplot(file, s.str());
}

// The library's options from the flags, checked against the scene's channels. @throws InputError.
SnapshotOptions ResolveOptions(const SnapshotArgs& args, const LoadedScene& l) {
  const PeriodicSystem& sys = l.system;
  if (sys.inputs() < 1 || sys.outputs() < 1)
    throw InputError("scene '" + l.scene.name + "' has no inputs or no outputs: no FRF to compute");
  if (args.angle && !sys.rotor_speed())
    throw InputError("scene '" + l.scene.name +
                     "' has no rotor speed: use --time instead of --angle");
  SnapshotOptions o;
  o.frequencies_hz = ParseFrequencyRange(args.freq, "--freq");
  o.time = args.time;
  o.angle_deg = args.angle;
  o.input = ResolveChannel(args.input, sys.labels().inputs, sys.inputs(), "--input", "input");
  o.output = ResolveChannel(args.output, sys.labels().outputs, sys.outputs(), "--output", "output");
  o.compare = args.compare;
  std::tie(o.min_order, o.max_order) = ParseOrderRange(args.orders, "--orders");
  return o;
}

// Snapshot eigenvalues or Floquet exponents, each with its frequency.
json ExponentsJson(const std::vector<std::complex<double>>& exponents) {
  json list = json::array();
  for (const auto& e : exponents)
    list.push_back({{"re", JsonNumber(e.real())},
                    {"im", JsonNumber(e.imag())},
                    {"frequency_hz", JsonNumber(e.imag() / (2 * kPi))}});
  return list;
}

json SnapshotJson(const LoadedScene& l, const SnapshotOptions& o, const SnapshotResult& r) {
  json vals = json::array();
  for (size_t i = 0; i < r.frequencies_hz.size(); ++i) {
    json v = {{"f_hz", r.frequencies_hz[i]},
              {"re", JsonNumber(r.snapshot[i].real())},
              {"im", JsonNumber(r.snapshot[i].imag())}};
    if (o.compare) {
      v["summed_re"] = JsonNumber(r.summed[i].real());
      v["summed_im"] = JsonNumber(r.summed[i].imag());
      v["summed_error_estimate"] = JsonNumber(r.summed_error[i]);
    }
    vals.push_back(v);
  }
  return {{"scene", l.scene.name},
          {"parameters", ParametersJson(l.parameters)},
          {"time", r.time},
          {"angle_deg", r.angle_deg ? json(*r.angle_deg) : json(nullptr)},
          {"input", o.input},
          {"output", o.output},
          {"snapshot_eigenvalues", ExponentsJson(r.eigenvalues)},
          {"compare", o.compare},
          {"floquet_exponents", ExponentsJson(r.floquet_exponents)},
          {"max_summed_disagreement", JsonNumber(r.max_summed_disagreement)},
          {"modal_reliable", r.modal_reliable},
          {"values", vals},
          {"elapsed_s", r.elapsed_s},
          {"diagnostics", Texts(r.diagnostics)}};
}

// One line per conjugate pair: only the exponents with Im >= 0.
void PrintExponents(const std::vector<std::complex<double>>& exponents) {
  for (const auto& e : exponents)
    if (e.imag() >= 0)
      std::cout << std::string(34, ' ') << Num(e.real(), 6, 12) << Num(e.imag() / (2 * kPi), 6, 14)
                << "\n";
}

// The FRF values themselves when they fit on a screen; else where to find them.
void PrintValues(const SnapshotResult& r, bool compare, bool csv_written) {
  if (r.frequencies_hz.size() <= 20) {
    std::cout << "\n      f [Hz]        |H_snap|   phase [°]"
              << (compare ? "        |G_sum|   phase [°]" : "") << "\n";
    for (size_t i = 0; i < r.frequencies_hz.size(); ++i) {
      std::cout << Num(r.frequencies_hz[i], 6, 12) << Num(std::abs(r.snapshot[i]), 6, 16)
                << Num(PhaseDeg(r.snapshot[i].real(), r.snapshot[i].imag()), 5, 12);
      if (compare)
        std::cout << Num(std::abs(r.summed[i]), 6, 15)
                  << Num(PhaseDeg(r.summed[i].real(), r.summed[i].imag()), 5, 12);
      std::cout << "\n";
    }
  } else if (!csv_written) {
    std::cout << "\n  (" << r.frequencies_hz.size()
              << " values: write them with --csv FILE, or --json)\n";
  }
}

void PrintSnapshot(const LoadedScene& l, const SnapshotOptions& o, const SnapshotResult& r,
                   const std::string& at, bool csv_written) {
  std::cout << "Snapshot FRF of " << l.scene.name;
  if (!l.parameters.empty()) std::cout << " (" << ParameterList(l.parameters) << ")";
  std::cout << "\n  frozen at " << at << ": H(ω) = C (jωI − A)⁻¹ B + D, output " << o.output
            << " / input " << o.input << ", " << r.frequencies_hz.size() << " frequencies "
            << Num(r.frequencies_hz.front(), 6) << " … " << Num(r.frequencies_hz.back(), 6)
            << " Hz\n"
            << "\n  snapshot eigenvalues (frozen A)      Re [1/s]     freq [Hz]\n";
  PrintExponents(r.eigenvalues);
  if (o.compare) {
    std::cout << "\n  Floquet exponents (periodic system)  Re [1/s]     freq [Hz]\n";
    PrintExponents(r.floquet_exponents);
    std::cout << "\n  summed partials Σ_z H_z(ω − zΩp), z = " << o.min_order << " … " << o.max_order
              << " (response of the periodic system to an impulse), modal route "
              << (r.modal_reliable ? "(reliable)" : "(UNRELIABLE)")
              << ", htf check: max disagreement " << Num(r.max_summed_disagreement, 3)
              << " of the largest |H_z| at " << o.check_points << " excitation frequencies\n";
  }
  PrintValues(r, o.compare, csv_written);
  if (!r.diagnostics.empty()) {
    std::cout << "\n  notes:\n";
    for (const Diagnostic& d : r.diagnostics) std::cout << "    - " << d.text << "\n";
  }
  std::cout << "\n  total " << Num(r.elapsed_s * 1e3, 4) << " ms\n";
}

int RunSnapshot(SnapshotArgs& args) {
  if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);
  if (args.angle.has_value() == args.time.has_value())
    throw InputError("give exactly one of --angle DEG and --time T");
  if (args.freq.empty()) throw InputError("--freq F0:F1:DF is required");
  LoadedScene l = LoadSceneArgs(args.scene);
  const SnapshotOptions o = ResolveOptions(args, l);
  const SnapshotResult r = ComputeSnapshotFrf(l.system, o);
  const std::string at =
      r.angle_deg ? "rotor angle " + Num(*r.angle_deg, 6) + "° (t = " + Num(r.time, 6) + " s)"
                  : "t = " + Num(r.time, 8) + " s";
  if (!args.csv.empty()) WriteCsv(r, o.compare, args.csv);
  if (!args.plot.empty())
    Plot(r, o.compare, GnuplotEscape(l.scene.name + ": frozen at " + at), args.plot);
  if (args.json)
    std::cout << SnapshotJson(l, o, r).dump(2) << "\n";
  else
    PrintSnapshot(l, o, r, at, !args.csv.empty());
  return 0;
}

}  // namespace

Command AddSnapshotCommand(CLI::App& app) {
  static SnapshotArgs args;
  args = SnapshotArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand("snapshot",
                                 "FRF of the system frozen at one time or rotor angle; --compare "
                                 "overlays the periodic system");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--angle", args.angle, "freeze at this rotor angle (degrees)");
  cmd->add_option("--time", args.time, "freeze at this time (s)");
  cmd->add_option("--input", args.input, "input channel: index from 0 or name")
      ->capture_default_str();
  cmd->add_option("--output", args.output, "output channel: index from 0 or name")
      ->capture_default_str();
  cmd->add_option("--freq", args.freq, "frequencies F0:F1:DF in Hz (F:F:DF = one)")->required();
  cmd->add_option("--orders", args.orders, "orders z summed for --compare, ZMIN:ZMAX")
      ->capture_default_str();
  cmd->add_flag("--compare", args.compare,
                "also the periodic system's impulse response Σ_z H_z(ω − zΩp) (paper Fig. 6)");
  cmd->add_option("--csv", args.csv, "write the FRF(s) to CSV");
  cmd->add_option("--plot", args.plot, "draw |H| (FILE.svg or .png)");
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  return {cmd, [] { return RunSnapshot(args); }};
}

}  // namespace ltp::cli
