// `ltp chart`: Campbell and damping diagrams over one parameter, stability maps over two, with
// the unstable intervals (or boundary points) refined beyond the grid. Streams every point to
// disk as it completes, resumes an interrupted sweep, and shows progress on a terminal.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>

#ifdef LTP_WITH_MPI
#include <mpi.h>
#endif

#include "campbell_output.h"
#include "chart_mpi.h"
#include "chart_plot.h"
#include "chart_record.h"
#include "command.h"
#include "format.h"
#include "ltp/core/error.h"
#include "ltp/floquet/formed_monodromy.h"
#include "ltp/integrate/threads.h"
#include "ltp/studies/chart.h"
#include "ltp/studies/chart_options.h"
#include "ltp/studies/mode_tracking.h"
#include "ltp/studies/stability_boundary.h"
#include "ltp/studies/sweep.h"
#include "plot.h"
#include "progress_bar.h"
#include "scene_args.h"

namespace ltp::cli {

namespace {

using nlohmann::json;

// Defaults from the library's ChartOptions (Python's ltp.chart has the same).
struct ChartArgs {
  SceneArgs scene;
  std::string sweep, sweep2;
  std::string method{ToString(ChartOptions{}.method)};
  std::string integrator;  // empty: ChartIntegrator's choice
  double tol = ChartOptions{}.tol;
  int threads = ChartOptions{}.threads;
  std::string csv, plot;
  std::string plot_x;  // maps: the parameter drawn horizontally (empty: the first sweep's)
  bool json = false, resume = false, compare = false, no_refine = false, no_curves = false;
  std::optional<int> check_every;  // empty: the library's choice (1-D: all, maps: every 97th)
  int refine_lines = ChartOptions{}.refine_lines;
  double refine_tol = ChartOptions{}.refine_tol;
  int sidebands = 1;
  CampbellOptions campbell = ChartOptions{}.campbell;
  long stop_after = 0;  // tests: interrupt after this many points, as Ctrl-C would
};

std::atomic<bool> g_interrupted{false};
extern "C" void OnInterrupt(int) { g_interrupted = true; }

// "rotor speed Omega (rad/s), > 0" → "Omega [rad/s]".
std::string AxisLabel(const Scene& scene, const std::string& name) {
  for (const auto& p : scene.parameters) {
    if (p.name != name) continue;
    const auto open = p.description.find('('), close = p.description.find(')');
    if (open != std::string::npos && close != std::string::npos && close > open + 1)
      return name + "  [" + p.description.substr(open + 1, close - open - 1) + "]";
  }
  return name;
}

json BoundaryJson(const BoundaryEstimate& e) {
  return {{"value", JsonNumber(e.value)},     {"refined", e.refined},
          {"bracket", JsonNumber(e.bracket)}, {"at_sweep_edge", e.at_sweep_edge},
          {"evaluations", e.evaluations},     {"note", e.note}};
}

// Maps: the traced boundary curves, each with its kind and per point its bracket, the
// parameter solved along and whether the tongue's edges merge there (boundary_curves.h).
json CurvesJson(const BoundaryCurves& curves, const SweepGrid& grid) {
  json list = json::array();
  for (const BoundaryCurve& c : curves.curves) {
    json points = json::array(), across = json::array(), bracket = json::array(),
         merged = json::array();
    for (size_t i = 0; i < c.points.size(); ++i) {
      points.push_back({JsonNumber(c.points[i][0]), JsonNumber(c.points[i][1])});
      across.push_back(grid.axes[static_cast<size_t>(c.across[i])].name);
      bracket.push_back(JsonNumber(c.bracket[i]));
      merged.push_back(c.merged[i] != 0);
    }
    list.push_back({{"kind", c.kind == BoundaryKind::kRealPlusOne ? "+1" : "-1"},
                    {"symmetry", ToString(c.symmetry)},
                    {"points", points},
                    {"across", across},
                    {"bracket", bracket},
                    {"merged", merged},
                    {"end_notes", {c.end_notes[0], c.end_notes[1]}},
                    {"evaluations", c.evaluations}});
  }
  json untraced = json::array();
  for (size_t k = 0; k < curves.untraced.size(); ++k)
    untraced.push_back({{"index", curves.untraced[k]}, {"note", curves.untraced_notes[k]}});
  return {{"curves", list},
          {"untraced_boundary_points", untraced},
          {"evaluations", curves.evaluations}};
}

// Maps: FILE-curves.csv beside --csv, one row per curve point.
std::string CurvesCsvPath(const std::string& csv) {
  const std::string stem = csv.ends_with(".csv") ? csv.substr(0, csv.size() - 4) : csv;
  return stem + "-curves.csv";
}

void WriteCurvesCsv(const std::string& path, const BoundaryCurves& curves, const SweepGrid& grid) {
  std::ofstream f(path);
  f << "curve,kind,symmetry," << grid.axes[0].name << "," << grid.axes[1].name
    << ",across,bracket,merged\n";
  for (size_t k = 0; k < curves.curves.size(); ++k) {
    const BoundaryCurve& c = curves.curves[k];
    for (size_t i = 0; i < c.points.size(); ++i)
      f << k + 1 << "," << (c.kind == BoundaryKind::kRealPlusOne ? "+1" : "-1") << ","
        << ToString(c.symmetry) << "," << Num(c.points[i][0], 17) << "," << Num(c.points[i][1], 17)
        << "," << grid.axes[static_cast<size_t>(c.across[i])].name << "," << Num(c.bracket[i], 3)
        << "," << (c.merged[i] ? 1 : 0) << "\n";
  }
  if (!f) throw InputError("cannot write '" + path + "'");
}

ChartOptions MakeOptions(const ChartArgs& args) {
  ChartOptions o;
  const auto method = ParseSweepMethod(args.method);
  if (!method)
    throw InputError("--method must be 'monodromy' or 'hill', got '" + args.method + "'");
  o.method = *method;
  if (!args.integrator.empty()) {
    const auto type = ParseIntegratorType(args.integrator);
    if (!type) throw InputError("--integrator: unknown integrator '" + args.integrator + "'");
    o.integrator = *type;
  }
  if (!(args.tol > 0 && args.tol < 1)) throw InputError("--tol must be in (0, 1)");
  o.tol = args.tol;
  o.compare = args.compare;
  if (args.check_every && *args.check_every < 0)
    throw InputError("--check-every must be >= 0 (0 = no error estimates)");
  o.check_every = args.check_every;
  if (args.threads < 0) throw InputError("--threads must be >= 0");
  o.threads = args.threads;
  o.refine = !args.no_refine;
  o.curves = !args.no_curves;
  o.refine_tol = args.refine_tol;
  o.refine_lines = args.refine_lines;
  o.campbell = args.campbell;
  o.Validate();
  return o;
}

// Everything one chart computed, for the writers.
struct ChartOutcome {
  explicit ChartOutcome(LoadedScene loaded) : scene(std::move(loaded)) {}
  size_t count(StabilityVerdict v) const { return analysis.tally.counts.at(v); }
  LoadedScene scene;
  ChartPlan plan;
  int threads = 0;
  std::vector<SweepPoint> points;  ///< grid order
  size_t resumed = 0;
  double sweep_s = 0;
  ChartAnalysis analysis;
  std::string title;  ///< the scene and what the user set
  std::string plot_note;
};

// A map of a time-reversible system (at the scene's base point): its unchecked points integrate
// half a period.
bool HalfPeriodRoute(const ChartOutcome& c) {
  return c.plan.sweep.method == SweepMethod::kMonodromy && !c.plan.sweep.modes &&
         FormsMonodromyFromHalfPeriod(c.scene.system);
}

// The points of the grid: those the journal holds (--resume), then the rest on every rank,
// streamed to the record. False when interrupted (Ctrl-C or --stop-after) before the end.
bool SweepAllPoints(ChartArgs& args, const Ranks& ranks, ChartRecord* record, ChartOutcome& c) {
  const bool root = ranks.rank == 0;
  const size_t size = c.plan.grid.size();
  ChartSweepHooks hooks;
  if (root) hooks.resumed = record->resumed();
  ProgressBar progress("chart", root && !args.json);
  size_t swept_so_far = 0;
  hooks.on_start = [&](size_t resumed) { swept_so_far = resumed; };
  hooks.on_point = [&](const SweepPoint& p) {
    record->Add(p);
    progress.Update(static_cast<double>(++swept_so_far), static_cast<double>(size), "points");
    if (args.stop_after > 0 && --args.stop_after == 0) g_interrupted = true;
  };
  hooks.cancel = &g_interrupted;
  hooks.runner = [&](const std::vector<size_t>& todo,
                     const std::function<void(SweepPoint &&)>& on_point,
                     const std::atomic<bool>* cancel) {
    // Every rank needs the same list of missing points: rank 0's.
    std::vector<size_t> indices = todo;
#ifdef LTP_WITH_MPI
    if (ranks.size > 1) {
      unsigned long count = indices.size();
      MPI_Bcast(&count, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
      indices.resize(count);
      MPI_Bcast(indices.data(), static_cast<int>(count), MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
    }
#endif
    return DistributedSweep(ranks, c.scene.scene, c.scene.parameters, c.plan.grid, indices,
                            c.plan.sweep, on_point, cancel);
  };
  g_interrupted = false;
  auto previous = std::signal(SIGINT, OnInterrupt);
  ChartPoints swept = SweepChart(c.scene.scene, c.scene.parameters, c.plan, hooks);
  std::signal(SIGINT, previous);
  progress.Clear();
  c.points = std::move(swept.points);
  c.resumed = swept.resumed;
  c.sweep_s = swept.sweep_s;
  if (!root) return true;
  if (swept.complete()) return true;
  const size_t done = static_cast<size_t>(std::count(swept.have.begin(), swept.have.end(), 1));
  std::cerr << "ltp chart: interrupted after " << done << " of " << size << " points";
  if (!args.csv.empty())
    std::cerr << "; '" << args.csv << "' holds them; finish with the same command and --resume";
  std::cerr << "\n";
  return false;
}

// Mode tracking and the Campbell diagram (1-D), the refined boundaries, the summary counts.
void Analyse(const ChartArgs& args, ChartOutcome& c) {
  c.analysis =
      AnalyseChart(c.scene.scene, c.scene.parameters, c.scene.system.labels(), c.plan, c.points);
  c.title = c.scene.scene.name;
  if (!args.scene.set.empty()) {
    c.title += " (";
    for (size_t i = 0; i < args.scene.set.size(); ++i)
      c.title += (i ? ", " : "") + args.scene.set[i];
    c.title += ")";
  }
}

// --plot-x: the grid axis a map draws horizontally. @throws InputError for a name not swept.
int PlotXAxis(const ChartArgs& args, const SweepGrid& grid) {
  if (args.plot_x.empty()) return 0;
  for (size_t a = 0; a < grid.axes.size(); ++a)
    if (grid.axes[a].name == args.plot_x) return static_cast<int>(a);
  throw InputError("--plot-x '" + args.plot_x + "' is not a swept parameter");
}

// Every parameter of the scene that is not swept, defaults included: "c = 0.02".
std::string Caption(const ChartOutcome& c) {
  ParameterMap fixed = c.scene.parameters;
  std::string swept;
  for (const auto& a : c.plan.grid.axes) {
    fixed.erase(a.name);
    swept += (swept.empty() ? "" : ", ") + a.name;
  }
  std::string text = fixed.empty() ? "" : ParameterList(fixed);
  for (size_t i = 0; (i = text.find('=', i)) != std::string::npos; i += 3)
    text.replace(i, 1, " = ");
  return (text.empty() ? "" : text + "; ") + "swept: " + swept;
}

std::string Plot(const ChartArgs& args, const ChartOutcome& c) {
  ChartPlotInput in;
  in.title = (c.plan.map ? "Stability map: " : "Campbell diagram: ") + c.title;
  for (const auto& a : c.plan.grid.axes) in.axis_labels.push_back(AxisLabel(c.scene.scene, a.name));
  in.grid = &c.plan.grid;
  in.points = &c.points;
  in.campbell = &c.analysis.campbell;
  in.intervals = &c.analysis.intervals;
  in.boundary = &c.analysis.boundary;
  if (c.plan.map && c.plan.chart.refine && c.plan.chart.curves) in.curves = &c.analysis.curves;
  in.x_axis = PlotXAxis(args, c.plan.grid);
  in.caption = Caption(c);
  in.sidebands = args.sidebands;
  in.compare = args.compare;
  return DrawChart(in, args.plot);
}

json ChartJson(const ChartArgs& args, const Ranks& ranks, const ChartOutcome& c) {
  json j = {{"scene", c.scene.scene.name},
            {"parameters", ParametersJson(c.scene.parameters)},
            {"states", c.scene.system.states()},
            {"method", args.method},
            {"integrator", args.integrator},
            {"tol", args.tol},
            {"half_period", HalfPeriodRoute(c)},
            {"points", c.plan.grid.size()},
            {"resumed_points", c.resumed},
            {"stable", c.count(StabilityVerdict::kStable)},
            {"marginal", c.count(StabilityVerdict::kMarginal)},
            {"unstable", c.count(StabilityVerdict::kUnstable)},
            {"failed", c.count(StabilityVerdict::kFailed)},
            {"checked_points", c.analysis.tally.checked},
            {"max_error_estimate", JsonNumber(c.analysis.tally.max_error)},
            {"threads", c.threads},
            {"ranks", ranks.size},
            {"sweep_s", c.sweep_s},
            {"refine_s", c.analysis.refine_s},
            {"csv", args.csv},
            {"plot", args.plot}};
  for (const auto& a : c.plan.grid.axes)
    j["sweep"].push_back({{"name", a.name},
                          {"start", a.start},
                          {"stop", a.stop},
                          {"step", a.step},
                          {"count", a.Values().size()}});
  json failures = json::array();
  for (const SweepPoint& p : c.points)
    if (!p.ok) failures.push_back({{"values", p.values}, {"reason", p.failure}});
  j["failures"] = failures;
  if (!c.plan.map) {
    json list = json::array(), detail = json::array();
    for (const auto& in : c.analysis.intervals) {
      list.push_back({JsonNumber(in.lo.value), JsonNumber(in.hi.value)});
      detail.push_back({{"lo", BoundaryJson(in.lo)}, {"hi", BoundaryJson(in.hi)}});
    }
    j["unstable_intervals"] = list;
    j["unstable_interval_details"] = detail;
    j["mode_tracking"] = {{"min_mac", JsonNumber(c.analysis.tracking.min_mac)},
                          {"ambiguous_points", c.analysis.tracking.ambiguous.size()}};
    j["campbell"] = CampbellJson(c.analysis.campbell);
  } else {
    json list = json::array(), detail = json::array();
    for (const auto& b : c.analysis.boundary) {
      if (!b.estimate.refined) continue;
      list.push_back({JsonNumber(b.values[0]), JsonNumber(b.values[1])});
    }
    for (const auto& b : c.analysis.boundary)
      detail.push_back({{"values", {JsonNumber(b.values[0]), JsonNumber(b.values[1])}},
                        {"refined_parameter", c.plan.grid.axes[static_cast<size_t>(b.axis)].name},
                        {"entering_unstable", b.entering_unstable},
                        {"estimate", BoundaryJson(b.estimate)}});
    j["boundary_points"] = list;
    j["boundary_point_details"] = detail;
    j["boundary_curves"] = CurvesJson(c.analysis.curves, c.plan.grid);
    j["curves_s"] = c.analysis.curves_s;
  }
  if (!c.plot_note.empty()) j["plot_note"] = c.plot_note;
  return j;
}

// Maps: the traced curves, one line each: kind, extent, largest bracket, merged points.
void PrintCurves(const ChartOutcome& c) {
  const BoundaryCurves& t = c.analysis.curves;
  if (t.curves.empty() && t.untraced.empty()) return;
  std::cout << "  boundary curves: " << t.curves.size() << " traced by continuation ("
            << t.evaluations << " evaluations, " << Num(c.analysis.curves_s, 3)
            << " s); within ±bracket along the parameter solved for:\n";
  const auto& axes = c.plan.grid.axes;
  for (size_t k = 0; k < t.curves.size(); ++k) {
    const BoundaryCurve& curve = t.curves[k];
    double widest = 0;
    size_t merged = 0;
    for (size_t i = 0; i < curve.points.size(); ++i) {
      widest = std::max(widest, curve.bracket[i]);
      merged += curve.merged[i] != 0;
    }
    std::cout << "    " << std::setw(2) << k + 1 << "  " << ToString(curve.kind)
              << (curve.symmetry == BoundarySymmetry::kNone   ? ""
                  : curve.symmetry == BoundarySymmetry::kEven ? " (even solution)"
                                                              : " (odd solution)")
              << ", " << curve.points.size() << " points from (" << axes[0].name << ", "
              << axes[1].name << ") = (" << Num(curve.points.front()[0], 6) << ", "
              << Num(curve.points.front()[1], 6) << ") to (" << Num(curve.points.back()[0], 6)
              << ", " << Num(curve.points.back()[1], 6) << "), bracket <= " << Num(widest, 2);
    if (merged) std::cout << "; " << merged << " points where the tongue's edges merge";
    std::cout << "\n";
  }
  if (!t.untraced.empty())
    std::cout << "    " << t.untraced.size()
              << " refined points on no curve (drawn as dots): " << t.untraced_notes.front()
              << "\n";
}

void PrintChart(const ChartArgs& args, const Ranks& ranks, const ChartOutcome& c) {
  std::cout << (c.plan.map ? "Stability map of " : "Campbell sweep of ") << c.title << "\n  ";
  for (size_t a = 0; a < c.plan.grid.axes.size(); ++a)
    std::cout << (a ? " × " : "") << c.plan.grid.axes[a].name << " = "
              << Num(c.plan.grid.axes[a].start, 8) << " … " << Num(c.plan.grid.values[a].back(), 8)
              << " (" << c.plan.grid.values[a].size() << " points)";
  std::cout << "; " << args.method << " route";
  if (c.plan.sweep.method == SweepMethod::kMonodromy)
    std::cout << " (" << args.integrator << ", tol " << Num(args.tol, 2)
              << (HalfPeriodRoute(c) ? "; time-reversible: half a period per unchecked point" : "")
              << ")";
  std::cout << ", " << c.threads << (c.threads == 1 ? " thread" : " threads");
  if (ranks.size > 1) std::cout << " × " << ranks.size << " MPI ranks";
  std::cout << "\n  " << c.plan.grid.size() << " points in " << Num(c.sweep_s, 3) << " s";
  if (c.resumed) std::cout << " (" << c.resumed << " resumed from the journal)";
  std::cout << ": " << c.count(StabilityVerdict::kStable) << " stable, "
            << c.count(StabilityVerdict::kMarginal) << " marginal, "
            << c.count(StabilityVerdict::kUnstable) << " unstable, "
            << c.count(StabilityVerdict::kFailed) << " failed\n  error estimate: ";
  if (c.analysis.tally.max_error)
    // On a map only a sample is checked, and its largest estimate is no bound for the rest
    // (401 × 401 Mathieu at 1e-10: 2.8e-9 over the sample, 2.3e-8 the worst unchecked error).
    std::cout << "max " << Num(*c.analysis.tally.max_error, 2) << " 1/s over "
              << c.analysis.tally.checked << " checked points (tighter rerun"
              << (c.analysis.tally.checked < c.plan.grid.size()
                      ? "; a sample: an unchecked point's error can exceed it"
                      : "")
              << ")\n";
  else
    std::cout << "not computed (--check-every 0)\n";
  if (!c.plan.map) {
    std::cout << "  mode tracking by MAC: smallest accepted MAC "
              << Num(c.analysis.tracking.min_mac, 3);
    if (!c.analysis.tracking.ambiguous.empty())
      std::cout << ", ambiguous at " << c.analysis.tracking.ambiguous.size() << " points";
    std::cout << "\n";
    PrintCampbell(std::cout, c.analysis.campbell, c.plan.grid.axes[0].name);
    std::cout << "\n";
    if (c.analysis.intervals.empty()) {
      std::cout << "  no unstable interval in the sweep\n";
    } else {
      std::cout << "  unstable intervals of " << c.plan.grid.axes[0].name
                << " (boundaries refined to " << Num(args.refine_tol, 2) << " relative; "
                << Num(c.analysis.refine_s, 3) << " s):\n"
                << "              from                 to      max Re λ inside [1/s]\n";
      for (const auto& in : c.analysis.intervals) {
        double peak = -INFINITY;
        for (const SweepPoint& p : c.points)
          if (p.ok && p.values[0] >= in.lo.value && p.values[0] <= in.hi.value)
            peak = std::max(peak, p.max_real_exponent);
        auto end = [](const BoundaryEstimate& e) {
          std::ostringstream s;
          s << Num(e.value, 12, 18) << (e.refined ? " " : (e.at_sweep_edge ? "<" : "?"));
          return s.str();
        };
        std::cout << "    " << end(in.lo) << " " << end(in.hi) << Num(peak, 4, 14) << "\n";
        for (const auto* e : {&in.lo, &in.hi})
          if (!e->refined && !e->note.empty()) std::cout << "        note: " << e->note << "\n";
      }
      std::cout << "    (< : the instability continues beyond the sweep; ? : not refined)\n";
    }
  } else {
    size_t refined = 0;
    for (const auto& b : c.analysis.boundary) refined += b.estimate.refined;
    std::cout << "  boundary points: " << refined << " refined of " << c.analysis.boundary.size()
              << " grid crossings along "
              << (args.refine_lines ? std::to_string(args.refine_lines) : "all")
              << " lines per axis (" << Num(c.analysis.refine_s, 3) << " s)\n";
    PrintCurves(c);
  }
  const int failed = static_cast<int>(c.count(StabilityVerdict::kFailed));
  if (failed) {
    std::cout << "  failed points (first 5):\n";
    int shown = 0;
    for (const SweepPoint& p : c.points)
      if (!p.ok && shown++ < 5) {
        std::cout << "    ";
        for (size_t a = 0; a < p.values.size(); ++a)
          std::cout << (a ? ", " : "") << c.plan.grid.axes[a].name << " = " << Num(p.values[a], 8);
        std::cout << ": " << p.failure << "\n";
      }
  }
  if (!args.csv.empty())
    std::cout << "  wrote " << args.csv
              << (c.plan.map
                      ? (c.analysis.curves.curves.empty() ? "" : " and " + CurvesCsvPath(args.csv))
                      : " and " + CrossingsCsvPath(args.csv))
              << "\n";
  if (!args.plot.empty())
    std::cout << (c.plot_note.empty() ? "  wrote " + args.plot : "  " + c.plot_note) << "\n";
}

int RunChart(ChartArgs& args) {
  const Ranks ranks = StartRanks();
  struct StopAtExit {
    ~StopAtExit() { StopRanks(); }
  } stop_at_exit;
  const bool root = ranks.rank == 0;
  try {
    if (!args.plot.empty()) GnuplotTerminal(args.plot, 1, 1);  // a bad extension fails first
    if (args.sidebands < 0 || args.sidebands > 8) throw InputError("--sidebands must be in 0..8");
    if (!(args.refine_tol > 0 && args.refine_tol < 1e-2))
      throw InputError("--refine-tol must be in (0, 0.01)");
    ChartOutcome c(LoadSceneArgs(args.scene));
    std::vector<SweepAxis> axes = {SweepAxis::Parse(args.sweep)};
    if (!args.sweep2.empty()) axes.push_back(SweepAxis::Parse(args.sweep2));
    c.plan = PlanChart(c.scene.scene, c.scene.system, std::move(axes), MakeOptions(args));
    args.integrator = ToString(c.plan.sweep.floquet.integrator.type);
    PlotXAxis(args, c.plan.grid);  // a bad --plot-x fails before the sweep
    c.threads = ThreadsFor(c.plan.sweep.threads);

    json identity = {{"scene", c.scene.scene.name},
                     {"source", c.scene.scene.source},
                     {"parameters", ParametersJson(c.scene.parameters)},
                     {"method", args.method},
                     {"integrator", args.integrator},
                     {"tol", args.tol},
                     {"check_every", c.plan.sweep.check_every},
                     {"compare", c.plan.sweep.snapshot}};
    for (const auto& a : c.plan.grid.axes)
      identity["sweep"].push_back({a.name, a.start, a.stop, a.step});
    std::unique_ptr<ChartRecord> record;
    if (root)
      record = std::make_unique<ChartRecord>(args.csv, c.plan.grid, c.scene.system.states(),
                                             identity, args.resume);
    if (!SweepAllPoints(args, ranks, record.get(), c)) return 130;
    if (!root) return 0;

    Analyse(args, c);
    if (!c.plan.map && !args.csv.empty())
      WriteCrossingsCsv(CrossingsCsvPath(args.csv), c.analysis.campbell, c.plan.grid.axes[0].name);
    if (c.plan.map && !args.csv.empty() && !c.analysis.curves.curves.empty())
      WriteCurvesCsv(CurvesCsvPath(args.csv), c.analysis.curves, c.plan.grid);
    record->Finish(c.points, c.plan.map ? nullptr : &c.analysis.campbell);
    if (!args.plot.empty()) c.plot_note = Plot(args, c);
    const bool all_failed = c.count(StabilityVerdict::kFailed) == c.plan.grid.size();
    if (args.json) {
      std::cout << ChartJson(args, ranks, c).dump(2) << "\n";
    } else {
      PrintChart(args, ranks, c);
    }
    return all_failed ? 1 : 0;
  } catch (const std::exception& e) {
    if (ranks.size > 1) {
      std::string message = e.what();
      for (char& ch : message)
        if (ch == '\n') ch = ' ';
      std::cerr << "ltp: error (rank " << ranks.rank << "): " << message << "\n";
      AbortRanks(2);
    }
    throw;
  }
}

}  // namespace

Command AddChartCommand(CLI::App& app) {
  static ChartArgs args;
  args = ChartArgs{};  // fresh state for each RunLtp call (the argument fuzzer makes many)
  auto* cmd = app.add_subcommand(
      "chart", "Campbell/damping diagrams (one --sweep) or stability maps (--sweep and --sweep2)");
  AddSceneArgs(cmd, args.scene);
  cmd->add_option("--sweep", args.sweep, "NAME=START:STOP:STEP, e.g. Omega=0.3:1.8:0.005")
      ->required();
  cmd->add_option("--sweep2", args.sweep2, "second parameter for a stability map, e.g. q=0:8:0.02");
  cmd->add_option("--method", args.method, "monodromy | hill")->capture_default_str();
  cmd->add_option(
      "--integrator", args.integrator,
      "monodromy integrator (see `ltp floquet --help`); default for maps taylor when A(t) is a "
      "Fourier series of <= 2 states, else bs; rkf78 for 1-D");
  cmd->add_option("--tol", args.tol, "integrator relative tolerance (hill: truncation tolerance)")
      ->capture_default_str();
  cmd->add_option("--threads", args.threads, "threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--csv", args.csv, "one row per point, written as points complete");
  cmd->add_flag("--resume", args.resume, "finish the interrupted sweep of --csv FILE");
  cmd->add_option("--plot", args.plot,
                  "Campbell + damping diagram or stability map (FILE.svg|.png|.pdf)");
  cmd->add_option("--plot-x", args.plot_x,
                  "maps: the swept parameter drawn horizontally (default: --sweep's)");
  cmd->add_flag("--no-curves", args.no_curves,
                "maps: do not trace the boundaries as curves (refined points only)");
  cmd->add_flag("--json", args.json, "one JSON summary on stdout");
  cmd->add_flag("--compare", args.compare,
                "also snapshot A(0) and averaged-system frequencies (1-D)");
  cmd->add_option_function<int>(
      "--check-every", [](int k) { args.check_every = k; },
      "error estimate on every K-th point (default: all for 1-D, every 97th for maps; 0 = none)");
  cmd->add_flag("--no-refine", args.no_refine, "do not refine boundaries beyond the grid");
  cmd->add_option("--refine-tol", args.refine_tol, "relative tolerance of refined boundaries")
      ->capture_default_str();
  cmd->add_option("--refine-lines", args.refine_lines,
                  "maps: grid lines per axis along which "
                  "boundaries are refined (0 = all)")
      ->capture_default_str();
  cmd->add_option("--sidebands", args.sidebands, "Campbell: faint families f ± kΩp/2π, k = 1..K")
      ->capture_default_str();
  AddCampbellArgs(cmd, args.campbell);
  cmd->add_option("--stop-after", args.stop_after, "testing: stop after N points as if interrupted")
      ->group("");  // hidden
  return {cmd, [] { return RunChart(args); }};
}

}  // namespace ltp::cli
