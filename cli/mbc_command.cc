// `ltp mbc FILES...`: the MBC3 Campbell table of OpenFAST linearisation files at one operating
// point, with the Floquet analysis of the same samples beside it.
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

#include "command.h"
#include "format.h"
#include "ltp/core/error.h"
#include "ltp/floquet/estimate_source.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"
#include "ltp/studies/sampled_floquet.h"
#include "modal_reduction_output.h"
#include "progress_bar.h"

namespace ltp::cli {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;
constexpr const char* kFormulation =
    "MBC3 after G. Bir, NREL/CP-500-42553 (2008), eq. 29-32 (as OpenFAST's MBC3): "
    "A_NR = T^-1 (A_R T - dT/dt) at each azimuth, plain mean over the azimuths, eigenvalues of "
    "the mean";

struct MbcArgs {
  std::vector<std::string> files;
  bool json = false;
  std::string csv, shapes_csv;
  bool floquet = true;
  std::string speed = "operating-point";
  double tol = 1e-10;
  double modes_below_hz = 0;
};

std::string Hz(double rad_per_s) { return Num(rad_per_s / (2 * kPi), 6); }

std::string Fixed(double x, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

json ModeJson(const MbcMode& m, const Mbc3Result& r) {
  json dominant = json::array();
  for (const auto& s : m.dominant)
    dominant.push_back({{"state", r.states[s.state].description}, {"share", JsonNumber(s.share)}});
  return {{"natural_frequency_hz", JsonNumber(m.natural_frequency_hz)},
          {"damped_frequency_hz", JsonNumber(m.damped_frequency_hz)},
          {"damping_ratio", m.rigid_body ? json(nullptr) : JsonNumber(m.damping_ratio)},
          {"re", JsonNumber(m.eigenvalue.real())},
          {"im", JsonNumber(m.eigenvalue.imag())},
          {"kind", std::string(ToString(m.kind))},
          {"rigid_body", m.rigid_body},
          {"whirl", m.whirl.empty() ? json(nullptr) : json(m.whirl)},
          {"description", m.description},
          {"dominant_states", dominant},
          {"shape",
           {{"re", JsonNumbers(std::vector<double>(m.eigenvector.real().begin(),
                                                   m.eigenvector.real().end()))},
            {"im", JsonNumbers(std::vector<double>(m.eigenvector.imag().begin(),
                                                   m.eigenvector.imag().end()))}}},
          {"participation",
           {{"re", JsonNumbers(std::vector<double>(m.participation.real().begin(),
                                                   m.participation.real().end()))},
            {"im", JsonNumbers(std::vector<double>(m.participation.imag().begin(),
                                                   m.participation.imag().end()))}}}};
}

// One row per MBC state, per mode its shape's magnitude and phase (degrees, the leading state
// at 0): what one animates in ParaView or plots as a mode's bar chart.
void WriteShapesCsv(const std::string& file, const Mbc3Result& r) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  csv << "state";
  for (size_t k = 0; k < r.modes.size(); ++k) {
    const std::string name = "mode " + std::to_string(k + 1) + " (" + r.modes[k].description + ")";
    csv << "," << CsvText(name + " magnitude") << "," << CsvText(name + " phase [deg]");
  }
  csv << "\n" << std::setprecision(12);
  for (size_t i = 0; i < r.states.size(); ++i) {
    csv << CsvText(r.states[i].description);
    for (const MbcMode& m : r.modes) {
      const std::complex<double> v = m.eigenvector[static_cast<Eigen::Index>(i)];
      csv << "," << std::abs(v) << "," << std::arg(v) * 180 / kPi;
    }
    csv << "\n";
  }
}

json StateNames(const Mbc3Result& r) {
  json names = json::array();
  for (const auto& s : r.states) names.push_back(s.description);
  return names;
}

json ExponentJson(std::complex<double> l) {
  const double mag = std::abs(l);
  return {{"re", JsonNumber(l.real())},
          {"im", JsonNumber(l.imag())},
          {"natural_frequency_hz", JsonNumber(mag / (2 * kPi))},
          {"damping_ratio", JsonNumber(mag > 0 ? -l.real() / mag : 0.0)}};
}

json FloquetJson(const SampledFloquetResult& f) {
  json modes = json::array();
  for (const SampledFloquetMode& m : f.modes)
    modes.push_back({{"mbc_mode", m.mbc_mode ? json(*m.mbc_mode) : json(nullptr)},
                     {"hold", ExponentJson(m.hold)},
                     {"trig", ExponentJson(m.trig)},
                     {"difference", JsonNumber(m.difference)},
                     {"to_mbc", m.mbc_mode ? JsonNumber(m.to_reference) : json(nullptr)},
                     {"rigid_body", m.rigid_body}});
  return {{"ok", f.ok},
          {"coordinates", f.coordinates},
          {"samples", f.samples},
          {"resolved_harmonics", f.resolved_harmonics},
          {"modes", modes},
          {"max_real_exponent_hold", JsonNumber(f.max_real_hold)},
          {"max_real_exponent_trig", JsonNumber(f.max_real_trig)},
          {"stable", f.stable},
          {"verdict", ToString(f.verdict)},
          {"error_estimate", JsonNumber(f.error_estimate)},
          {"max_difference", JsonNumber(f.max_difference)},
          {"max_difference_to_mbc",
           f.max_to_reference >= 0 ? JsonNumber(f.max_to_reference) : json(nullptr)},
          {"error_estimate_hold", JsonNumber(f.hold.error_estimate)},
          {"error_estimate_trig", JsonNumber(f.trig.error_estimate)},
          {"elapsed_s", f.hold.elapsed_s + f.trig.elapsed_s},
          {"modes_below", ReductionJson(f.trig.reduction)},
          {"diagnostics_hold", Texts(f.hold.diagnostics)},
          {"diagnostics_trig", Texts(f.trig.diagnostics)},
          {"notes", Texts(f.diagnostics)}};
}

void WriteCsv(const std::string& file, const Mbc3Result& r, const SampledFloquetResult* f) {
  std::ofstream csv(file);
  if (!csv) throw InputError("cannot write '" + file + "'");
  csv << "mode,natural_frequency_hz,damped_frequency_hz,damping_ratio,re,im,kind,rigid_body,whirl,"
         "description";
  if (f) csv << ",floquet_hold_re,floquet_hold_im,floquet_trig_re,floquet_trig_im";
  csv << "\n" << std::setprecision(12);
  for (size_t k = 0; k < r.modes.size(); ++k) {
    const MbcMode& m = r.modes[k];
    csv << k + 1 << "," << m.natural_frequency_hz << "," << m.damped_frequency_hz << ","
        << m.damping_ratio << "," << m.eigenvalue.real() << "," << m.eigenvalue.imag() << ","
        << ToString(m.kind) << "," << (m.rigid_body ? 1 : 0) << "," << m.whirl << ","
        << CsvText(m.description);
    if (f) {
      const SampledFloquetMode* match = nullptr;
      for (const auto& fm : f->modes)
        if (fm.mbc_mode == k) match = &fm;
      if (match)
        csv << "," << match->hold.real() << "," << match->hold.imag() << "," << match->trig.real()
            << "," << match->trig.imag();
      else
        csv << ",,,,";
    }
    csv << "\n";
  }
}

void PrintHeader(const LinOperatingPoint& op, const Mbc3Result& r) {
  std::cout << "MBC3 Campbell table: OpenFAST linearisation at one operating point\n";
  std::cout << "  files      ";
  for (int k = 0; k < op.size(); ++k)
    std::cout << (k ? ", " : "") << std::filesystem::path(op.files[k]).filename().string() << " ("
              << Fixed(op.azimuths[k] * 180 / kPi, 1) << "°)";
  std::cout << "\n  rotor      Ω = " << Num(op.rotor_speed, 6)
            << " rad/s = " << Num(op.rotor_speed * 30 / kPi, 6)
            << " rpm (1P = " << Hz(op.rotor_speed) << " Hz); " << op.states.size() << " states, "
            << r.blades << " blades (" << r.state_coordinates.groups.size()
            << " blade tuples of states)\n";
}

void PrintTable(const Mbc3Result& r) {
  std::cout
      << "  transform  multi-blade coordinates after Bir (2008, NREL/CP-500-42553) eq. 29, as "
         "OpenFAST's MBC3;\n             ";
  if (r.transformed.size() == 1)
    std::cout << "one azimuth: its transformed state matrix, nothing to average\n\n";
  else
    std::cout << "mean of the " << r.transformed.size()
              << " transformed state matrices (their periodic part, "
              << Num(100 * r.periodic_part, 3) << "% of the mean, is dropped)\n\n";
  std::cout << "  mode   nat. freq [Hz]  damped [Hz]   damping ζ    Re λ [1/s]   description\n";
  for (size_t k = 0; k < r.modes.size(); ++k) {
    const MbcMode& m = r.modes[k];
    std::cout << "  " << std::setw(4) << k + 1 << Num(m.natural_frequency_hz, 6, 17)
              << Num(m.damped_frequency_hz, 6, 13)
              << (m.rigid_body ? std::string("  rigid body") : Num(m.damping_ratio, 5, 12))
              << Num(m.eigenvalue.real(), 5, 14) << "   " << m.description
              << (m.kind == MbcMode::Kind::kReal ? "  [real eigenvalue]" : "") << "\n";
  }
  std::cout << "\n  max Re λ = " << Num(r.max_real_part, 6) << " 1/s"
            << (r.rigid_body_modes ? " (rigid-body mode excluded)" : "") << "  →  "
            << (r.max_real_part < 0 ? "STABLE" : "UNSTABLE") << " (MBC3, azimuth-averaged)\n";
  if (!r.diagnostics.empty()) {
    std::cout << "  diagnostics:\n";
    for (const Diagnostic& d : r.diagnostics) std::cout << "    - " << d.text << "\n";
  }
}

void PrintFloquet(const SampledFloquetResult& f, const Mbc3Result& r) {
  const std::string_view brief =
      EstimateSourceBrief(f.trig.error_estimate_method, f.trig.integrator);
  std::cout << "\nFloquet analysis of the same " << f.samples
            << (f.samples == 1 ? " sample (" : " samples (") << f.coordinates << ", not averaged)\n"
            << "  hold: each sample held over the nearest azimuths (exact product of exponentials, "
            << f.hold.segments << " segments)\n"
            << "  trig: trigonometric interpolation through the samples ("
            << ToString(f.trig.integrator) << ", error estimate " << Num(f.trig.error_estimate, 2)
            << " 1/s" << (brief.empty() ? "" : " ") << brief << ")\n";
  if (!f.ok) {
    std::cout << "  FAILED\n";
    for (const Diagnostic& d : f.hold.diagnostics) std::cout << "    - hold: " << d.text << "\n";
    for (const Diagnostic& d : f.trig.diagnostics) std::cout << "    - trig: " << d.text << "\n";
    return;
  }
  if (f.trig.reduction) PrintReduction(*f.trig.reduction, f.trig.states);
  const bool with_mbc = !f.modes.empty() && f.modes.front().mbc_mode.has_value();
  std::cout << "\n  mode" << (with_mbc ? "   MBC f_n [Hz]    MBC ζ" : "")
            << "   hold f_n [Hz]   hold ζ   trig f_n [Hz]   trig ζ   |hold−trig| [1/s]"
            << (with_mbc ? "   to MBC [1/s]" : "") << "\n";
  auto freq = [](std::complex<double> l) { return std::abs(l) / (2 * kPi); };
  auto zeta = [](std::complex<double> l) {
    return std::abs(l) > 0 ? -l.real() / std::abs(l) : 0.0;
  };
  for (size_t k = 0; k < f.modes.size(); ++k) {
    const SampledFloquetMode& m = f.modes[k];
    std::cout << "  " << std::setw(4) << (with_mbc ? *m.mbc_mode + 1 : k + 1);
    if (with_mbc)
      std::cout << Num(freq(m.reference), 6, 15)
                << (m.rigid_body ? std::string("  rigid") : Num(zeta(m.reference), 4, 9));
    std::cout << Num(freq(m.hold), 6, 16)
              << (m.rigid_body ? std::string("    rigid") : Num(zeta(m.hold), 4, 9))
              << Num(freq(m.trig), 6, 16)
              << (m.rigid_body ? std::string("    rigid") : Num(zeta(m.trig), 4, 9))
              << Num(m.difference, 3, 20);
    if (with_mbc) std::cout << Num(m.to_reference, 3, 15);
    std::cout << "\n";
  }
  (void)r;
  bool rigid = false;
  for (const SampledFloquetMode& m : f.modes) rigid = rigid || m.rigid_body;
  std::cout << "\n  max Re λ" << (rigid ? " (rigid body excluded)" : "") << ": hold "
            << Num(f.max_real_hold, 6) << ", trig " << Num(f.max_real_trig, 6) << " 1/s  →  "
            << (f.verdict == StabilityVerdict::kStable     ? "STABLE"
                : f.verdict == StabilityVerdict::kUnstable ? "UNSTABLE"
                                                           : "MARGINAL (within the error estimate: "
                                                             "undecided)")
            << " (trig, error estimate " << Num(f.error_estimate, 2)
            << " 1/s: integration plus the routes' difference)\n  the routes differ by up to "
            << Num(f.max_difference, 3) << " 1/s";
  if (f.max_to_reference >= 0)
    std::cout << "; Floquet vs MBC3 up to " << Num(f.max_to_reference, 3) << " 1/s";
  std::cout << "\n  notes:\n";
  for (const Diagnostic& d : f.diagnostics) std::cout << "    - " << d.text << "\n";
}

int RunMbc(const MbcArgs& args) {
  if (args.speed != "operating-point" && args.speed != "header")
    throw InputError("--speed must be operating-point or header, got '" + args.speed + "'");
  const LinOperatingPoint op = ReadLinOperatingPoint(args.files);
  Mbc3Options options;
  options.speed_from_operating_point = args.speed == "operating-point";
  const Mbc3Result r = Mbc3(op, options);

  // The table first: the Floquet part can take long (60 states: seconds to a minute).
  if (!args.json) {
    PrintHeader(op, r);
    if (r.applicable) {
      PrintTable(r);
    } else {
      std::cout << "\n  MBC3: not applicable — " << r.reason << "\n";
    }
    std::cout << std::flush;
  }
  std::optional<SampledFloquetResult> f;
  std::string floquet_skipped;
  const std::optional<std::string> sampling = AzimuthSamplingProblem(op.azimuths);
  if (args.floquet && op.rotor_speed > 0 && !sampling) {
    SampledFloquetOptions fo;
    fo.floquet.integrator.rel_tol = args.tol;
    fo.floquet.modes_below = 2 * kPi * args.modes_below_hz;
    ProgressBar progress("mbc: Floquet", !args.json);
    fo.floquet.on_progress = [&progress](std::string_view phase, double fraction) {
      progress.Update(fraction, 1, {}, phase);
    };
    f = AnalyzeSampledFloquet(op, r, fo);
  } else if (args.floquet && sampling) {
    floquet_skipped = "not done: " + *sampling;
  } else if (args.floquet) {
    floquet_skipped =
        "rotor speed 0: a parked rotor is time-invariant, so there is no period "
        "and no Floquet analysis";
  }
  if (!args.csv.empty()) WriteCsv(args.csv, r, f ? &*f : nullptr);
  if (!args.shapes_csv.empty()) WriteShapesCsv(args.shapes_csv, r);
  const bool ok = (r.applicable || f) && (!f || f->ok);

  if (args.json) {
    json modes = json::array();
    for (const MbcMode& m : r.modes) modes.push_back(ModeJson(m, r));
    json j = {{"files", op.files},
              {"rotor_speed_rad_s", JsonNumber(op.rotor_speed)},
              {"azimuths_rad", op.azimuths},
              {"blades", r.blades},
              {"states", op.states.size()},
              {"state_names", StateNames(r)},
              {"mbc_applicable", r.applicable},
              {"formulation", kFormulation},
              {"periodic_part", JsonNumber(r.periodic_part)},
              {"modes", modes},
              {"rigid_body_modes", r.rigid_body_modes},
              {"max_real_part",
               r.applicable && !r.modes.empty() ? JsonNumber(r.max_real_part) : json(nullptr)},
              {"diagnostics", Texts(r.diagnostics)},
              {"notes", Texts(LinCaveats(op))}};
    if (!r.applicable) j["reason"] = r.reason;
    if (f) j["floquet"] = FloquetJson(*f);
    if (!floquet_skipped.empty()) j["floquet_skipped"] = floquet_skipped;
    std::cout << j.dump(2) << "\n";
    return ok ? 0 : 1;
  }
  if (f) PrintFloquet(*f, r);
  if (!floquet_skipped.empty()) std::cout << "\n  Floquet analysis: " << floquet_skipped << "\n";
  return ok ? 0 : 1;
}

}  // namespace

