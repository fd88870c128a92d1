// ltp.periodic_schur: the real periodic Schur form of a product of factors, and its result.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "binding.h"
#include "ltp/core/error.h"
#include "ltp/floquet/periodic_eigen.h"

namespace ltp::python {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A real (K, n, n) stack, K >= 1, finite: the layout of FloquetResult.segment_factors.
std::vector<Eigen::MatrixXd> FactorsFrom(const py::object& obj) {
  const Array a = Array::ensure(RealValued(
      obj, [] { return std::string("factors"); },
      "the factors of a real product must be real (segment_factors is float64)"));
  if (!a || a.ndim() != 3 || a.shape(0) < 1 || a.shape(1) != a.shape(2)) {
    std::ostringstream s;
    s << "factors must be a real (K, n, n) array with K >= 1, as FloquetResult.segment_factors";
    if (a) {
      s << "; got shape (";
      for (py::ssize_t d = 0; d < a.ndim(); ++d) s << (d ? ", " : "") << a.shape(d);
      s << (a.ndim() == 1 ? ",)" : ")");
    }
    throw InputError(s.str());
  }
  const auto view = a.unchecked<3>();
  std::vector<Eigen::MatrixXd> factors(a.shape(0), Eigen::MatrixXd(a.shape(1), a.shape(2)));
  for (py::ssize_t k = 0; k < a.shape(0); ++k) {
    for (py::ssize_t i = 0; i < a.shape(1); ++i)
      for (py::ssize_t j = 0; j < a.shape(2); ++j) factors[k](i, j) = view(k, i, j);
    if (!factors[k].allFinite())
      throw InputError("factors[" + std::to_string(k) + "] has non-finite entries (NaN or inf)");
  }
  return factors;
}

PeriodicSchurForm LtpPeriodicSchur(const py::object& factors) {
  const std::vector<Eigen::MatrixXd> f = FactorsFrom(factors);
  py::gil_scoped_release release;
  return PeriodicSchurDecomposition(f);
}

// A stack of the result's matrices, None when the decomposition failed.
py::object StackOrNone(const PeriodicSchurForm& s, const std::vector<Eigen::MatrixXd>& m) {
  if (!s.ok) return py::none();
  const int n = m.empty() ? 0 : static_cast<int>(m.front().rows());
  return RealStack(m, n, n);
}

void BindPeriodicSchurForm(py::module_& m) {
  py::class_<PeriodicSchurForm>(m, "PeriodicSchurForm", R"doc(
The real periodic Schur form of a product Φ = F[K-1] ⋯ F[1] F[0] of real n×n factors (the
product is never formed): orthogonal Z[k] and T[k] with

    Z[k+1].T @ F[k] @ Z[k] == T[k]   (k = 0..K-1, Z[K] = Z[0]),

so Z[0].T @ Φ @ Z[0] == T[K-1] ⋯ T[0]. T[K-1] (index quasi_triangular) is quasi-upper-
triangular, a 2×2 diagonal block for each complex pair of multipliers; every other T[k] is
upper triangular; the entries below are exactly 0. From SLICOT (MB03VD, MB03VY, MB03BD
JOB='S'), backward stable. See ltp.periodic_schur.)doc")
      .def_readonly("ok", &PeriodicSchurForm::ok, "the periodic QZ iteration converged")
      .def_property_readonly(
          "failure", [](const PeriodicSchurForm& s) { return s.ok ? std::string() : s.message; },
          "why ok is False (SLICOT's INFO), one sentence; empty when ok")
      .def_property_readonly(
          "warning", [](const PeriodicSchurForm& s) { return s.ok ? s.message : std::string(); },
          "SLICOT's warning (IWARN: multipliers of leading 2×2 blocks may be inaccurate); "
          "usually empty")
      .def_property_readonly(
          "Z", [](const PeriodicSchurForm& s) { return StackOrNone(s, s.z); },
          "Z[0..K-1], orthogonal: float64, shape (K, n, n); None when not ok")
      .def_property_readonly(
          "T", [](const PeriodicSchurForm& s) { return StackOrNone(s, s.t); },
          "T[0..K-1], T[K-1] quasi-upper-triangular, the others upper triangular: float64, "
          "shape (K, n, n); None when not ok")
      .def_readonly("quasi_triangular", &PeriodicSchurForm::quasi_triangular,
                    "the index K-1 of the one quasi-triangular factor")
      .def_property_readonly(
          "log_multipliers",
          [](const PeriodicSchurForm& s) -> py::object {
            if (!s.ok) return py::none();
            return ComplexArray(s.log_values);
          },
          "log ρ of the product in the order of T's diagonal (not sorted), complex128 (n,): "
          "sums of logs of the diagonal entries, so e^{±1000} does not overflow; a 2×2 block "
          "gives its conjugate pair, +arg first; imaginary part in (-π, π]; a zero multiplier "
          "-inf. None when not ok")
      .def("__repr__", [](const PeriodicSchurForm& s) {
        if (!s.ok) return "<ltp.PeriodicSchurForm: failed: " + s.message + ">";
        return "<ltp.PeriodicSchurForm: K = " + std::to_string(s.t.size()) +
               " factors, n = " + std::to_string(s.log_values.size()) + ">";
      });
}

void BindPeriodicSchurFunction(py::module_& m) {
  m.def("periodic_schur", &LtpPeriodicSchur, py::arg("factors"), R"doc(
The real periodic Schur form of the product factors[K-1] ⋯ factors[0] without forming it:
where the monodromy matrix over- or underflows (multipliers e^{±1000}), its factors still hold
it exactly, and this form gives the multipliers as logarithms and the Schur vectors.

  factors   real array (K, n, n), K >= 1, in the layout of FloquetResult.segment_factors
            (factors[i] = Φ(t_{i+1}, t_i), the product last factor leftmost); complex,
            non-finite or wrongly shaped input raises ltp.InputError (a ValueError)

Returns a PeriodicSchurForm: Z and T (float64, (K, n, n)) with
Z[k+1].T @ factors[k] @ Z[k] == T[k] (Z[K] = Z[0]), T[K-1] quasi-triangular, and
log_multipliers (complex128, n, in the order of T's diagonal). Runs without the GIL.

    r = ltp.floquet(ltp.scene("mathieu"), keep_factors=True)
    s = ltp.periodic_schur(r.segment_factors)
    s.log_multipliers / r.period      # the exponents, modulo jΩp
    s.Z[0].T @ r.monodromy @ s.Z[0]   # == the product of s.T, last leftmost)doc");
}

}  // namespace

void BindPeriodicSchur(py::module_& m) {
  BindPeriodicSchurForm(m);
  BindPeriodicSchurFunction(m);
}

}  // namespace ltp::python
