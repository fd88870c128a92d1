// `ltp campbell POINT...`: the Campbell diagram of OpenFAST linearisations at several operating
// points (each POINT one set of azimuth files: a directory or a quoted glob), by MBC3 at each
// point with modes tracked across points.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

#include "campbell_output.h"
#include "chart_plot.h"
#include "command.h"
#include "format.h"
#include "ltp/core/error.h"
#include "ltp/studies/lin_campbell.h"
#include "plot.h"

namespace ltp::cli {

namespace {

using nlohmann::json;

struct CampbellArgs {
  std::vector<std::string> points;
  std::string by = "auto";
  bool keep_going = false;
  CampbellOptions campbell = LinCampbellOptions{}.campbell;  // the library's defaults
  std::vector<std::string> exclude_modules;
  std::string csv, plot;
  bool json = false;
};

LinCampbellOptions MakeOptions(const CampbellArgs& args) {
  LinCampbellOptions o;
  const auto axis = ParseOperatingPointAxis(args.by);
  if (!axis)
    throw InputError("--by must be auto, rotor-speed or wind-speed, got '" + args.by + "'");
  o.axis = *axis;
  o.keep_going = args.keep_going;
  o.campbell = args.campbell;
  o.exclude_modules = args.exclude_modules;
  o.Validate();
  return o;
}

// The point's collective pitch in degrees, as OpenFAST's tables and ACDC show it.
std::optional<double> PitchDeg(const LinCampbellPoint& p) {
  if (!p.collective_pitch) return std::nullopt;
  return *p.collective_pitch * 180 / std::numbers::pi;
}

// One row per operating point: the ordering quantity first (rotor speed in rpm or wind speed),
// then the other and the collective pitch (empty without inputs), then per line its frequency
// (damped or natural, as the header says) and damping ratio, each column named by the line's number
// and mode (empty cells where the line is not tracked).
void WriteLinesCsv(const std::string& path, const LinCampbellResult& r) {
  const bool by_rpm = r.axis == OperatingPointAxis::kRotorSpeed;
  const std::string kind(ToString(r.diagram.frequency));
  std::ofstream out(path);
  out.precision(12);
  out << (by_rpm ? "rotor_speed_rpm,wind_speed_m_s" : "wind_speed_m_s,rotor_speed_rpm")
      << ",pitch_deg";
  for (size_t k = 0; k < r.diagram.lines.size(); ++k) {
    const std::string name =
        "mode " + std::to_string(k + 1) + " (" + r.diagram.lines[k].description + ")";
    out << "," << CsvText(name + " " + kind + " frequency [Hz]") << ","
        << CsvText(name + " damping ratio");
  }
  out << "\n";
  for (size_t p = 0; p < r.points.size(); ++p) {
    const std::string rpm = CsvNumber(r.points[p].rotor_speed * 30 / std::numbers::pi);
    const std::string wind = CsvNumber(r.points[p].wind_speed);
    out << (by_rpm ? rpm + "," + wind : wind + "," + rpm) << ","
        << CsvNumber(PitchDeg(r.points[p]));
    for (const CampbellLine& line : r.diagram.lines) {
      if (std::isfinite(line.frequency_hz[p]))
        out << "," << line.frequency_hz[p] << "," << line.damping_ratio[p];
      else
        out << ",,";
    }
    out << "\n";
  }
  if (!out) throw InputError("cannot write '" + path + "'");
}

// Where a point's files are, as one pattern: "omega-0.4/rotor.*.lin" (OpenFAST numbers the
// linearisations of a simulation <root>.<k>.lin).
std::string FilesPattern(const std::vector<std::string>& files) {
  const std::filesystem::path first(files.front());
  std::string name = first.filename().string();
  const size_t dot = name.rfind('.', name.size() - 5);
  if (files.size() > 1 && dot != std::string::npos &&
      name.find_first_not_of("0123456789", dot + 1) == name.size() - 4)
    name = name.substr(0, dot) + ".*.lin";
  return (first.parent_path().filename() / name).string();
}

int RunCampbell(const CampbellArgs& args) {
  if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);  // a bad extension fails first
  const LinCampbellOptions options = MakeOptions(args);
  const LinCampbellResult r = ComputeLinCampbell(args.points, options);
  const std::string axis = r.axis == OperatingPointAxis::kRotorSpeed ? "rpm" : "wind_speed";
  if (!args.csv.empty()) {
    WriteLinesCsv(args.csv, r);
    WriteCrossingsCsv(CrossingsCsvPath(args.csv), r.diagram, axis);
  }
  std::string plot_note;
  if (!args.plot.empty()) {
    ChartPlotInput in;
    in.title = "Campbell diagram: " + std::to_string(r.points.size()) + " operating points (MBC3)";
    in.axis_labels = {r.axis_label};
    in.points = &r.sweep;
    in.campbell = &r.diagram;
    in.sidebands = 0;
    in.eigenvalues = "MBC3 frequencies (azimuth-averaged)";
    in.real_parts = "MBC3 eigenvalues";
    in.damping_ratio_panel = true;
    plot_note = DrawChart(in, args.plot);
  }
  if (args.json) {
    json points = json::array();
    for (const LinCampbellPoint& p : r.points)
      points.push_back({{"files", p.files},
                        {"parameter", JsonNumber(p.parameter)},
                        {"rotor_speed_rad_s", JsonNumber(p.rotor_speed)},
                        {"wind_speed_m_s", JsonNumber(p.wind_speed)},
                        {"pitch_deg", JsonNumber(PitchDeg(p))},
                        {"blades", p.mbc.blades},
                        {"max_real_part", JsonNumber(p.mbc.max_real_part)},
                        {"notes", Texts(p.diagnostics)}});
    json j = {{"axis", r.axis_label}, {"points", points},
              {"skipped", r.skipped}, {"campbell", CampbellJson(r.diagram)},
              {"csv", args.csv},      {"plot", args.plot}};
    if (!plot_note.empty()) j["plot_note"] = plot_note;
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "Campbell diagram of " << r.points.size()
            << " operating points (MBC3 at each, modes tracked by MAC)\n"
            << "  "
            << (r.axis == OperatingPointAxis::kRotorSpeed ? "rotor speed [rpm]"
                                                          : "wind speed [m/s]")
            << "   files   blades   max Re λ [1/s]   files of the point\n";
  for (const LinCampbellPoint& p : r.points) {
    std::cout << "  " << Num(p.parameter, 6, 17) << Num(static_cast<double>(p.files.size()), 3, 8)
              << Num(p.mbc.blades, 3, 9) << Num(p.mbc.max_real_part, 4, 17) << "   "
              << FilesPattern(p.files) << "\n";
    for (const Diagnostic& d : p.diagnostics) std::cout << "        note: " << d.text << "\n";
  }
  for (const std::string& why : r.skipped)
    std::cout << "  left out (--keep-going): " << why << "\n";
  std::cout << "\n";
  PrintCampbell(std::cout, r.diagram, axis);
  if (!args.csv.empty())
    std::cout << "  wrote " << args.csv << " and " << CrossingsCsvPath(args.csv) << "\n";
  if (!args.plot.empty())
    std::cout << (plot_note.empty() ? "  wrote " + args.plot : "  " + plot_note) << "\n";
  return 0;
}

}  // namespace

Command AddCampbellCommand(CLI::App& app) {
  static CampbellArgs args;
  args = CampbellArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand(
      "campbell",
      "Campbell diagram of OpenFAST .lin files at several operating points (MBC3 at "
      "each, modes tracked across points, per-rev crossings)");
  cmd->add_option("points", args.points,
                  "the operating points: directories, .lin files or globs; OpenFAST's "
                  "<root>.<k>.lin files are grouped by root, so a flat output folder of several "
                  "simulations gives one point each")
      ->required();
  cmd->add_option("--by", args.by,
                  "order and plot the points by rotor-speed (rpm) or wind-speed (m/s); auto: "
                  "rotor speed unless two points share one")
      ->capture_default_str();
  cmd->add_flag("--keep-going", args.keep_going,
                "leave out an operating point that cannot be read or analysed (said which and "
                "why) instead of failing the diagram");
  AddCampbellArgs(cmd, args.campbell);
  cmd->add_option("--exclude-module", args.exclude_modules,
                  "leave out modes carried mostly by this module's states (AD: AeroDyn's inflow; "
                  "BD: BeamDyn; repeatable)")
      ->type_name("NAME");
  cmd->add_option("--csv", args.csv, "one row per operating point (and FILE-crossings.csv)");
  cmd->add_option("--plot", args.plot, "Campbell + damping diagram (FILE.svg|.png)");
  cmd->add_flag("--json", args.json, "one JSON object on stdout");
  return {cmd, [] { return RunCampbell(args); }};
}

}  // namespace ltp::cli
