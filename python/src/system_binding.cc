// ltp.System and ltp.scene: every way to make the one type the analyses take.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "binding.h"
#include "diagnostic_properties.h"
#include "ltp/core/bounded_coefficients.h"
#include "ltp/core/error.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_coefficients.h"
#include "ltp/core/second_order.h"
#include "ltp/models/scene_input.h"

namespace ltp::python {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using ComplexArrayIn = py::array_t<Complex, py::array::c_style | py::array::forcecast>;

std::string Shape(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s << (d ? ", " : "") << a.shape(d);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

Eigen::MatrixXd MatrixFrom(const py::object& obj, const std::string& name) {
  const Array a = Array::ensure(RealValued(obj, [&] { return name; }));
  if (!a || a.ndim() != 2) throw InputError(name + " must be a real 2-D array");
  Eigen::MatrixXd m(a.shape(0), a.shape(1));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (py::ssize_t j = 0; j < a.shape(1); ++j) m(i, j) = a.at(i, j);
  return m;
}

// A 2-D real array (constant) or (2H+1, rows, cols) complex coefficients M_w at index w + H.
FourierMatrix FourierFrom(const py::object& obj, const std::string& name) {
  if (obj.is_none()) return {};
  const ComplexArrayIn a = ComplexArrayIn::ensure(obj);
  if (!a || (a.ndim() != 2 && a.ndim() != 3))
    throw InputError(name +
                     " must be a 2-D array (constant) or a 3-D array of Fourier coefficients "
                     "(2H+1, rows, cols) for harmonics -H..H");
  for (int d = 0; d < a.ndim(); ++d)
    if (a.shape(d) == 0)
      throw InputError(name + " is missing or empty (shape " + Shape(a) +
                       "): A needs at least one state; give None for no inputs or outputs");
  if (a.ndim() == 2) {
    Eigen::MatrixXcd m(a.shape(0), a.shape(1));
    for (py::ssize_t i = 0; i < a.shape(0); ++i)
      for (py::ssize_t j = 0; j < a.shape(1); ++j) m(i, j) = a.at(i, j);
    if (m.imag().cwiseAbs().maxCoeff() > 0)
      throw InputError(name + ": a constant matrix must be real");
    return FourierMatrix::Constant(m.real());
  }
  if (a.shape(0) % 2 == 0)
    throw InputError(name +
                     ": the first axis holds harmonics -H..H, so its length must be odd, got " +
                     Shape(a));
  const int h = static_cast<int>(a.shape(0) / 2);
  FourierMatrix f(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(2)), h);
  double scale = 0;
  for (int w = -h; w <= h; ++w) {
    Eigen::MatrixXcd m(a.shape(1), a.shape(2));
    for (py::ssize_t i = 0; i < a.shape(1); ++i)
      for (py::ssize_t j = 0; j < a.shape(2); ++j) m(i, j) = a.at(w + h, i, j);
    scale = std::max(scale, m.norm());
    f[w] = m;
  }
  // A(t) is real: M_{-w} = conj(M_w). The analyses use the coefficients as given, so a series
  // that is not real would be analysed as something else than what A(t) evaluates to.
  const double defect = f.HermitianDefect();
  if (defect > 1e-12 * std::max(scale, 1.0)) {
    std::ostringstream s;
    s << name << " is not the series of a real matrix function: " << name
      << "[H - w] must equal conj(" << name << "[H + w]) (largest difference " << defect << ")";
    throw InputError(s.str());
  }
  return f;
}

// A callable of t, or a constant array.
struct TimeFunction {
  PeriodicSystem::MatrixFunction function;
  int rows = 0, cols = 0;
};

TimeFunction FunctionFrom(const py::object& obj, const char* name,
                          std::vector<py::object>* callables,
                          std::shared_ptr<std::shared_ptr<Callbacks>> owner) {
  if (obj.is_none()) return {};
  if (PyCallable_Check(obj.ptr())) {
    const Eigen::MatrixXd first = MatrixFrom(obj(0.0), std::string(name) + "(0)");
    const size_t which = callables->size();
    callables->push_back(obj);
    TimeFunction f;
    f.rows = static_cast<int>(first.rows());
    f.cols = static_cast<int>(first.cols());
    // The Callbacks object exists once every callable is known (see FromFunction).
    f.function = [owner, which, name](double t, Eigen::Ref<Eigen::MatrixXd> out) {
      (*owner)->Evaluate(which, name, t, out);
    };
    return f;
  }
  const Eigen::MatrixXd m = MatrixFrom(obj, name);
  return {[m](double, Eigen::Ref<Eigen::MatrixXd> out) { out = m; }, static_cast<int>(m.rows()),
          static_cast<int>(m.cols())};
}

System FromFunction(Real period, const py::object& a, const py::object& b, const py::object& c,
                    const py::object& d, const std::vector<Real>& breakpoints) {
  if (!PyCallable_Check(a.ptr()))
    throw InputError("A must be a callable A(t) returning an n×n array");
  std::vector<py::object> callables;
  auto owner = std::make_shared<std::shared_ptr<Callbacks>>();
  TimeFunction fa = FunctionFrom(a, "A", &callables, owner);
  TimeFunction fb = FunctionFrom(b, "B", &callables, owner);
  TimeFunction fc = FunctionFrom(c, "C", &callables, owner);
  TimeFunction fd = FunctionFrom(d, "D", &callables, owner);
  if (fa.rows != fa.cols)
    throw InputError("A(t) must be square, got " + std::to_string(fa.rows) + "×" +
                     std::to_string(fa.cols));
  if (fb.function && fb.rows != fa.rows) throw InputError("B must have as many rows as A");
  if (fc.function && fc.cols != fa.rows) throw InputError("C must have as many columns as A");
  const int inputs = fb.function ? fb.cols : 0, outputs = fc.function ? fc.rows : 0;
  if (fd.function && (fd.rows != outputs || fd.cols != inputs))
    throw InputError("D must be outputs × inputs");
  *owner = std::make_shared<Callbacks>(std::move(callables));
  PeriodicSystem system = PeriodicSystem::FromFunctions(
      period, fa.rows, inputs, outputs, {fa.function, fb.function, fc.function, fd.function},
      Doubles(breakpoints));
  // Checked as scene files are: a NaN or a pole inside the period is refused here, in one line,
  // not found by the integrator after seconds and thousands of diagnostics.
  if (const auto problem = UnboundedCoefficients(system)) throw InputError(*problem);
  if (const auto problem = NonPeriodicCoefficients(system)) throw InputError(*problem);
  (*owner)->RethrowIfFailed();  // what a callable raised during the checks
  return System{std::move(system), std::nullopt, {}, {}, *owner, {}};
}

// (K, rows, cols) samples, or one (rows, cols) matrix held for every sample.
std::vector<Eigen::MatrixXd> SamplesFrom(const py::object& obj, size_t count,
                                         const std::string& name) {
  if (obj.is_none()) return std::vector<Eigen::MatrixXd>(count);
  const Array a = Array::ensure(RealValued(obj, [&] { return name; }));
  if (a && a.ndim() == 2) return std::vector<Eigen::MatrixXd>(count, MatrixFrom(obj, name));
  if (!a || a.ndim() != 3 || static_cast<size_t>(a.shape(0)) != count)
    throw InputError(name +
                     " must be a (K, rows, cols) array with one matrix per sample time (K = " +
                     std::to_string(count) + "), or one constant 2-D array");
  std::vector<Eigen::MatrixXd> out(count, Eigen::MatrixXd(a.shape(1), a.shape(2)));
  for (size_t k = 0; k < count; ++k)
    for (py::ssize_t i = 0; i < a.shape(1); ++i)
      for (py::ssize_t j = 0; j < a.shape(2); ++j)
        out[k](i, j) = a.at(static_cast<py::ssize_t>(k), i, j);
  return out;
}

System FromSamples(Real period, const std::vector<Real>& times_in, const py::object& a,
                   const py::object& b, const py::object& c, const py::object& d) {
  const std::vector<double> times = Doubles(times_in);
  const size_t k = times.size();
  const auto as = SamplesFrom(a, k, "A"), bs = SamplesFrom(b, k, "B"), cs = SamplesFrom(c, k, "C"),
             ds = SamplesFrom(d, k, "D");
  std::vector<LtiSystem> samples(k);
  for (size_t i = 0; i < k; ++i) {
    const Eigen::Index n = as[i].rows();
    samples[i].A = as[i];
    samples[i].B = b.is_none() ? Eigen::MatrixXd(n, 0) : bs[i];
    samples[i].C = c.is_none() ? Eigen::MatrixXd(0, n) : cs[i];
    samples[i].D =
        d.is_none() ? Eigen::MatrixXd::Zero(samples[i].C.rows(), samples[i].B.cols()) : ds[i];
  }
  return System{PeriodicSystem::FromSamples(period, times, std::move(samples)),
                std::nullopt,
                {},
                {},
                nullptr,
                {}};
}

// A scene parameter value as the CLI's --set takes it: numbers exactly (shortest repr), text
// as an expression.
std::string ParameterText(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "1" : "0";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (IsComplexNumber(value))  // float() would keep the real part of a numpy complex
    throw InputError("a scene parameter must be a real number or an expression string, got " +
                     py::repr(value).cast<std::string>());
  try {
    return py::str(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
  } catch (const py::error_already_set&) {
    throw InputError("a scene parameter must be a number or an expression string, got " +
                     py::repr(value).cast<std::string>());
  }
}

System SceneSystem(const py::object& name, const py::kwargs& parameters) {
  std::vector<std::string> names;
  if (py::isinstance<py::str>(name)) {
    names.push_back(name.cast<std::string>());
  } else {
    try {
      names = name.cast<std::vector<std::string>>();  // several OpenFAST .lin files
    } catch (const py::cast_error&) {
      throw InputError("scene must be a name, a path, or a list of OpenFAST .lin paths");
    }
  }
  std::vector<std::string> assignments;
  for (const auto& [key, value] : parameters)
    assignments.push_back(key.cast<std::string>() + "=" + ParameterText(value));
  std::optional<LoadedScene> loaded;
  {
    py::gil_scoped_release release;  // .lin files and finite-element scenes take a while
    loaded.emplace(LoadSceneInput(names, assignments));
  }
  return System{loaded->system,      loaded->scene, loaded->parameters,
                loaded->diagnostics, nullptr,       loaded->model_alternatives};
}

py::object MaybeFourier(const FourierMatrix* f) {
  if (!f || f->rows() == 0) return py::none();
  std::vector<Eigen::MatrixXcd> m;
  for (int w = -f->max_harmonic(); w <= f->max_harmonic(); ++w) m.push_back((*f)[w]);
  return ComplexStack(m, f->rows(), f->cols());
}

Eigen::MatrixXd Evaluate(const System& s, char which, double t) {
  t = PeriodicTime(t, s.system.period(), std::string(1, which) + "(t)");
  if (s.callbacks) s.callbacks->Reset();
  Eigen::MatrixXd m;
  switch (which) {
    case 'A':
      m = s.system.A(t);
      break;
    case 'B':
      m = s.system.B(t);
      break;
    case 'C':
      m = s.system.C(t);
      break;
    default:
      m = s.system.D(t);
      break;
  }
  if (s.callbacks) s.callbacks->RethrowIfFailed();
  return m;
}

std::string FormName(PeriodicSystem::Form form) {
  switch (form) {
    case PeriodicSystem::Form::kFourier:
      return "fourier";
    case PeriodicSystem::Form::kFunction:
      return "function";
    case PeriodicSystem::Form::kPiecewiseConstant:
      return "piecewise-constant";
  }
  return "?";
}

// System.from_fourier: every matrix as Fourier coefficients (or constant).
System FromFourier(Real period, const py::object& a, const py::object& b, const py::object& c,
                   const py::object& d) {
  return System{PeriodicSystem::FromFourier(period, FourierFrom(a, "A"), FourierFrom(b, "B"),
                                            FourierFrom(c, "C"), FourierFrom(d, "D")),
                std::nullopt,
                {},
                {},
                nullptr,
                {}};
}

// System.from_second_order: M q'' + D q' + K q = F u, each as Fourier coefficients (or constant).
System FromSecondOrder(Real period, const py::object& mass, const py::object& stiffness,
                       const py::object& damping, const py::object& f, const py::object& cd,
                       const py::object& cv) {
  return System{FromSecondOrderSeries(period, FourierFrom(mass, "M"), FourierFrom(damping, "D"),
                                      FourierFrom(stiffness, "K"), FourierFrom(f, "F"),
                                      FourierFrom(cd, "Cd"), FourierFrom(cv, "Cv")),
                std::nullopt,
                {},
                {},
                nullptr,
                {}};
}

// System.with_labels: a copy whose names are replaced where given.
System SystemWithLabels(
    const System& s, std::optional<std::vector<std::string>> states,
    std::optional<std::vector<std::string>> inputs, std::optional<std::vector<std::string>> outputs,
    std::optional<std::vector<std::pair<std::string, std::string>>> whirl_pairs) {
  SystemLabels labels = s.system.labels();
  if (states) labels.states = *states;
  if (inputs) labels.inputs = *inputs;
  if (outputs) labels.outputs = *outputs;
  if (whirl_pairs) {
    labels.whirl_pairs.clear();
    auto index = [&](const std::string& name) {
      const auto it = std::find(labels.states.begin(), labels.states.end(), name);
      if (it == labels.states.end())
        throw InputError("with_labels: whirl pair state '" + name + "' is not a state name");
      return static_cast<int>(it - labels.states.begin());
    };
    for (const auto& [x, y] : *whirl_pairs) {
      if (x == y) throw InputError("with_labels: a whirl pair needs two different states");
      labels.whirl_pairs.push_back({index(x), index(y)});
    }
  }
  System out = s;
  out.system = s.system.WithLabels(labels);
  return out;
}

std::string SystemRepr(const System& s) {
  std::ostringstream r;
  r << "<ltp.System";
  if (s.scene) r << " " << s.scene->name;
  r << ": " << s.system.states() << " states, " << s.system.inputs() << " inputs, "
    << s.system.outputs() << " outputs, T = " << s.system.period() << " s, "
    << FormName(s.system.form()) << ">";
  return r.str();
}

// ltp.scenes: name, description and parameters of each built-in scene.
py::list BuiltinSceneList() {
  py::list out;
  for (const Scene& s : BuiltinScenes()) {
    py::list parameters;
    for (const SceneParameter& p : s.parameters)
      parameters.append(py::dict(py::arg("name") = p.name, py::arg("value") = p.value,
                                 py::arg("description") = p.description));
    out.append(py::dict(py::arg("name") = s.name, py::arg("description") = s.description,
                        py::arg("parameters") = parameters));
  }
  return out;
}

// The ways to make a System besides ltp.scene.
void BindSystemConstructors(py::class_<System>& c) {
  c.def_static("from_fourier", &FromFourier, py::arg("period"), py::arg("A"),
               py::arg("B") = py::none(), py::arg("C") = py::none(), py::arg("D") = py::none(),
               R"doc(
A system from the Fourier coefficients of its matrices (the fastest form: every analysis
uses the exact coefficients).

Each of A, B, C, D is either a real 2-D array (constant) or a complex array of shape
(2H+1, rows, cols) holding M_w for w = -H..H at index w + H, with
M(t) = sum_w M_w exp(j w 2 pi t / period) and M_{-w} = conj(M_w) (real functions).
A is n×n, B n×m, C p×n, D p×m; B, C, D may be None (no inputs, no outputs, D = 0).

Example (damped Mathieu as the scene "mathieu" has it, x'' + c x' + (a - 2 q cos 2t) x = 0,
period pi; -2q cos 2t = -q e^{2jt} - q e^{-2jt} in the stiffness, so +q in A):
    A = np.zeros((3, 2, 2), complex)
    A[1] = [[0, 1], [-a, -c]]; A[0][1, 0] = A[2][1, 0] = q
    system = ltp.System.from_fourier(np.pi, A)

Raises ltp.InputError (a ValueError) on inconsistent sizes, a period <= 0, non-finite or
non-real series.)doc")
      .def_static("from_second_order", &FromSecondOrder, py::arg("period"), py::arg("M"),
                  py::arg("K"), py::arg("D") = py::none(), py::arg("F") = py::none(),
                  py::arg("Cd") = py::none(), py::arg("Cv") = py::none(),
                  R"doc(
A system from second-order matrices, as a finite-element model gives them:
    M(t) q'' + D(t) q' + K(t) q = F(t) u,   y = Cd(t) q + Cv(t) q',
with the state x = [q; q']. Each matrix is a real 2-D array (constant) or a complex array
(2H+1, rows, cols) of Fourier coefficients M_w for w = -H..H, as in from_fourier. D holds the
damping and gyroscopic terms (Ω·G for a rotor); D, F, Cd, Cv may be None.

A constant M (the usual case: rotating asymmetry, periodic bearings or stiffness) gives an
exact Fourier-form system, A_w = [[0, δ_w I], [-M⁻¹K_w, -M⁻¹D_w]], the fastest form for every
analysis; a periodic M gives a function-form system (M(t)⁻¹ is evaluated at every step).
States in physical units far apart (metres and radians, stiffness entries of 1e9 N/m) need
no scaling by hand: the Floquet analysis balances them.

Raises ltp.InputError (a ValueError) on inconsistent sizes or non-finite entries, and on a
singular or ill-conditioned mass matrix (the time is named).)doc")
      .def_static("from_function", &FromFunction, py::arg("period"), py::arg("A"),
                  py::arg("B") = py::none(), py::arg("C") = py::none(), py::arg("D") = py::none(),
                  py::arg("breakpoints") = std::vector<Real>{}, R"doc(
A system from a Python callable A(t) returning an n×n array (B, C, D: callables or constant
2-D arrays, or None). `breakpoints`: times in [0, period) where a matrix jumps (the
integrators restart there).

What it costs against Fourier input: the library calls A(t) with the GIL released and
each call takes the GIL back, so the calls run one at a time (an analysis of such a system
uses one thread unless threads= says otherwise: more only wait for the GIL), each costing
your function's time plus about a microsecond. Measured on the damped Mathieu equation
(tests/python/test_systems.py prints it): ltp.floquet takes 0.25 ms on Fourier input (3100
evaluations of the series in C++) and 7–11 ms with a small numpy A(t) (4100 calls), some 30–45×
more; Hill's method fits A(t) by FFT from a few hundred calls and costs about the same either
way. When A(t) is a known trigonometric polynomial, give its coefficients to from_fourier.

An exception raised by a callable (or a wrong shape) stops the analysis and is raised by
it.)doc")
      .def_static("from_samples", &FromSamples, py::arg("period"), py::arg("times"), py::arg("A"),
                  py::arg("B") = py::none(), py::arg("C") = py::none(), py::arg("D") = py::none(),
                  R"doc(
A piecewise-constant system: the matrices A[k] (arrays of shape (K, rows, cols), or one
constant 2-D array) hold on [times[k], times[k+1]), times[K] = times[0] + period. `times`
must be strictly increasing in [0, period). The state transition is then an exact product
of matrix exponentials (e.g. a rotor measured at K azimuths).)doc");
}

// Copies with names or a rotor speed added.
void BindSystemCopies(py::class_<System>& c) {
  c.def("with_labels", &SystemWithLabels, py::arg("states") = py::none(),
        py::arg("inputs") = py::none(), py::arg("outputs") = py::none(),
        py::arg("whirl_pairs") = py::none(),
        "A copy with these names of states, inputs and outputs (None keeps the present ones); "
        "pfrf and snapshot then take input= and output= by name. whirl_pairs: [(x, y), ...] "
        "state names of a rotor's lateral displacements, the rotor turning from x towards y: "
        "floquet results then give each mode's forward_whirl.")
      .def(
          "with_rotor_speed",
          [](const System& s, Real speed) {
            System out = s;
            out.system = s.system.WithRotorSpeed(speed);
            return out;
          },
          py::arg("rad_per_s"), "A copy whose rotor angle is rad_per_s · t (snapshot(angle=...)).");
}

// What the system is: its sizes, form, names and where it came from.
void BindSystemProperties(py::class_<System>& c) {
  c.def_property_readonly(
       "period", [](const System& s) { return s.system.period(); }, "T (s)")
      .def_property_readonly(
          "omega", [](const System& s) { return s.system.omega(); }, "Ωp = 2π/T (rad/s)")
      .def_property_readonly(
          "states", [](const System& s) { return s.system.states(); }, "n")
      .def_property_readonly(
          "inputs", [](const System& s) { return s.system.inputs(); }, "m")
      .def_property_readonly(
          "outputs", [](const System& s) { return s.system.outputs(); }, "p")
      .def_property_readonly(
          "form", [](const System& s) { return FormName(s.system.form()); },
          "'fourier', 'function' or 'piecewise-constant'")
      .def_property_readonly(
          "state_names", [](const System& s) { return s.system.labels().states; },
          "names of the states (may be empty)")
      .def_property_readonly(
          "input_names", [](const System& s) { return s.system.labels().inputs; },
          "names of the inputs")
      .def_property_readonly(
          "output_names", [](const System& s) { return s.system.labels().outputs; },
          "names of the outputs")
      .def_property_readonly(
          "rotor_speed", [](const System& s) { return s.system.rotor_speed(); },
          "rad/s, or None when the system is not a rotor")
      .def_property_readonly(
          "breakpoints", [](const System& s) { return RealArray(s.system.breakpoints()); },
          "times in [0, T) where the matrices jump")
      .def_property_readonly(
          "scene",
          [](const System& s) -> py::object {
            if (!s.scene) return py::none();
            return py::str(s.scene->name);
          },
          "the scene's name (ltp.scene), else None")
      .def_property_readonly(
          "parameters", [](const System& s) { return s.parameters; },
          "the scene's parameters, all resolved (ltp.scene), else {}")
      .def_property_readonly(
          "notes", [](const System& s) { return Texts(s.notes); },
          "caveats that belong beside any result (OpenFAST .lin input)")
      .def_property_readonly(
          "note_codes", [](const System& s) { return CodeNames(s.notes); },
          "the notes' codes (snake_case, one per note), for code that branches on them")
      .def_property_readonly(
          "fourier_A", [](const System& s) { return MaybeFourier(s.system.fourier_A()); },
          "A's coefficients (2H+1, n, n) for w = -H..H when the system is in "
          "Fourier form, else None");
}

void BindSystemClass(py::module_& m) {
  py::class_<System> c(m, "System", R"doc(
A linear T-periodic system  x' = A(t) x + B(t) u,  y = C(t) x + D(t) u.

Make one with ltp.scene(...) (a built-in scene, a YAML scene file or OpenFAST .lin
files) or with System.from_fourier, System.from_function or System.from_samples.
Immutable; every analysis (ltp.floquet, ltp.hill, ltp.pfrf, ltp.snapshot) takes it.
ltp.chart takes a system made by ltp.scene, whose parameters it sweeps.)doc");
  BindSystemConstructors(c);
  BindSystemCopies(c);
  BindSystemProperties(c);
  c.def(
       "A", [](const System& s, Real t) { return Evaluate(s, 'A', t); }, py::arg("t"), "A(t)")
      .def(
          "B", [](const System& s, Real t) { return Evaluate(s, 'B', t); }, py::arg("t"), "B(t)")
      .def(
          "C", [](const System& s, Real t) { return Evaluate(s, 'C', t); }, py::arg("t"), "C(t)")
      .def(
          "D", [](const System& s, Real t) { return Evaluate(s, 'D', t); }, py::arg("t"), "D(t)")
      .def("__repr__", &SystemRepr);
}

void BindSceneFunctions(py::module_& m) {
  m.def("scene", &SceneSystem, py::arg("scene"), R"doc(
scene(name_or_path, **parameters) -> System

A built-in scene (see ltp.scenes()), a YAML scene file, or OpenFAST .lin files (a path, a
directory, a glob, or a list of paths), with parameters overridden as the CLI's
--set name=value does: numbers, or expressions in pi as strings.

    ltp.scene("mathieu", a=1.5, q=2)
    ltp.scene("rotor", blades=3, Omega="2*pi/3")
    ltp.scene("scenes/meissner.yaml")

Raises ltp.InputError (unknown scene or parameter, bad value) or ltp.SceneError (a file
that cannot be read, naming file, line and entry).)doc");

  m.def("scenes", &BuiltinSceneList,
        "The built-in scenes (what `ltp scenes` lists): name, description, parameters with "
        "defaults.");
}

}  // namespace

void BindSystem(py::module_& m) {
  BindSystemClass(m);
  BindSceneFunctions(m);
}

}  // namespace ltp::python
