#include "campbell_output.h"

#include <fstream>
#include <numbers>
#include <ostream>

#include "format.h"
#include "ltp/core/error.h"

namespace ltp::cli {

using nlohmann::json;

json CampbellJson(const CampbellDiagram& d) {
  json lines = json::array(), crossings = json::array(), weak = json::array();
  for (size_t k = 0; k < d.lines.size(); ++k) {
    const CampbellLine& line = d.lines[k];
    json j = {{"mode", k + 1},
              {"description", line.description},
              {"frequency_hz", JsonNumbers(line.frequency_hz)},
              {"real_part", JsonNumbers(line.real_part)},
              {"damping_ratio", JsonNumbers(line.damping_ratio)}};
    if (line.description_end != line.description) j["description_end"] = line.description_end;
    if (line.lost_after) j["lost_after"] = JsonNumber(d.parameter[*line.lost_after]);
    lines.push_back(j);
  }
  for (const CampbellCrossing& c : d.crossings)
    crossings.push_back({{"mode", c.line + 1},
                         {"description", d.lines[c.line].description},
                         {"per_rev", c.per_rev},
                         {"parameter", JsonNumber(c.parameter)},
                         {"parameter_error", JsonNumber(c.parameter_error)},
                         {"rotor_speed", JsonNumber(c.rotor_speed)},
                         {"frequency_hz", JsonNumber(c.frequency_hz)},
                         {"real_part", JsonNumber(c.real_part)},
                         {"damping_ratio", JsonNumber(c.damping_ratio)}});
  for (const auto& [lo, hi] : d.weakly_damped) weak.push_back({JsonNumber(lo), JsonNumber(hi)});
  return {{"frequency", std::string(ToString(d.frequency))},
          {"lines", lines},
          {"per_rev", d.per_rev},
          {"crossings", crossings},
          {"weakly_damped", weak},
          {"diagnostics", Texts(d.diagnostics)}};
}

void PrintCampbell(std::ostream& out, const CampbellDiagram& d, const std::string& axis) {
  out << "  modes (one line per conjugate pair, named by the states' participation):\n";
  for (size_t k = 0; k < d.lines.size(); ++k) {
    const CampbellLine& line = d.lines[k];
    out << "    " << Num(static_cast<double>(k + 1), 3, 3) << "  " << line.description;
    if (line.description_end != line.description) out << "  →  " << line.description_end;
    out << "\n";
  }
  if (d.per_rev.empty()) {
    out << "  no per-rev lines: the scene gives no rotor speed\n";
  } else if (d.crossings.empty()) {
    out << "  no mode crosses the lines 1P.." << d.per_rev.back() << "P in the sweep\n";
  } else {
    out << "\n  crossings with the per-rev lines n·Ω/2π (" << d.crossings.size() << "):\n"
        << "    mode   nP " << std::string(axis.size() < 14 ? 14 - axis.size() : 0, ' ') << axis
        << "   ± error    Ω [rad/s]     f [Hz]    Re λ [1/s]   damping\n";
    constexpr size_t kShown = 40;  // the rest are in --json and the crossings CSV
    for (size_t k = 0; k < d.crossings.size() && k < kShown; ++k) {
      const CampbellCrossing& c = d.crossings[k];
      out << "    " << Num(static_cast<double>(c.line + 1), 3, 4) << Num(c.per_rev, 3, 5) << "P "
          << Num(c.parameter, 8, 14) << Num(c.parameter_error, 2, 10) << Num(c.rotor_speed, 7, 13)
          << Num(c.frequency_hz, 7, 11) << Num(c.real_part, 4, 14) << Num(c.damping_ratio, 3, 10)
          << "\n";
    }
    if (d.crossings.size() > kShown)
      out << "    … " << d.crossings.size() - kShown
          << " more (all of them in --json and the --csv crossings file)\n";
  }
  for (const auto& [lo, hi] : d.weakly_damped)
    out << "  weakly damped for " << axis << " in [" << Num(lo, 6) << ", " << Num(hi, 6) << "]\n";
  for (const Diagnostic& note : d.diagnostics) out << "  note: " << note.text << "\n";
}

void WriteCrossingsCsv(const std::string& path, const CampbellDiagram& d, const std::string& axis) {
  std::ofstream out(path);
  out.precision(12);
  out << "mode,description,per_rev," << axis << "," << axis
      << "_error,rotor_speed_rad_s,frequency_hz,real_part,damping_ratio\n";
  for (const CampbellCrossing& c : d.crossings) {
    out << c.line + 1 << "," << CsvText(d.lines[c.line].description) << "," << c.per_rev << ","
        << c.parameter << "," << c.parameter_error << "," << c.rotor_speed << "," << c.frequency_hz
        << "," << c.real_part << "," << c.damping_ratio << "\n";
  }
  if (!out) throw InputError("cannot write '" + path + "'");
}

void AddCampbellArgs(CLI::App* cmd, CampbellOptions& options) {
  // The library's names; CLI11 then sets the enum from its number.
  const CLI::Validator kinds(
      [](std::string& name) -> std::string {
        const auto kind = ParseCampbellFrequency(name);
        if (!kind) return "must be damped or natural, got '" + name + "'";
        name = std::to_string(static_cast<int>(*kind));
        return "";
      },
      "");
  cmd->add_option("--frequency", options.frequency,
                  "Campbell: damped (Im λ/2π) or natural (|λ|/2π, as ACDC draws) frequencies")
      ->transform(kinds)
      ->option_text("damped|natural=" + std::string(ToString(options.frequency)));
  cmd->add_option("--max-damping", options.max_damping_ratio,
                  "Campbell: leave out lines damped above this ratio wherever tracked (e.g. 0.3 "
                  "hides inflow states; 1 = keep all)")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 1.0));
  cmd->add_option("--max-frequency", options.max_frequency_hz,
                  "Campbell: the band of interest; leave out lines above this many Hz wherever "
                  "tracked (0 = keep all)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--per-rev", options.max_per_rev,
                  "Campbell: per-rev lines 1P..NP (0 = automatic: B..3B)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  cmd->add_option("--weak-damping", options.weak_damping_ratio,
                  "Campbell: shade where a mode's damping ratio is below this (0 = never)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.999));
}

std::string CrossingsCsvPath(const std::string& csv) {
  const std::string stem = csv.ends_with(".csv") ? csv.substr(0, csv.size() - 4) : csv;
  return stem + "-crossings.csv";
}

}  // namespace ltp::cli
