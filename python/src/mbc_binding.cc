// ltp.mbc: the MBC3 table of `ltp mbc --no-floquet` (openfast/mbc3.h) for a notebook. The Floquet
// part is ltp.floquet(ltp.scene(files)), which carries the sampling error in its estimate.
#include <limits>
#include <string>
#include <vector>

#include "binding.h"
#include "diagnostic_properties.h"
#include "ltp/core/error.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"

namespace ltp::python {

namespace {

// One field of every mode, as a numpy array or a list.
template <class T, class Get>
std::vector<T> ModeColumn(const Mbc3Result& r, Get get) {
  std::vector<T> v;
  for (const MbcMode& m : r.modes) v.push_back(get(m));
  return v;
}

// A numeric column as a numpy array (a copy).
template <class T>
py::array_t<T> AsArray(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

// A per-mode vector of every mode as one matrix: a column per mode, a row per MBC state.
Eigen::MatrixXcd PerModeColumns(const Mbc3Result& x, Eigen::VectorXcd MbcMode::*field) {
  Eigen::MatrixXcd v(static_cast<Eigen::Index>(x.states.size()),
                     static_cast<Eigen::Index>(x.modes.size()));
  for (size_t k = 0; k < x.modes.size(); ++k)
    v.col(static_cast<Eigen::Index>(k)) = x.modes[k].*field;
  return v;
}

// One entry per mode, in the order of natural frequency.
void BindMbcModes(py::class_<Mbc3Result>& r) {
  r.def_property_readonly(
       "eigenvalues",
       [](const Mbc3Result& x) {
         return AsArray(
             ModeColumn<std::complex<double>>(x, [](const MbcMode& m) { return m.eigenvalue; }));
       },
       "λ of the averaged MBC state matrix (1/s), Im λ >= 0")
      .def_property_readonly(
          "natural_frequencies_hz",
          [](const Mbc3Result& x) {
            return AsArray(
                ModeColumn<double>(x, [](const MbcMode& m) { return m.natural_frequency_hz; }));
          },
          "|λ|/2π: what ACDC and openfast_toolbox tabulate")
      .def_property_readonly(
          "damped_frequencies_hz",
          [](const Mbc3Result& x) {
            return AsArray(
                ModeColumn<double>(x, [](const MbcMode& m) { return m.damped_frequency_hz; }));
          },
          "Im λ/2π")
      .def_property_readonly(
          "damping_ratios",
          [](const Mbc3Result& x) {
            return AsArray(ModeColumn<double>(x, [](const MbcMode& m) {
              return m.rigid_body ? std::numeric_limits<double>::quiet_NaN() : m.damping_ratio;
            }));
          },
          "−Re λ/|λ| (NaN for the rigid rotation)")
      .def_property_readonly(
          "kinds",
          [](const Mbc3Result& x) {
            return ModeColumn<std::string>(
                x, [](const MbcMode& m) { return std::string(ToString(m.kind)); });
          },
          "'oscillatory', 'real' or 'rigid-body' per mode")
      .def_property_readonly(
          "rigid_body",
          [](const Mbc3Result& x) {
            return ModeColumn<bool>(x, [](const MbcMode& m) { return m.rigid_body; });
          },
          "the rigid rotation of the rotor (left out of max_real_part)")
      .def_property_readonly(
          "whirl",
          [](const Mbc3Result& x) {
            return ModeColumn<py::object>(x, [](const MbcMode& m) -> py::object {
              if (m.whirl.empty()) return py::none();
              return py::str(m.whirl);
            });
          },
          "'forward' or 'backward' for a cyclic mode whose pattern travels with or against the "
          "rotor, else None")
      .def_property_readonly(
          "descriptions",
          [](const Mbc3Result& x) {
            return ModeColumn<std::string>(x, [](const MbcMode& m) { return m.description; });
          },
          "what carries each mode: its participation summed per coordinate family (a "
          "displacement with its rate, a collective, a cosine/sine pair), unit-free")
      .def_property_readonly(
          "eigenvectors",
          [](const Mbc3Result& x) { return PerModeColumns(x, &MbcMode::eigenvector); },
          "complex mode shapes in MBC coordinates (rows: states), one column "
          "per mode, each scaled so "
          "its largest entry is 1 (what one animates; ltp mbc --shapes-csv)")
      .def_property_readonly(
          "participation",
          [](const Mbc3Result& x) { return PerModeColumns(x, &MbcMode::participation); },
          "participation factors v_i·w_i (right and left eigenvectors of A, w·v = 1), one "
          "column per mode, rows as states: unit-free, each column sums to 1; a second-order "
          "DOF's displacement and rate rows add up to its share of the mode's energy "
          "(docs/mode-descriptions.md)");
}

void BindMbcResult(py::module_& m) {
  py::class_<Mbc3Result> r(m, "MbcResult",
                           "The MBC3 eigen-analysis of OpenFAST .lin files at one operating point "
                           "(ltp mbc --no-floquet --json as an object). Modes are sorted by "
                           "natural frequency; each complex pair is listed once.");
  r.def_readonly("applicable", &Mbc3Result::applicable,
                 "False for 1 or 2 blades (reason says why; no modes)")
      .def_readonly("reason", &Mbc3Result::reason, "why MBC does not apply; empty when it does")
      .def_readonly("blades", &Mbc3Result::blades, "number of rotor blades found in the states")
      .def_readonly("rotor_speed", &Mbc3Result::rotor_speed, "mean Ω (rad/s)")
      .def_property_readonly(
          "azimuths", [](const Mbc3Result& x) { return RealArray(x.azimuths); },
          "ψ_k of the files (rad)")
      .def_property_readonly(
          "states",
          [](const Mbc3Result& x) {
            std::vector<std::string> s;
            for (const LinChannel& c : x.states) s.push_back(c.description);
            return s;
          },
          "the MBC state descriptions (collective, cosine, sine per blade family)");
  BindMbcModes(r);
  r.def_property_readonly(
       "A", [](const Mbc3Result& x) { return x.average.A; }, "the averaged MBC state matrix")
      .def_readonly("max_real_part", &Mbc3Result::max_real_part,
                    "max Re λ over the modes that are not rigid-body (1/s)")
      .def_readonly("periodic_part", &Mbc3Result::periodic_part,
                    "max_k ‖A_NR(ψ_k) − mean‖/‖mean‖: what averaging discards (0: isotropic)")
      .def_property_readonly("diagnostics", DiagnosticTexts(&Mbc3Result::diagnostics),
                             "what the transform noticed, one line each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&Mbc3Result::diagnostics),
                             kDiagnosticCodesDoc)
      .def("__repr__", [](const Mbc3Result& x) {
        return "<ltp.MbcResult: " + std::to_string(x.modes.size()) + " modes, " +
               std::to_string(x.blades) + " blades, max Re λ = " + std::to_string(x.max_real_part) +
               " 1/s>";
      });
}

// ltp.mbc: one path or a list of them; the files read and analysed without the GIL.
Mbc3Result LtpMbc(const py::object& files) {
  std::vector<std::string> names;
  if (py::isinstance<py::str>(files)) {
    names.push_back(files.cast<std::string>());
  } else {
    try {
      names = files.cast<std::vector<std::string>>();
    } catch (const py::cast_error&) {
      throw InputError("files must be a path (a folder or one .lin file) or a list of paths");
    }
  }
  py::gil_scoped_release release;
  return Mbc3(ReadLinOperatingPoint(names));
}

void BindMbcFunction(py::module_& m) {
  m.def("mbc", &LtpMbc, py::arg("files"), R"doc(
The MBC3 eigen-analysis of OpenFAST .lin files at one operating point: `ltp mbc FILES
--no-floquet --json` as a function (Bir 2008: each azimuth's matrices in multi-blade
coordinates, averaged, eigenvalues). Natural and damped frequencies, damping, whirl direction
(forward/backward), what carries each mode, complex mode shapes.

The averaging drops the periodic part (periodic_part says how much); the exact answer with
an error estimate that includes the sampling error is ltp.floquet(ltp.scene(files)).

    m = ltp.mbc("tests/data/openfast/nrel5mw-rotating")
    m.natural_frequencies_hz, m.damping_ratios, m.whirl, m.descriptions)doc");
}

}  // namespace

void BindMbc(py::module_& m) {
  BindMbcResult(m);
  BindMbcFunction(m);
}

}  // namespace ltp::python
