#pragma once
// Failure map: every method in every hard regime, with one of three verdicts —
//   works           accurate (error ≤ 1e-6 relative) and the reported error estimate covers
//                   the true error (or the error is at round-off, ≤ 1e-12 relative);
//   fails, says so  not accurate (or not computed), but ltp says so: ok = false, a non-finite
//                   value, an error estimate that covers the true error, or a warning diagnostic;
//   fails silently  anything else: a wrong number presented as a good one.
// The true error is measured against a reference by a *different* method (closed form where
// one exists). Used by benchmarks/work_precision_benchmark.cc (docs/benchmarks.md) and by
// tests/htf/failure_map_test.cc (which asserts that no cell is silent).
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <map>
#include <numbers>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/floquet/floquet.h"
#include "ltp/hill/hill.h"
#include "ltp/htf/pfrf.h"
#include "ltp/models/scene.h"
#include "support/systems.h"
#include "support/work_precision_common.h"

namespace ltp::wp {

enum class Verdict { kWorks, kFailsSaysSo, kFailsSilently, kNotApplicable };

inline const char* VerdictText(Verdict v) {
  switch (v) {
    case Verdict::kWorks:
      return "works";
    case Verdict::kFailsSaysSo:
      return "fails, says so";
    case Verdict::kFailsSilently:
      return "**FAILS SILENTLY**";
    case Verdict::kNotApplicable:
      return "n/a";
  }
  return "?";
}

struct Cell {
  Verdict verdict = Verdict::kNotApplicable;
  double error_rel = -1;     ///< true error / scale
  double estimate_rel = -1;  ///< reported estimate / scale (-1: none)
  std::string how;           ///< what ltp said (short)
  double elapsed_s = 0;
};

struct Regime {
  std::string name;
  std::string reference;  ///< where the reference comes from
  PeriodicSystem sys;     ///< with input 0 on the last state and output 0 = state 0
  /// Reference exponents; empty: measured by the other route at a tight tolerance.
  std::vector<cd> exact;
  std::vector<double> freqs_hz;  ///< PFRF frequencies
  bool resonance = false;        ///< the PFRF reference is infinite (excited exactly at a pole)
  int hill_ref_harmonics = 32;   ///< truncation of the Hill reference (when not exact)
};

struct FailureMap {
  std::vector<std::string> methods;
  std::vector<Regime> regimes;
  std::vector<std::vector<Cell>> cells;  ///< [regime][method]
  std::vector<std::string> notes;
};

namespace fm {

constexpr double kPi = std::numbers::pi;

/// The same homogeneous part with B = e_n (last state) and C = e_1ᵀ.
inline PeriodicSystem WithIo(const PeriodicSystem& s) {
  const int n = s.states();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, 1), C = Eigen::MatrixXd::Zero(1, n);
  B(n - 1, 0) = 1;
  C(0, 0) = 1;
  if (s.fourier_A())
    return PeriodicSystem::FromFourier(s.period(), *s.fourier_A(), FourierMatrix::Constant(B),
                                       FourierMatrix::Constant(C));
  PeriodicSystem::Functions f;
  f.A = [s](double t, Eigen::Ref<Eigen::MatrixXd> out) { s.EvalA(t, out); };
  f.B = [B](double, Eigen::Ref<Eigen::MatrixXd> out) { out = B; };
  f.C = [C](double, Eigen::Ref<Eigen::MatrixXd> out) { out = C; };
  return PeriodicSystem::FromFunctions(s.period(), n, 1, 1, f, s.breakpoints());
}

/// x = R(t) z, z' = J z with J = [[0,1],[0,0]] (a Jordan block) and R a rotation by `rate`·t:
/// A(t) = R J Rᵀ + rate·[[0,−1],[1,0]], period 2π. Φ(2π) = R(2π) e^{2πJ}: a defective double
/// multiplier at +1 (rate 1) or −1 (rate 1/2). Exponents exactly 0 resp. j/2 (mod j).
inline PeriodicSystem Defective(double rate) {
  PeriodicSystem::Functions f;
  f.A = [rate](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const double c = std::cos(rate * t), s = std::sin(rate * t);
    Eigen::Matrix2d R, J, S;
    R << c, -s, s, c;
    J << 0, 1, 0, 0;
    S << 0, -rate, rate, 0;
    out = R * J * R.transpose() + S;
  };
  return PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f);
}

