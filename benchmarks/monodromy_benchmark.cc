// Monodromy route: cost of Mathieu multipliers at relative error <= 1e-10 per integrator, and
// of a rotor-size system (n = 40). For each integrator the loosest tolerance (or fewest fixed
// steps) that still reaches 1e-10 is found once, before timing, against an rkf78 reference at
// rel_tol 1e-14; the counters report the error actually reached.
//
// BulirschStoer/{ltp,boost}: the Bulirsch–Stoer stepper alone, ltp's allocation-free copy
// (integrate/src/bulirsch_stoer.h) against the Boost.Odeint stepper it copies, side by side on the
// same 2×2 Mathieu monodromy at rel_tol 1e-10 (identical steps and values: the counters say so).
//
//   build/benchmarks/monodromy_benchmark --benchmark_repetitions=5
//   --benchmark_report_aggregates_only
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // odeint's fixed-size Eigen states
#include <benchmark/benchmark.h>

#include <boost/numeric/odeint.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>
#include <cmath>
#include <complex>
#include <map>
#include <numbers>

#include "bulirsch_stoer.h"
#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "ltp/models/scene.h"
#include "support/systems.h"

namespace {

using ltp::FloquetOptions;
using ltp::IntegratorType;
using cd = std::complex<double>;

double MaxLogError(const ltp::FloquetResult& r, const ltp::FloquetResult& ref) {
  std::vector<cd> a, b;
  for (const auto& m : r.modes) a.push_back(m.log_multiplier);
  for (const auto& m : ref.modes) b.push_back(m.log_multiplier);
  return ltp::MaxExponentMismatch(a, b, 2 * std::numbers::pi);
}

FloquetOptions Fast(IntegratorType type) {
  FloquetOptions o;
  o.integrator.type = type;
  o.estimate_error = false;  // time one run of the multipliers, as a user's inner loop would
  o.compute_modes = false;
  o.segments = 1;
  o.threads = 1;
  return o;
}

// Loosest setting reaching `target` (error in log ρ relative to max|log ρ|, or absolute when
// the multipliers sit on the unit circle).
FloquetOptions Calibrate(const ltp::PeriodicSystem& sys, IntegratorType type, double target,
                         double* reached) {
  FloquetOptions ref_options = Fast(IntegratorType::kRkf78);
  ref_options.integrator.rel_tol = 1e-14;
  const ltp::FloquetResult ref = ltp::AnalyzeFloquet(sys, ref_options);
  const bool fixed = type == IntegratorType::kMagnus4 || type == IntegratorType::kMagnus6 ||
                     type == IntegratorType::kExpm;
  FloquetOptions best = Fast(type);
  for (int i = 0; i < 40; ++i) {
    FloquetOptions o = Fast(type);
    if (fixed) {
      o.integrator.steps_per_period = 4 << i;
    } else {
      o.integrator.rel_tol = std::pow(10.0, -4.0 - 0.5 * i);
      o.integrator.abs_tol = o.integrator.rel_tol * 1e-3;
    }
    const ltp::FloquetResult r = ltp::AnalyzeFloquet(sys, o);
    const double err = r.ok ? MaxLogError(r, ref) : 1e300;
    best = o;
    *reached = err;
    if (err <= target) break;
  }
  return best;
}

void BM_MathieuMultipliers(benchmark::State& state, IntegratorType type) {
  const ltp::PeriodicSystem sys = ltp::test::Mathieu(1.5, 2.0, 0.05);
  double err = 0;
  const FloquetOptions o = Calibrate(sys, type, 1e-10, &err);
  ltp::FloquetResult r;
  for (auto _ : state) benchmark::DoNotOptimize(r = ltp::AnalyzeFloquet(sys, o));
  state.counters["error"] = err;
  state.counters["rel_tol"] = o.integrator.rel_tol;
  state.counters["steps_per_T"] = o.integrator.steps_per_period;
  state.counters["rhs_evals"] = static_cast<double>(r.rhs_evals);
}

void BM_Chain40(benchmark::State& state, IntegratorType type) {
  const ltp::PeriodicSystem sys = ltp::test::MathieuChain(20, /*damping=*/0.02, /*excitation=*/0.3);
  double err = 0;
  const FloquetOptions o = Calibrate(sys, type, 1e-8, &err);
  ltp::FloquetResult r;
  for (auto _ : state) benchmark::DoNotOptimize(r = ltp::AnalyzeFloquet(sys, o));
  state.counters["dim"] = sys.states();
  state.counters["error"] = err;
  state.counters["rhs_evals"] = static_cast<double>(r.rhs_evals);
}

// The full analysis a user gets from `ltp floquet` (auto segments on all cores, modes, branch
// choice, error estimate by a second run).
void BM_Chain40FullAnalysis(benchmark::State& state) {
  const ltp::PeriodicSystem sys = ltp::test::MathieuChain(20, /*damping=*/0.02, /*excitation=*/0.3);
  FloquetOptions o;
  ltp::FloquetResult r;
  for (auto _ : state) benchmark::DoNotOptimize(r = ltp::AnalyzeFloquet(sys, o));
  state.counters["segments"] = r.segments;
  state.counters["error_estimate"] = r.error_estimate.value_or(std::nan(""));
}

// Φ' = A(t)Φ for y'' + 0.05 y' + (1.5 − 4 cos 2t) y = 0 on vec(Φ).
struct MathieuRhs {
  using State = Eigen::Matrix<double, 4, 1>;
  void operator()(const State& x, State& dxdt, double t) const {
    const double k = 1.5 - 4.0 * std::cos(2 * t);
    for (int j = 0; j < 2; ++j) {  // column j of Φ: (y, y')
      dxdt(2 * j) = x(2 * j + 1);
      dxdt(2 * j + 1) = -k * x(2 * j) - 0.05 * x(2 * j + 1);
    }
  }
};

bool Accepted(boost::numeric::odeint::controlled_step_result r) {
  return r == boost::numeric::odeint::success;
}
bool Accepted(bool accepted) { return accepted; }

template <class Stepper>
void BM_BulirschStoer(benchmark::State& state) {
  using State = MathieuRhs::State;
  const MathieuRhs rhs;
  long attempts = 0;
  State x;
  for (auto _ : state) {
    Stepper stepper = [] {
      if constexpr (std::is_constructible_v<Stepper, double, double, Eigen::Index>)
        return Stepper(1e-10, 1e-10, 4);
      else
        return Stepper(1e-10, 1e-10);
    }();
    x << 1, 0, 0, 1;
    double t = 0, dt = 0.01;
    const double T = std::numbers::pi;
    attempts = 0;
    while (t < T) {
      const bool last = dt >= T - t;
      double h = last ? T - t : dt;
      const bool ok = Accepted(stepper.try_step(rhs, x, t, h));
      if (ok && last) t = T;
      dt = h;
      ++attempts;
    }
    benchmark::DoNotOptimize(x);
  }
  state.counters["attempts"] = static_cast<double>(attempts);
  state.counters["phi00"] = x(0);  // the same in both rows: the same algorithm, bit for bit
}
using LtpBs = ltp::internal::BulirschStoer<MathieuRhs::State>;
using BoostBs =
    boost::numeric::odeint::bulirsch_stoer<MathieuRhs::State, double, MathieuRhs::State, double,
                                           boost::numeric::odeint::vector_space_algebra>;

}  // namespace

