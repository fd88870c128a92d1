// ltp.hill: Hill's method, and its result.
#include <limits>
#include <type_traits>

#include "binding.h"
#include "diagnostic_properties.h"
#include "floquet_modes.h"
#include "ltp/core/error.h"
#include "ltp/floquet/model_error.h"
#include "ltp/hill/hill.h"
#include "ltp/hill/hill_model_error.h"

namespace ltp::python {

namespace {

// Per exponent: field(info) of each of the result's HillModeInfo, as a numpy array of T.
template <class T, class Field>
auto InfoColumn(Field field) {
  return [field](const HillResult& h) {
    py::array_t<T> a(static_cast<py::ssize_t>(h.info.size()));
    for (size_t k = 0; k < h.info.size(); ++k)
      a.mutable_at(static_cast<py::ssize_t>(k)) = field(h.info[k]);
    return a;
  };
}

// One column of the convergence study's table, as doubles: `member` of every row.
template <class Member>
auto StudyColumn(Member HillStudyRow::*member) {
  return [member](const HillStudyRun& r) {
    if constexpr (std::is_integral_v<Member>) {  // counts stay integers (N, sizes): int64
      py::array_t<std::int64_t> a(static_cast<py::ssize_t>(r.study.rows.size()));
      for (size_t i = 0; i < r.study.rows.size(); ++i)
        a.mutable_at(static_cast<py::ssize_t>(i)) = r.study.rows[i].*member;
      return py::object(a);
    } else {
      std::vector<double> v;
      for (const HillStudyRow& row : r.study.rows) {
        if constexpr (std::is_same_v<Member, std::optional<double>>)
          v.push_back(OrNaN(row.*member));
        else
          v.push_back(row.*member);
      }
      return py::object(RealArray(v));
    }
  };
}

// What was solved: the truncation, the matrix, the solver and the selection rule.
void BindHillRun(py::class_<HillResult>& r) {
  r.def_readonly("ok", &HillResult::ok, "the exponents were found and passed the Liouville check")
      .def_readonly("failure", &HillResult::failure, "why ok is False, one sentence; empty when ok")
      .def_readonly("states", &HillResult::states, "n")
      .def_readonly("harmonics", &HillResult::harmonics, "N actually used (harmonics -N..N)")
      .def_readonly("matrix_size", &HillResult::matrix_size, "(2N+1) n")
      .def_readonly("period", &HillResult::period, "T (s)")
      .def_property_readonly(
          "solver", [](const HillResult& h) { return h.SolverDescription(); },
          "'dense', 'structured' (auto resolved) or 'structured→dense' after a fallback")
      .def_readonly("selection_rule", &HillResult::selection_rule,
                    "how the physical eigenvalues were picked");
}

// Per mode: how clearly its eigenvalue was picked among the Hill matrix's, and its shape.
void BindHillSelection(py::class_<HillResult>& r) {
  r.def_property_readonly("centroids",
                          InfoColumn<double>([](const HillModeInfo& i) { return i.centroid; }),
                          "energy centroid of each eigenvector over the harmonic blocks")
      .def_property_readonly("selection_margins", InfoColumn<double>([](const HillModeInfo& i) {
                               return i.selection_margin;
                             }),
                             "1 = clean choice, 0 = tie between λ and λ ± jΩp")
      .def_property_readonly(
          "tail_weights", InfoColumn<double>([](const HillModeInfo& i) { return i.tail_weight; }),
          "energy on the outermost blocks ±N (large: N too small for the mode)")
      .def_property_readonly("truncation_changes", InfoColumn<double>([](const HillModeInfo& i) {
                               return OrNaN(i.truncation_change);
                             }),
                             "|λ_N − λ_{N+Δ}| mod jΩp per mode (1/s); NaN when not computed")
      .def_property_readonly("residuals",
                             InfoColumn<double>([](const HillModeInfo& i) { return i.residual; }),
                             "relative eigen-residual of each selected eigenvalue")
      .def_property_readonly("passed",
                             InfoColumn<bool>([](const HillModeInfo& i) { return i.passed; }),
                             "the selection rule's pass condition per mode")
      .def_property_readonly("ambiguous",
                             InfoColumn<bool>([](const HillModeInfo& i) { return i.ambiguous; }),
                             "selection margin below the threshold (a tie between λ and λ ± jΩp)")
      .def_readonly("mode_shapes", &HillResult::mode_shapes,
                    "periodic mode shapes at t = 0 (n × n complex, one column per exponent): "
                    "the eigenvector's harmonic blocks summed")
      .def_readonly("eigenvectors", &HillResult::eigenvectors,
                    "the Hill matrix's eigenvectors of the selected eigenvalues ((2N+1)n × n "
                    "complex128, column k for exponents[k], unit 2-norm; rows: harmonic blocks "
                    "-N..N of n states, as ltp.hill_matrix orders them): hill_matrix v_k = λ_k v_k "
                    "up to round-off (a tie reported as λ + jΩp: λ's vector shifted one block "
                    "down, exact but for the truncation edge)");
}

// The verdict and the error estimate with the parts it is made of.
void BindHillVerdict(py::class_<HillResult>& r) {
  r.def_readonly("max_real_exponent", &HillResult::max_real_exponent,
                 "max Re λ over the modes that are not rigid-body (1/s)")
      .def_readonly("stable", &HillResult::stable, "verdict == 'stable'")
      .def_property_readonly(
          "verdict", [](const HillResult& h) { return std::string(ToString(h.verdict)); },
          "'stable', 'unstable' (beyond the error estimate), 'marginal' or 'failed'")
      .def_readonly("delta_harmonics", &HillResult::delta_harmonics,
                    "Δ of the N vs N+Δ estimate (0: not computed)")
      .def_readonly("truncation_estimate", &HillResult::truncation_estimate,
                    "max_k |λ_k(N) − λ_k(N+Δ)| mod jΩp (1/s); None when not computed")
      .def_readonly("apriori_bound", &HillResult::apriori_bound,
                    "a-priori bound on the exponent error (inf: none)")
      .def_property_readonly(
          "coefficient_decay",
          [](const HillResult& h) {
            return py::dict(py::arg("kind") = std::string(ToString(h.decay.kind)),
                            py::arg("rate") = h.decay.rate,
                            py::arg("harmonics") = h.decay.harmonics,
                            py::arg("fourier_tail") = h.decay.fourier_tail,
                            py::arg("norms") = RealArray(h.decay.norms));
          },
          "how fast the Fourier coefficients of A decay: kind 'finite', 'exponential' or "
          "'algebraic'")
      .def_readonly("fourier_fit_error", &HillResult::fourier_fit_error,
                    "error of the exponents due to the FFT fit of A(t) (1/s); 0 for Fourier input")
      .def_readonly("tolerance_met", &HillResult::tolerance_met,
                    "harmonics='auto': whether tol was met; else None")
      .def_readonly(
          "error_estimate", &HillResult::error_estimate,
          "the error estimate of every exponent (1/s); see the C++ HillResult for its parts; "
          "None when no exponents were found")
      .def_readonly("model_error", &HillResult::model_error,
                    "for OpenFAST samples: the part of error_estimate that is the sampling "
                    "error (other interpolations of the same samples); None otherwise");
}

void BindHillResult(py::module_& m) {
  py::class_<HillResult> r(m, "HillResult", R"doc(
The result of ltp.hill: the n physical Floquet exponents among the eigenvalues of the
truncated Hill matrix, in the same order and with the same per-mode arrays as a
FloquetResult, with the selection's margins, the truncation error estimates and the
Koopman–Hill cross-check.)doc");
  BindModeArrays<HillResult>(r);
  BindHillRun(r);
  BindHillSelection(r);
  BindHillVerdict(r);
  r.def_property_readonly(
       "koopman_log_multipliers",
       [](const HillResult& h) { return ComplexArray(h.koopman_log_multipliers); },
       "log eig of the Koopman–Hill transition (sorting-free cross-check)")
      .def_readonly("koopman_discrepancy", &HillResult::koopman_discrepancy,
                    "max gap to the Koopman–Hill exponents (1/s); None when skipped")
      .def_property_readonly(
          "eigenvalues", [](const HillResult& h) { return ComplexArray(h.eigenvalues); },
          "every eigenvalue of the Hill matrix found")
      .def_readonly("elapsed_s", &HillResult::elapsed_s, "wall time (s)")
      .def_property_readonly("diagnostics", DiagnosticTexts(&HillResult::diagnostics),
                             "what the analysis noticed, one line each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&HillResult::diagnostics),
                             kDiagnosticCodesDoc)
      .def("__repr__",
           [](const HillResult& h) { return "<ltp.HillResult: " + h.BriefReport() + ">"; });
}

void BindHillStudyResult(py::module_& m) {
  py::class_<HillStudyRun>(m, "HillStudy", R"doc(
The result of ltp.hill_study: Hill's method at N = 1 .. max_harmonics (every N up to 10,
then about ×1.25), each row with its error against the monodromy route (modulo jΩp), the
a-priori bound and the N vs N+Δ estimate; the fitted convergence law; and the full analysis
at N = max_harmonics (`last`).)doc")
      .def_property_readonly("harmonics", StudyColumn(&HillStudyRow::harmonics), "N of each row")
      .def_property_readonly("matrix_size", StudyColumn(&HillStudyRow::matrix_size),
                             "(2N+1) n of each row")
      .def_property_readonly(
          "errors",
          [](const HillStudyRun& r) {
            std::vector<std::vector<double>> v;
            for (const HillStudyRow& row : r.study.rows) v.push_back(row.errors);
            return RealTable(v, r.study.reference.size());
          },
          "|λ_Hill − λ_ref| mod jΩp (1/s), float64 (rows, n): per row and mode, columns as in "
          "exponents and reference (empty without a reference)")
      .def_property_readonly(
          "exponents",
          [](const HillStudyRun& r) {
            size_t width = 0;
            for (const HillStudyRow& row : r.study.rows)
              width = std::max(width, row.exponents.size());
            const std::complex<double> nan(std::numeric_limits<double>::quiet_NaN(), 0.0);
            py::array_t<std::complex<double>> a(
                {static_cast<py::ssize_t>(r.study.rows.size()), static_cast<py::ssize_t>(width)});
            for (size_t i = 0; i < r.study.rows.size(); ++i)
              for (size_t k = 0; k < width; ++k)
                a.mutable_at(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) =
                    k < r.study.rows[i].exponents.size() ? r.study.rows[i].exponents[k] : nan;
            return a;
          },
          "Hill's exponents at each N (1/s), complex128 (len(harmonics), n): Hill's branch, one "
          "column per mode in the order of last.exponents (the last row is last.exponents); with "
          "a reference, Hill's match of each reference exponent; NaN where none matched")
      .def_property_readonly("max_error", StudyColumn(&HillStudyRow::max_error),
                             "per row; NaN without a reference")
      .def_property_readonly("apriori_bound", StudyColumn(&HillStudyRow::apriori_bound),
                             "a-priori error bound per row (inf: none)")
      .def_property_readonly("truncation_estimate", StudyColumn(&HillStudyRow::truncation_estimate),
                             "N vs N+Δ estimate per row (NaN when not computed)")
      .def_property_readonly("error_estimate", StudyColumn(&HillStudyRow::error_estimate),
                             "the analysis' error estimate per row (inf: no bound)")
      .def_property_readonly("selection_margin", StudyColumn(&HillStudyRow::selection_margin),
                             "smallest selection margin per row")
      .def_property_readonly("tail_weight", StudyColumn(&HillStudyRow::tail_weight),
                             "largest tail weight per row")
      .def_property_readonly(
          "convergence",
          [](const HillStudyRun& r) {
            return py::dict(py::arg("kind") = std::string(ToString(r.study.rate_kind)),
                            py::arg("rate") = r.study.rate);
          },
          "fitted law: kind 'exponential' (error ~ e^{-rate N}), 'algebraic' (~ N^{-rate}) or ''")
      .def_property_readonly(
          "coefficient_decay",
          [](const HillStudyRun& r) {
            return py::dict(py::arg("kind") = std::string(ToString(r.study.decay.kind)),
                            py::arg("rate") = r.study.decay.rate,
                            py::arg("harmonics") = r.study.decay.harmonics,
                            py::arg("fourier_tail") = r.study.decay.fourier_tail);
          },
          "how fast the Fourier coefficients of A decay")
      .def_property_readonly(
          "reference", [](const HillStudyRun& r) { return ComplexArray(r.study.reference); },
          "the monodromy route's exponents (rel tol 1e-12), in the columns' order of exponents "
          "and errors (empty: no reference)")
      .def_readonly("last", &HillStudyRun::last, "the HillResult at N = max_harmonics")
      .def_property_readonly(
          "elapsed_s", [](const HillStudyRun& r) { return r.study.elapsed_s; }, "wall time (s)")
      .def_property_readonly("diagnostics", DiagnosticTexts(&HillStudyRun::diagnostics),
                             "what the study noticed, one line each")
      .def_property_readonly("diagnostic_codes", DiagnosticCodes(&HillStudyRun::diagnostics),
                             kDiagnosticCodesDoc)
      .def("__repr__", [](const HillStudyRun& r) {
        return "<ltp.HillStudy: " + std::to_string(r.study.rows.size()) + " truncations, " +
               (r.study.rate_kind ? std::string(ToString(r.study.rate_kind)) : "rate not fitted") +
               ">";
      });
}

// The solver and the selection rule by the CLI's names, in the CLI's words when unknown; a long
// analysis of `function` warns before it starts.
HillOptions HillOptionsFrom(const std::string& function, const std::string& solver,
                            const std::string& selection) {
  HillOptions o;
  o.on_long_work = WarnLongWork(function);
  const auto s = ParseHillSolver(solver);
  if (!s) throw InputError("solver must be 'auto', 'dense' or 'structured', got '" + solver + "'");
  o.solver = *s;
  const auto rule = ParseHillSelectionRule(selection);
  if (!rule)
    throw InputError("selection must be 'centroid', 'central-weight' or 'strip', got '" +
                     selection + "'");
  o.selection = *rule;
  return o;
}

// ltp.hill_study: the options checked as the CLI checks them; the study runs without the GIL.
HillStudyRun LtpHillStudy(const System& system, int max_harmonics, const std::string& solver,
                          const std::string& selection, bool reference) {
  HillOptions o = HillOptionsFrom("hill_study", solver, selection);
  if (max_harmonics < 1) throw InputError("max_harmonics must be >= 1");
  return WithoutGil(system,
                    [&] { return RunHillStudy(system.system, max_harmonics, o, reference); });
}

void BindHillStudyFunction(py::module_& m) {
  m.def("hill_study", &LtpHillStudy, py::arg("system"), py::kw_only(),
        py::arg("max_harmonics") = kHillStudyMaxHarmonics,
        py::arg("solver") = std::string(ToString(HillOptions{}.solver)),
        py::arg("selection") = std::string(ToString(HillOptions{}.selection)),
        py::arg("reference") = true,
        R"doc(
Convergence study of Hill's method over the truncation N: `ltp hill SCENE --json` as a
function, with the same options and defaults.

  max_harmonics  largest truncation N
  solver         auto | dense | structured
  selection      centroid | central-weight | strip
  reference      measure each row's error against the monodromy route (rel tol 1e-12);
                 False: the CLI's --no-reference

The whole study is weighed before its first solve: refused (ltp.InputError) beyond an hour of
CPU even at its fastest, announced as a UserWarning beyond 10 s.

Returns a HillStudy. Runs without the GIL.)doc");
}

// ltp.hill: harmonics 'auto' or a positive integer; the analysis runs without the GIL.
HillResult LtpHill(const System& system, const py::object& harmonics, const std::string& solver,
                   const std::string& selection, Real tol) {
  HillOptions o = HillOptionsFrom("hill", solver, selection);
  if (!(tol > 0 && tol < 1)) throw InputError("tol must be in (0, 1)");
  if (py::isinstance<py::str>(harmonics) && harmonics.cast<std::string>() == "auto") {
    o.Validate();
    return WithoutGil(system, [&] {
      HillResult h = AnalyzeHillToTolerance(system.system, o, tol);
      IncludeModelError(system.model_alternatives, FloquetOptions{}, h);  // as the CLI
      return h;
    });
  }
  if (!py::isinstance<py::int_>(harmonics) || py::isinstance<py::bool_>(harmonics) ||
      harmonics.cast<long>() < 1 || harmonics.cast<long>() > 100000)
    throw InputError("harmonics must be a positive integer or 'auto', got " +
                     py::repr(harmonics).cast<std::string>());
  o.harmonics = harmonics.cast<int>();
  o.Validate();
  return WithoutGil(system, [&] {
    HillResult h = AnalyzeHill(system.system, o);
    IncludeModelError(system.model_alternatives, FloquetOptions{}, h);  // as the CLI
    return h;
  });
}

// ltp.hill_matrix: the library's Hill matrix of the system (exact or FFT-fitted coefficients, as
// ltp.hill uses them).
Eigen::MatrixXcd LtpHillMatrix(const System& system, const py::object& harmonics) {
  if (!py::isinstance<py::int_>(harmonics) || py::isinstance<py::bool_>(harmonics) ||
      harmonics.cast<long>() < 0 || harmonics.cast<long>() > 100000)
    throw InputError("harmonics must be an integer >= 0, got " +
                     py::repr(harmonics).cast<std::string>());
  const int N = harmonics.cast<int>();
  return WithoutGil(system, [&] { return HillMatrix(system.system, N); });
}

void BindHillMatrixFunction(py::module_& m) {
  m.def("hill_matrix", &LtpHillMatrix, py::arg("system"), py::kw_only(), py::arg("harmonics"),
        R"doc(
The truncated Hill matrix H_N of the system, as ltp.hill builds it: a complex128 array of
shape ((2N+1)n, (2N+1)n) whose block (v, u) (rows v·n.., columns u·n.. for the harmonics
v, u = -N..N in that order) is

    A_{v-u} - j v Ωp δ_vu I,     A(t) = sum_w A_w exp(j w Ωp t),  Ωp = 2π/T.

Its eigenvalues approximate λ_k + j m Ωp for every exponent λ_k and shift m; ltp.hill picks
n of them (HillResult.eigenvectors are this matrix's). A system not in Fourier form has A(t)
fitted by FFT first, as ltp.hill does. Raises ltp.ResourceError beyond 2 GiB.)doc");
}

void BindHillFunction(py::module_& m) {
  const HillOptions defaults;
  m.def("hill", &LtpHill, py::arg("system"), py::kw_only(), py::arg("harmonics") = "auto",
        py::arg("solver") = std::string(ToString(defaults.solver)),
        py::arg("selection") = std::string(ToString(defaults.selection)),
        py::arg("tol") = IntegratorOptions{}.rel_tol, R"doc(
Floquet exponents by Hill's method: `ltp floquet SCENE --method hill --json` as a function,
with the same options and defaults.

  harmonics   truncation N (harmonics -N..N), or 'auto': N = 4, 8, ... until the N vs N+Δ
              estimate is below max(tol, 1e-12) (the library's AnalyzeHillToTolerance)
  solver      auto | dense | structured (auto: per N, as the work-precision study found)
  selection   centroid | central-weight | strip: how the n physical eigenvalues are picked
  tol         the tolerance of harmonics='auto'

Returns a HillResult. Runs without the GIL. Systems not in Fourier form are fitted by FFT
first (the fit's error is part of the estimate). Raises ltp.InputError for bad options,
ltp.ResourceError when the Hill matrix would not fit in memory.)doc");
}

}  // namespace

void BindHill(py::module_& m) {
  BindHillResult(m);
  BindHillStudyResult(m);
  BindHillStudyFunction(m);
  BindHillFunction(m);
  BindHillMatrixFunction(m);
}

}  // namespace ltp::python