/// Jeffcott rotor (fixed frame) at speed Ω: closed-form exponents s + jΩ (mod 2jΩ), s the
/// eigenvalues of the time-invariant rotating-frame system (tests/support/systems.h).
inline std::vector<cd> JeffcottExact(double m, double k1, double k2, double c, double omega) {
  const Eigen::VectorXcd s = test::JeffcottRotatingEigenvalues(m, k1, k2, c, omega);
  std::vector<cd> e;
  for (Eigen::Index k = 0; k < s.size(); ++k) e.push_back(s(k) + cd(0, omega));
  return e;
}

/// Very high harmonic content: y'' + 0.1 y' + (2 + 0.5 · 0.19/(1.01 − cos t)) y = 0 — a sharp
/// stiffness pulse once per period, Fourier coefficients decaying only like e^{−0.14|w|}.
inline PeriodicSystem Pulse() {
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const double k = 2 + 0.5 * 0.19 / (1.01 - std::cos(t));
    out << 0, 1, -k, -0.1;
  };
  return PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f);
}

/// The source tree (for tests/data/stiff.yaml): compile-time in the benchmarks, the
/// LTP_SOURCE_DIR environment variable under ctest.
inline std::string SourceDir() {
#ifdef LTP_SOURCE_DIR
  return LTP_SOURCE_DIR;
#else
  const char* dir = std::getenv("LTP_SOURCE_DIR");
  return dir ? dir : ".";
#endif
}

// A warning or failure among the diagnostics (by severity, not by its words); `which` gets the
// first one's text.
inline bool Warns(const std::vector<Diagnostic>& diagnostics, std::string* which) {
  for (const Diagnostic& d : diagnostics)
    if (d.severity != Severity::kNote) {
      if (which) *which = d.text.substr(0, 90);
      return true;
    }
  return false;
}

/// Verdict from what the method claimed and what it got.
inline Cell Judge(bool ok, double err, std::optional<double> estimate, double scale,
                  const std::vector<Diagnostic>& diagnostics, const std::string& failure = "") {
  Cell c;
  c.error_rel = std::isfinite(err) ? err / scale : kInf;
  c.estimate_rel = estimate ? *estimate / scale : -1;
  const bool covers = estimate && *estimate >= err;  // +inf estimate covers: "unknown"
  std::string warning;
  const bool warns = Warns(diagnostics, &warning);
  if (ok && std::isfinite(err) && c.error_rel <= 1e-6 && (covers || c.error_rel <= 1e-12)) {
    c.verdict = Verdict::kWorks;
  } else if (!ok) {
    c.verdict = Verdict::kFailsSaysSo;
    // What it said: its warning if it gave one (the first diagnostics may be informational,
    // such as which integrator `auto` picked), else its last word.
    c.how = !failure.empty()      ? failure
            : warns               ? warning
            : diagnostics.empty() ? "not ok"
                                  : diagnostics.back().text.substr(0, 90);
  } else if (covers) {
    c.verdict = Verdict::kFailsSaysSo;
    c.how = "estimate covers the error";
  } else if (warns) {
    c.verdict = Verdict::kFailsSaysSo;
    c.how = warning;
  } else {
    c.verdict = Verdict::kFailsSilently;
    std::ostringstream h;
    h << "error " << std::setprecision(2) << c.error_rel << " relative, estimate "
      << c.estimate_rel;
    c.how = h.str();
  }
  return c;
}

}  // namespace fm

