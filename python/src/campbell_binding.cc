// ltp.campbell: the Campbell diagram of OpenFAST operating points (`ltp campbell`,
// studies/lin_campbell.h) for a notebook: MBC3 at each point, modes tracked across them.
#include <numbers>
#include <string>
#include <vector>

#include "binding.h"
#include "diagnostic_properties.h"
#include "ltp/core/error.h"
#include "ltp/openfast/linearization.h"
#include "ltp/studies/lin_campbell.h"

namespace ltp::python {

namespace {

void BindCampbellResult(py::module_& m) {
  py::class_<LinCampbellResult> r(
      m, "CampbellResult",
      "A Campbell diagram of OpenFAST operating points (ltp campbell as an object): the MBC3 "
      "modes of each point, tracked across the points into lines.");
  r.def_readonly("axis_label", &LinCampbellResult::axis_label,
                 "'rotor speed [rpm]' or 'wind speed [m/s]'")
      .def_readonly("skipped", &LinCampbellResult::skipped,
                    "operating points left out by keep_going: 'files: reason', one each")
      .def_property_readonly(
          "parameter", [](const LinCampbellResult& x) { return RealArray(x.diagram.parameter); },
          "the abscissa per point (rpm or m/s), ascending")
      .def_property_readonly(
          "rotor_speeds",
          [](const LinCampbellResult& x) {
            std::vector<double> v;
            for (const LinCampbellPoint& p : x.points) v.push_back(p.rotor_speed);
            return RealArray(v);
          },
          "rotor speed per point (rad/s)")
      .def_property_readonly(
          "wind_speeds",
          [](const LinCampbellResult& x) {
            std::vector<double> v;
            for (const LinCampbellPoint& p : x.points)
              v.push_back(p.wind_speed.value_or(std::numeric_limits<double>::quiet_NaN()));
            return RealArray(v);
          },
          "wind speed per point (m/s; NaN where the files do not give it)")
      .def_property_readonly(
          "pitches",
          [](const LinCampbellResult& x) {
            std::vector<double> v;
            for (const LinCampbellPoint& p : x.points)
              v.push_back(p.collective_pitch ? *p.collective_pitch * 180 / std::numbers::pi
                                             : std::numeric_limits<double>::quiet_NaN());
            return RealArray(v);
          },
          "collective blade pitch per point (deg; NaN where the files have no pitch input)")
      .def_property_readonly(
          "points",
          [](const LinCampbellResult& x) {
            std::vector<Mbc3Result> v;
            for (const LinCampbellPoint& p : x.points) v.push_back(p.mbc);
            return v;
          },
          "the MBC3 analysis of each point (ltp.MbcResult), in the order of parameter")
      .def_property_readonly(
          "files",
          [](const LinCampbellResult& x) {
            std::vector<std::vector<std::string>> v;
            for (const LinCampbellPoint& p : x.points) v.push_back(p.files);
            return v;
          },
          "the .lin files of each point, sorted by azimuth")
      .def_property_readonly(
          "lines", [](const LinCampbellResult& x) { return CampbellLines(x.diagram); },
          "one line per tracked mode: description, per-point frequency_hz (natural or damped, "
          "as .frequency says), real_part, "
          "damping_ratio (NaN where not tracked), lost_after (point index or -1)")
      .def_property_readonly(
          "frequency",
          [](const LinCampbellResult& x) { return std::string(ToString(x.diagram.frequency)); },
          "'natural' (|λ|/2π) or 'damped' (Im λ/2π): what the lines' frequency_hz hold")
      .def_property_readonly(
          "crossings", [](const LinCampbellResult& x) { return CampbellCrossings(x.diagram); },
          "where each line crosses a per-rev line n·Ω/2π (mode numbered as in lines, from 1)")
      .def_property_readonly(
          "per_rev",
          [](const LinCampbellResult& x) {
            const std::vector<std::int64_t> n(x.diagram.per_rev.begin(), x.diagram.per_rev.end());
            return py::array_t<std::int64_t>(static_cast<py::ssize_t>(n.size()), n.data());
          },
          "n of the per-rev lines drawn")
      .def_property_readonly(
          "weakly_damped", [](const LinCampbellResult& x) { return WeaklyDamped(x.diagram); },
          "(lo, hi) intervals of the abscissa where some mode's damping ratio is low")
      .def_property_readonly(
          "notes",
          [](const LinCampbellResult& x) {
            std::vector<std::string> v = Texts(x.diagram.diagnostics);
            for (const LinCampbellPoint& p : x.points)
              for (const Diagnostic& d : p.diagnostics) v.push_back(d.text);
            return v;
          },
          "what the diagram and each point noticed, one line each")
      .def_property_readonly(
          "note_codes",
          [](const LinCampbellResult& x) {
            std::vector<std::string> v = CodeNames(x.diagram.diagnostics);
            for (const LinCampbellPoint& p : x.points)
              for (const std::string& c : CodeNames(p.diagnostics)) v.push_back(c);
            return v;
          },
          "the notes' codes (snake_case, one per note), for code that branches on them")
      .def("__repr__", [](const LinCampbellResult& x) {
        return "<ltp.CampbellResult: " + std::to_string(x.points.size()) + " points, " +
               std::to_string(x.diagram.lines.size()) + " lines over " + x.axis_label + ">";
      });
}

// ltp.campbell: the options checked in the CLI's words; the diagram computed without the GIL.
LinCampbellResult LtpCampbell(const std::vector<std::string>& points, const std::string& by,
                              const std::string& frequency, Real max_damping, Real max_frequency,
                              const std::vector<std::string>& exclude_modules, bool keep_going) {
  LinCampbellOptions o;
  const auto kind = ParseCampbellFrequency(frequency);
  if (!kind) throw InputError("frequency must be 'damped' or 'natural', got '" + frequency + "'");
  o.campbell.frequency = *kind;
  o.campbell.max_damping_ratio = max_damping;
  o.campbell.max_frequency_hz = max_frequency;
  o.exclude_modules = exclude_modules;
  const auto axis = ParseOperatingPointAxis(by);
  if (!axis) throw InputError("by must be 'auto', 'rotor-speed' or 'wind-speed', got '" + by + "'");
  o.axis = *axis;
  o.keep_going = keep_going;
  o.Validate();
  py::gil_scoped_release release;
  return ComputeLinCampbell(points, o);
}

void BindCampbellFunction(py::module_& m) {
  m.def("campbell", &LtpCampbell, py::arg("points"), py::kw_only(), py::arg("by") = "auto",
        py::arg("frequency") = "natural", py::arg("max_damping") = 1.0,
        py::arg("max_frequency") = 0.0, py::arg("exclude_modules") = std::vector<std::string>{},
        py::arg("keep_going") = false, R"doc(
The Campbell diagram of OpenFAST operating points: `ltp campbell POINT... --json` as a
function. `points` are folders, .lin files or globs; OpenFAST's <root>.<k>.lin files are
grouped by root, so one flat output folder of several simulations gives one point each. Each
point is analysed by MBC3 (as ltp.mbc) and the modes are tracked across the points by their
shapes.

  by           'auto' (rotor speed unless two points share one, then wind speed) |
               'rotor-speed' (abscissa in rpm) | 'wind-speed' (m/s, from the files' headers)
  keep_going   leave out a point that cannot be read or analysed (reasons in .skipped)
  frequency    'natural' (|λ|/2π, as ACDC and openfast_toolbox draw; the default) |
               'damped' (Im λ/2π)
  max_damping  leave out lines damped above this ratio wherever tracked (1: keep all)
  max_frequency  leave out lines above this many Hz wherever tracked (0: keep all)
  exclude_modules  leave out modes carried mostly by these modules' states, e.g. ["AD"]

    c = ltp.campbell(sorted(glob.glob("runs/omega-*")))
    for line in c.lines: plt.plot(c.parameter, line["frequency_hz"], label=line["description"]))doc");
}

}  // namespace

void BindCampbell(py::module_& m) {
  BindCampbellResult(m);
  BindCampbellFunction(m);
}

}  // namespace ltp::python
