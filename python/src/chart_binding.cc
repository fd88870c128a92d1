// ltp.chart: Campbell and damping diagrams over one scene parameter, stability maps over two,
// with the stability boundaries refined beyond the grid (what `ltp chart` computes, in memory:
// no journal, no plot).
#include <cmath>
#include <map>

#include "binding.h"
#include "ltp/core/error.h"
#include "ltp/integrate/threads.h"
#include "ltp/studies/boundary_curves.h"
#include "ltp/studies/campbell.h"
#include "ltp/studies/chart.h"
#include "ltp/studies/chart_options.h"
#include "ltp/studies/mode_tracking.h"
#include "ltp/studies/stability_boundary.h"
#include "ltp/studies/sweep.h"

namespace ltp::python {

namespace {

// The library's chart and what the binding adds: where it came from, the threads it ran on.
struct ChartResult {
  std::string scene;
  ParameterMap parameters;
  int states = 0;
  int threads = 0;
  ltp::Chart chart;
};

SweepAxis AxisFrom(const py::object& spec) {
  if (py::isinstance<py::str>(spec)) return SweepAxis::Parse(spec.cast<std::string>());
  if (py::isinstance<py::sequence>(spec) && py::len(spec) == 4) {
    const auto s = spec.cast<py::sequence>();
    try {
      return {s[0].cast<std::string>(), s[1].cast<double>(), s[2].cast<double>(),
              s[3].cast<double>()};
    } catch (const py::cast_error&) {
    }
  }
  throw InputError("a sweep is 'NAME=START:STOP:STEP' or (name, start, stop, step), got " +
                   py::repr(spec).cast<std::string>());
}

py::dict BoundaryDict(const BoundaryEstimate& e) {
  return py::dict(py::arg("value") = e.value, py::arg("refined") = e.refined,
                  py::arg("bracket") = e.bracket, py::arg("at_sweep_edge") = e.at_sweep_edge,
                  py::arg("evaluations") = e.evaluations, py::arg("note") = e.note);
}

// A numpy array of str (dtype '<U…') from strings.
py::array StringArray(const std::vector<std::string>& v) {
  return py::array(py::cast(v)).attr("astype")("str");
}

py::array_t<long> IntArray(const std::vector<long>& v) {
  py::array_t<long> a(static_cast<py::ssize_t>(v.size()));
  for (size_t i = 0; i < v.size(); ++i) a.mutable_at(static_cast<py::ssize_t>(i)) = v[i];
  return a;
}

template <class Field>
auto PointArray(Field field) {
  return [field](const ChartResult& c) {
    py::array_t<double> a(static_cast<py::ssize_t>(c.chart.points.size()));
    for (size_t i = 0; i < c.chart.points.size(); ++i)
      a.mutable_at(static_cast<py::ssize_t>(i)) = field(c.chart.points[i]);
    return a;
  };
}

ChartResult ChartOfScene(const System& system, std::vector<SweepAxis> axes,
                         const ChartOptions& options) {
  if (!system.scene)
    throw InputError("chart sweeps a scene's parameters: give a system made by ltp.scene(...)");
  const Scene& scene = *system.scene;
  ChartResult r;
  r.scene = scene.name;
  r.parameters = system.parameters;
  r.states = system.system.states();
  r.chart = ComputeChart(scene, system.parameters, system.system, std::move(axes), options);
  r.threads = ThreadsFor(r.chart.plan.sweep.threads);
  return r;
}

}  // namespace

py::list CampbellLines(const CampbellDiagram& d) {
  py::list out;
  for (const CampbellLine& line : d.lines)
    out.append(py::dict(
        py::arg("description") = line.description,
        py::arg("description_end") = line.description_end,
        py::arg("frequency_hz") = RealArray(line.frequency_hz),
        py::arg("real_part") = RealArray(line.real_part),
        py::arg("damping_ratio") = RealArray(line.damping_ratio),
        py::arg("lost_after") = line.lost_after ? static_cast<long>(*line.lost_after) : -1L));
  return out;
}

py::list CampbellCrossings(const CampbellDiagram& d) {
  py::list out;
  for (const CampbellCrossing& x : d.crossings)
    out.append(
        py::dict(py::arg("mode") = x.line + 1, py::arg("description") = d.lines[x.line].description,
                 py::arg("per_rev") = x.per_rev, py::arg("parameter") = x.parameter,
                 py::arg("parameter_error") = x.parameter_error,
                 py::arg("rotor_speed") = x.rotor_speed, py::arg("frequency_hz") = x.frequency_hz,
                 py::arg("real_part") = x.real_part, py::arg("damping_ratio") = x.damping_ratio));
  return out;
}

py::array_t<double> WeaklyDamped(const CampbellDiagram& d) {
  std::vector<std::vector<double>> v;
  for (const auto& [lo, hi] : d.weakly_damped) v.push_back({lo, hi});
  return RealTable(v, 2);
}

namespace {

// The grid, the method and the threads the chart ran with.
void BindChartPlan(py::class_<ChartResult>& r) {
  r.def_readonly("scene", &ChartResult::scene, "the scene's name")
      .def_readonly("parameters", &ChartResult::parameters,
                    "the scene's parameters besides the swept ones")
      .def_property_readonly(
          "method",
          [](const ChartResult& c) { return std::string(ToString(c.chart.plan.chart.method)); },
          "'monodromy' or 'hill'")
      .def_property_readonly(
          "integrator",
          [](const ChartResult& c) {
            return std::string(ToString(c.chart.plan.sweep.floquet.integrator.type));
          },
          "the monodromy integrator used")
      .def_property_readonly(
          "tol", [](const ChartResult& c) { return c.chart.plan.chart.tol; }, "the tolerance used")
      .def_readonly("threads", &ChartResult::threads, "threads used over points")
      .def_property_readonly(
          "check_every", [](const ChartResult& c) { return c.chart.plan.sweep.check_every; },
          "error estimate on every k-th point")
      .def_property_readonly(
          "axes",
          [](const ChartResult& c) {
            std::vector<std::string> names;
            for (const auto& a : c.chart.plan.grid.axes) names.push_back(a.name);
            return StringArray(names);
          },
          "the swept parameters' names (numpy array of str)")
      .def_property_readonly(
          "values",
          [](const ChartResult& c) {
            py::list out;
            for (const auto& v : c.chart.plan.grid.values) out.append(RealArray(v));
            return out;
          },
          "the grid values of each axis");
}

// Per point: where it lies, its verdict and its largest exponent.
void BindChartPoints(py::class_<ChartResult>& r) {
  r.def_property_readonly(
       "point_values",
       [](const ChartResult& c) {
         std::vector<std::vector<double>> v;
         for (const SweepPoint& p : c.chart.points) v.push_back(p.values);
         return RealTable(v, c.chart.plan.grid.axes.size());
       },
       "parameter values of every point, shape (points, axes)")
      .def_property_readonly(
          "ok",
          [](const ChartResult& c) {
            py::array_t<bool> a(static_cast<py::ssize_t>(c.chart.points.size()));
            for (size_t i = 0; i < c.chart.points.size(); ++i)
              a.mutable_at(static_cast<py::ssize_t>(i)) = c.chart.points[i].ok;
            return a;
          },
          "per point: the analysis succeeded")
      .def_property_readonly(
          "verdicts",
          [](const ChartResult& c) {
            std::vector<std::string> v;
            for (const SweepPoint& p : c.chart.points) v.emplace_back(ToString(p.verdict));
            return StringArray(v);  // a numpy array of str, like every other column
          },
          "'stable', 'marginal', 'unstable' or 'failed' per point (numpy array of str)")
      .def_property_readonly("periods", PointArray([](const SweepPoint& p) { return p.period; }),
                             "per point: the period T (s)")
      .def_property_readonly("max_real_exponent",
                             PointArray([](const SweepPoint& p) { return p.max_real_exponent; }),
                             "per point: max Re λ (1/s)")
      .def_property_readonly("max_log_multiplier",
                             PointArray([](const SweepPoint& p) { return p.max_log_multiplier; }),
                             "per point: max log|ρ| = T max Re λ")
      .def_property_readonly(
          "error_estimate", PointArray([](const SweepPoint& p) { return OrNaN(p.error_estimate); }),
          "per point (1/s); NaN where the point was not checked");
}

// Per point: every exponent, as computed and by tracked mode; with compare=True the frozen and
// averaged systems' eigenvalues.
void BindChartExponents(py::class_<ChartResult>& r) {
  r.def_property_readonly(
       "exponents",
       [](const ChartResult& c) {
         std::vector<std::vector<Complex>> v;
         for (const SweepPoint& p : c.chart.points) {
           v.emplace_back();
           for (const FloquetMode& mode : p.modes) v.back().push_back(mode.exponent);
         }
         return ComplexTable(v, static_cast<size_t>(c.states));
       },
       "exponents of every point in its own display order, shape (points, n); NaN where failed")
      .def_property_readonly(
          "tracked_exponents",
          [](const ChartResult& c) {
            std::vector<std::vector<Complex>> v;
            for (size_t i = 0; i < c.chart.points.size(); ++i) {
              v.emplace_back();
              if (i >= c.chart.analysis.tracking.labels.size()) continue;
              for (int index : c.chart.analysis.tracking.labels[i])
                v.back().push_back(
                    index >= 0 ? c.chart.points[i].modes[static_cast<size_t>(index)].exponent
                               : Complex(NAN, NAN));
            }
            return ComplexTable(v, static_cast<size_t>(c.states));
          },
          "1-D: exponents by tracked label ([:, k] is one Campbell line), shape (points, n)")
      .def_property_readonly(
          "tracked_frequencies_hz",
          [](const ChartResult& c) {
            return RealTable(c.chart.analysis.tracking.frequency_hz, static_cast<size_t>(c.states));
          },
          "1-D: tracked frequencies, unwrapped along each line (Hz), shape (points, n)")
      .def_property_readonly(
          "snapshot_eigenvalues",
          [](const ChartResult& c) {
            std::vector<std::vector<Complex>> v;
            for (const SweepPoint& p : c.chart.points) v.push_back(p.snapshot_eigenvalues);
            return ComplexTable(v, static_cast<size_t>(c.states));
          },
          "compare=True: eigenvalues of the frozen A(0) per point")
      .def_property_readonly(
          "averaged_eigenvalues",
          [](const ChartResult& c) {
            std::vector<std::vector<Complex>> v;
            for (const SweepPoint& p : c.chart.points) v.push_back(p.averaged_eigenvalues);
            return ComplexTable(v, static_cast<size_t>(c.states));
          },
          "compare=True: eigenvalues of the averaged A_0 per point");
}

// The points per verdict, how many were checked, and why the failed ones failed.
void BindChartTally(py::class_<ChartResult>& r) {
  r.def_property_readonly(
       "counts",
       [](const ChartResult& c) {
         std::map<std::string, size_t> counts;
         for (const auto& [verdict, n] : c.chart.analysis.tally.counts)
           counts[std::string(ToString(verdict))] = n;
         return counts;
       },
       "points per verdict")
      .def_property_readonly(
          "checked_points", [](const ChartResult& c) { return c.chart.analysis.tally.checked; },
          "points with an error estimate")
      .def_property_readonly(
          "max_error_estimate",
          [](const ChartResult& c) { return c.chart.analysis.tally.max_error; },
          "over the checked points (1/s); None when none was checked")
      .def_property_readonly(
          "failures",
          [](const ChartResult& c) {
            py::list out;
            for (const SweepPoint& p : c.chart.points)
              if (!p.ok)
                out.append(py::dict(py::arg("values") = p.values, py::arg("reason") = p.failure));
            return out;
          },
          "the failed points: values and reason");
}

// The stability boundaries refined beyond the grid: intervals (1-D) or points (maps).
void BindChartBoundaries(py::class_<ChartResult>& r) {
  r.def_property_readonly(
       "unstable_intervals",
       [](const ChartResult& c) {
         std::vector<std::vector<double>> v;
         for (const auto& in : c.chart.analysis.intervals) v.push_back({in.lo.value, in.hi.value});
         return RealTable(v, 2);
       },
       "1-D: (lo, hi) of every unstable interval, refined beyond the grid")
      .def_property_readonly(
          "unstable_interval_details",
          [](const ChartResult& c) {
            py::list out;
            for (const auto& in : c.chart.analysis.intervals)
              out.append(py::dict(py::arg("lo") = BoundaryDict(in.lo),
                                  py::arg("hi") = BoundaryDict(in.hi)));
            return out;
          },
          "1-D: per end of each interval: value, refined, bracket, at_sweep_edge, evaluations, "
          "note")
      .def_property_readonly(
          "boundary_points",
          [](const ChartResult& c) {
            std::vector<std::vector<double>> v;
            for (const auto& b : c.chart.analysis.boundary)
              if (b.estimate.refined) v.push_back(b.values);
            return RealTable(v, 2);
          },
          "maps: the refined boundary points, shape (count, 2)")
      .def_property_readonly(
          "boundary_point_details",
          [](const ChartResult& c) {
            py::list out;
            for (const auto& b : c.chart.analysis.boundary)
              out.append(py::dict(py::arg("values") = b.values,
                                  py::arg("refined_parameter") =
                                      c.chart.plan.grid.axes[static_cast<size_t>(b.axis)].name,
                                  py::arg("entering_unstable") = b.entering_unstable,
                                  py::arg("estimate") = BoundaryDict(b.estimate)));
            return out;
          },
          "maps: every grid crossing, refined or not, with its estimate");
}

// Maps: the boundaries traced as curves through the refined points (boundary_curves.h).
void BindChartCurves(py::class_<ChartResult>& r) {
  r.def_property_readonly(
       "boundary_curves",
       [](const ChartResult& c) {
         py::list out;
         for (const BoundaryCurve& curve : c.chart.analysis.curves.curves) {
           std::vector<std::vector<double>> v;
           for (const auto& p : curve.points) v.push_back({p[0], p[1]});
           out.append(RealTable(v, 2));
         }
         return out;
       },
       "maps: every stability boundary traced as a curve, a float64 array of shape (points, 2) "
       "(columns in the order of axes)")
      .def_property_readonly(
          "boundary_curve_kinds",
          [](const ChartResult& c) {
            std::vector<std::string> v;
            for (const BoundaryCurve& curve : c.chart.analysis.curves.curves)
              v.emplace_back(curve.kind == BoundaryKind::kRealPlusOne ? "+1" : "-1");
            return StringArray(v);
          },
          "maps: per curve, the multiplier σ whose crossing it follows: '+1' (a T-periodic "
          "solution on the curve) or '-1' (2T-periodic)")
      .def_property_readonly(
          "boundary_curve_brackets",
          [](const ChartResult& c) {
            py::list out;
            for (const BoundaryCurve& curve : c.chart.analysis.curves.curves)
              out.append(RealArray(curve.bracket));
            return out;
          },
          "maps: per curve, per point: the boundary crosses the line through the point along "
          "boundary_curve_details[k]['across'] within ±bracket")
      .def_property_readonly(
          "boundary_curve_details",
          [](const ChartResult& c) {
            py::list out;
            for (const BoundaryCurve& curve : c.chart.analysis.curves.curves) {
              std::vector<std::string> across;
              py::array_t<bool> merged(static_cast<py::ssize_t>(curve.merged.size()));
              for (size_t i = 0; i < curve.merged.size(); ++i) {
                across.push_back(c.chart.plan.grid.axes[static_cast<size_t>(curve.across[i])].name);
                merged.mutable_at(static_cast<py::ssize_t>(i)) = curve.merged[i] != 0;
              }
              out.append(py::dict(
                  py::arg("kind") = std::string(ToString(curve.kind)),
                  py::arg("symmetry") = std::string(ToString(curve.symmetry)),
                  py::arg("across") = StringArray(across), py::arg("merged") = merged,
                  py::arg("end_notes") = py::make_tuple(curve.end_notes[0], curve.end_notes[1]),
                  py::arg("evaluations") = curve.evaluations));
            }
            return out;
          },
          "maps: per curve: kind; symmetry ('even'/'odd': the periodic solution on the curve of "
          "a time-reversible undamped system, traced as a root of one half-period block; "
          "'none': of det(Phi(T) -/+ I)); per point the parameter the root was solved along "
          "(across) and "
          "whether the tongue's two edges merge there below resolution (merged: the bracket holds "
          "both), why each end stopped, evaluations")
      .def_property_readonly(
          "untraced_boundary_points",
          [](const ChartResult& c) {
            py::list out;
            const auto& t = c.chart.analysis.curves;
            for (size_t k = 0; k < t.untraced.size(); ++k)
              out.append(
                  py::dict(py::arg("values") = c.chart.analysis.boundary[t.untraced[k]].values,
                           py::arg("note") = t.untraced_notes[k]));
            return out;
          },
          "maps: refined boundary points on no curve (a complex pair crossing), with why")
      .def_property_readonly(
          "curves_s", [](const ChartResult& c) { return c.chart.analysis.curves_s; },
          "wall time of tracing the boundary curves (s)")
      .def_property_readonly(
          "curve_evaluations",
          [](const ChartResult& c) { return c.chart.analysis.curves.evaluations; },
          "analyses the curves took");
}

// 1-D: the modes tracked along the sweep, as a Campbell diagram.
void BindChartCampbell(py::class_<ChartResult>& r) {
  r.def_property_readonly(
       "mode_tracking",
       [](const ChartResult& c) {
         std::vector<long> ambiguous;
         for (const auto i : c.chart.analysis.tracking.ambiguous)
           ambiguous.push_back(static_cast<long>(i));
         return py::dict(py::arg("min_mac") = c.chart.analysis.tracking.min_mac,
                         py::arg("ambiguous_points") = IntArray(ambiguous));
       },
       "1-D: smallest accepted MAC and the points where a match was ambiguous")
      .def_property_readonly(
          "lines", [](const ChartResult& c) { return CampbellLines(c.chart.analysis.campbell); },
          "1-D: one Campbell line per physical mode: description (states carrying it), per-point "
          "frequency_hz, real_part, damping_ratio (NaN where not tracked), lost_after (point index "
          "or -1)")
      .def_property_readonly(
          "rotor_speeds",
          [](const ChartResult& c) { return RealArray(c.chart.analysis.campbell.rotor_speed); },
          "1-D: rotor speed per point (rad/s; NaN when the scene is not a rotor)")
      .def_property_readonly(
          "per_rev",
          [](const ChartResult& c) {
            const auto& n = c.chart.analysis.campbell.per_rev;
            return IntArray(std::vector<long>(n.begin(), n.end()));
          },
          "1-D: n of the per-rev lines n*Omega/2pi of the diagram (numpy int array)")
      .def_property_readonly(
          "crossings",
          [](const ChartResult& c) { return CampbellCrossings(c.chart.analysis.campbell); },
          "1-D: where each line crosses a per-rev line (mode numbered as in lines, from 1)")
      .def_property_readonly(
          "weakly_damped",
          [](const ChartResult& c) { return WeaklyDamped(c.chart.analysis.campbell); },
          "1-D: (lo, hi) intervals where the system is stable but some mode's damping ratio is low")
      .def_property_readonly(
          "campbell_notes",
          [](const ChartResult& c) { return Texts(c.chart.analysis.campbell.diagnostics); },
          "1-D: lost lines and ambiguous tracking");
}

void BindChartResult(py::module_& m) {
  py::class_<ChartResult> r(m, "ChartResult", R"doc(
The result of ltp.chart: one Floquet analysis per grid point (arrays over the points, in
grid order, first axis fastest), mode tracking along a 1-D sweep (Campbell lines), and the
unstable intervals (1-D) or boundary points (maps) refined beyond the grid.

For a Campbell diagram plot each of `lines` (one per physical mode, named by its states)
against values[0], with the per-rev lines n*rotor_speeds/2pi for n in per_rev; `crossings`
lists where they meet. tracked_exponents/tracked_frequencies_hz keep every exponent (both
members of each conjugate pair).)doc");
  BindChartPlan(r);
  BindChartPoints(r);
  BindChartExponents(r);
  BindChartTally(r);
  BindChartBoundaries(r);
  BindChartCurves(r);
  BindChartCampbell(r);
  r.def_property_readonly(
       "sweep_s", [](const ChartResult& c) { return c.chart.sweep_s; },
       "wall time of the sweep (s)")
      .def_property_readonly(
          "refine_s", [](const ChartResult& c) { return c.chart.analysis.refine_s; },
          "wall time of the boundary refinement (s)")
      .def("__repr__", [](const ChartResult& c) {
        return "<ltp.ChartResult: " + c.scene + ", " + std::to_string(c.chart.points.size()) +
               " points>";
      });
}

// ltp.chart: a scene by name is made as ltp.scene makes it; the chart runs without the GIL.
// A scene whose systems a Python callable builds: builder(**parameters) -> ltp.System. The
// chart calls it from its worker threads, each call with the GIL; what it raises fails that
// point with the message (as a scene's bad parameter value does). The callable is held through
// a shared_ptr so that copies of the scene never touch Python's reference counts without the GIL.
Scene BuilderScene(const py::object& builder, const py::dict& parameters) {
  Scene scene;
  scene.name = py::str(py::getattr(builder, "__name__", py::str("builder"))).cast<std::string>();
  scene.description = "systems built by a Python callable";
  scene.source = "python";
  for (const auto& [name, value] : parameters) {
    if (!py::isinstance<py::str>(name))
      throw InputError("parameters: names must be strings, got " +
                       py::repr(name).cast<std::string>());
    Real real;
    try {
      real = value.cast<Real>();
    } catch (const py::cast_error&) {
      throw InputError("parameters: " + name.cast<std::string>() + " must be a real number, got " +
                       py::repr(value).cast<std::string>());
    }
    scene.parameters.push_back({name.cast<std::string>(), real.value, ""});
  }
  const std::shared_ptr<py::object> fn(new py::object(builder), [](py::object* o) {
    py::gil_scoped_acquire gil;
    delete o;
  });
  scene.build = [fn](const ParameterMap& p) -> PeriodicSystem {
    py::gil_scoped_acquire gil;
    try {
      py::dict kwargs;
      for (const auto& [name, value] : p) kwargs[py::str(name)] = value;
      const py::object result = (*fn)(**kwargs);
      if (!py::isinstance<System>(result))
        throw InputError("the builder must return an ltp.System, got " +
                         py::str(py::type::of(result).attr("__name__")).cast<std::string>());
      const System& system = result.cast<const System&>();
      if (system.callbacks)
        throw InputError(
            "the builder returned a System.from_function system; a chart needs "
            "systems from from_fourier, from_second_order or from_samples");
      return system.system;
    } catch (py::error_already_set& e) {
      // The exception's type and message, without pybind11's appended traceback.
      throw InputError("the builder raised " +
                       py::str(e.type().attr("__name__")).cast<std::string>() + ": " +
                       py::str(e.value()).cast<std::string>());
    }
  };
  return scene;
}

System SystemToSweep(const py::object& scene, const py::object& parameters) {
  if (py::isinstance<py::str>(scene))
    return py::module_::import("ltp").attr("scene")(scene).cast<System>();
  if (py::isinstance<System>(scene)) {
    if (!parameters.is_none())
      throw InputError(
          "parameters= belongs to a builder; a scene's parameters are set in ltp.scene");
    return scene.cast<System>();
  }
  if (!PyCallable_Check(scene.ptr()))
    throw InputError("chart sweeps a scene (ltp.scene(...) or its name) or a builder callable");
  if (parameters.is_none() || !py::isinstance<py::dict>(parameters) || py::len(parameters) == 0)
    throw InputError(
        "a builder needs parameters={name: default, ...}: the base point and the "
        "names the sweeps may use");
  Scene built = BuilderScene(scene, parameters.cast<py::dict>());
  ParameterMap base;
  for (const SceneParameter& p : built.parameters) base[p.name] = p.value;
  System system{built.build(base), std::move(built), base, {}, nullptr, {}};
  return system;
}

ChartResult LtpChart(const py::object& scene, const py::object& sweep, const py::object& sweep2,
                     const std::string& method, std::optional<std::string> integrator, Real tol,
                     int threads, bool compare, std::optional<int> check_every, bool refine,
                     Real refine_tol, int refine_lines, bool curves, int per_rev, Real weak_damping,
                     const py::object& parameters) {
  const System system = SystemToSweep(scene, parameters);
  std::vector<SweepAxis> axes{AxisFrom(sweep)};
  if (!sweep2.is_none()) axes.push_back(AxisFrom(sweep2));
  ChartOptions o;
  const auto m = ParseSweepMethod(method);
  if (!m) throw InputError("method must be 'monodromy' or 'hill', got '" + method + "'");
  o.method = *m;
  if (integrator) o.integrator = IntegratorFrom(*integrator);
  o.tol = tol;
  o.threads = threads;
  o.compare = compare;
  o.check_every = check_every;
  o.refine = refine;
  o.refine_tol = refine_tol;
  o.refine_lines = refine_lines;
  o.curves = curves;
  o.campbell.max_per_rev = per_rev;
  o.campbell.weak_damping_ratio = weak_damping;
  o.Validate();
  py::gil_scoped_release release;
  return ChartOfScene(system, axes, o);
}

void BindChartFunction(py::module_& m) {
  const ChartOptions defaults;
  m.def("chart", &LtpChart, py::arg("scene"), py::arg("sweep"), py::arg("sweep2") = py::none(),
        py::kw_only(), py::arg("method") = std::string(ToString(defaults.method)),
        py::arg("integrator") = py::none(), py::arg("tol") = defaults.tol,
        py::arg("threads") = defaults.threads, py::arg("compare") = defaults.compare,
        py::arg("check_every") = defaults.check_every, py::arg("refine") = defaults.refine,
        py::arg("refine_tol") = defaults.refine_tol,
        py::arg("refine_lines") = defaults.refine_lines, py::arg("curves") = defaults.curves,
        py::arg("per_rev") = defaults.campbell.max_per_rev,
        py::arg("weak_damping") = defaults.campbell.weak_damping_ratio,
        py::arg("parameters") = py::none(), R"doc(
Campbell/damping diagram (one sweep) or stability map (sweep and sweep2) of a scene's
parameters: `ltp chart SCENE --sweep ... --json` as a function, with the same options and
defaults (the library's ChartOptions).

  scene         a System made by ltp.scene(...) (its parameters are the base), a scene name,
                or a builder: a callable builder(**params) -> ltp.System, swept over
                parameters={name: default, ...} (called with the GIL from the worker threads;
                what it raises fails that point with the message)
  sweep, sweep2 'NAME=START:STOP:STEP' or (name, start, stop, step)
  method        monodromy | hill
  integrator    None: rkf78 for 1-D sweeps; for maps taylor when A(t) is a Fourier series
                of <= 2 states, else bs; or any name ltp.floquet takes
  tol           integrator relative tolerance (hill: truncation tolerance)
  threads       threads over points (0 = all cores)
  compare       1-D: also the frozen A(0) and averaged-system eigenvalues
  check_every   error estimate on every k-th point (None: 1 for 1-D, 97 for maps; 0 = none)
  refine        refine the stability boundaries beyond the grid
  refine_tol    relative tolerance of refined boundaries
  refine_lines  maps: grid lines per axis along which boundaries are refined (0 = all)
  curves        maps: trace the boundaries through the refined points as curves
                (boundary_curves, boundary_curve_kinds, boundary_curve_brackets)
  per_rev       1-D: per-rev lines 1P..NP (0 = up to the highest mode frequency)
  weak_damping  1-D: damping ratio below which a stable point counts as weakly damped

Returns a ChartResult. Runs without the GIL.

    c = ltp.chart(ltp.scene("rotor", blades=3), "Omega=0.2:2:0.05")
    for line in c.lines: plt.plot(c.values[0], line["frequency_hz"], label=line["description"]))doc");
}

}  // namespace

void BindChart(py::module_& m) {
  BindChartResult(m);
  BindChartFunction(m);
}

}  // namespace ltp::python