/// Regimes of the issue, each with its reference.
inline std::vector<Regime> FailureRegimes(bool quick) {
  using namespace fm;
  std::vector<Regime> r;
  r.push_back({"multipliers beyond the double range (stiff.yaml: ρ = e^{-5027}, e^{942})",
               "closed form (triangular)",
               WithIo(LoadScene(SourceDir() + "/tests/data/stiff.yaml").Build()),
               {cd(-800, 0), cd(150, 0), cd(-3, 0)},
               {0.1, 1.3}});
  // Overdamped y'' + 2000 y' + (1 − 2·0.5 cos Ωp t) y, Ωp = 200: exponents ≈ −2000 and ≈ −5e-4.
  r.push_back({"stiff damping, fast rotation (c = 2000, Ωp = 200)",
               "monodromy rkf78 1e-13 vs Hill N = 32",
               WithIo(test::Mathieu(1, 0.5, 2000, 200)),
               {},
               {1.0, 40.0}});
  r.push_back({"discontinuous coefficients (Meissner a=2, b=0.5, c=0.05)",
               "closed-form monodromy",
               WithIo(LoadScene("meissner").Build({{"a", "2"}, {"b", "0.5"}, {"c", "0.05"}})),
               {},
               {0.1, 0.3}});
  {
    const Eigen::Matrix2d phi = [] {
      auto E = [](double k, double tau) -> Eigen::Matrix2d {
        Eigen::Matrix2d m;
        m << 0, 1, -k, -0.05;
        return (m * tau).exp();
      };
      return Eigen::Matrix2d(E(2.5, kPi / 2) * E(1.5, kPi) * E(2.5, kPi / 2));
    }();
    for (int k = 0; k < 2; ++k)
      r.back().exact.push_back(std::log(cd(phi.eigenvalues()(k))) / (2 * kPi));
  }
  r.push_back({"exponents on the strip edge (Mathieu a=1.5, q=2: negative real multipliers)",
               "monodromy rkf78 1e-13 vs Hill N = 32",
               WithIo(test::Mathieu(1.5, 2, 0.05)),
               {},
               {0.1, 0.25}});
  r.push_back({"defective double multiplier at +1 (Jordan block, Lyapunov-reducible)",
               "closed form: λ = 0, 0",
               WithIo(Defective(1.0)),
               {cd(0, 0), cd(0, 0)},
               {0.3, 0.7}});
  r.push_back({"defective double multiplier at −1 (Jordan block, Lyapunov-reducible)",
               "closed form: λ = j/2, j/2",
               WithIo(Defective(0.5)),
               {cd(0, 0.5), cd(0, 0.5)},
               {0.2, 0.9}});
  {
    // Undamped stable Mathieu excited exactly at its Floquet frequency: H is infinite there.
    Regime res{"undamped, excited exactly at a resonance (Mathieu a=1.5, q=0.2, c=0)",
               "H is infinite: any finite value must come with a warning",
               WithIo(test::Mathieu(1.5, 0.2, 0)),
               {},
               {},
               true};
    FloquetOptions o;
    o.integrator.type = IntegratorType::kRkf78;
    o.integrator.rel_tol = 1e-14;
    const FloquetResult fl = AnalyzeFloquet(res.sys, o);
    double f = 0;
    for (const auto& m : fl.modes) f = std::max(f, m.exponent.imag() / (2 * kPi));
    res.freqs_hz = {f};
    r.push_back(res);
  }
  r.push_back({"very slow rotation (Jeffcott, Ω = 0.02: Ωp/ω₀ ≈ 0.04)",
               "closed form: rotating-frame eigenvalues",
               WithIo(test::Jeffcott(1, 1, 1.5, 0.05, 0.02)),
               JeffcottExact(1, 1, 1.5, 0.05, 0.02),
               {0.1, 0.2}});
  r.push_back({"very high harmonic content (stiffness pulse, ‖A_w‖ ~ e^{−0.14|w|})",
               "monodromy rkf78 1e-13 vs Hill N = 256",
               WithIo(Pulse()),
               {},
               {0.1, 0.3}});
  r.back().hill_ref_harmonics = 256;
  // x = R(θ(t)) z, z' = diag(120, −120.5) z: the exponents lie far from A_0's eigenvalues
  // (−0.25 ± j), where a banded search finds only truncation-edge eigenvalues that N vs N+Δ
  // and Liouville both pass (docs/hill-method.md, "Edge eigenvalues").
  r.push_back({"truncation-edge eigenvalues (reducible x = R(θ)z, exponents 120 and −120.5)",
               "closed form: λ = 120, −120.5",
               WithIo(test::ReducibleRotation(120, -120.5, 0.5)),
               {cd(120, 0), cd(-120.5, 0)},
               {0.1, 0.3}});
  // Coefficients ∝ 0.9^|w|: N vs N+Δ alone fell 1–4 % short of the error at N = 32–64.
  r.push_back({"slowly decaying harmonics (Poisson kernel, ‖A_w‖ ~ 0.9^|w|)",
               "monodromy rkf78 1e-13 vs Hill N = 96",
               WithIo(test::PoissonKernel(0.8, 0.2, 0.9, 0.02)),
               {},
               {0.1, 0.3}});
  r.back().hill_ref_harmonics = 96;
  r.push_back({quick ? "large n (chain of 10 Mathieu oscillators, n = 20)"
                     : "large n (chain of 20 Mathieu oscillators, n = 40)",
               "monodromy rkf78 1e-13 vs Hill structured N = 24",
               WithIo(test::MathieuChain(quick ? 10 : 20, 0.05, 0.3)),
               {},
               {0.1, 0.2}});
  r.back().hill_ref_harmonics = 24;
  return r;
}

