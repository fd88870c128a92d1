// ltp.HarmonicTransferFunction: the HTF as an operator (MIMO, any complex s) with its H∞ and
// H2 norms, each by two routes (ltp/htf/harmonic_transfer_function.h).
#include <cmath>
#include <iomanip>
#include <sstream>

#include "binding.h"
#include "ltp/core/error.h"
#include "ltp/htf/harmonic_transfer_function.h"
#include "ltp/htf/response_orbit.h"

namespace ltp::python {

namespace {

/// The operator and the Python system it belongs to (whose callables it may call again).
struct PyHtf {
  System system;
  std::shared_ptr<const HarmonicTransferFunction> htf;
};

// ResponseOrbits as a dict of numpy arrays, one entry per order.
py::dict OrbitsDict(const std::vector<ResponseOrbit>& orbits) {
  std::vector<double> frequency, forward, backward, major, minor, tilt;
  std::vector<Complex> x, y;
  py::array_t<std::int64_t> order(static_cast<py::ssize_t>(orbits.size()));
  for (size_t k = 0; k < orbits.size(); ++k) {
    const ResponseOrbit& o = orbits[k];
    order.mutable_at(static_cast<py::ssize_t>(k)) = o.order;
    frequency.push_back(o.frequency);
    x.push_back(o.x);
    y.push_back(o.y);
    forward.push_back(o.orbit.forward);
    backward.push_back(o.orbit.backward);
    major.push_back(o.orbit.semi_major);
    minor.push_back(o.orbit.semi_minor);
    tilt.push_back(o.orbit.tilt);
  }
  return py::dict(py::arg("order") = order, py::arg("frequency") = RealArray(frequency),
                  py::arg("x") = ComplexArray(x), py::arg("y") = ComplexArray(y),
                  py::arg("forward") = RealArray(forward),
                  py::arg("backward") = RealArray(backward),
                  py::arg("semi_major") = RealArray(major),
                  py::arg("semi_minor") = RealArray(minor), py::arg("tilt") = RealArray(tilt));
}

OperatorRoute RouteFrom(const std::string& name) {
  const auto route = ParseOperatorRoute(name);
  if (!route) throw InputError("route must be modal or hill, not '" + name + "'");
  return *route;
}

PyHtf MakeHtf(const System& system, double rel_tol, int hill_harmonics, int probe_orders,
              int threads) {
  if (system.system.inputs() < 1 || system.system.outputs() < 1)
    throw InputError("the system has no inputs or no outputs: no transfer function");
  HtfOperatorOptions o;
  o.floquet.integrator.rel_tol = rel_tol;
  o.floquet.threads = AnalysisThreads(system, threads);
  o.floquet.on_long_work = WarnLongWork("HarmonicTransferFunction");
  o.hill.harmonics = hill_harmonics;
  o.probe_orders = probe_orders;
  return PyHtf{system, WithoutGil(system, [&] {
                 return std::make_shared<const HarmonicTransferFunction>(system.system, o);
               })};
}

NormOptions NormOptionsFrom(const System& system, double rel_tol, int grid_points,
                            int max_section_harmonics, int max_lyapunov_states, int threads) {
  NormOptions o;
  o.rel_tol = rel_tol;
  o.grid_points = grid_points;
  o.max_section_harmonics = max_section_harmonics;
  o.max_lyapunov_states = max_lyapunov_states;
  o.threads = AnalysisThreads(system, threads);
  o.Validate();
  return o;
}

std::string NormRepr(const char* name, double value, double estimate, bool ok,
                     const std::string& failure) {
  std::ostringstream s;
  s << std::setprecision(10) << "<" << name << " " << value << " ± " << std::setprecision(2)
    << estimate << (ok ? "" : " (not ok: " + failure + ")") << ">";
  return s.str();
}

void BindNormResults(py::module_& m) {
  py::class_<HinfNorm>(m, "HinfNorm", R"doc(
‖G‖∞ of a periodic system (HarmonicTransferFunction.hinf): the L2-induced gain, by a frequency
search over sections of the operator (a lower bound) and a bisection on γ with the periodic
Hamiltonian's Floquet exponents (a bracket). ok when both ran and agree.)doc")
      .def_readonly("ok", &HinfNorm::ok, "both routes ran and agree within the estimate")
      .def_readonly("failure", &HinfNorm::failure, "why ok is False ('' when ok)")
      .def_readonly("value", &HinfNorm::value, "‖G‖∞ (inf for an unstable system)")
      .def_readonly("error_estimate", &HinfNorm::error_estimate,
                    "absolute: half the bracket plus the routes' disagreement")
      .def_readonly("lower", &HinfNorm::lower,
                    "the Hamiltonian has exponents on the imaginary axis at this level")
      .def_readonly("upper", &HinfNorm::upper, "the Hamiltonian has none at this level")
      .def_readonly("hamiltonian_analyses", &HinfNorm::hamiltonian_analyses,
                    "Floquet analyses of the Hamiltonian system (bisection steps)")
      .def_readonly("search_value", &HinfNorm::search_value,
                    "the frequency search's largest σmax of a section (a lower bound)")
      .def_readonly("peak_omega", &HinfNorm::peak_omega,
                    "excitation frequency (rad/s) of that largest value")
      .def_readonly("section_harmonics", &HinfNorm::section_harmonics,
                    "K of the section (harmonics −K…K) the search converged at")
      .def_readonly("search_points", &HinfNorm::search_points, "sections evaluated")
      .def_readonly("elapsed_s", &HinfNorm::elapsed_s, "wall time of the whole call (s)")
      .def_readonly("diagnostics", &HinfNorm::diagnostics, "notes, one sentence each")
      .def("__repr__", [](const HinfNorm& r) {
        return NormRepr("HinfNorm", r.value, r.error_estimate, r.ok, r.failure);
      });
  py::class_<H2Norm>(m, "H2Norm", R"doc(
‖G‖₂ of a periodic system (HarmonicTransferFunction.h2), by the Floquet modal form integrated
over frequency in closed form and by the periodic Lyapunov differential equation. ok when the
routes ran (or the modal one alone, said in diagnostics) and agree.)doc")
      .def_readonly("ok", &H2Norm::ok, "the routes ran and agree within the estimate")
      .def_readonly("failure", &H2Norm::failure, "why ok is False ('' when ok)")
      .def_readonly(
          "value", &H2Norm::value,
          "‖G‖₂: the value of the route with the smaller own estimate (inf for an unstable "
          "system or D ≠ 0)")
      .def_readonly("error_estimate", &H2Norm::error_estimate,
                    "absolute: the chosen route's estimate, or the disagreement beyond the other's")
      .def_readonly("modal_value", &H2Norm::modal_value, "the modal route's value")
      .def_property_readonly(
          "lyapunov_value", [](const H2Norm& r) { return r.lyapunov_value; },
          "the Lyapunov route's value (None when skipped)")
      .def_readonly("elapsed_s", &H2Norm::elapsed_s, "wall time of the whole call (s)")
      .def_readonly("diagnostics", &H2Norm::diagnostics, "notes, one sentence each")
      .def("__repr__", [](const H2Norm& r) {
        return NormRepr("H2Norm", r.value, r.error_estimate, r.ok, r.failure);
      });
}

}  // namespace

void BindHtfOperator(py::module_& m) {
  BindNormResults(m);
  const NormOptions norm;
  py::class_<PyHtf>(m, "HarmonicTransferFunction", R"doc(
The harmonic transfer function of a periodic system as an operator: for an input
u(t) = Σ_u U_u e^{(s + juΩp)t} the output is y(t) = Σ_v Y_v e^{(s + jvΩp)t}, Y_v = Σ_u 𝓗_{v,u}(s) U_u,
𝓗_{v,u}(s) = H_{v−u}(s + juΩp). Set up once (a Floquet decomposition and the Hill route's
truncation; runs without the GIL), then evaluated at any complex s, MIMO.

  rel_tol         integrator tolerance of the Floquet decomposition
  hill_harmonics  truncation N of the Hill route (0 = automatic)
  probe_orders    the Hill truncation is chosen for orders −probe_orders…probe_orders

    h = ltp.HarmonicTransferFunction(sys)
    h.partial(-0.1 + 1j, orders=(-2, 2))      # H_z(s), shape (5, outputs, inputs)
    h.section(1j, harmonics=3)                # the operator's section −3…3
    h.orbits(0.7, [1, -1j], x="x", y="y")     # an unbalance orbit, order by order
    h.hinf().value, h.h2().value)doc")
      .def(py::init([](const System& system, double rel_tol, int hill_harmonics, int probe_orders,
                       int threads) {
             return MakeHtf(system, rel_tol, hill_harmonics, probe_orders, threads);
           }),
           py::arg("system"), py::kw_only(), py::arg("rel_tol") = IntegratorOptions{}.rel_tol,
           py::arg("hill_harmonics") = 0, py::arg("probe_orders") = 4, py::arg("threads") = 0)
      .def(
          "partial",
          [](const PyHtf& h, Complex s, const py::object& orders, const std::string& route) {
            const auto [z0, z1] = OrdersFrom(orders);
            const PartialFrfs H = h.htf->Partial(s, z0, z1, RouteFrom(route));
            return ComplexStack(H, h.system.system.outputs(), h.system.system.inputs());
          },
          py::arg("s"), py::kw_only(), py::arg("orders") = py::make_tuple(-2, 2),
          py::arg("route") = "modal",
          "H_z(s) for z in orders ('ZMIN:ZMAX', an int or a pair) at the complex frequency s "
          "(s = jω on the frequency axis): complex array (orders, outputs, inputs). route: "
          "modal or hill.")
      .def(
          "orbits",
          [](const PyHtf& h, Real omega, const std::vector<Complex>& input, const py::object& x,
             const py::object& y, const py::object& orders, const std::string& route) {
            const SystemLabels& labels = h.system.system.labels();
            const int outputs = h.system.system.outputs();
            const int xi = ChannelFrom(x, labels.outputs, outputs, "x");
            const int yi = ChannelFrom(y, labels.outputs, outputs, "y");
            const auto [z0, z1] = OrdersFrom(orders);
            const Eigen::VectorXcd u = Eigen::Map<const Eigen::VectorXcd>(
                input.data(), static_cast<Eigen::Index>(input.size()));
            return OrbitsDict(
                ResponseOrbits(*h.htf, omega.value, u, xi, yi, z0, z1, RouteFrom(route)));
          },
          py::arg("omega"), py::arg("input"), py::kw_only(), py::arg("x") = 0, py::arg("y") = 1,
          py::arg("orders") = py::make_tuple(-2, 2), py::arg("route") = "modal",
          "The orbit of outputs (x, y) (names or indices) under the input Re(input e^{jωt}), one "
          "complex weight per input (an unbalance on (fx, fy): [1, -1j], i.e. fx = cos ωt, "
          "fy = sin ωt), order by order at ω + zΩp: dict of numpy arrays order (int64), "
          "frequency (rad/s), x, y (complex phasors), forward, backward (radii of the circles "
          "turning with / against the rotor), semi_major, semi_minor, tilt (rad, from x towards "
          "y). One analysis serves every order and input.")
      .def(
          "section",
          [](const PyHtf& h, Complex s, int harmonics, const std::string& route) {
            return h.htf->Section(s, harmonics, RouteFrom(route));
          },
          py::arg("s"), py::kw_only(), py::arg("harmonics") = 2, py::arg("route") = "modal",
          "The operator's section with input and output harmonics −K…K: complex array "
          "((2K+1)·outputs, (2K+1)·inputs), block (v, u) = H_{v−u}(s + juΩp).")
      .def(
          "hinf",
          [](const PyHtf& h, double rel_tol, int grid_points, int max_section_harmonics,
             int threads) {
            const NormOptions o =
                NormOptionsFrom(h.system, rel_tol, grid_points, max_section_harmonics, 0, threads);
            return WithoutGil(h.system, [&] { return h.htf->Hinf(o); });
          },
          py::kw_only(), py::arg("rel_tol") = norm.rel_tol,
          py::arg("grid_points") = norm.grid_points,
          py::arg("max_section_harmonics") = norm.max_section_harmonics, py::arg("threads") = 0,
          "‖G‖∞ by two routes (an HinfNorm); runs without the GIL.")
      .def(
          "h2",
          [norm](const PyHtf& h, double rel_tol, int max_lyapunov_states) {
            const NormOptions o =
                NormOptionsFrom(h.system, rel_tol, norm.grid_points, norm.max_section_harmonics,
                                max_lyapunov_states, 0);
            return WithoutGil(h.system, [&] { return h.htf->H2(o); });
          },
          py::kw_only(), py::arg("rel_tol") = norm.rel_tol,
          py::arg("max_lyapunov_states") = norm.max_lyapunov_states,
          "‖G‖₂ by two routes (an H2Norm); runs without the GIL.")
      .def_property_readonly(
          "exponents",
          [](const PyHtf& h) {
            std::vector<Complex> e;
            for (const FloquetMode& mode : h.htf->floquet().modes) e.push_back(mode.exponent);
            return ComplexArray(e);
          },
          "the Floquet exponents λ_k of the decomposition (1/s)")
      .def_property_readonly(
          "omega_p", [](const PyHtf& h) { return h.system.system.omega(); },
          "the fundamental Ωp = 2π/T (rad/s)")
      .def_property_readonly(
          "hill_harmonics", [](const PyHtf& h) { return h.htf->hill_harmonics(); },
          "the Hill route's truncation N")
      .def_property_readonly(
          "ok", [](const PyHtf& h) { return h.htf->ok(); },
          "the modal form is reliable and the Hill truncation converged")
      .def_property_readonly(
          "diagnostics", [](const PyHtf& h) { return h.htf->diagnostics(); },
          "notes of the decomposition, the modal form and the Hill route")
      .def("__repr__", [](const PyHtf& h) {
        return "<HarmonicTransferFunction " + std::to_string(h.system.system.states()) +
               " states, " + std::to_string(h.system.system.inputs()) + " inputs, " +
               std::to_string(h.system.system.outputs()) + " outputs>";
      });
}

}  // namespace ltp::python
