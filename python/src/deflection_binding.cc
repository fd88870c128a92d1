// ltp.deflection: a mode's deflected structure over a period (ltp/studies/mode_deflection.h),
// what `ltp floquet --deflection-csv` writes, as numpy arrays.
#include <optional>

#include "binding.h"
#include "ltp/core/error.h"
#include "ltp/studies/mode_deflection.h"

namespace ltp::python {
namespace {

// Per body: (frames, nodes, 3) positions of `which` (rest, moved or standing) over the frames.
py::dict Positions(const ModeDeflections& d, const ModeDeflection& m,
                   std::vector<Eigen::Matrix3Xd> DeflectionFrame::*which) {
  py::dict out;
  for (size_t b = 0; b < d.bodies.size(); ++b) {
    const py::ssize_t frames = static_cast<py::ssize_t>(m.frames.size());
    const py::ssize_t nodes = m.frames.front().rest[b].cols();
    py::array_t<double> a({frames, nodes, py::ssize_t{3}});
    auto view = a.mutable_unchecked<3>();
    for (py::ssize_t f = 0; f < frames; ++f) {
      const Eigen::Matrix3Xd& p = (m.frames[static_cast<size_t>(f)].*which)[b];
      for (py::ssize_t j = 0; j < nodes; ++j)
        for (py::ssize_t i = 0; i < 3; ++i) view(f, j, i) = p(i, j);
    }
    out[py::str(d.bodies[b])] = a;
  }
  return out;
}

py::dict LtpDeflection(const System& system, const FloquetResult& result,
                       const std::optional<std::vector<int>>& modes, double amplitude) {
  if (!system.scene || !system.scene->geometry)
    throw InputError(
        "deflection: this system has no structure to draw (ltp.scene('tower-rotor') has one); "
        "FloquetResult.mode_samples holds the mode shapes of any system");
  ModeDeflectionOptions options;
  options.amplitude = amplitude;
  const ModeDeflections d = DeflectModes(system.scene->geometry(system.parameters), result,
                                         modes.value_or(std::vector<int>{}), options);
  py::list out_modes;
  for (const ModeDeflection& m : d.modes) {
    py::dict one;
    one["mode"] = m.mode;
    one["exponent"] = m.exponent;
    one["description"] = m.description;
    one["scale"] = m.scale;
    one["rest"] = Positions(d, m, &DeflectionFrame::rest);
    one["moved"] = Positions(d, m, &DeflectionFrame::moved);
    one["standing"] = Positions(d, m, &DeflectionFrame::standing);
    out_modes.append(one);
  }
  py::dict out;
  out["axes"] = d.axes;
  out["bodies"] = d.bodies;
  out["t"] = RealArray(result.sample_times);
  out["modes"] = out_modes;
  return out;
}

}  // namespace

void BindDeflection(py::module_& m) {
  m.def("deflection", &LtpDeflection, py::arg("system"), py::arg("result"), py::kw_only(),
        py::arg("modes") = py::none(), py::arg("amplitude") = ModeDeflectionOptions{}.amplitude,
        R"doc(
Each mode's deflected structure over one period, for scenes that draw one (tower-rotor): the
free motion Re(e^{λt} ξ(t)) of the mode carried to the structure's nodes at the result's mode
sample times (`ltp floquet --deflection-csv`). `result` is ltp.floquet(system); `modes` are
indices into result.exponents (default: every mode); `amplitude` is the largest node
displacement as a fraction of the structure's size.

Returns {axes, bodies, t, modes}: modes[i] = {mode, exponent, description, scale, rest, moved,
standing}, where rest[body], moved[body] and standing[body] are arrays (len(t), nodes, 3) of
positions in m: at rest and deflected as the structure turns, and deflected on the structure as
it stands at t = 0 (the blades stand still and show their own flap and lag).

    s = ltp.scene("tower-rotor")
    d = ltp.deflection(s, ltp.floquet(s), modes=[0])
    d["modes"][0]["moved"]["blade1"][:, -1]   # blade 1's tip over the period)doc");
}

}  // namespace ltp::python
