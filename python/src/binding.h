#pragma once
// Shared pieces of the Python module: the system as Python holds it, running library work
// without the GIL, and numpy conversions. Each Bind* function adds one part of the module.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <complex>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/floquet/work_estimate.h"
#include "ltp/integrate/integrator.h"
#include "ltp/models/scene.h"
#include "ltp/studies/campbell.h"

namespace ltp::python {

namespace py = pybind11;

/// A complex number of any kind: Python's complex, a numpy complex scalar (np.complex64 is not a
/// subclass of complex) or a 0-d complex array. Converted to a double they lose their imaginary
/// part with at most a ComplexWarning.
bool IsComplexNumber(py::handle value);

/// A real number argument (a double in a binding's signature): what pybind11 takes for a double,
/// except a complex number of any kind, refused with the TypeError pybind11 raises for Python's
/// complex (a numpy complex scalar would otherwise pass as its real part).
struct Real {
  double value = 0;
  Real() = default;
  Real(double v) : value(v) {}  // NOLINT(google-explicit-constructor): defaults are doubles
  operator double() const { return value; }  // NOLINT(google-explicit-constructor)
};
/// `v` as doubles.
std::vector<double> Doubles(const std::vector<Real>& v);

/// on_long_work for an analysis started from Python: a UserWarning with the library's estimate
/// before the work, where the command prints it on stderr. Under warnings.simplefilter("error")
/// the warning is raised and the work does not start.
inline std::function<void(const WorkEstimate&)> WarnLongWork(std::string function) {
  return [function = std::move(function)](const WorkEstimate& w) {
    py::gil_scoped_acquire gil;  // called before the work, from the analysing thread
    const std::string message = "ltp." + function + ": about " +
                                py::str("{:.2g}").attr("format")(w.seconds()).cast<std::string>() +
                                " CPU s of work ahead (" + w.basis + ")";
    if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) < 0) throw py::error_already_set();
  };
}
using Complex = std::complex<double>;

/// The Python callables behind a system built by System.from_function. The library calls them
/// from its OpenMP threads with the GIL released: each call takes the GIL back. An exception
/// raised by a callable (or a wrong shape) cannot cross the library's parallel loops, so it is
/// kept here and re-raised when the analysis returns; meanwhile every call answers a zero
/// matrix, on which every route finishes at once (NaN would send the adaptive integrators and
/// the automatic refinements through their longest paths: 50 s on Mathieu).
class Callbacks {
 public:
  explicit Callbacks(std::vector<py::object> functions) : functions_(std::move(functions)) {}
  ~Callbacks();
  Callbacks(const Callbacks&) = delete;
  Callbacks& operator=(const Callbacks&) = delete;

  /// Calls function `which` at t (taking the GIL) and writes its rows × cols result to `out`.
  void Evaluate(size_t which, const char* name, double t, Eigen::Ref<Eigen::MatrixXd> out);
  /// Before an analysis: forget an earlier failure.
  void Reset();
  /// After an analysis (GIL held): raise what a callable raised.
  void RethrowIfFailed();

 private:
  std::vector<py::object> functions_;
  std::mutex mutex_;
  std::exception_ptr error_;
  std::atomic<bool> failed_{false};
};

/// A system as Python holds it: the library's immutable system, and where it came from.
struct System {
  PeriodicSystem system;
  std::optional<Scene> scene;            ///< when built by ltp.scene: what ltp.chart sweeps
  ParameterMap parameters;               ///< the scene's resolved parameters
  std::vector<Diagnostic> notes;         ///< caveats that belong beside any result (.lin input)
  std::shared_ptr<Callbacks> callbacks;  ///< from_function with Python callables
  /// For OpenFAST samples: the other interpolations of the same samples, whose exponents give
  /// the sampling error that floquet() and hill() add to their estimate (IncludeModelError).
  std::vector<PeriodicSystem> model_alternatives;
};

/// Runs `work` with the GIL released (long work: other Python threads run meanwhile). Python
/// callables behind `system` take the GIL back per call; what they raised is raised here.
template <class Work>
auto WithoutGil(const System& system, Work&& work) {
  if (system.callbacks) system.callbacks->Reset();
  using Result = decltype(work());
  std::optional<Result> result;
  std::exception_ptr thrown;
  {
    py::gil_scoped_release release;
    try {
      result.emplace(work());
    } catch (...) {
      thrown = std::current_exception();
    }
  }
  if (system.callbacks) system.callbacks->RethrowIfFailed();  // the cause comes first
  if (thrown) std::rethrow_exception(thrown);
  return std::move(*result);
}

