#include "ltp/studies/lin_campbell.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <tuple>

#include "ltp/core/error.h"

namespace ltp {

namespace {

constexpr double kPi = std::numbers::pi;

std::string Name(const LinOperatingPoint& op) {
  return op.files.empty() ? std::string("?") : op.files.front();
}

LinCampbellPoint AnalysePoint(const LinOperatingPoint& op, const LinCampbellOptions& options) {
  LinCampbellPoint p;
  p.files = op.files;
  p.rotor_speed = op.rotor_speed;
  p.wind_speed = op.wind_speed;
  p.collective_pitch = op.collective_pitch;
  if (options.axis == OperatingPointAxis::kRotorSpeed) {
    p.parameter = op.rotor_speed * 30 / kPi;
  } else {
    if (!op.wind_speed)
      throw InputError(Name(op) + ": no wind speed in the header; order the points by rotor speed");
    p.parameter = *op.wind_speed;
  }
  p.mbc = Mbc3(op, options.mbc);
  if (!p.mbc.applicable) throw InputError(Name(op) + ": MBC3 does not apply: " + p.mbc.reason);
  if (op.size() < 3 && p.mbc.blades >= 3)
    p.diagnostics.push_back(
        {DiagnosticCode::kTooFewAzimuths, Severity::kWarning,
         std::to_string(op.size()) + " azimuth" + (op.size() == 1 ? "" : "s") +
             ": too few to average the periodic part (OpenFAST recommends 36 for MBC3)"});
  if (p.mbc.rigid_body_modes)
    p.diagnostics.push_back({DiagnosticCode::kRigidBodyMode, Severity::kNote,
                             std::to_string(p.mbc.rigid_body_modes) + " rigid-body mode" +
                                 (p.mbc.rigid_body_modes == 1 ? "" : "s") +
                                 " (the rotor's free rotation) left out"});
  p.diagnostics.insert(p.diagnostics.end(), op.diagnostics.begin(), op.diagnostics.end());
  p.diagnostics.insert(p.diagnostics.end(), p.mbc.diagnostics.begin(), p.mbc.diagnostics.end());
  return p;
}

// Whether a state belongs to one of `modules`: its module ("ED", "BD_1", "AD") starts with one
// of them.
bool InModules(const LinChannel& state, const std::vector<std::string>& modules) {
  const std::string module = ModuleOf(state);
  return std::any_of(modules.begin(), modules.end(),
                     [&](const std::string& m) { return module.starts_with(m); });
}

// The share of a mode carried by the states of `modules`: |Σ p_i| over those states (the
// participations sum to 1); without left eigenvectors, the sum of its dominant shares there.
double ModuleShare(const MbcMode& m, const std::vector<LinChannel>& states,
                   const std::vector<std::string>& modules) {
  if (m.participation.size() == static_cast<Eigen::Index>(states.size())) {
    std::complex<double> sum = 0;
    for (size_t i = 0; i < states.size(); ++i)
      if (InModules(states[i], modules)) sum += m.participation(static_cast<Eigen::Index>(i));
    return std::abs(sum);
  }
  double share = 0;
  for (const MbcMode::Share& s : m.dominant)
    if (InModules(states[static_cast<size_t>(s.state)], modules)) share += s.share;
  return share;
}

// The MBC3 modes of a point as a sweep point (rigid-body modes and those of excluded modules
// left out, the latter counted in `excluded`); `index_of[j]` is the MbcMode behind sweep mode j.
SweepPoint AsSweepPoint(const LinCampbellPoint& p, size_t index,
                        const std::vector<std::string>& exclude_modules, std::vector<int>& index_of,
                        long& excluded) {
  SweepPoint s;
  s.index = index;
  s.values = {p.parameter};
  s.ok = true;
  s.period = 0;  // time-invariant (averaged) system: frequencies are not modulo Ω
  s.rotor_speed = p.rotor_speed;
  std::vector<int> kept;
  for (size_t k = 0; k < p.mbc.modes.size(); ++k) {
    if (p.mbc.modes[k].rigid_body) continue;
    if (!exclude_modules.empty() &&
        ModuleShare(p.mbc.modes[k], p.mbc.states, exclude_modules) > 0.5) {
      ++excluded;
      continue;
    }
    kept.push_back(static_cast<int>(k));
  }
  const Eigen::Index n =
      kept.empty() ? 0 : p.mbc.modes[static_cast<size_t>(kept[0])].eigenvector.size();
  s.shapes.resize(n, static_cast<Eigen::Index>(kept.size()));
  for (size_t j = 0; j < kept.size(); ++j) {
    const MbcMode& m = p.mbc.modes[static_cast<size_t>(kept[j])];
    FloquetMode f;
    f.exponent = m.eigenvalue;
    f.frequency_hz = m.eigenvalue.imag() / (2 * kPi);
    f.damping_ratio = m.damping_ratio;
    s.modes.push_back(f);
    s.shapes.col(static_cast<Eigen::Index>(j)) = m.eigenvector;
  }
  index_of = kept;
  s.max_real_exponent = p.mbc.max_real_part;
  s.max_log_multiplier = p.mbc.max_real_part;  // no period: the sign is what counts
  s.verdict = ClassifyStability(true, p.mbc.max_real_part, 0);
  return s;
}

// Rotor speed unless two points share one; then wind speed when every point has its own.
OperatingPointAxis ResolveAxis(const std::vector<LinOperatingPoint>& points,
                               OperatingPointAxis asked) {
  if (asked != OperatingPointAxis::kAuto) return asked;
  auto distinct = [&](auto value) {
    for (size_t i = 0; i < points.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (!value(points[i]) || !value(points[j]) ||
            std::abs(*value(points[i]) - *value(points[j])) <=
                1e-9 * std::max(std::abs(*value(points[j])), 1.0))
          return false;
    return true;
  };
  const auto rotor = [](const LinOperatingPoint& p) {
    return std::optional<double>(p.rotor_speed);
  };
  const auto wind = [](const LinOperatingPoint& p) { return p.wind_speed; };
  if (!distinct(rotor) && distinct(wind)) return OperatingPointAxis::kWindSpeed;
  return OperatingPointAxis::kRotorSpeed;
}

std::string SameAbscissaMessage(const LinCampbellPoint& a, const LinCampbellPoint& b,
                                const std::string& axis_label, OperatingPointAxis axis) {
  std::string m = a.files.front() + " and " + b.files.front() + " are at the same " + axis_label +
                  " " + MessageNumber(a.parameter) + ": one set of files per operating point";
  if (axis == OperatingPointAxis::kRotorSpeed && a.wind_speed && b.wind_speed &&
      *a.wind_speed != *b.wind_speed)
    m += " (their wind speeds differ: order them by wind speed, --by wind-speed)";
  return m;
}

}  // namespace

std::optional<OperatingPointAxis> ParseOperatingPointAxis(std::string_view name) {
  if (name == "auto") return OperatingPointAxis::kAuto;
  if (name == "rotor-speed") return OperatingPointAxis::kRotorSpeed;
  if (name == "wind-speed") return OperatingPointAxis::kWindSpeed;
  return std::nullopt;
}

void LinCampbellOptions::Validate() const {
  campbell.Validate();
  const OptionCheck check("LinCampbellOptions");
  for (const std::string& m : exclude_modules)
    if (m.empty() || m.find_first_of(" \t,") != std::string::npos)
      check.Fail("exclude_modules", std::string_view(m),
                 "module names such as AD or BD: one word each");
}

LinCampbellResult MakeLinCampbell(const std::vector<LinOperatingPoint>& points,
                                  const LinCampbellOptions& options) {
  options.Validate();
  if (points.empty()) throw InputError("a Campbell diagram needs at least one operating point");
  LinCampbellResult r;
  r.axis = ResolveAxis(points, options.axis);
  r.axis_label =
      r.axis == OperatingPointAxis::kRotorSpeed ? "rotor speed [rpm]" : "wind speed [m/s]";
  LinCampbellOptions resolved = options;
  resolved.axis = r.axis;
  for (const LinOperatingPoint& op : points) try {
      r.points.push_back(AnalysePoint(op, resolved));
    } catch (const InputError& e) {
      if (!options.keep_going) throw;
      r.skipped.push_back(e.what());
    }
  if (r.points.empty())
    throw InputError("no operating point could be analysed: " + r.skipped.front());
  std::stable_sort(r.points.begin(), r.points.end(),
                   [](const auto& a, const auto& b) { return a.parameter < b.parameter; });
  for (size_t i = 1; i < r.points.size(); ++i)
    if (r.points[i].parameter == r.points[i - 1].parameter)
      throw InputError(SameAbscissaMessage(r.points[i], r.points[i - 1], r.axis_label, r.axis));
  auto same_states = [](const std::vector<LinChannel>& a, const std::vector<LinChannel>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const auto& x, const auto& y) { return x.description == y.description; });
  };
  // The model most points share is the diagram's (the first point's when none is left out).
  size_t model = 0, shared = 0;
  for (size_t i = 0; i < r.points.size() && options.keep_going; ++i) {
    const auto n =
        static_cast<size_t>(std::count_if(r.points.begin(), r.points.end(), [&](const auto& p) {
          return same_states(p.mbc.states, r.points[i].mbc.states);
        }));
    if (n > shared) std::tie(model, shared) = std::make_pair(i, n);
  }
  const std::vector<LinChannel> reference_states = r.points[model].mbc.states;
  const std::string reference_file = r.points[model].files.front();
  std::erase_if(r.points, [&](const LinCampbellPoint& p) {
    if (same_states(p.mbc.states, reference_states)) return false;
    const std::string why = p.files.front() + " has other states than " + reference_file +
                            ": modes can only be tracked across operating points of one model";
    if (!options.keep_going) throw InputError(why);
    r.skipped.push_back(why);
    return true;
  });
  const auto& reference = r.points.front();
  std::vector<std::vector<int>> index_of(r.points.size());
  long excluded = 0;
  for (size_t i = 0; i < r.points.size(); ++i)
    r.sweep.push_back(AsSweepPoint(r.points[i], i, options.exclude_modules, index_of[i], excluded));
  r.tracking = TrackModes(r.sweep);
  SystemLabels labels;
  for (const LinChannel& c : reference.mbc.states) labels.states.push_back(c.description);
  labels.blades = reference.mbc.blades;
  // MBC3 names its modes better than shares of single states can: its descriptions sum the
  // cosine/sine pair of a cyclic family and name the whirl.
  const CampbellModeNamer by_mbc = [&](size_t p, int mode) {
    return r.points[p]
        .mbc.modes[static_cast<size_t>(index_of[p][static_cast<size_t>(mode)])]
        .description;
  };
  r.diagram = MakeCampbellDiagram(r.sweep, r.tracking, labels, options.campbell, by_mbc);
  if (!options.exclude_modules.empty()) {
    std::string names;
    for (const std::string& m : options.exclude_modules) names += (names.empty() ? "" : ", ") + m;
    r.diagram.diagnostics.push_back(
        {DiagnosticCode::kModulesLeftOut, Severity::kNote,
         std::to_string(excluded) + " mode" + (excluded == 1 ? "" : "s") + " over " +
             std::to_string(r.points.size()) + " points left out: carried mostly by " + names +
             " states"});
  }
  return r;
}

LinCampbellResult ComputeLinCampbell(const std::vector<std::string>& arguments,
                                     const LinCampbellOptions& options) {
  options.Validate();
  std::vector<std::string> unreadable;
  const std::vector<LinOperatingPoint> points =
      ReadLinOperatingPoints(arguments, options.keep_going ? &unreadable : nullptr);
  LinCampbellResult r = MakeLinCampbell(points, options);
  r.skipped.insert(r.skipped.begin(), unreadable.begin(), unreadable.end());
  return r;
}

}  // namespace ltp
