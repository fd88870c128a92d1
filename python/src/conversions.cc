// numpy conversions, argument parsing shared by the analyses, and Python callables behind
// systems.
#include <cmath>
#include <complex>
#include <functional>
#include <sstream>

#include "binding.h"
#include "ltp/core/channel.h"
#include "ltp/core/error.h"
#include "ltp/htf/frequency_range.h"

namespace ltp::python {

bool IsComplexNumber(py::handle value) {
  if (PyComplex_Check(value.ptr())) return true;
  if (!py::hasattr(value, "dtype")) return false;  // numpy scalars and 0-d arrays have one
  const py::object dtype = value.attr("dtype");
  return py::isinstance<py::dtype>(dtype) && dtype.cast<py::dtype>().kind() == 'c';
}

std::vector<double> Doubles(const std::vector<Real>& v) { return {v.begin(), v.end()}; }

py::array RealValued(const py::handle& value, const std::function<std::string()>& what,
                     const char* why) {
  // An ndarray is taken as it is (its dtype says whether to look further); a list or a scalar is
  // converted here once, and the caller casts this array, not the value again.
  const py::array raw = py::array::ensure(value);
  if (!raw || raw.dtype().kind() != 'c') return raw;
  const auto c = py::array_t<std::complex<double>, py::array::forcecast>::ensure(raw);
  double imag = 0;
  if (c)
    for (py::ssize_t i = 0; i < c.size(); ++i) imag = std::max(imag, std::abs(c.data()[i].imag()));
  if (imag > 0) {
    std::ostringstream s;
    s << what() << " has complex values (|Im| up to " << imag << "): " << why;
    throw InputError(s.str());
  }
  // All imaginary parts 0: the real part, without the ComplexWarning of numpy's cast.
  return py::array::ensure(raw.attr("real"));
}

Callbacks::~Callbacks() {
  // The callables are Python objects: drop them with the GIL (none at interpreter exit).
  if (!Py_IsInitialized()) {
    for (py::object& f : functions_) f.release();
    return;
  }
  py::gil_scoped_acquire gil;
  functions_.clear();
}

void Callbacks::Reset() {
  std::lock_guard<std::mutex> lock(mutex_);
  error_ = nullptr;
  failed_ = false;
}

void Callbacks::RethrowIfFailed() {
  std::exception_ptr error;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    error = error_;
    error_ = nullptr;
    failed_ = false;
  }
  if (error) std::rethrow_exception(error);
}

void Callbacks::Evaluate(size_t which, const char* name, double t,
                         Eigen::Ref<Eigen::MatrixXd> out) {
  if (failed_) {  // one failure is enough: the analysis is abandoned
    out.setZero();
    return;
  }
  py::gil_scoped_acquire gil;
  try {
    const py::array value = RealValued(functions_[which](t), [&] {
      return std::string(name) + "(t) at t = " + std::to_string(t);
    });
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    const bool scalar_ok = out.rows() == 1 && out.cols() == 1 && a && a.size() == 1;
    if (!a ||
        (!scalar_ok && (a.ndim() != 2 || a.shape(0) != out.rows() || a.shape(1) != out.cols()))) {
      std::ostringstream s;
      s << name << "(t) must return a real " << out.rows() << "×" << out.cols() << " array";
      if (a) {
        s << ", got shape (";
        for (py::ssize_t d = 0; d < a.ndim(); ++d) s << (d ? ", " : "") << a.shape(d);
        s << (a.ndim() == 1 ? ",)" : ")");
      }
      s << " at t = " << t;
      throw InputError(s.str());
    }
    const double* data = a.data();
    for (Eigen::Index i = 0; i < out.rows(); ++i)
      for (Eigen::Index j = 0; j < out.cols(); ++j) out(i, j) = data[i * out.cols() + j];
  } catch (...) {
    out.setZero();
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = std::current_exception();
    failed_ = true;
  }
}

