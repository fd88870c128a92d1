// Hill's method: dense (zgeev, all (2N+1)n eigenpairs, ~N³) against structured (banded LU +
// shift-invert Arnoldi for the n physical exponents, ~N), for n = 4 (Jeffcott rotor) and
// n = 40 (chain of coupled damped Mathieu oscillators), as the truncation N grows. Only the
// eigen-solve and the selection are timed (no N+Δ estimate, no Koopman–Hill check).
//
//   build/benchmarks/hill_benchmark --benchmark_filter='n4|n40'
#include <benchmark/benchmark.h>

#include <complex>
#include <numbers>

#include "ltp/hill/hill.h"
#include "support/systems.h"

namespace {

using ltp::HillOptions;
using ltp::HillSolver;

ltp::PeriodicSystem Jeffcott() {
  // m = 1, k1 = 1, k2 = 1.4, c = 0.05, Ω = 0.45 (tests/support/systems.h), fixed frame.
  const double k0 = 1.2, dk = 0.2, c = 0.05, omega = 0.45;
  using cd = std::complex<double>;
  ltp::FourierMatrix A(4, 4, 1);
  Eigen::MatrixXcd a0 = Eigen::MatrixXcd::Zero(4, 4), a1 = Eigen::MatrixXcd::Zero(4, 4);
  a0(0, 2) = a0(1, 3) = 1;
  a0(2, 0) = a0(3, 1) = -k0;
  a0(2, 2) = a0(3, 3) = -c;
  Eigen::Matrix2cd k1m;
  k1m << cd(1, 0), cd(0, -1), cd(0, -1), cd(-1, 0);
  a1.block(2, 0, 2, 2) = -dk / 2 * k1m;
  A.SetHarmonic(0, a0);
  A.SetHarmonic(1, a1);
  return ltp::PeriodicSystem::FromFourier(std::numbers::pi / omega, A);
}

void Run(benchmark::State& state, const ltp::PeriodicSystem& system, HillSolver solver) {
  HillOptions o;
  o.harmonics = static_cast<int>(state.range(0));
  o.solver = solver;
  o.delta_harmonics = -1;
  o.koopman_check = false;
  o.structured_fallback = false;
  bool ok = true;
  for (auto _ : state) {
    const ltp::HillResult r = ltp::AnalyzeHill(system, o);
    ok = ok && r.ok;
    benchmark::DoNotOptimize(r.modes.data());
  }
  state.counters["size"] = (2.0 * o.harmonics + 1) * system.states();
  state.counters["ok"] = ok;
}

void BM_Dense_n4(benchmark::State& s) { Run(s, Jeffcott(), HillSolver::kDense); }
void BM_Structured_n4(benchmark::State& s) { Run(s, Jeffcott(), HillSolver::kStructured); }
void BM_Dense_n40(benchmark::State& s) { Run(s, ltp::test::MathieuChain(20), HillSolver::kDense); }
void BM_Structured_n40(benchmark::State& s) {
  Run(s, ltp::test::MathieuChain(20), HillSolver::kStructured);
}

BENCHMARK(BM_Dense_n4)->RangeMultiplier(2)->Range(2, 128)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Structured_n4)->RangeMultiplier(2)->Range(2, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Dense_n40)
    ->DenseRange(1, 4, 1)
    ->Arg(6)
    ->Arg(8)
    ->Arg(12)
    ->Arg(16)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Structured_n40)
    ->DenseRange(1, 4, 1)
    ->Arg(6)
    ->Arg(8)
    ->Arg(12)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
