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
#include "ltp/floquet/hill.h"
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
    map.regimes.erase(
        std::remove_if(map.regimes.begin(), map.regimes.end(),
                       [&](const Regime& r) { return r.name.find(only) == std::string::npos; }),
        map.regimes.end());
  for (const Regime& reg : map.regimes) {
    const PeriodicSystem& s = reg.sys;
    const double omega = s.omega();
    // Reference exponents: the closed form, or the other route at a tight tolerance.
    FloquetOptions tight;
    tight.integrator.type = IntegratorType::kRkf78;
    tight.integrator.rel_tol = 1e-13;
    tight.integrator.abs_tol = 1e-16;
    tight.estimate_error = false;
    std::vector<cd> ref_for_mono = reg.exact, ref_for_hill = reg.exact;
    if (reg.exact.empty()) {
      const FloquetResult fl = AnalyzeFloquet(s, tight);
      ref_for_hill = Exponents(fl.modes);
      HillOptions ho;
      ho.solver = HillSolver::kStructured;
      ho.harmonics = reg.hill_ref_harmonics;
      ho.expected = ref_for_hill;
      ho.delta_harmonics = -1;
      ho.koopman_check = false;
      ho.fourier.tol = 1e-15;
      const HillResult h = AnalyzeHill(s, ho);
      ref_for_mono = Exponents(h.modes);
      const double agree = ExponentError(ref_for_mono, ref_for_hill, omega);
      std::ostringstream n;
      n << reg.name << ": references agree to " << agree << " 1/s";
      map.notes.push_back(n.str());
    }
    double scale = 1;
    for (const cd& x : ref_for_hill) scale = std::max(scale, std::abs(x));
    std::vector<Cell> row;
    // 1, 2: monodromy route (defaults of `ltp floquet`: integrator auto), and the single-shot
    // multipliers.
    for (MultiplierMethod mm : {MultiplierMethod::kPeriodicSchur, MultiplierMethod::kSingleShot}) {
      FloquetOptions o;
      o.integrator.type = IntegratorType::kAuto;
      o.multipliers = mm;
      const double t0 = WallNow();
      const FloquetResult r = AnalyzeFloquet(s, o);
      const double err = r.ok ? ExponentError(Exponents(r.modes), ref_for_mono, omega) : kInf;
      Cell c = Judge(r.ok, err, r.error_estimate, scale, r.diagnostics);
      // Each exponent's own estimate (FloquetMode::error_estimate) must cover its own error.
      if (r.ok && c.verdict != Verdict::kFailsSilently &&
          Exponents(r.modes).size() == ref_for_mono.size()) {
        const std::vector<double> own_errors =
            MatchExponents(Exponents(r.modes), ref_for_mono, omega);
        for (size_t k = 0; k < r.modes.size(); ++k) {
          const auto& own = r.modes[k].error_estimate;
          if (own && !(*own >= own_errors[k]) && own_errors[k] > 1e-12 * scale) {
            std::ostringstream h;
            h << "exponent " << r.modes[k].exponent << ": error " << own_errors[k]
              << ", its own estimate " << *own;
            c.verdict = Verdict::kFailsSilently;
            c.how = h.str();
          }
        }
      }
      c.elapsed_s = WallNow() - t0;
      row.push_back(c);
    }
    // 3, 4: Hill with the truncation chosen automatically (`--method hill`, tol 1e-10; solver
    // auto as `ltp floquet` picks it, and structured); 5: its Koopman–Hill projection
    // (estimate: the disagreement with Hill's exponents plus Hill's own estimate).
    HillResult hill_auto;
    for (HillSolver solver : {HillSolver::kAuto, HillSolver::kStructured}) {
      HillOptions ho;
      ho.solver = solver;
      const double t0 = WallNow();
      HillResult h;
      Cell c;
      try {
        h = AnalyzeHillAuto(s, ho, 1e-10, quick ? 64 : 128);
        const double err = h.ok ? ExponentError(Exponents(h.modes), ref_for_hill, s.omega()) : kInf;
        c = Judge(h.ok, err, HillEstimate(h), scale, h.diagnostics);
      } catch (const Error& e) {
        c = Judge(false, kInf, std::nullopt, scale, {}, e.what());
      }
      c.elapsed_s = WallNow() - t0;
      row.push_back(c);
      if (solver == HillSolver::kAuto) hill_auto = h;
    }
    {
      Cell c;
      const HillResult& h = hill_auto;
      if (h.koopman_log_multipliers.empty()) {
        c = Judge(false, kInf, std::nullopt, scale, {},
                  h.koopman_discrepancy ? "no result" : "skipped (matrix too large), says so");
      } else {
        const auto e = FromLogMultipliers(h.koopman_log_multipliers, h.period);
        const double err = ExponentError(e, ref_for_hill, s.omega());
        // Its error is at most its gap to Hill's exponents plus Hill's own error (the gap alone
        // fell short on the Poisson kernel, where Hill's error is 5 % of the gap).
        std::optional<double> bound;
        if (h.koopman_discrepancy && h.error_estimate)
          bound = *h.koopman_discrepancy + *h.error_estimate;
        c = Judge(h.ok, err, bound, scale, h.diagnostics);
      }
      row.push_back(c);
    }
    // 6–9: partial FRFs, `ltp pfrf --route R` (checks: htf for modal, modal otherwise) with a
    // check at every frequency. Reference: shooting at 1e-13 (modal at 1e-13 for shooting).
    // Three candidate references; each route is measured against another route's.
    std::vector<PartialFrfs> ref_shoot, ref_modal, ref_htf;
    bool shoot_ok = !reg.resonance, modal_ok = !reg.resonance, htf_ok = !reg.resonance;
    if (!reg.resonance) {
      try {
        ShootingOptions so;
        so.rel_tol = 1e-13;
        so.abs_tol = 1e-16;
        so.integrator = tight.integrator;
        ForcedResponseSolver fs(s, so);
        for (double f : reg.freqs_hz) {
          bool ok = true;
          ref_shoot.push_back(fs.Shooting(2 * kPi * f, -2, 2, &ok));
          shoot_ok = shoot_ok && ok && ref_shoot.back().back().allFinite();
        }
      } catch (const Error&) {
        shoot_ok = false;
      }
      try {
        FloquetResult fl = AnalyzeFloquet(s, tight);
        ModalOptions mo;
        mo.integrator = tight.integrator;
        const ModalModel mm = BuildModalModel(s, fl, mo);
        modal_ok = fl.ok && mm.reliable;
        for (double f : reg.freqs_hz) ref_modal.push_back(mm.Evaluate(2 * kPi * f, -2, 2));
      } catch (const Error&) {
        modal_ok = false;
      }
      try {
        HtfOptions ho;
        ho.harmonics = 256;
        HtfSolver htf(s, ho);
        for (double f : reg.freqs_hz) {
          ref_htf.push_back(htf.Evaluate(2 * kPi * f, -2, 2));
          htf_ok = htf_ok && ref_htf.back().back().allFinite();
        }
        // Jumps: the HTF converges like N^-1 at best, no reference.
        if (!s.breakpoints().empty()) htf_ok = false;
      } catch (const Error&) {
        htf_ok = false;
      }
    }
    auto reference_for = [&](PfrfRoute route, bool* ok) -> const std::vector<PartialFrfs>& {
      *ok = true;
      if (route != PfrfRoute::kShooting && shoot_ok) return ref_shoot;
      if (route != PfrfRoute::kModal && modal_ok) return ref_modal;
      if (route != PfrfRoute::kHtf && htf_ok) return ref_htf;
      *ok = false;
      return ref_shoot;
    };
    for (PfrfRoute route : {PfrfRoute::kAuto, PfrfRoute::kModal, PfrfRoute::kHtf,
                            PfrfRoute::kShooting, PfrfRoute::kTime}) {
      PfrfOptions po;
      po.frequencies_hz = reg.freqs_hz;
      po.min_order = -2;
      po.max_order = 2;
      po.primary = route;
      po.checks = {route == PfrfRoute::kModal ? PfrfRoute::kHtf : PfrfRoute::kModal};
      if (route == PfrfRoute::kAuto) {  // exactly `ltp pfrf`'s defaults
        po.checks = {PfrfRoute::kAuto};
        po.floquet.integrator.type = IntegratorType::kAuto;
        po.modal.integrator.type = IntegratorType::kAuto;
      }
      po.check_every = 1;
      const double t0 = WallNow();
      Cell c;
      try {
        const PfrfResult pr = ComputePartialFrf(s, po);
        bool ref_ok = false;
        // Auto: measured against a reference from a route other than the one it picked.
        const auto& ref =
            reference_for(route == PfrfRoute::kAuto ? pr.routes.front().route : route, &ref_ok);
        double hscale = 0, err = 0, est = kInf, worst_ratio = kInf;
        std::string worst_at;
        bool finite = pr.ok;
        bool covered = true;
        // What the references themselves disagree by (shooting vs modal, when both exist):
        // a smaller "error" is not measurable.
        double spread = 0;
        if (shoot_ok && modal_ok)
          for (size_t f = 0; f < ref_shoot.size(); ++f)
            for (size_t z = 0; z < ref_shoot[f].size(); ++z)
              spread = std::max(spread, std::abs(ref_shoot[f][z](0, 0) - ref_modal[f][z](0, 0)));
        for (size_t f = 0; f < pr.values.size(); ++f)
          for (size_t z = 0; z < pr.values[f].size(); ++z) {
            const cd v = pr.values[f][z];
            if (!std::isfinite(v.real()) || !std::isfinite(v.imag())) finite = false;
            if (!reg.resonance && ref_ok) {
              const cd rv = ref[f][z](0, 0);
              hscale = std::max(hscale, std::abs(rv));
              const double d = std::abs(v - rv);
              err = std::max(err, d);
              if (d > spread) {
                if (pr.error_estimate[f][z] / d < worst_ratio) {
                  worst_ratio = pr.error_estimate[f][z] / d;
                  std::ostringstream w;
                  w << std::setprecision(2) << " at f = " << reg.freqs_hz[f]
                    << " Hz, z = " << int(z) - 2 << ": |H| " << std::abs(rv) << ", error " << d
                    << ", estimate " << pr.error_estimate[f][z];
                  worst_at = w.str();
                }
                if (!(pr.error_estimate[f][z] >= d)) covered = false;
              }
            }
          }
        if (reg.resonance) {
          // Infinite reference: a finite answer must say it is unreliable (estimate of the order
          // of the value itself, or a warning).
          double vmax = 0, emin = kInf;
          for (size_t z = 0; z < pr.values[0].size(); ++z) {
            vmax = std::max(vmax, std::abs(pr.values[0][z]));
            emin = std::min(emin, pr.error_estimate[0][z]);
          }
          std::string w;
          if (!finite) {
            c.verdict = Verdict::kFailsSaysSo;
            c.how = "non-finite value / not ok";
          } else if (Warns(pr.diagnostics, &w)) {
            c.verdict = Verdict::kFailsSaysSo;
            c.how = w;
          } else {
            c.verdict = Verdict::kFailsSilently;
            std::ostringstream h;
            h << "finite |H| = " << vmax << ", estimate " << emin;
            c.how = h.str();
          }
        } else if (!ref_ok) {
          c.verdict = Verdict::kNotApplicable;
          c.how = "no reference";
        } else {
          hscale = std::max(hscale, 1e-300);
          // Per-value estimates: "covers" means every value's estimate covers its error.
          est = covered ? err : 0;
          c = Judge(finite, err, covered ? est : 0, hscale, pr.diagnostics);
          if (c.verdict == Verdict::kFailsSilently) {
            std::ostringstream h;
            h << "error " << std::setprecision(2) << c.error_rel
              << " relative; smallest estimate/error " << worst_ratio << worst_at
              << " (reference spread " << spread / hscale << ")";
            c.how = h.str();
          }
        }
      } catch (const Error& e) {
        c = Judge(false, kInf, std::nullopt, 1, {}, std::string(e.what()).substr(0, 90));
      }
      c.elapsed_s = WallNow() - t0;
      row.push_back(c);
    }
    if (progress) {
      *progress << "failure map: " << reg.name << ":";
      for (size_t m = 0; m < row.size(); ++m)
        *progress << " " << std::setprecision(2) << row[m].elapsed_s << "s";
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
