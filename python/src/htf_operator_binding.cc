// ltp.HarmonicTransferFunction: the HTF as an operator (MIMO, any complex s) with its H∞ and
// H2 norms, each by two routes (ltp/htf/harmonic_transfer_function.h).
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <tuple>

#include "binding.h"
#include "diagnostic_properties.h"
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

// ResponseOrbitSweep as a dict: per-frequency × per-order arrays, the routes, the verdict.
py::dict OrbitSweepDict(const OrbitSweep& r) {
  const py::ssize_t nf = static_cast<py::ssize_t>(r.orbits.size());
  const py::ssize_t nz = static_cast<py::ssize_t>(r.max_order - r.min_order + 1);
  auto grid = [&](auto value) {
    using T = decltype(value(r.orbits[0][0], 0, 0));
    py::array_t<T> a({nf, nz});
    for (py::ssize_t i = 0; i < nf; ++i)
      for (py::ssize_t k = 0; k < nz; ++k)
        a.mutable_at(i, k) = value(r.orbits[i][k], static_cast<size_t>(i), static_cast<size_t>(k));
    return a;
  };
  py::list sense;
  for (const auto& row : r.sense) {
    py::list names;
    for (OrbitSense s : row) names.append(std::string(ToString(s)));
    sense.append(names);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  py::array_t<std::int64_t> order(nz);
  for (py::ssize_t k = 0; k < nz; ++k) order.mutable_at(k) = r.min_order + k;
  py::dict d;
  d["omega"] = RealArray(r.omegas);
  d["order"] = order;
  d["frequency"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.frequency; });
  d["x"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.x; });
  d["y"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.y; });
  d["forward"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.orbit.forward; });
  d["backward"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.orbit.backward; });
  d["semi_major"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.orbit.semi_major; });
  d["semi_minor"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.orbit.semi_minor; });
  d["tilt"] = grid([](const ResponseOrbit& o, size_t, size_t) { return o.orbit.tilt; });
  d["error_estimate"] = grid([&](const ResponseOrbit&, size_t i, size_t k) {
    return r.error_estimate.empty() ? nan : r.error_estimate[i][k];
  });
  d["sense"] = sense;
  d["route"] = std::string(ToString(r.route));
  d["check_route"] =
      r.check_route ? py::object(py::str(std::string(ToString(*r.check_route)))) : py::none();
  d["ok"] = r.ok;
  d["failure"] = r.failure;
  d["diagnostics"] = Texts(r.diagnostics);
  return d;
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
      .def_property_readonly("diagnostics", DiagnosticTexts(&HinfNorm::diagnostics),
                             "notes, one sentence each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&HinfNorm::diagnostics),
                             kDiagnosticCodesDoc)
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
      .def_property_readonly("diagnostics", DiagnosticTexts(&H2Norm::diagnostics),
                             "notes, one sentence each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&H2Norm::diagnostics),
                             kDiagnosticCodesDoc)
      .def("__repr__", [](const H2Norm& r) {
        return NormRepr("H2Norm", r.value, r.error_estimate, r.ok, r.failure);
      });
}

// One array per field of the zeros, in the result's order.
py::array_t<Complex> ComplexZeroColumn(const TransmissionZeros& r,
                                       Complex (*field)(const TransmissionZero&)) {
  std::vector<Complex> v;
  for (const TransmissionZero& z : r.zeros) v.push_back(field(z));
  return ComplexArray(v);
}

py::array_t<double> RealZeroColumn(const TransmissionZeros& r,
                                   double (*field)(const TransmissionZero&)) {
  std::vector<double> v;
  for (const TransmissionZero& z : r.zeros) v.push_back(field(z));
  return RealArray(v);
}

