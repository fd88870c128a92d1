// The extension module ltp._ltp; the package ltp (python/ltp/__init__.py) re-exports it.
#include "binding.h"
#include "ltp/core/error.h"
#include "ltp/integrate/threads.h"

namespace {

// A new exception class ltp.NAME (bases: a class or a tuple of classes), kept alive by the module.
PyObject* NewException(pybind11::module_& m, const char* name, PyObject* bases, const char* doc) {
  const std::string qualified = std::string("ltp.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases, nullptr);
  if (!type) throw pybind11::error_already_set();
  m.add_object(name, pybind11::handle(type));
  return type;
}

}  // namespace

PYBIND11_MODULE(_ltp, m) {
  namespace py = pybind11;
  using namespace ltp::python;
  m.doc() = "ltp: analysis of linear time-periodic systems (see help(ltp))";
  m.attr("__version__") = LTP_VERSION;
  // As the ltp command: ltp runs its own threads, and OpenBLAS's under them oversubscribe the
  // cores (ltp/integrate/threads.h); it also keeps the results equal to the command's to the bit.
  ltp::UseSingleThreadedBlas();

  // The library's typed errors as Python exceptions carrying its one-line message. Bad input is
  // a ValueError too, so `except ValueError` catches what a caller got wrong.
  static PyObject* error =
      NewException(m, "Error", PyExc_Exception, "Base of every error ltp raises on purpose.");
  static PyObject* input_error =
      NewException(m, "InputError",
                   py::make_tuple(py::handle(error), py::handle(PyExc_ValueError)).release().ptr(),
                   "Bad input: an unknown scene or parameter, wrong sizes, NaN, a bad option.");
  static PyObject* scene_error =
      NewException(m, "SceneError", input_error,
                   "A scene file that cannot be read or is malformed (names file, line, entry).");
  static PyObject* singular_mass_error =
      NewException(m, "SingularMassError", input_error,
                   "The mass matrix of a second-order scene is singular at some time.");
  static PyObject* resource_error = NewException(
      m, "ResourceError", error,
      "A computation would not fit in memory, or was asked for something it cannot do.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ltp::SceneError& e) {
      PyErr_SetString(scene_error, e.what());
    } catch (const ltp::SingularMassError& e) {
      PyErr_SetString(singular_mass_error, e.what());
    } catch (const ltp::InputError& e) {
      PyErr_SetString(input_error, e.what());
    } catch (const ltp::ResourceError& e) {
      PyErr_SetString(resource_error, e.what());
    } catch (const ltp::Error& e) {
      PyErr_SetString(error, e.what());
    }
  });

  BindSystem(m);
  BindPeriodicSchur(m);
  BindFloquet(m);
  BindHill(m);
  BindFrf(m);
  BindChart(m);
  BindMbc(m);
  BindCampbell(m);
  BindDeflection(m);
  BindIdentify(m);
  BindHtfOperator(m);
}
