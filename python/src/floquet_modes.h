#pragma once
// The per-mode arrays both routes report (FloquetResult and HillResult hold the same
// FloquetMode structs), computed as `ltp floquet --json` prints them.
#include <cmath>

#include "binding.h"
#include "ltp/floquet/floquet.h"

namespace ltp::python {

template <class Result, class Class>
void BindModeArrays(Class& c) {
  auto real = [](auto field) {
    return [field](const Result& r) {
      py::array_t<double> a(static_cast<py::ssize_t>(r.modes.size()));
      for (size_t k = 0; k < r.modes.size(); ++k)
        a.mutable_at(static_cast<py::ssize_t>(k)) = field(r.modes[k]);
      return a;
    };
  };
  c.def_property_readonly(
       "exponents", [](const Result& r) { return ComplexArray(Exponents(r.modes)); },
       "Floquet exponents λ_k (1/s), complex")
      .def_property_readonly(
          "log_multipliers",
          [](const Result& r) {
            std::vector<Complex> v;
            for (const FloquetMode& m : r.modes) v.push_back(m.log_multiplier);
            return ComplexArray(v);
          },
          "log ρ_k = log|ρ_k| + j arg ρ_k, arg in (−π, π]: exact where ρ under- or overflows")
      .def_property_readonly(
          "multipliers",
          [](const Result& r) {
            std::vector<Complex> v;
            for (const FloquetMode& m : r.modes) {
              // |ρ| = e^{log|ρ|}, overflowing to inf and underflowing to 0 on purpose (as the CLI).
              const double mag =
                  m.log_multiplier.real() > 709.78 ? INFINITY : std::exp(m.log_multiplier.real());
              v.emplace_back(mag * std::cos(m.log_multiplier.imag()),
                             mag * std::sin(m.log_multiplier.imag()));
            }
            return ComplexArray(v);
          },
          "Floquet multipliers ρ_k = exp(λ_k T), complex")
      .def_property_readonly("frequencies_hz",
                             real([](const FloquetMode& m) { return m.frequency_hz; }),
                             "Im λ_k / 2π (Hz)")
      .def_property_readonly("damping_ratios",
                             real([](const FloquetMode& m) { return m.damping_ratio; }),
                             "−Re λ_k / |λ_k|")
      .def_property_readonly(
          "branches",
          [](const Result& r) {
            py::array_t<std::int64_t> a(static_cast<py::ssize_t>(r.modes.size()));
            for (size_t k = 0; k < r.modes.size(); ++k)
              a.mutable_at(static_cast<py::ssize_t>(k)) = r.modes[k].branch;
            return a;
          },
          "m in λ = Log(ρ)/T + j m Ωp")
      .def_property_readonly("central_weights",
                             real([](const FloquetMode& m) { return m.central_weight; }),
                             "fraction of the mode shape's Fourier energy on harmonic 0")
      .def_property_readonly("branch_margins",
                             real([](const FloquetMode& m) { return m.branch_margin; }),
                             "distance of the energy centroid from a branch tie (0.5 clean, 0 tie)")
      .def_property_readonly("eigenvector_residuals",
                             real([](const FloquetMode& m) { return m.eigvec_residual; }),
                             "cyclic residual of each periodic eigenvector")
      .def_property_readonly(
          "rigid_body",
          [](const Result& r) {
            py::array_t<bool> a(static_cast<py::ssize_t>(r.modes.size()));
            for (size_t k = 0; k < r.modes.size(); ++k)
              a.mutable_at(static_cast<py::ssize_t>(k)) = r.modes[k].rigid_body;
            return a;
          },
          "True for the free rotation of a rigid-body state (left out of the verdict)");
}

}  // namespace ltp::python
