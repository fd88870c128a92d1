// ltp.floquet: the monodromy route, and its result.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

#include "binding.h"
#include "diagnostic_properties.h"
#include "floquet_modes.h"
#include "ltp/core/error.h"
#include "ltp/floquet/estimate_source.h"
#include "ltp/floquet/floquet.h"
#include "ltp/floquet/model_error.h"
#include "ltp/floquet/periodic_eigen.h"
#include "ltp/studies/rotor_mbc_check.h"

namespace ltp::python {

namespace {

int SegmentsFrom(const py::object& segments) {
  if (py::isinstance<py::str>(segments) && segments.cast<std::string>() == "auto") return 0;
  if (py::isinstance<py::int_>(segments) && !py::isinstance<py::bool_>(segments)) {
    const long k = segments.cast<long>();
    if (k >= 1 && k <= std::numeric_limits<int>::max()) return static_cast<int>(k);
  }
  throw InputError("segments must be a positive integer or 'auto', got " +
                   py::repr(segments).cast<std::string>());
}

MultiplierMethod MultipliersFrom(const std::string& name) {
  if (name == "schur" || name == "periodic-schur") return MultiplierMethod::kPeriodicSchur;
  if (name == "single-shot") return MultiplierMethod::kSingleShot;
  throw InputError("multipliers must be 'schur' or 'single-shot', got '" + name + "'");
}

}  // namespace

IntegratorType IntegratorFrom(const std::string& name) {
  const auto type = ParseIntegratorType(name);
  if (!type) throw InputError("unknown integrator '" + name + "' (" + IntegratorNames() + ")");
  return *type;
}

namespace {

// The run: whether it succeeded, and how the period was cut and integrated.
void BindFloquetRun(py::class_<FloquetResult>& r) {
  r.def_readonly("ok", &FloquetResult::ok, "the analysis succeeded and passed its own checks")
      .def_readonly("failure", &FloquetResult::failure,
                    "why ok is False, one sentence; empty when ok")
      .def_readonly("states", &FloquetResult::states, "n")
      .def_readonly("period", &FloquetResult::period, "T (s)")
      .def_property_readonly(
          "integrator", [](const FloquetResult& r) { return std::string(ToString(r.integrator)); },
          "the integrator used (auto resolved)")
      .def_property_readonly(
          "multiplier_method",
          [](const FloquetResult& r) { return std::string(ToString(r.multiplier_method)); },
          "'periodic-schur' or 'single-shot'")
      .def_readonly("segments", &FloquetResult::segments, "K, the number of segments used")
      .def_property_readonly(
          "segment_times", [](const FloquetResult& f) { return RealArray(f.segment_times); },
          "t_0 = 0 < ... < t_K = T");
}

// error_estimate_method's docstring, with the library's words for what each integrator carries.
const std::string kEstimateMethodDoc =
    "'refined-run' (the difference to a second, tighter run that gives the numbers) or "
    "'local-errors' (one run: " +
    std::string(kLocalErrorSources) + ")";

// The verdict and the error estimate it rests on.
void BindFloquetVerdict(py::class_<FloquetResult>& r) {
  r.def_readonly("max_real_exponent", &FloquetResult::max_real_exponent,
                 "max Re λ (1/s), rigid-body modes excluded")
      .def_readonly("max_log_abs_multiplier", &FloquetResult::max_log_abs_multiplier,
                    "max log|ρ| = T max Re λ")
      .def_readonly("stable", &FloquetResult::stable, "verdict == 'stable'")
      .def_property_readonly(
          "verdict", [](const FloquetResult& f) { return std::string(ToString(f.verdict)); },
          "'stable' or 'unstable' only when max Re λ lies beyond the error estimate; "
          "'marginal' within it; 'failed'")
      .def_readonly("error_estimate", &FloquetResult::error_estimate,
                    "estimated absolute error of every exponent (1/s), by error_estimate_method; "
                    "None when not computed")
      .def_readonly("model_error", &FloquetResult::model_error,
                    "for OpenFAST samples: the part of error_estimate that is the sampling "
                    "error (other interpolations of the same samples); None otherwise")
      .def_property_readonly(
          "exponent_error_estimates",
          [](const FloquetResult& f) {
            std::vector<double> e;
            for (const FloquetMode& m : f.modes)
              e.push_back(m.error_estimate.value_or(std::numeric_limits<double>::quiet_NaN()));
            return RealArray(e);
          },
          "each exponent's own estimate (1/s), in the order of `exponents` (NaN when not "
          "computed); the verdict asks each exponent for its own, error_estimate is the largest")
      .def_property_readonly(
          "error_estimate_method",
          [](const FloquetResult& f) { return std::string(ToString(f.error_estimate_method)); },
          kEstimateMethodDoc.c_str())
      .def_property_readonly(
          "estimate_source",
          [](const FloquetResult& f) {
            return std::string(EstimateSource(f.error_estimate_method, f.integrator));
          },
          "how this result's error estimate was made and where its numbers come from, in words "
          "(as `ltp floquet` prints it)")
      .def_readonly("liouville_residual", &FloquetResult::liouville_residual,
                    "|Σ log|ρ_k| − ∫ tr A dt| / max(1, |∫ tr A dt|); None when the analysis "
                    "stopped before its multipliers");
}

// The monodromy matrix and the periodic mode shapes: sampled, as Fourier series, and what a
// reduction left out.
void BindFloquetModes(py::class_<FloquetResult>& r) {
  r.def_readonly("mode_condition", &FloquetResult::mode_condition,
                 "cond Ξ(t), the best of up to 16 sample times; large = (near-)defective; None "
                 "without mode shapes")
      .def_readonly("monodromy", &FloquetResult::monodromy,
                    "Φ(T, 0), n×n (with modes_below: the part of the modes analysed, U Φ_r Wᵀ)")
      .def_property_readonly(
          "segment_factors",
          [](const FloquetResult& f) -> py::object {
            if (f.segment_factors.empty()) return py::none();
            const int n = static_cast<int>(f.segment_factors.front().rows());
            return RealStack(f.segment_factors, n, n);
          },
          "with keep_factors=True: Φ(t_{i+1}, t_i) over segment i of segment_times, shape (K, n, "
          "n); their product (last leftmost) is the monodromy. None otherwise")
      .def_property_readonly(
          "reduction",
          [](const FloquetResult& f) -> py::object {
            if (!f.reduction) return py::none();
            const ModalReduction& m = *f.reduction;
            return py::dict(py::arg("cutoff_hz") = m.cutoff / (2 * std::numbers::pi),
                            py::arg("states") = m.kept,
                            py::arg("check_cutoff_hz") = m.check_cutoff / (2 * std::numbers::pi),
                            py::arg("check_states") = m.check_kept,
                            py::arg("truncation_change") = m.truncation_change,
                            py::arg("tail") = m.tail,
                            py::arg("dropped_mean_eigenvalues") = ComplexArray(m.dropped),
                            py::arg("periodic_part") = m.periodic_part);
          },
          "None, or with modes_below: what was analysed and left out — cutoff_hz, states, "
          "check_cutoff_hz, check_states, truncation_change (1/s, in every estimate), tail (the "
          "modes "
          "beyond the check, second order; twice in every estimate), "
          "dropped_mean_eigenvalues, periodic_part (max ‖A(t) − Ā‖_F)")
      .def_property_readonly(
          "mode_descriptions",
          [](const FloquetResult& f) { return StringArray(f.mode_descriptions); },
          "what carries each mode (numpy str array): each state's participation in it at t = 0 "
          "(unit-free; a second-order DOF's share of the mode's energy, its rate counted with it), "
          "blade states as multiblade families (e.g. 'zeta cyclic 78%, x 22%'; "
          "docs/mode-descriptions.md)")
      .def_property_readonly(
          "forward_whirl",
          [](const FloquetResult& f) -> py::object {
            std::vector<double> share;
            for (const FloquetMode& m : f.modes)
              share.push_back(m.forward_whirl.value_or(std::numeric_limits<double>::quiet_NaN()));
            if (std::none_of(f.modes.begin(), f.modes.end(),
                             [](const FloquetMode& m) { return m.forward_whirl.has_value(); }))
              return py::none();
            return RealArray(share);
          },
          "per mode, the share (0..1) of its motion in the scene's whirl planes (whirl_pairs) "
          "that turns with the rotor: 1 forward, 0 backward whirl (NaN: the mode does not move "
          "there); None when the system declares no whirl pairs or there are no mode shapes")
      .def_property_readonly(
          "sample_times", [](const FloquetResult& f) { return RealArray(f.sample_times); },
          "uniform times of mode_samples")
      .def_property_readonly(
          "mode_samples",
          [](const FloquetResult& f) {
            return ComplexStack(f.mode_samples, f.states, static_cast<int>(f.modes.size()));
          },
          "ξ_k(t_s): shape (S, n, n), column k of [s] is mode k at sample_times[s]")
      .def_property_readonly(
          "mode_harmonics",
          [](const FloquetResult& f) {
            return ComplexStack(f.mode_fourier, f.states, static_cast<int>(f.modes.size()));
          },
          "Fourier coefficients of the mode shapes: shape (2H+1, n, n), [v + H][:, k] is "
          "harmonic v of mode k (v = -H..H, see mode_harmonic_orders)")
      .def_property_readonly(
          "mode_harmonic_orders",
          [](const FloquetResult& f) {
            py::array_t<std::int64_t> v(2 * f.mode_harmonics + 1);
            for (int h = -f.mode_harmonics; h <= f.mode_harmonics; ++h)
              v.mutable_at(h + f.mode_harmonics) = h;
            return v;
          },
          "the harmonics v = -H..H of mode_harmonics");
}

void BindFloquetResult(py::module_& m) {
  py::class_<FloquetResult> r(m, "FloquetResult", R"doc(
The result of ltp.floquet: Floquet exponents λ_k (1/s) on the branch whose periodic mode
shape is centred on harmonic 0, multipliers ρ_k = exp(λ_k T), the mode shapes, the
stability verdict and an error estimate. Arrays are numpy arrays, one entry per mode in
the order `ltp floquet` prints them (by |frequency|, then Re λ).

ok is False when the integration failed or the result failed its own checks (Liouville's
formula beyond the error estimate): the diagnostics say why.)doc");
  BindModeArrays<FloquetResult>(r);
  BindFloquetRun(r);
  BindFloquetVerdict(r);
  BindFloquetModes(r);
  r.def_readonly("rhs_evals", &FloquetResult::rhs_evals,
                 "evaluations of A(t) (taylor: products A_j Phi_k of the series)")
      .def_readonly("elapsed_s", &FloquetResult::elapsed_s, "wall time (s)")
      .def_property_readonly("diagnostics", DiagnosticTexts(&FloquetResult::diagnostics),
                             "what the analysis noticed, one line each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&FloquetResult::diagnostics),
                             kDiagnosticCodesDoc)
      .def_property_readonly(
          "termination",
          [](const FloquetResult& f) { return std::string(ToString(f.termination)); },
          "how the analysis ended: 'completed' (ok), 'integration_failed', "
          "'eigenvalues_failed', 'checks_failed' or 'no_modes_below_cutoff'")
      .def(
          "mode_matrix",
          [](const FloquetResult& f, Real t) {
            return f.ModeMatrix(PeriodicTime(t, f.period, "mode_matrix"));
          },
          py::arg("t"),
          "Ξ(t): the mode shapes at time t (spectral interpolation), n×n, column k = mode k")
      .def(
          "left_modes",
          [](const FloquetResult& f, Real t) {
            return f.LeftModes(PeriodicTime(t, f.period, "left_modes"));
          },
          py::arg("t"), "rows of Ξ(t)⁻¹")
      .def(
          "periodic_schur",
          [](const FloquetResult& f) {
            if (f.segment_factors.empty())
              throw InputError(
                  "periodic_schur needs the segment factors: run ltp.floquet(..., "
                  "keep_factors=True)");
            py::gil_scoped_release release;
            return PeriodicSchurDecomposition(f.segment_factors);
          },
          "ltp.periodic_schur(segment_factors): the periodic Schur form of the kept factors "
          "(keep_factors=True, else ltp.InputError)")
      .def("__repr__",
           [](const FloquetResult& f) { return "<ltp.FloquetResult: " + f.BriefReport() + ">"; });
}

// ltp.floquet: the options checked as the CLI checks them; the analysis runs without the GIL,
// a progress callable is called with it.
FloquetResult LtpFloquet(const System& system, const std::string& integrator, Real tol, int steps,
                         const py::object& segments, const std::string& multipliers,
                         const std::string& estimate, int mode_samples, int threads, Real max_work,
                         Real modes_below, bool keep_factors, const py::object& progress) {
  FloquetOptions o;
  o.keep_segment_factors = keep_factors;
  o.integrator.type = IntegratorFrom(integrator);
  o.integrator.rel_tol = tol;
  o.integrator.steps_per_period = steps;
  o.segments = SegmentsFrom(segments);
  o.multipliers = MultipliersFrom(multipliers);
  const auto method = ParseErrorEstimateMethod(estimate);
  if (!method)
    throw InputError("estimate must be 'auto', 'refined-run' or 'local-errors', got '" + estimate +
                     "'");
  o.error_estimate_method = *method;
  o.mode_samples = mode_samples;
  o.threads = AnalysisThreads(system, threads);
  o.max_work_seconds = max_work;
  o.modes_below = 2 * std::numbers::pi * modes_below;
  o.on_long_work = WarnLongWork("floquet");
  o.Validate();
  // A notebook's progress bar: called with the GIL, from whatever thread integrates (the
  // library serialises the calls); what it raises is raised once the analysis is done.
  std::exception_ptr raised;
  if (!progress.is_none()) {
    if (!PyCallable_Check(progress.ptr()))
      throw InputError("progress must be a callable (phase, fraction) or None");
    o.on_progress = [&progress, &raised](std::string_view phase, double fraction) {
      if (raised) return;
      py::gil_scoped_acquire gil;
      try {
        progress(std::string(phase), fraction);
      } catch (...) {
        raised = std::current_exception();
      }
    };
  }
  FloquetResult r = WithoutGil(system, [&] {
    FloquetResult result = AnalyzeFloquet(system.system, o);
    IncludeModelError(system.model_alternatives, o, result);  // sampled models, as the CLI
    return result;
  });
  if (raised) std::rethrow_exception(raised);
  return r;
}

void BindFloquetFunction(py::module_& m) {
  const FloquetOptions defaults;
  m.def("floquet", &LtpFloquet, py::arg("system"), py::kw_only(),
        py::arg("integrator") = std::string(ToString(defaults.integrator.type)),
        py::arg("tol") = defaults.integrator.rel_tol,
        py::arg("steps") = defaults.integrator.steps_per_period, py::arg("segments") = "auto",
        py::arg("multipliers") = "schur",
        py::arg("estimate") = std::string(ToString(defaults.error_estimate_method)),
        py::arg("mode_samples") = defaults.mode_samples, py::arg("threads") = defaults.threads,
        py::arg("max_work") = defaults.max_work_seconds, py::arg("modes_below") = 0.0,
        py::arg("keep_factors") = defaults.keep_segment_factors, py::arg("progress") = py::none(),
        R"doc(
Floquet analysis by the monodromy matrix: `ltp floquet SCENE --json` as a function, with
the same options and defaults.

  integrator    auto | dopri5 | rkf78 | bs | cvode | cvode-adams | magnus4 | magnus6 | expm | taylor
                | magnus-filon (taylor and magnus-filon: Fourier-form A(t) only)
                (auto: the work-precision study's cheapest for the system; the result's
                integrator and diagnostics say which and why)
  tol           relative tolerance (the exponents inherit about this error)
  steps         fixed-step methods: steps per period (0 = automatic)
  segments      number of segments K of the period, or 'auto'
  multipliers   'schur' (periodic Schur of the segment factors) | 'single-shot'
  estimate      'auto' ('local-errors' for Taylor series and Magnus, 'refined-run' otherwise) |
                'refined-run' (a second run at tol/100 gives the numbers) | 'local-errors'
                (one run: what each integrator carries, FloquetResult.error_estimate_method
                says; FloquetResult.estimate_source says how a result's estimate was made)
  mode_samples  samples of the mode shapes per period (power of two; 0 = automatic)
  threads       OpenMP threads (0 = all cores; one for a system behind Python callables)
  max_work      refuse (ltp.InputError, with the estimate) an analysis that would need more CPU
                seconds than this even at its fastest (0 = no limit); an analysis estimated
                beyond 10 s says so in its diagnostics and, before it starts, as a UserWarning
  modes_below   analyse only the modes whose eigenvalue of the mean A(t) is below this many Hz
                (|λ|/2π), checked against twice the cut-off (its change is in each estimate;
                result.reduction says what was left out); 0 = every mode
  keep_factors  keep the segment factors Φ(t_{i+1}, t_i) (result.segment_factors): the monodromy
                as the product it is, where the formed one under- or overflows
  progress      None, or a callable progress(phase, fraction) told each phase of the work
                ('run', 'refined run', 'mode shapes'; 'other model 1 of 2: run' for .lin data)
                and the fraction of its period integrated, at most every half percent

Returns a FloquetResult. Runs without the GIL. Raises ltp.InputError (a ValueError) for
bad options; a failed analysis is not an exception: see result.ok and diagnostics.

    r = ltp.floquet(ltp.scene("mathieu", a=1.5, q=2))
    r.exponents, r.multipliers, r.verdict, r.error_estimate)doc");
}

// ltp.mbc_check: None for anything but the built-in rotor scene.
py::object LtpMbcCheck(const System& system, const FloquetResult& result) {
  if (!system.scene) return py::none();
  const auto check = CheckRotorByMbc(*system.scene, system.parameters, result);
  if (!check) return py::none();
  return py::dict(py::arg("applicable") = check->applicable, py::arg("reason") = check->reason,
                  py::arg("blades") = check->blades,
                  py::arg("max_difference") = check->max_difference);
}

void BindMbcCheckFunction(py::module_& m) {
  m.def("mbc_check", &LtpMbcCheck, py::arg("system"), py::arg("result"), R"doc(
The multi-blade-coordinate cross-check `ltp floquet rotor` prints: for the built-in rotor
scene with N >= 3 identical blades, the largest distance (1/s) between the Floquet exponents of
`result` (ltp.floquet of `system`) and the eigenvalues of the constant multi-blade-coordinate
system, matched modulo jΩ. A dict {applicable, reason, blades, max_difference}; None for other
scenes or a failed result.

    s = ltp.scene("rotor")
    ltp.mbc_check(s, ltp.floquet(s))["max_difference"]   # ~1e-12)doc");
}

}  // namespace

void BindFloquet(py::module_& m) {
  BindFloquetResult(m);
  BindFloquetFunction(m);
  BindMbcCheckFunction(m);
}

}  // namespace ltp::python