void BindZerosResult(py::module_& m) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  py::class_<TransmissionZeros>(m, "TransmissionZeros", R"doc(
The transmission zeros of a square periodic system (HarmonicTransferFunction.zeros): the s for
which u = e^{st} p_u(t), x = e^{st} p_x(t) (p_u, p_x T-periodic) give y ≡ 0, defined modulo jΩp.
Found as the generalized eigenvalues of the truncated harmonic pencil (route 'hill', converged
from N to N + Δ) and, where it applies, checked by the Floquet exponents of the zero dynamics
(check_route 'zero-dynamics' for D(t) invertible, 'relative-degree-one' for D = 0 with C(t)B(t)
invertible). The arrays are parallel, one entry per zero.)doc")
      .def_readonly("ok", &TransmissionZeros::ok,
                    "the truncation converged and the check route (where it applies) agrees")
      .def_readonly("failure", &TransmissionZeros::failure, "why ok is False ('' when ok)")
      .def_property_readonly(
          "zeros",
          [](const TransmissionZeros& r) {
            return ComplexZeroColumn(r, [](const TransmissionZero& z) { return z.value; });
          },
          "the zeros in the strip −Ωp/2 < Im z <= Ωp/2 (complex128, 1/s), by `route`")
      .def_property_readonly(
          "centred",
          [](const TransmissionZeros& r) {
            return ComplexZeroColumn(r, [](const TransmissionZero& z) { return z.centred; });
          },
          "the member z + jmΩp of each zero whose direction is centred on harmonic 0 "
          "(complex128)")
      .def_property_readonly(
          "hill_values",
          [](const TransmissionZeros& r) {
            return ComplexZeroColumn(r, [](const TransmissionZero& z) { return z.hill_value; });
          },
          "the Hill route's value of each zero at N + Δ, centred branch (complex128)")
      .def_property_readonly(
          "error_estimates",
          [](const TransmissionZeros& r) {
            return RealZeroColumn(r, [](const TransmissionZero& z) { return z.error_estimate; });
          },
          "absolute estimate per zero (1/s): the N vs N + Δ change, or the disagreement with the "
          "check route beyond its own estimate")
      .def_property_readonly(
          "truncation_changes",
          [](const TransmissionZeros& r) {
            return RealZeroColumn(r, [](const TransmissionZero& z) { return z.truncation_change; });
          },
          "|z(N) − z(N + Δ)| modulo jΩp per zero (1/s; inf: no partner at N)")
      .def_property_readonly(
          "centroids",
          [](const TransmissionZeros& r) {
            return RealZeroColumn(r, [](const TransmissionZero& z) { return z.centroid; });
          },
          "energy centroid of each zero's direction over the harmonics (|c| <= 1/2)")
      .def_property_readonly(
          "check_values",
          [nan](const TransmissionZeros& r) {
            std::vector<Complex> v;
            for (const TransmissionZero& z : r.zeros) v.push_back(z.check_value.value_or(nan));
            return ComplexArray(v);
          },
          "the check route's matching exponent per zero (complex128; NaN without a check)")
      .def_property_readonly(
          "check_error_estimates",
          [](const TransmissionZeros& r) {
            std::vector<double> v;
            for (const TransmissionZero& z : r.zeros) v.push_back(OrNaN(z.check_error_estimate));
            return RealArray(v);
          },
          "the check route's own estimate per zero (1/s; NaN without a check)")
      .def_property_readonly(
          "route", [](const TransmissionZeros& r) { return std::string(ToString(r.route)); },
          "whose values are reported: 'hill', or the check route's name when its estimates "
          "are the smaller ones")
      .def_property_readonly(
          "check_route",
          [](const TransmissionZeros& r) -> std::optional<std::string> {
            if (!r.check_route) return std::nullopt;
            return std::string(ToString(*r.check_route));
          },
          "'zero-dynamics', 'relative-degree-one', or None when no check route applies")
      .def_property_readonly(
          "check_zeros", [](const TransmissionZeros& r) { return ComplexArray(r.check_zeros); },
          "every zero the check route found, on its own branches (complex128)")
      .def_readonly("harmonics", &TransmissionZeros::harmonics, "the truncation N")
      .def_readonly("delta", &TransmissionZeros::delta, "Δ (the values are at N + Δ)")
      .def_readonly("pencil_size", &TransmissionZeros::pencil_size, "rows of the pencil at N + Δ")
      .def_readonly("infinite_eigenvalues", &TransmissionZeros::infinite_eigenvalues,
                    "generalized eigenvalues at N + Δ taken as infinite")
      .def_readonly("uncentred_eigenvalues", &TransmissionZeros::uncentred_eigenvalues,
                    "finite eigenvalues at N + Δ not centred on harmonic 0")
      .def_readonly("elapsed_s", &TransmissionZeros::elapsed_s, "wall time of the call (s)")
      .def_property_readonly("diagnostics", DiagnosticTexts(&TransmissionZeros::diagnostics),
                             "notes, one sentence each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&TransmissionZeros::diagnostics),
                             kDiagnosticCodesDoc)
      .def("__repr__", [](const TransmissionZeros& r) {
        std::ostringstream s;
        s << "<TransmissionZeros " << r.zeros.size() << " zeros, N = " << r.harmonics
          << (r.check_route ? ", checked by " + std::string(ToString(*r.check_route)) : "")
          << (r.ok ? "" : " (not ok: " + r.failure + ")") << ">";
        return s.str();
      });
}

using HtfClass = py::class_<PyHtf>;