namespace fm {

/// The reference integration: RKF78 at 1e-13, no estimate.
inline FloquetOptions TightFloquet() {
  FloquetOptions tight;
  tight.integrator.type = IntegratorType::kRkf78;
  tight.integrator.rel_tol = 1e-13;
  tight.integrator.abs_tol = 1e-16;
  tight.estimate_error = false;
  return tight;
}

/// Reference exponents for each route: the closed form, or the other route at a tight
/// tolerance (then `note` says how far the two references agree).
struct ExponentReferences {
  std::vector<cd> for_monodromy, for_hill;
  double scale = 1;  ///< max(1, largest |exponent|)
};

inline ExponentReferences ReferenceExponents(const Regime& reg, std::vector<std::string>& notes) {
  const PeriodicSystem& s = reg.sys;
  ExponentReferences ref{reg.exact, reg.exact};
  if (reg.exact.empty()) {
    const FloquetResult fl = AnalyzeFloquet(s, TightFloquet());
    ref.for_hill = Exponents(fl.modes);
    HillOptions ho;
    ho.solver = HillSolver::kStructured;
    ho.harmonics = reg.hill_ref_harmonics;
    ho.expected = ref.for_hill;
    ho.delta_harmonics = -1;
    ho.koopman_check = false;
    ho.fourier.tol = 1e-15;
    const HillResult h = AnalyzeHill(s, ho);
    ref.for_monodromy = Exponents(h.modes);
    const double agree = ExponentError(ref.for_monodromy, ref.for_hill, s.omega());
    std::ostringstream n;
    n << reg.name << ": references agree to " << agree << " 1/s";
    notes.push_back(n.str());
  }
  for (const cd& x : ref.for_hill) ref.scale = std::max(ref.scale, std::abs(x));
  return ref;
}

/// A silent cell when some exponent's own estimate (FloquetMode::error_estimate) does not cover
/// its own error.
inline void JudgeOwnEstimates(const FloquetResult& r, const ExponentReferences& ref, double omega,
                              Cell& c) {
  if (!r.ok || c.verdict == Verdict::kFailsSilently ||
      Exponents(r.modes).size() != ref.for_monodromy.size())
    return;
  const std::vector<double> own_errors =
      MatchExponents(Exponents(r.modes), ref.for_monodromy, omega);
  for (size_t k = 0; k < r.modes.size(); ++k) {
    const auto& own = r.modes[k].error_estimate;
    if (own && !(*own >= own_errors[k]) && own_errors[k] > 1e-12 * ref.scale) {
      std::ostringstream h;
      h << "exponent " << r.modes[k].exponent << ": error " << own_errors[k]
        << ", its own estimate " << *own;
      c.verdict = Verdict::kFailsSilently;
      c.how = h.str();
    }
  }
}

/// Methods 1, 2: the monodromy route (defaults of `ltp floquet`: integrator auto), and the
/// single-shot multipliers.
inline std::vector<Cell> MonodromyCells(const Regime& reg, const ExponentReferences& ref) {
  std::vector<Cell> cells;
  for (MultiplierMethod mm : {MultiplierMethod::kPeriodicSchur, MultiplierMethod::kSingleShot}) {
    FloquetOptions o;
    o.integrator.type = IntegratorType::kAuto;
    o.multipliers = mm;
    const double t0 = WallNow();
    const FloquetResult r = AnalyzeFloquet(reg.sys, o);
    const double err =
        r.ok ? ExponentError(Exponents(r.modes), ref.for_monodromy, reg.sys.omega()) : kInf;
    Cell c = Judge(r.ok, err, r.error_estimate, ref.scale, r.diagnostics);
    JudgeOwnEstimates(r, ref, reg.sys.omega(), c);
    c.elapsed_s = WallNow() - t0;
    cells.push_back(c);
  }
  return cells;
}

/// The Koopman–Hill projection of an automatic Hill run. Its error is at most its gap to Hill's
/// exponents plus Hill's own error (the gap alone fell short on the Poisson kernel, where Hill's
/// error is 5 % of the gap).
inline Cell KoopmanCell(const HillResult& h, const ExponentReferences& ref, double omega) {
  if (h.koopman_log_multipliers.empty())
    return Judge(false, kInf, std::nullopt, ref.scale, {},
                 h.koopman_discrepancy ? "no result" : "skipped (matrix too large), says so");
  const auto e = FromLogMultipliers(h.koopman_log_multipliers, h.period);
  const double err = ExponentError(e, ref.for_hill, omega);
  std::optional<double> bound;
  if (h.koopman_discrepancy && h.error_estimate) bound = *h.koopman_discrepancy + *h.error_estimate;
  return Judge(h.ok, err, bound, ref.scale, h.diagnostics);
}

/// Methods 3, 4: Hill with the truncation chosen automatically (`--method hill`, tol 1e-10;
/// solver auto as `ltp floquet` picks it, and structured); 5: its Koopman–Hill projection.
inline std::vector<Cell> HillCells(const Regime& reg, const ExponentReferences& ref, bool quick) {
  std::vector<Cell> cells;
  HillResult hill_auto;
  for (HillSolver solver : {HillSolver::kAuto, HillSolver::kStructured}) {
    HillOptions ho;
    ho.solver = solver;
    const double t0 = WallNow();
    HillResult h;
    Cell c;
    try {
      h = AnalyzeHillAuto(reg.sys, ho, 1e-10, quick ? 64 : 128);
      const double err =
          h.ok ? ExponentError(Exponents(h.modes), ref.for_hill, reg.sys.omega()) : kInf;
      c = Judge(h.ok, err, HillEstimate(h), ref.scale, h.diagnostics);
    } catch (const Error& e) {
      c = Judge(false, kInf, std::nullopt, ref.scale, {}, e.what());
    }
    c.elapsed_s = WallNow() - t0;
    cells.push_back(c);
    if (solver == HillSolver::kAuto) hill_auto = h;
  }
  cells.push_back(KoopmanCell(hill_auto, ref, reg.sys.omega()));
  return cells;
}

/// Reference partial FRFs at the regime's frequencies, orders −2…2, by three routes: shooting
/// at 1e-13, modal at 1e-13 and the HTF at 256 harmonics. Each route is measured against
/// another route's.
struct PfrfReferences {
  std::vector<PartialFrfs> shooting, modal, htf;
  bool shooting_ok = false, modal_ok = false, htf_ok = false;

