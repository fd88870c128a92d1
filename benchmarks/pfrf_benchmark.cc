// Partial-FRF sweeps at the paper's size (Sect. 5.2.2: 751 excitation frequencies, 0–450 Hz in
// 0.6 Hz steps, fp = 15.9 Hz, i.e. a band of ~28 fp), orders −4…4, for a 40-state system:
// a 20-mass chain whose ground spring varies as k(1 + 0.3 cos Ωp t), fp = 1 Hz, band 0–28.2 Hz.
// The modal route is timed over the whole sweep (after one decomposition); htf, shooting and
// time per frequency (multiply by 751 for the sweep). Measured on the shared 2-core machine
// (Release): decomposition ~50 s (AnalyzeFloquet, K = 1728 segments; BuildModalModel ~1 s
// of it), modal sweep 125 ms for all 751 × 9 values, htf 16.6 ms/point (12 s per sweep),
// shooting 111 ms/point (83 s), time 9.6 s/point (settling 977 s = 977 periods; ~2 h per sweep).
#include <benchmark/benchmark.h>

#include <numbers>

#include "ltp/htf/pfrf.h"
#include "ltp/integrate/threads.h"

namespace {

// As the ltp command runs: OpenBLAS single-threaded under ltp's own threads.
const bool kSingleThreadedBlas = ltp::UseSingleThreadedBlas();

using namespace ltp;
constexpr int kDofs = 20;
constexpr int kFrequencies = 751;
constexpr double kBandHz = 28.2;

PeriodicSystem Chain40() {
  const int n = 2 * kDofs;
  const double k = 4000, alpha = 0.05, beta = 1e-4;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(kDofs, kDofs);
  for (int i = 0; i < kDofs; ++i) {
    K(i, i) = 2 * k;
    if (i + 1 < kDofs) K(i, i + 1) = K(i + 1, i) = -k;
  }
  K(kDofs - 1, kDofs - 1) = k;  // free end
  const Eigen::MatrixXd D = alpha * Eigen::MatrixXd::Identity(kDofs, kDofs) + beta * K;
  FourierMatrix A(n, n, 1);
  Eigen::MatrixXcd a0 = Eigen::MatrixXcd::Zero(n, n), a1 = Eigen::MatrixXcd::Zero(n, n);
  a0.topRightCorner(kDofs, kDofs).setIdentity();
  a0.bottomLeftCorner(kDofs, kDofs) = -K.cast<std::complex<double>>();
  a0.bottomRightCorner(kDofs, kDofs) = -D.cast<std::complex<double>>();
  a1(kDofs, 0) = -0.3 * k / 2;  // −ΔK_{00}/2 per e^{±jΩp t}
  A.SetHarmonic(0, a0);
  A.SetHarmonic(1, a1);
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, 1), C = Eigen::MatrixXd::Zero(1, n);
  B(n - 1, 0) = 1;      // force on the free end
  C(0, kDofs - 1) = 1;  // its displacement (driving point)
  return PeriodicSystem::FromFourier(1.0, A, FourierMatrix::Constant(B),
                                     FourierMatrix::Constant(C));
}

std::vector<double> Omegas() {
  std::vector<double> w;
  for (int i = 0; i < kFrequencies; ++i)
    w.push_back(2 * std::numbers::pi * kBandHz * i / (kFrequencies - 1));
  return w;
}

void BM_Decomposition(benchmark::State& state) {
  const PeriodicSystem sys = Chain40();
  for (auto _ : state) {
    const FloquetResult fl = AnalyzeFloquet(sys);
    benchmark::DoNotOptimize(BuildModalModel(sys, fl).harmonics);
  }
}

void BM_ModalSweep(benchmark::State& state) {
  const PeriodicSystem sys = Chain40();
  const ModalModel model = BuildModalModel(sys, AnalyzeFloquet(sys));
  const auto w = Omegas();
  for (auto _ : state)
    for (double x : w) benchmark::DoNotOptimize(model.Evaluate(x, -4, 4));
  state.counters["V"] = model.harmonics;
}

void BM_HtfPoint(benchmark::State& state) {
  const PeriodicSystem sys = Chain40();
  HtfSolver htf(sys);
  const auto w = Omegas();
  htf.ChooseTruncation(-4, 4, {w.front(), w[w.size() / 2], w.back()});
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(htf.Evaluate(w[i], -4, 4));
    i = (i + 37) % w.size();
  }
  state.counters["N"] = htf.harmonics();
}

void BM_ShootingPoint(benchmark::State& state) {
  const PeriodicSystem sys = Chain40();
  ForcedResponseSolver solver(sys);
  const auto w = Omegas();
  bool ok = false;
  solver.Shooting(w[1], -4, 4, &ok);  // Φ(t_s, 0) and the sample count, once
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(solver.Shooting(w[i], -4, 4, &ok));
    i = (i + 37) % w.size();
  }
}

void BM_TimePoint(benchmark::State& state) {
  const PeriodicSystem sys = Chain40();
  const FloquetResult fl = AnalyzeFloquet(sys);
  const double settle = ForcedResponseSolver::SettlingTime(fl, 1e-9);
  ForcedResponseSolver solver(sys);
  const auto w = Omegas();
  bool ok = false;
  size_t i = 100;
  for (auto _ : state) {
    benchmark::DoNotOptimize(solver.TimeSimulation(w[i], -4, 4, settle, &ok));
    i = (i + 37) % w.size();
  }
  state.counters["settle_s"] = settle;
}

void BM_DefaultSweep(benchmark::State& state) {
  // What `ltp pfrf` does by default: decomposition, modal on all 751, htf on every 10th.
  const PeriodicSystem sys = Chain40();
  PfrfOptions o;
  for (double x : Omegas()) o.frequencies_hz.push_back(x / (2 * std::numbers::pi));
  for (auto _ : state) benchmark::DoNotOptimize(ComputePartialFrf(sys, o).max_disagreement);
}

BENCHMARK(BM_Decomposition)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ModalSweep)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HtfPoint)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShootingPoint)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TimePoint)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_DefaultSweep)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