// Evaluations of the operator: H_z(s), response orbits, sections.
void AddEvaluations(HtfClass& htf) {
  htf.def(
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
          "orbit_sweep",
          [](const PyHtf& h, const std::vector<Real>& omegas, const std::vector<Complex>& input,
             const py::object& x, const py::object& y, const py::object& orders,
             const std::optional<std::string>& route) {
            const SystemLabels& labels = h.system.system.labels();
            const int outputs = h.system.system.outputs();
            OrbitSweepOptions o;
            std::tie(o.min_order, o.max_order) = OrdersFrom(orders);
            if (route) o.route = RouteFrom(*route);
            o.threads = 1;  // keeps every evaluation on the thread that holds the GIL
            std::vector<double> w;
            for (const Real& omega : omegas) w.push_back(omega.value);
            const Eigen::VectorXcd u = Eigen::Map<const Eigen::VectorXcd>(
                input.data(), static_cast<Eigen::Index>(input.size()));
            return OrbitSweepDict(
                ResponseOrbitSweep(*h.htf, w, u, ChannelFrom(x, labels.outputs, outputs, "x"),
                                   ChannelFrom(y, labels.outputs, outputs, "y"), o));
          },
          py::arg("omegas"), py::arg("input"), py::kw_only(), py::arg("x") = 0, py::arg("y") = 1,
          py::arg("orders") = py::make_tuple(-2, 2), py::arg("route") = py::none(),
          "orbits at every frequency of omegas (rad/s) on this one set-up, each value checked by "
          "the other route (what `ltp orbit` prints): dict with omega, order (int64), and "
          "(frequencies, orders) arrays frequency, x, y, forward, backward, semi_major, "
          "semi_minor, tilt, error_estimate (|ΔX| + |ΔY| between the routes; NaN unchecked); "
          "sense (FW, BW, line or still per value, judged against its uncertainty), route and "
          "check_route, ok (the routes agree), failure, diagnostics (e.g. an unstable system's "
          "orbits are no steady state). route: None (modal unless unreliable), modal or hill.")
      .def(
          "section",
          [](const PyHtf& h, Complex s, int harmonics, const std::string& route) {
            return h.htf->Section(s, harmonics, RouteFrom(route));
          },
          py::arg("s"), py::kw_only(), py::arg("harmonics") = 2, py::arg("route") = "modal",
          "The operator's section with input and output harmonics −K…K: complex array "
          "((2K+1)·outputs, (2K+1)·inputs), block (v, u) = H_{v−u}(s + juΩp).");
}

// The norms and the transmission zeros (each runs without the GIL).
void AddNormsAndZeros(HtfClass& htf) {
  const ZerosOptions zeros;
  const NormOptions norm;
  htf.def(
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
      .def(
          "zeros",
          [](const PyHtf& h, double tol, int harmonics, int max_harmonics, int max_pencil_size,
             bool check, double rel_tol) {
            ZerosOptions o;
            o.tol = tol;
            o.harmonics = harmonics;
            o.max_harmonics = max_harmonics;
            o.max_pencil_size = max_pencil_size;
            o.check = check;
            o.floquet.integrator.rel_tol = rel_tol;
            o.floquet.threads = AnalysisThreads(h.system, 0);
            o.Validate();
            return WithoutGil(h.system, [&] { return h.htf->Zeros(o); });
          },
          py::kw_only(), py::arg("tol") = zeros.tol, py::arg("harmonics") = zeros.harmonics,
          py::arg("max_harmonics") = zeros.max_harmonics,
          py::arg("max_pencil_size") = zeros.max_pencil_size, py::arg("check") = zeros.check,
          py::arg("rel_tol") = zeros.floquet.integrator.rel_tol,
          "The transmission zeros of a square system (a TransmissionZeros): the generalized "
          "eigenvalues of the harmonic pencil at truncation N (0 = automatic, grown until every "
          "zero moves by less than tol · max(|z|, Ωp) from N to N + Δ), checked by the zero "
          "dynamics' Floquet exponents (at integrator tolerance rel_tol) where D(t) is "
          "invertible or D = 0 with C(t)B(t) invertible. Raises InputError for a system with "
          "more inputs than outputs or the reverse. Runs without the GIL.");
}

void AddProperties(HtfClass& htf) {
  htf.def_property_readonly(
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
          "diagnostics", [](const PyHtf& h) { return Texts(h.htf->diagnostics()); },
          "notes of the decomposition, the modal form and the Hill route")
      .def_property_readonly(
          "diagnostic_codes", [](const PyHtf& h) { return CodeNames(h.htf->diagnostics()); },
          kDiagnosticCodesDoc)
      .def("__repr__", [](const PyHtf& h) {
        return "<HarmonicTransferFunction " + std::to_string(h.system.system.states()) +
               " states, " + std::to_string(h.system.system.inputs()) + " inputs, " +
               std::to_string(h.system.system.outputs()) + " outputs>";
      });
}

}  // namespace

void BindHtfOperator(py::module_& m) {
  BindNormResults(m);
  BindZerosResult(m);
  HtfClass htf(m, "HarmonicTransferFunction", R"doc(
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
    h.hinf().value, h.h2().value)doc");
  htf.def(py::init([](const System& system, double rel_tol, int hill_harmonics, int probe_orders,
                      int threads) {
            return MakeHtf(system, rel_tol, hill_harmonics, probe_orders, threads);
          }),
          py::arg("system"), py::kw_only(), py::arg("rel_tol") = IntegratorOptions{}.rel_tol,
          py::arg("hill_harmonics") = 0, py::arg("probe_orders") = 4, py::arg("threads") = 0);
  AddEvaluations(htf);
  AddNormsAndZeros(htf);
  AddProperties(htf);
}

}  // namespace ltp::python