  /// The reference for `route`: one computed by another route; null when none exists.
  const std::vector<PartialFrfs>* For(PfrfRoute route) const {
    if (route != PfrfRoute::kShooting && shooting_ok) return &shooting;
    if (route != PfrfRoute::kModal && modal_ok) return &modal;
    if (route != PfrfRoute::kHtf && htf_ok) return &htf;
    return nullptr;
  }

  /// How far the references themselves disagree (shooting vs modal, when both exist): a
  /// smaller "error" is not measurable.
  double Spread() const {
    double spread = 0;
    if (shooting_ok && modal_ok)
      for (size_t f = 0; f < shooting.size(); ++f)
        for (size_t z = 0; z < shooting[f].size(); ++z)
          spread = std::max(spread, std::abs(shooting[f][z](0, 0) - modal[f][z](0, 0)));
    return spread;
  }
};

inline void ShootingReference(const Regime& reg, PfrfReferences& refs) {
  try {
    ShootingOptions so;
    so.rel_tol = 1e-13;
    so.abs_tol = 1e-16;
    so.integrator = TightFloquet().integrator;
    ForcedResponseSolver fs(reg.sys, so);
    refs.shooting_ok = true;
    for (double f : reg.freqs_hz) {
      bool ok = true;
      refs.shooting.push_back(fs.Shooting(2 * kPi * f, -2, 2, &ok));
      refs.shooting_ok = refs.shooting_ok && ok && refs.shooting.back().back().allFinite();
    }
  } catch (const Error&) {
    refs.shooting_ok = false;
  }
}

inline void ModalReference(const Regime& reg, PfrfReferences& refs) {
  try {
    const FloquetOptions tight = TightFloquet();
    FloquetResult fl = AnalyzeFloquet(reg.sys, tight);
    ModalOptions mo;
    mo.integrator = tight.integrator;
    const ModalModel mm = BuildModalModel(reg.sys, fl, mo);
    refs.modal_ok = fl.ok && mm.reliable;
    for (double f : reg.freqs_hz) refs.modal.push_back(mm.Evaluate(2 * kPi * f, -2, 2));
  } catch (const Error&) {
    refs.modal_ok = false;
  }
}

inline void HtfReference(const Regime& reg, PfrfReferences& refs) {
  try {
    HtfOptions ho;
    ho.harmonics = 256;
    HtfSolver htf(reg.sys, ho);
    refs.htf_ok = true;
    for (double f : reg.freqs_hz) {
      refs.htf.push_back(htf.Evaluate(2 * kPi * f, -2, 2));
      refs.htf_ok = refs.htf_ok && refs.htf.back().back().allFinite();
    }
    // Jumps: the HTF converges like N^-1 at best, no reference.
    if (!reg.sys.breakpoints().empty()) refs.htf_ok = false;
  } catch (const Error&) {
    refs.htf_ok = false;
  }
}

/// None at a resonance (the reference is infinite there).
inline PfrfReferences ReferencePfrfs(const Regime& reg) {
  PfrfReferences refs;
  if (reg.resonance) return refs;
  ShootingReference(reg, refs);
  ModalReference(reg, refs);
  HtfReference(reg, refs);
  return refs;
}

/// `ltp pfrf --route R` (checks: htf for modal, modal otherwise) with a check at every
/// frequency; auto exactly as `ltp pfrf`'s defaults.
inline PfrfOptions PfrfOptionsFor(const Regime& reg, PfrfRoute route) {
  PfrfOptions po;
  po.frequencies_hz = reg.freqs_hz;
  po.min_order = -2;
  po.max_order = 2;
  po.primary = route;
  po.checks = {route == PfrfRoute::kModal ? PfrfRoute::kHtf : PfrfRoute::kModal};
  if (route == PfrfRoute::kAuto) {
    po.checks = {PfrfRoute::kAuto};
    po.floquet.integrator.type = IntegratorType::kAuto;
    po.modal.integrator.type = IntegratorType::kAuto;
  }
  po.check_every = 1;
  return po;
}

inline bool AllFinite(const PfrfResult& pr) {
  if (!pr.ok) return false;
  for (const auto& row : pr.values)
    for (const cd& v : row)
      if (!std::isfinite(v.real()) || !std::isfinite(v.imag())) return false;
  return true;
}

/// At a resonance the reference is infinite: a finite answer must say it is unreliable
/// (a warning, or not ok).
inline Cell JudgeAtResonance(const PfrfResult& pr) {
  Cell c;
  std::string w;
  if (!AllFinite(pr)) {
    c.verdict = Verdict::kFailsSaysSo;
    c.how = "non-finite value / not ok";
  } else if (Warns(pr.diagnostics, &w)) {
    c.verdict = Verdict::kFailsSaysSo;
    c.how = w;
  } else {
    double vmax = 0, emin = kInf;
    for (size_t z = 0; z < pr.values[0].size(); ++z) {
      vmax = std::max(vmax, std::abs(pr.values[0][z]));
      emin = std::min(emin, pr.error_estimate[0][z]);
    }
    c.verdict = Verdict::kFailsSilently;
    std::ostringstream h;
    h << "finite |H| = " << vmax << ", estimate " << emin;
    c.how = h.str();
  }
  return c;
}

/// Against a reference: "covers" means every value's estimate covers its error (errors below
/// the references' own spread are not measurable and not counted).
inline Cell JudgeAgainst(const Regime& reg, const PfrfResult& pr,
                         const std::vector<PartialFrfs>& ref, double spread) {
  double hscale = 0, err = 0, worst_ratio = kInf;
  std::string worst_at;
  bool covered = true;
  for (size_t f = 0; f < pr.values.size(); ++f)
    for (size_t z = 0; z < pr.values[f].size(); ++z) {
      const cd rv = ref[f][z](0, 0);
      hscale = std::max(hscale, std::abs(rv));
      const double d = std::abs(pr.values[f][z] - rv);
      err = std::max(err, d);
      if (d <= spread) continue;
      if (pr.error_estimate[f][z] / d < worst_ratio) {
        worst_ratio = pr.error_estimate[f][z] / d;
        std::ostringstream w;
        w << std::setprecision(2) << " at f = " << reg.freqs_hz[f] << " Hz, z = " << int(z) - 2
          << ": |H| " << std::abs(rv) << ", error " << d << ", estimate "
          << pr.error_estimate[f][z];
        worst_at = w.str();
      }
      if (!(pr.error_estimate[f][z] >= d)) covered = false;
    }
  hscale = std::max(hscale, 1e-300);
  Cell c = Judge(AllFinite(pr), err, covered ? err : 0, hscale, pr.diagnostics);
  if (c.verdict == Verdict::kFailsSilently) {
    std::ostringstream h;
    h << "error " << std::setprecision(2) << c.error_rel << " relative; smallest estimate/error "
      << worst_ratio << worst_at << " (reference spread " << spread / hscale << ")";
    c.how = h.str();
  }
  return c;
}

/// Methods 6–10: partial FRFs by each route.
inline Cell PfrfCell(const Regime& reg, PfrfRoute route, const PfrfReferences& refs) {
  const double t0 = WallNow();
  Cell c;
  try {
    const PfrfResult pr = ComputePartialFrf(reg.sys, PfrfOptionsFor(reg, route));
    // Auto: measured against a reference from a route other than the one it picked.
    const auto* ref = refs.For(route == PfrfRoute::kAuto ? pr.routes.front().route : route);
    if (reg.resonance) {
      c = JudgeAtResonance(pr);
    } else if (!ref) {
      c.verdict = Verdict::kNotApplicable;
      c.how = "no reference";
    } else {
      c = JudgeAgainst(reg, pr, *ref, refs.Spread());
    }
  } catch (const Error& e) {
    c = Judge(false, kInf, std::nullopt, 1, {}, std::string(e.what()).substr(0, 90));
  }
  c.elapsed_s = WallNow() - t0;
  return c;
}

}  // namespace fm

