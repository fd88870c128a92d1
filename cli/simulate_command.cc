// `ltp simulate SCENE`: time data of a scene as a test rig would record it — step-sine (one
// record per excitation frequency) or multisine (every frequency at once, several records with
// random phases), after the transient, with optional output noise — written as CSV for
// `ltp identify` (or for any other tool).
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "format.h"
#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/htf/frequency_range.h"
#include "ltp/htf/simulate.h"
#include "scene_args.h"
#include "time_data_csv.h"
#include "uff58.h"

namespace ltp::cli {

namespace {

using nlohmann::json;

struct SimulateArgs {
  SceneArgs scene;
  std::string input = "0";
  std::string excitation;
  int periods = SimulateOptions{}.periods;
  int samples_per_period = SimulateOptions{}.samples_per_period;
  double amplitude = SimulateOptions{}.amplitude;
  double noise_db = SimulateOptions{}.noise_snr_db;
  double input_noise_db = SimulateOptions{}.input_noise_snr_db;
  double speed_offset_pct = 0, speed_ramp_pct = 0;
  double cubic = 0;
  double max_transient = SimulateOptions{}.max_settle_periods;
  bool tacho = false;
  std::uint64_t seed = SimulateOptions{}.seed;
  int records = SimulateOptions{}.records;
  std::string out;
  bool binary = false;  ///< UFF output as 58b
  bool json = false;
};

// "sine:F", "stepsine:F0:F1:DF" or "multisine:F0:F1:DF" → the kind and the frequencies.
std::pair<std::string, std::vector<double>> Excitation(const std::string& text) {
  const auto colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (kind == "sine")
    return {"step-sine", ParseFrequencyRange(rest + ":" + rest + ":1", "--excitation sine:F")};
  if (kind == "stepsine")
    return {"step-sine", ParseFrequencyRange(rest, "--excitation stepsine:F0:F1:DF")};
  if (kind == "multisine")
    return {"multisine", ParseFrequencyRange(rest, "--excitation multisine:F0:F1:DF")};
  if (kind == "noise") {  // every line of the record's grid in the band (see RunSimulate)
    const auto [f0, f1] = ParseFrequencyBand(rest, "--excitation noise:F0:F1");
    return {"noise", {f0, f1}};
  }
  throw InputError(
      "--excitation must be sine:F, stepsine:F0:F1:DF or multisine:F0:F1:DF (Hz), got '" + text +
      "'");
}

int RunSimulate(const SimulateArgs& args) {
  const LoadedScene l = LoadSceneArgs(args.scene);
  SimulateOptions o;
  o.input =
      ResolveChannel(args.input, l.system.labels().inputs, l.system.inputs(), "--input", "input");
  const auto [kind, frequencies] = Excitation(args.excitation);
  o.frequencies_hz = frequencies;
  if (kind == "noise") {
    // Periodic Gaussian noise: every line 1/(periods·T) apart in [F0, F1], Rayleigh amplitudes.
    if (args.periods < 1 || args.periods > 100000)
      throw InputError("--periods must be in 1..100000, got " + std::to_string(args.periods));
    const double step = 1.0 / (args.periods * l.system.period());
    const double f0 = frequencies.front(), f1 = frequencies.back();
    if ((f1 - f0) / step > 1e5)
      throw InputError("--excitation noise: more than 10^5 lines in the band on the record's grid");
    o.frequencies_hz.clear();
    for (double f = std::ceil(f0 / step) * step; f <= f1 * (1 + 1e-12); f += step)
      if (f > 0) o.frequencies_hz.push_back(f);
    if (o.frequencies_hz.empty())
      throw InputError("--excitation noise: no line of the record's grid (" + Num(step, 6) +
                       " Hz apart) in the band");
    o.random_amplitudes = true;
  }
  o.records = args.records;
  o.periods = args.periods;
  o.samples_per_period = args.samples_per_period;
  o.amplitude = args.amplitude;
  o.noise_snr_db = args.noise_db;
  o.input_noise_snr_db = args.input_noise_db;
  o.speed_offset = args.speed_offset_pct / 100;
  o.speed_ramp = args.speed_ramp_pct / 100;
  o.tacho = args.tacho;
  o.cubic_stiffness = args.cubic;
  o.max_settle_periods = args.max_transient;
  o.seed = args.seed;
  const SimulationResult r =
      kind == "step-sine" ? SimulateStepSine(l.system, o) : SimulateMultisine(l.system, o);
  std::string comment = "ltp simulate " + l.scene.name;
  if (!l.parameters.empty()) comment += " (" + ParameterList(l.parameters) + ")";
  comment +=
      ", " + kind + " on input " + std::to_string(o.input) + ", amplitude " + Num(o.amplitude) +
      (std::isfinite(o.noise_snr_db)
           ? ", output noise " + Num(o.noise_snr_db) + " dB SNR, seed " + std::to_string(o.seed)
           : "") +
      (std::isfinite(o.input_noise_snr_db)
           ? ", input noise " + Num(o.input_noise_snr_db) + " dB SNR"
           : "") +
      (o.speed_offset != 0 || o.speed_ramp != 0
           ? ", rotor " + Num(100 * o.speed_offset) + " % off the model's speed, ramp " +
                 Num(100 * o.speed_ramp) + " % per record"
           : "") +
      (o.tacho ? ", tacho pulse rising through mid-level at phase 0" : "") +
      (o.cubic_stiffness > 0 ? ", cubic spring " + Num(o.cubic_stiffness) + " y^3 on the input"
                             : "");
  std::vector<std::string> notes = Texts(r.diagnostics);
  if (IsUffName(args.out)) {
    // UFF keeps 7 digits of the time axis: a rig's tacho makes identification independent of it.
    const double rounding = WriteTimeDataUff(args.out, r.data, comment, args.binary);
    if (rounding > 1e-12 * std::abs(r.data.records.back().time.back()) && !o.tacho)
      notes.push_back("the UFF time axis keeps 7 digits: sample times moved by up to " +
                      Num(rounding, 2) +
                      " s, which shifts the phase of H_z (z ≠ 0) against "
                      "2πt/T; record a tacho (--tacho) and identify with it, as on a rig");
  } else {
    if (args.binary) throw InputError("--binary: only UFF files (.uff, .unv) have a binary form");
    WriteTimeDataCsv(args.out, r.data, comment);
  }
  size_t samples = 0;
  for (const TimeRecord& rec : r.data.records) samples += rec.time.size();
  if (args.json) {
    std::vector<double> frequencies;
    for (const TimeRecord& rec : r.data.records) frequencies.push_back(rec.excitation_hz);
    std::cout << json{{"scene", l.scene.name},
                      {"parameters", ParametersJson(l.parameters)},
                      {"input", o.input},
                      {"period_s", r.data.period},
                      {"records", r.data.records.size()},
                      {"samples", samples},
                      {"excitation_hz", frequencies},
                      {"settle_time_s", r.settle_time},
                      {"max_real_exponent", JsonNumber(r.max_real_exponent)},
                      {"out", args.out},
                      {"diagnostics", notes}}
                     .dump(2)
              << "\n";
    return 0;
  }
  std::cout << "Simulated " << kind << " test of " << l.scene.name << ": " << r.data.records.size()
            << " record" << (r.data.records.size() == 1 ? "" : "s") << " of " << o.periods
            << " periods (" << o.samples_per_period
            << " samples per period, T = " << Num(r.data.period, 10) << " s), each after "
            << Num(r.settle_time, 6) << " s of transient (slowest exponent "
            << Num(r.max_real_exponent, 4) << " 1/s)\n";
  for (const std::string& d : notes) std::cout << "  note: " << d << "\n";
  std::cout << "  wrote " << args.out << " (" << samples << " rows)\n";
  return 0;
}

}  // namespace

Command AddSimulateCommand(CLI::App& app) {
  static SimulateArgs args;
  args = SimulateArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand("simulate",
                                 "step-sine or multisine time data of a scene (for ltp identify)");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--input", args.input, "excited input (index or name)")->capture_default_str();
  cmd->add_option("--excitation", args.excitation,
                  "sine:F, stepsine:F0:F1:DF (one record per frequency), multisine:F0:F1:DF "
                  "(all at once, --records realisations) or noise:F0:F1 (periodic Gaussian "
                  "noise on every line of the record's grid) (Hz)")
      ->required();
  cmd->add_option("--records", args.records,
                  "multisine: records with random phases (at least the orders to identify)")
      ->capture_default_str();
  cmd->add_option("--periods", args.periods,
                  "recorded periods per record (frequencies move to whole cycles)")
      ->capture_default_str();
  cmd->add_option("--samples-per-period", args.samples_per_period, "sampling rate")
      ->capture_default_str();
  cmd->add_option("--amplitude", args.amplitude, "of the input sine")->capture_default_str();
  cmd->add_option("--noise", args.noise_db, "white output noise at this SNR (dB)");
  cmd->add_option("--input-noise", args.input_noise_db,
                  "white noise on the recorded input at this SNR (dB)");
  cmd->add_option("--speed-offset", args.speed_offset_pct,
                  "step-sine: the rotor turns this many % faster than the model's speed (a rig's; "
                  "the system's phase runs faster, its coefficients are the model's)");
  cmd->add_option("--speed-ramp", args.speed_ramp_pct,
                  "step-sine: and its speed rises by this many % over each record");
  cmd->add_flag("--tacho", args.tacho,
                "step-sine: write a once-per-period tacho column aux:tacho (for identify --tacho)");
  cmd->add_option("--cubic", args.cubic,
                  "K3: a hardening cubic spring between output 0 and the input (force u − K3·y³)");
  cmd->add_option("--max-transient", args.max_transient,
                  "refuse a transient (before the records) longer than this many periods")
      ->check(NumberAboveZero())
      ->capture_default_str();
  cmd->add_option("--seed", args.seed, "noise (and multisine phase) generator seed")
      ->capture_default_str();
  cmd->add_option("--out", args.out,
                  "the file to write: ltp's time-data CSV, or UFF 58 time records (.uff, .unv)")
      ->required();
  cmd->add_flag("--binary", args.binary, "UFF as binary dataset 58b (full precision, smaller)");
  cmd->add_flag("--json", args.json, "one JSON summary on stdout");
  return {cmd, [] { return RunSimulate(args); }};
}

}  // namespace ltp::cli