py::array_t<double> RealArray(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::array StringArray(const std::vector<std::string>& v) {
  return py::module_::import("numpy").attr("array")(py::cast(v), "U");
}

py::array_t<Complex> ComplexArray(const std::vector<Complex>& v) {
  py::array_t<Complex> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

namespace {
template <class Scalar, class Matrix>
py::array_t<Scalar> Stack(const std::vector<Matrix>& m, int rows, int cols) {
  py::array_t<Scalar> a({static_cast<py::ssize_t>(m.size()), static_cast<py::ssize_t>(rows),
                         static_cast<py::ssize_t>(cols)});
  auto out = a.template mutable_unchecked<3>();
  for (size_t k = 0; k < m.size(); ++k)
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) out(static_cast<py::ssize_t>(k), i, j) = m[k](i, j);
  return a;
}
}  // namespace

py::array_t<Complex> ComplexStack(const std::vector<Eigen::MatrixXcd>& m, int rows, int cols) {
  return Stack<Complex>(m, rows, cols);
}

py::array_t<double> RealStack(const std::vector<Eigen::MatrixXd>& m, int rows, int cols) {
  return Stack<double>(m, rows, cols);
}

py::array_t<Complex> ComplexTable(const std::vector<std::vector<Complex>>& rows, size_t cols) {
  py::array_t<Complex> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
  auto out = a.mutable_unchecked<2>();
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < cols; ++j)
      out(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) =
          j < rows[i].size() ? rows[i][j] : Complex(NAN, NAN);
  return a;
}

py::array_t<double> RealTable(const std::vector<std::vector<double>>& rows, size_t cols) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
  auto out = a.mutable_unchecked<2>();
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < cols; ++j)
      out(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) =
          j < rows[i].size() ? rows[i][j] : NAN;
  return a;
}

std::vector<double> FrequenciesFrom(const py::object& freq) {
  if (py::isinstance<py::str>(freq)) return ParseFrequencyRange(freq.cast<std::string>(), "freq");
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(RealValued(
      freq, [] { return std::string("freq"); }, "frequencies are real numbers (Hz)"));
  if (!a || a.ndim() > 1)
    throw InputError("freq must be 'F0:F1:DF' (Hz) or a 1-D array of frequencies in Hz");
  std::vector<double> f(a.data(), a.data() + a.size());
  if (f.empty()) throw InputError("freq: no frequencies");
  for (double x : f)
    if (!std::isfinite(x)) throw InputError("freq: frequencies must be finite numbers");
  return f;
}

std::pair<int, int> OrdersFrom(const py::object& orders) {
  if (py::isinstance<py::str>(orders)) return ParseOrderRange(orders.cast<std::string>(), "orders");
  if (py::isinstance<py::int_>(orders))
    return ParseOrderRange(std::to_string(orders.cast<long>()), "orders");
  if (py::isinstance<py::sequence>(orders) && py::len(orders) == 2) {
    const auto seq = orders.cast<py::sequence>();
    if (py::isinstance<py::int_>(seq[0]) && py::isinstance<py::int_>(seq[1]))
      return ParseOrderRange(
          std::to_string(seq[0].cast<long>()) + ":" + std::to_string(seq[1].cast<long>()),
          "orders");
  }
  throw InputError("orders must be 'ZMIN:ZMAX', an int or a pair of ints");
}

int ChannelFrom(const py::object& channel, const std::vector<std::string>& names, int count,
                const std::string& what) {
  std::string text;
  if (py::isinstance<py::str>(channel)) {
    text = channel.cast<std::string>();
  } else if (py::isinstance<py::int_>(channel) && !py::isinstance<py::bool_>(channel)) {
    text = std::to_string(channel.cast<long>());
  } else {
    throw InputError(what + " must be a channel index (int) or name (str)");
  }
  return ResolveChannel(text, names, count, what, what);
}

double PeriodicTime(double t, double period, const std::string& what) {
  if (!std::isfinite(t)) throw InputError(what + ": t must be finite");
  if (t >= 0 && t < period) return t;
  const double r = std::fmod(t, period);
  return r < 0 ? r + period : r;
}

}  // namespace ltp::python