/// The OpenMP threads of an analysis: `requested`, except that 0 (all cores) means one for a
/// system behind Python callables, whose calls take turns on the GIL anyway (more threads only
/// wait for it: measured in docs/python.md, "Python callables, threads and errors").
inline int AnalysisThreads(const System& system, int requested) {
  return system.callbacks && requested == 0 ? 1 : requested;
}

// numpy arrays out (copies: results own their numbers).
/// An array cell for a quantity that may not have been computed: NaN when it was not (scalars
/// go out as None instead).
inline double OrNaN(std::optional<double> x) {
  return x.value_or(std::numeric_limits<double>::quiet_NaN());
}
py::array_t<double> RealArray(const std::vector<double>& v);
/// Strings as a numpy str array (dtype '<U…', as chart.verdicts).
py::array StringArray(const std::vector<std::string>& v);
py::array_t<Complex> ComplexArray(const std::vector<Complex>& v);
/// Matrices of equal size stacked along a first axis: shape (count, rows, cols).
py::array_t<Complex> ComplexStack(const std::vector<Eigen::MatrixXcd>& m, int rows, int cols);
py::array_t<double> RealStack(const std::vector<Eigen::MatrixXd>& m, int rows, int cols);
/// Rows of equal length: shape (rows, cols).
py::array_t<Complex> ComplexTable(const std::vector<std::vector<Complex>>& rows, size_t cols);
py::array_t<double> RealTable(const std::vector<std::vector<double>>& rows, size_t cols);

// Arguments in.
/// A list of finite frequencies (Hz) from "F0:F1:DF" (the CLI's --freq) or a 1-D array-like.
std::vector<double> FrequenciesFrom(const py::object& freq);
/// (min, max) from "ZMIN:ZMAX", "Z", an int or a pair (the CLI's --orders).
std::pair<int, int> OrdersFrom(const py::object& orders);
/// A channel by index or name (the CLI's --input/--output).
int ChannelFrom(const py::object& channel, const std::vector<std::string>& names, int count,
                const std::string& what);

/// `value` (an array, a list or a scalar) as numpy reads it: an ndarray as it is, anything else
/// converted once; null when numpy cannot. @throws InputError when it holds a complex number
/// with a non-zero imaginary part, which numpy's cast to float would drop silently; `what()`
/// names the value (built only then), `why` says what it must be. An array of complex dtype whose
/// imaginary parts are all 0 comes back as its real part.
py::array RealValued(
    const py::handle& value, const std::function<std::string()>& what,
    const char* why = "a system's matrices must be real (give the real form of the equations)");

/// t of a periodic quantity of period `period`: finite (else InputError naming `what`), reduced
/// exactly to [0, T) by fmod, so t = 1e308 is the value at its remainder, not cos(ω·1e308)'s NaN.
double PeriodicTime(double t, double period, const std::string& what);

/// An integrator by the CLI's name. @throws InputError listing the names.
IntegratorType IntegratorFrom(const std::string& name);

void BindSystem(py::module_& m);
void BindFloquet(py::module_& m);
void BindHill(py::module_& m);
void BindFrf(py::module_& m);
void BindChart(py::module_& m);
void BindMbc(py::module_& m);
void BindCampbell(py::module_& m);
void BindDeflection(py::module_& m);
void BindIdentify(py::module_& m);
void BindHtfOperator(py::module_& m);
/// ltp.periodic_schur and its result; before BindFloquet (FloquetResult.periodic_schur returns it).
void BindPeriodicSchur(py::module_& m);

/// A Campbell diagram's lines (dicts with per-point arrays), its per-rev crossings (dicts) and
/// weakly damped intervals, as ltp.chart and ltp.campbell give them (chart_binding.cc).
py::list CampbellLines(const CampbellDiagram& d);
py::list CampbellCrossings(const CampbellDiagram& d);
py::array_t<double> WeaklyDamped(const CampbellDiagram& d);

}  // namespace ltp::python

namespace pybind11::detail {
template <>
struct type_caster<ltp::python::Real> {
  PYBIND11_TYPE_CASTER(ltp::python::Real, const_name("float"));
  bool load(handle src, bool convert) {
    if (!src || ltp::python::IsComplexNumber(src)) return false;
    make_caster<double> d;
    if (!d.load(src, convert)) return false;
    value.value = cast_op<double>(d);
    return true;
  }
  static handle cast(ltp::python::Real r, return_value_policy, handle) {
    return PyFloat_FromDouble(r.value);
  }
};
}  // namespace pybind11::detail