Command AddMbcCommand(CLI::App& app) {
  static MbcArgs args;
  args = MbcArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand(
      "mbc",
      "Campbell table (MBC3 with azimuth averaging) of OpenFAST .lin files, with the "
      "Floquet analysis of the same azimuth samples");
  cmd->add_option("files", args.files,
                  "OpenFAST .lin files at one operating point (one per azimuth), a directory of "
                  "them, or a glob")
      ->required();
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  cmd->add_option("--csv", args.csv, "write the Campbell table to CSV");
  cmd->add_option("--shapes-csv", args.shapes_csv,
                  "write each mode's shape to CSV: one row per MBC state, magnitude and phase");
  cmd->add_flag("!--no-floquet", args.floquet, "skip the Floquet analysis of the samples");
  cmd->add_option("--speed", args.speed,
                  "rotor speed in the transform: operating-point (OpenFAST's MBC3: Ω and dΩ/dt "
                  "of the generator azimuth) or header")
      ->capture_default_str();
  cmd->add_option("--tol", args.tol, "relative tolerance of the Floquet integrations")
      ->capture_default_str()
      ->check(NumberAboveZero());
  cmd->add_option("--modes-below", args.modes_below_hz,
                  "Floquet part: only the modes whose MBC eigenvalue is below this many Hz "
                  "(|λ|/2π), checked against twice the cut-off, as ltp floquet --modes-below; 0 = "
                  "every mode")
      ->capture_default_str()
      ->check(NumberAboveZero(true));
  return {cmd, [] { return RunMbc(args); }};
}

}  // namespace ltp::cli
