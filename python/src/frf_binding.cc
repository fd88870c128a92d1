// ltp.pfrf and ltp.snapshot: partial FRFs H_z(ω) and the frozen-system comparison.
#include <cmath>

#include "binding.h"
#include "diagnostic_properties.h"
#include "ltp/core/error.h"
#include "ltp/htf/pfrf.h"
#include "ltp/htf/pfrf_model_error.h"
#include "ltp/htf/snapshot.h"

namespace ltp::python {

namespace {

void NeedChannels(const System& s) {
  if (s.system.inputs() < 1 || s.system.outputs() < 1)
    throw InputError("the system has no inputs or no outputs: no FRF to compute");
}

py::dict RouteDict(const RouteRun& run) {
  double worst = 0;
  for (double d : run.deviation) worst = std::max(worst, d);
  py::array_t<std::int64_t> points(static_cast<py::ssize_t>(run.points.size()));
  for (size_t i = 0; i < run.points.size(); ++i)
    points.mutable_at(static_cast<py::ssize_t>(i)) = run.points[i];
  return py::dict(py::arg("route") = std::string(ToString(run.route)), py::arg("points") = points,
                  py::arg("values") =
                      ComplexTable(run.values, run.values.empty() ? 0 : run.values.front().size()),
                  py::arg("deviation") = RealArray(run.deviation),
                  py::arg("own_error") = RealArray(run.own_error),
                  py::arg("max_deviation_from_primary") = worst, py::arg("failures") = run.failures,
                  py::arg("setup_s") = run.setup_s, py::arg("elapsed_s") = run.elapsed_s,
                  py::arg("diagnostics") = Texts(run.diagnostics));
}

// H over excitation frequency and order, with its error estimate.
void BindPfrfValues(py::class_<PfrfResult>& r) {
  r.def_property_readonly(
       "frequencies_hz", [](const PfrfResult& r) { return RealArray(r.frequencies_hz); },
       "excitation frequencies f (Hz)")
      .def_property_readonly(
          "orders",
          [](const PfrfResult& r) {
            py::array_t<std::int64_t> a(r.max_order - r.min_order + 1);
            for (int z = r.min_order; z <= r.max_order; ++z) a.mutable_at(z - r.min_order) = z;
            return a;
          },
          "the orders z, zmin..zmax")
      .def_property_readonly(
          "H",
          [](const PfrfResult& r) {
            return ComplexTable(r.values, static_cast<size_t>(r.max_order - r.min_order + 1));
          },
          "H_z(2πf): shape (frequencies, orders)")
      .def_property_readonly(
          "response_frequencies_hz",
          [](const PfrfResult& r) {
            std::vector<std::vector<double>> f;
            for (double fe : r.frequencies_hz) {
              f.emplace_back();
              for (int z = r.min_order; z <= r.max_order; ++z) f.back().push_back(fe + z * r.fp_hz);
            }
            return RealTable(f, static_cast<size_t>(r.max_order - r.min_order + 1));
          },
          "f + z fp: where each value shows up in the response, shape (frequencies, orders)")
      .def_property_readonly(
          "error_estimate",
          [](const PfrfResult& r) {
            return RealTable(r.error_estimate, static_cast<size_t>(r.max_order - r.min_order + 1));
          },
          "absolute error estimate of every H value, shape (frequencies, orders)")
      .def_property_readonly(
          "checked",
          [](const PfrfResult& r) {
            py::array_t<bool> a(static_cast<py::ssize_t>(r.checked.size()));
            for (size_t i = 0; i < r.checked.size(); ++i)
              a.mutable_at(static_cast<py::ssize_t>(i)) = r.checked[i];
            return a;
          },
          "the check routes ran at this frequency");
}

// Which routes ran, and how far they agree.
void BindPfrfRoutes(py::class_<PfrfResult>& r) {
  r.def_property_readonly(
       "primary_route",
       [](const PfrfResult& r) {
         return r.routes.empty() ? std::string() : std::string(ToString(r.routes.front().route));
       },
       "the route that gave H")
      .def_readonly("route_choice", &PfrfResult::route_choice,
                    "why these routes (automatic choice), or 'as requested'")
      .def_property_readonly(
          "route_reason", [](const PfrfResult& r) { return std::string(CodeName(r.route_reason)); },
          "why these routes, as a code for programs: 'as_requested', 'no_decomposition', "
          "'modal_resolved', 'modal_unreliable' or 'modal_check_failed' (route_choice says it "
          "in a sentence)")
      .def_property_readonly(
          "routes",
          [](const PfrfResult& r) {
            py::list out;
            for (const RouteRun& run : r.routes) out.append(RouteDict(run));
            return out;
          },
          "every route run, primary first: route, points, values, deviation, own_error, timings, "
          "diagnostics")
      .def_readonly("modal_cross_check_failed", &PfrfResult::modal_cross_check_failed,
                    "route auto found the modal route wrong by its check and used htf/shooting")
      .def_readonly("max_disagreement", &PfrfResult::max_disagreement,
                    "max |H_check − H_primary| over check points and orders")
      .def_readonly("max_relative_disagreement", &PfrfResult::max_relative_disagreement,
                    "max_disagreement / max |H|")
      .def_readonly("htf_harmonics", &PfrfResult::htf_harmonics,
                    "HTF truncation N (0: htf did not run)")
      .def_readonly("htf_truncation_change", &PfrfResult::htf_truncation_change,
                    "max |H(N) − H(N+Δ)| where the htf route ran; None when it did not")
      .def_readonly("settle_time", &PfrfResult::settle_time,
                    "time route: settling time (s); None when it did not run")
      .def_readonly("model_error", &PfrfResult::model_error,
                    "systems from .lin files: max |H_z| difference to the other models of the "
                    "same samples (in every estimate); None otherwise");
}

// The Floquet decomposition behind the modal route, and the resonances it attributes.
void BindPfrfModal(py::class_<PfrfResult>& r) {
  r.def_readonly("floquet", &PfrfResult::floquet,
                 "the Floquet decomposition behind the modal route")
      .def_property_readonly(
          "modal_reliable",
          [](const PfrfResult& r) -> py::object {
            if (!r.modal) return py::none();
            return py::bool_(r.modal->reliable);
          },
          "the modal model's own verdict, or None")
      .def_property_readonly(
          "modal_condition",
          [](const PfrfResult& r) -> py::object {
            if (!r.modal) return py::none();
            return py::float_(r.modal->condition);
          },
          "condition number of the mode matrix, or None")
      .def_property_readonly(
          "order_max", [](const PfrfResult& r) { return RealArray(r.order_max); },
          "max_f |H_z| per order")
      .def_property_readonly(
          "resonances",
          [](const PfrfResult& r) {
            py::list out;
            for (const Resonance& p : r.resonances)
              out.append(
                  py::dict(py::arg("z") = p.order, py::arg("f_exc_hz") = p.f_exc_hz,
                           py::arg("f_resp_hz") = p.f_resp_hz, py::arg("abs") = p.magnitude,
                           py::arg("mode") = p.mode ? py::object(py::int_(*p.mode)) : py::none(),
                           py::arg("harmonic") = p.harmonic,
                           py::arg("mode_line_hz") = p.mode_line_hz, py::arg("share") = p.share));
            return out;
          },
          "peaks of |H_z|, each attributed to Floquet mode `mode` (index into floquet.exponents, "
          "-1 unknown) and harmonic v");
}

void BindPfrfResult(py::module_& m) {
  py::class_<PfrfResult> r(m, "PfrfResult", R"doc(
The result of ltp.pfrf: the partial FRFs H_z(ω) of one input/output channel, indexed by the
excitation frequency f (the response to u = e^{j2πft} has lines at f + z fp), with an error
estimate for every value from the independent routes' disagreement.

  H[i, z - zmin]  H_z at frequencies_hz[i] (complex); orders = zmin..zmax
  error_estimate  same shape: absolute error estimate of every value)doc");
  r.def_readonly("ok", &PfrfResult::ok, "every route ran and the result passed its checks")
      .def_readonly("failure", &PfrfResult::failure,
                    "why ok is False, one sentence; empty when ok");
  BindPfrfValues(r);
  r.def_readonly("input", &PfrfResult::input, "the input channel (index)")
      .def_readonly("output", &PfrfResult::output, "the output channel (index)")
      .def_readonly("period", &PfrfResult::period, "T (s)")
      .def_readonly("fp_hz", &PfrfResult::fp_hz, "1/T (Hz)");
  BindPfrfRoutes(r);
  BindPfrfModal(r);
  r.def_readonly("elapsed_s", &PfrfResult::elapsed_s, "wall time (s)")
      .def_property_readonly("diagnostics", DiagnosticTexts(&PfrfResult::diagnostics),
                             "what the routes noticed, one line each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&PfrfResult::diagnostics),
                             kDiagnosticCodesDoc)
      .def("__repr__", [](const PfrfResult& r) {
        return "<ltp.PfrfResult: " + std::to_string(r.frequencies_hz.size()) +
               " frequencies, orders " + std::to_string(r.min_order) + ".." +
               std::to_string(r.max_order) + ", " + (r.ok ? "ok" : "FAILED") + ">";
      });
}

// ltp.pfrf: the options checked as the CLI checks them; the routes run without the GIL.
PfrfResult LtpPfrf(const System& system, const py::object& freq, const py::object& input,
                   const py::object& output, const py::object& orders, const std::string& route,
                   int check_every, int htf_harmonics) {
  NeedChannels(system);
  PfrfOptions o;
  o.frequencies_hz = FrequenciesFrom(freq);
  std::tie(o.min_order, o.max_order) = OrdersFrom(orders);
  const SystemLabels& labels = system.system.labels();
  o.input = ChannelFrom(input, labels.inputs, system.system.inputs(), "input");
  o.output = ChannelFrom(output, labels.outputs, system.system.outputs(), "output");
  if (check_every < 1) throw InputError("check_every must be >= 1");
  o.check_every = check_every;
  if (htf_harmonics < 0) throw InputError("htf_harmonics must be >= 0 (0 = automatic)");
  o.htf.harmonics = htf_harmonics;
  if (!SelectPfrfRoutes(route, &o))
    throw InputError("route must be auto, modal, htf, shooting, time or all, got '" + route + "'");
  o.floquet.threads = AnalysisThreads(system, o.floquet.threads);
  o.Validate();
  return WithoutGil(system, [&] {
    PfrfResult r = ComputePartialFrf(system.system, o);
    IncludeModelError(system.model_alternatives, o, r);  // sampled models, as the CLI
    return r;
  });
}

void BindPfrfFunction(py::module_& m) {
  const PfrfOptions defaults;
  m.def("pfrf", &LtpPfrf, py::arg("system"), py::arg("freq"), py::kw_only(), py::arg("input") = 0,
        py::arg("output") = 0,
        py::arg("orders") =
            std::to_string(defaults.min_order) + ":" + std::to_string(defaults.max_order),
        py::arg("route") = std::string(ToString(defaults.primary)),
        py::arg("check_every") = defaults.check_every,
        py::arg("htf_harmonics") = defaults.htf.harmonics,
        R"doc(
Partial frequency response functions H_z(ω): `ltp pfrf SCENE --freq ... --json` as a
function, with the same options and defaults.

  freq           'F0:F1:DF' in Hz (the CLI's grid, to the last bit) or an array of Hz
  input, output  channel index or name
  orders         'ZMIN:ZMAX', an int, or a pair
  route          auto | modal | htf | shooting | time | all (the primary route; auto: modal
                 unless it reports itself unreliable, checked by htf, or by shooting when
                 A(t) jumps; all: modal checked by the other three)
  check_every    run the check routes on every k-th frequency (and the last)
  htf_harmonics  HTF truncation N (0 = automatic)

Returns a PfrfResult (H over frequency and order, error estimates, resonances, the Floquet
decomposition). Runs without the GIL.

    r = ltp.pfrf(ltp.scene("tower-rotor"), "0:450:0.6", input="Fz_tip", output="z_tip")
    abs(r.H[:, list(r.orders).index(0)]))doc");
}

void BindSnapshotResult(py::module_& m) {
  py::class_<SnapshotResult>(m, "SnapshotResult", R"doc(
The result of ltp.snapshot: the FRF of the system frozen at one instant, and with
compare=True the periodic system's response to an impulse, the summed partial FRFs
G(ω) = Σ_z H_z(ω − zΩp) (paper Fig. 6), with an error estimate.)doc")
      .def_readonly("time", &SnapshotResult::time, "the instant frozen (s)")
      .def_readonly("angle_deg", &SnapshotResult::angle_deg, "the rotor angle frozen, or None")
      .def_property_readonly(
          "A", [](const SnapshotResult& r) { return r.frozen.A; }, "the frozen A")
      .def_property_readonly(
          "B", [](const SnapshotResult& r) { return r.frozen.B; }, "the frozen B")
      .def_property_readonly(
          "C", [](const SnapshotResult& r) { return r.frozen.C; }, "the frozen C")
      .def_property_readonly(
          "D", [](const SnapshotResult& r) { return r.frozen.D; }, "the frozen D")
      .def_property_readonly(
          "eigenvalues", [](const SnapshotResult& r) { return ComplexArray(r.eigenvalues); },
          "eigenvalues of the frozen A ('snapshot modes', 1/s)")
      .def_property_readonly(
          "frequencies_hz", [](const SnapshotResult& r) { return RealArray(r.frequencies_hz); },
          "frequencies (Hz)")
      .def_property_readonly(
          "snapshot", [](const SnapshotResult& r) { return ComplexArray(r.snapshot); },
          "H(2πf) = C (j2πf I − A)⁻¹ B + D of the frozen system")
      .def_property_readonly(
          "summed", [](const SnapshotResult& r) { return ComplexArray(r.summed); },
          "compare=True: G(2πf) of the periodic system (else empty)")
      .def_property_readonly(
          "summed_error", [](const SnapshotResult& r) { return RealArray(r.summed_error); },
          "compare=True: error estimate of summed")
      .def_readonly("max_summed_disagreement", &SnapshotResult::max_summed_disagreement,
                    "modal vs htf, relative to max |H_z|")
      .def_readonly("modal_reliable", &SnapshotResult::modal_reliable,
                    "the modal model's own verdict, or None")
      .def_property_readonly(
          "floquet_exponents",
          [](const SnapshotResult& r) { return ComplexArray(r.floquet_exponents); },
          "compare=True: the periodic system's exponents")
      .def_readonly("elapsed_s", &SnapshotResult::elapsed_s, "wall time (s)")
      .def_property_readonly("diagnostics", DiagnosticTexts(&SnapshotResult::diagnostics),
                             "what the routes noticed, one line each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&SnapshotResult::diagnostics),
                             kDiagnosticCodesDoc)
      .def("__repr__", [](const SnapshotResult& r) {
        return "<ltp.SnapshotResult: frozen at t = " + std::to_string(r.time) + " s, " +
               std::to_string(r.frequencies_hz.size()) + " frequencies>";
      });
}

// ltp.snapshot: exactly one of angle and time; the FRFs computed without the GIL.
SnapshotResult LtpSnapshot(const System& system, const py::object& freq, std::optional<Real> angle,
                           std::optional<Real> time, const py::object& input,
                           const py::object& output, const py::object& orders, bool compare) {
  if (angle.has_value() == time.has_value())
    throw InputError("give exactly one of angle= (degrees) and time= (s)");
  NeedChannels(system);
  if (angle && !system.system.rotor_speed())
    throw InputError("the system has no rotor speed: give time= instead of angle=");
  SnapshotOptions o;
  o.frequencies_hz = FrequenciesFrom(freq);
  o.time = time;
  o.angle_deg = angle;
  const SystemLabels& labels = system.system.labels();
  o.input = ChannelFrom(input, labels.inputs, system.system.inputs(), "input");
  o.output = ChannelFrom(output, labels.outputs, system.system.outputs(), "output");
  o.compare = compare;
  std::tie(o.min_order, o.max_order) = OrdersFrom(orders);
  o.floquet.threads = AnalysisThreads(system, o.floquet.threads);
  o.Validate();
  return WithoutGil(system, [&] { return ComputeSnapshotFrf(system.system, o); });
}

void BindSnapshotFunction(py::module_& m) {
  const SnapshotOptions snapshot_defaults;
  m.def("snapshot", &LtpSnapshot, py::arg("system"), py::arg("freq"), py::kw_only(),
        py::arg("angle") = py::none(), py::arg("time") = py::none(), py::arg("input") = 0,
        py::arg("output") = 0,
        py::arg("orders") = std::to_string(snapshot_defaults.min_order) + ":" +
                            std::to_string(snapshot_defaults.max_order),
        py::arg("compare") = snapshot_defaults.compare, R"doc(
The FRF of the system frozen at one rotor angle (degrees) or time (s): `ltp snapshot SCENE
--freq ... --json` as a function. compare=True adds the periodic system's response to an
impulse, Σ_z H_z(ω − zΩp) over `orders` (paper Fig. 6), checked against the HTF route.

    s = ltp.snapshot(ltp.scene("tower-rotor"), "0:450:0.6", angle=90, compare=True,
                     input="Fz_tip", output="z_tip")
    abs(s.snapshot), abs(s.summed))doc");
}

}  // namespace

void BindFrf(py::module_& m) {
  BindPfrfResult(m);
  BindPfrfFunction(m);
  BindSnapshotResult(m);
  BindSnapshotFunction(m);
}

}  // namespace ltp::python