/// `only`: run just the regimes whose name contains it (empty: all).
inline FailureMap RunFailureMap(bool quick = false, std::ostream* progress = nullptr,
                                const std::string& only = "") {
  using namespace fm;
  FailureMap map;
  map.methods = {"monodromy (ltp floquet)",
                 "monodromy single-shot",
                 "Hill auto solver (auto N)",
                 "Hill structured (auto N)",
                 "Koopman–Hill",
                 "PFRF auto (ltp pfrf)",
                 "PFRF modal",
                 "PFRF htf",
                 "PFRF shooting",
                 "PFRF time"};
  map.regimes = FailureRegimes(quick);
  if (!only.empty())
    std::erase_if(map.regimes,
                  [&](const Regime& r) { return r.name.find(only) == std::string::npos; });
  for (const Regime& reg : map.regimes) {
    const ExponentReferences ref = ReferenceExponents(reg, map.notes);
    std::vector<Cell> row = MonodromyCells(reg, ref);
    for (const Cell& c : HillCells(reg, ref, quick)) row.push_back(c);
    const PfrfReferences refs = ReferencePfrfs(reg);
    for (PfrfRoute route : {PfrfRoute::kAuto, PfrfRoute::kModal, PfrfRoute::kHtf,
                            PfrfRoute::kShooting, PfrfRoute::kTime})
      row.push_back(PfrfCell(reg, route, refs));
    if (progress) {
      *progress << "failure map: " << reg.name << ":";
      for (const Cell& c : row) *progress << " " << std::setprecision(2) << c.elapsed_s << "s";
      *progress << "\n";
    }
    map.cells.push_back(row);
  }
  return map;
}