// One evaluation of a scene file's A(t) through its compiled muParser expressions (2×2, two
// t-dependent entries): integrators call it millions of times (it was a unit test's timing).
void BM_SceneExpressionA(benchmark::State& state) {
  const ltp::PeriodicSystem system = ltp::ParseSceneYaml(R"yaml(period: 2*pi
parameters: {k: 10}
state_space:
  A: [["0", "1"], ["-k*cos(t)", "-24 - k*sin(t)"]]
)yaml",
                                                         "scene.yaml")
                                         .Build();
  Eigen::MatrixXd a(2, 2);
  double t = 0;
  for (auto _ : state) {
    system.EvalA(t, a);
    benchmark::DoNotOptimize(a.data());
    t += 1e-5;
  }
}
BENCHMARK(BM_SceneExpressionA);

BENCHMARK_TEMPLATE(BM_BulirschStoer, LtpBs)->Name("BulirschStoer/ltp");
BENCHMARK_TEMPLATE(BM_BulirschStoer, BoostBs)->Name("BulirschStoer/boost");
BENCHMARK_CAPTURE(BM_MathieuMultipliers, dopri5, IntegratorType::kDopri5)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MathieuMultipliers, rkf78, IntegratorType::kRkf78)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MathieuMultipliers, cvode_bdf, IntegratorType::kCvodeBdf)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MathieuMultipliers, cvode_adams, IntegratorType::kCvodeAdams)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MathieuMultipliers, magnus4, IntegratorType::kMagnus4)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MathieuMultipliers, magnus6, IntegratorType::kMagnus6)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MathieuMultipliers, bs, IntegratorType::kBulirschStoer)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MathieuMultipliers, taylor, IntegratorType::kTaylor)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Chain40, dopri5, IntegratorType::kDopri5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Chain40, rkf78, IntegratorType::kRkf78)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Chain40, cvode_bdf, IntegratorType::kCvodeBdf)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Chain40, magnus6, IntegratorType::kMagnus6)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Chain40, bs, IntegratorType::kBulirschStoer)->Unit(benchmark::kMillisecond);
// Taylor series on 40 states: 1 + 2H products of 40 × 40 matrices per order (0.46× bs on
// 2026-11-29; 2.7× while a step was p²/2 products).
BENCHMARK_CAPTURE(BM_Chain40, taylor, IntegratorType::kTaylor)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Chain40FullAnalysis)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