inline void WriteFailureMap(const FailureMap& map, std::ostream& out) {
  out << "| regime (reference) |";
  for (const auto& m : map.methods) out << " " << m << " |";
  out << "\n|---|";
  for (size_t i = 0; i < map.methods.size(); ++i) out << "---|";
  out << "\n";
  std::vector<std::string> footnotes;
  for (size_t r = 0; r < map.regimes.size(); ++r) {
    out << "| " << map.regimes[r].name << " (" << map.regimes[r].reference << ") |";
    for (const Cell& c : map.cells[r]) {
      out << " " << VerdictText(c.verdict);
      if (c.verdict == Verdict::kWorks) {
        std::ostringstream e;
        e << std::setprecision(1) << std::scientific << c.error_rel;
        out << " (" << e.str() << ")";
      } else if (!c.how.empty()) {
        footnotes.push_back(c.how);
        out << " [" << footnotes.size() << "]";
      }
      out << " |";
    }
    out << "\n";
  }
  out << "\n";
  for (size_t i = 0; i < footnotes.size(); ++i)
    out << "[" << i + 1 << "] " << footnotes[i] << "  \n";
  for (const auto& n : map.notes) out << "- " << n << "\n";
}

inline int SilentCells(const FailureMap& map) {
  int n = 0;
  for (const auto& row : map.cells)
    for (const Cell& c : row) n += c.verdict == Verdict::kFailsSilently;
  return n;
}

}  // namespace ltp::wp
