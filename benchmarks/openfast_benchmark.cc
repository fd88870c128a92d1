// `ltp mbc` on a 60-state OpenFAST set (tests/data/openfast/lin-60-states, 3 azimuths): the MBC3
// table and the Floquet analysis of the same samples, as the command runs them; and the same
// analysis of a 200-state set of the same kind, written by this benchmark.
//
//   build/benchmarks/openfast_benchmark --benchmark_repetitions=3
//
// Mbc3Only           the MBC3 table (azimuth averaging in multi-blade coordinates)
// SampledFloquet     the Floquet analysis of the samples as `ltp mbc` runs it: both routes'
//                    monodromies and error estimates (the trigonometric one from its carried
//                    local errors, docs/local-error-estimate.md); no mode shapes, the table
//                    shows each exponent on its MBC branch
// SampledFloquet200  the same for 200 states. Lin-60-states is three independent random
//                    matrices (diagonal uniform in [−7.5, −2.5], off-diagonal standard
//                    normal); the 200-state set is drawn the same way (seeded), written to
//                    $TMPDIR/ltp-lin-200-states/Big.{0,1,2}.lin for `ltp mbc` to time.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ltp/integrate/threads.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"
#include "ltp/studies/sampled_floquet.h"

namespace {

// As the ltp command runs: OpenBLAS single-threaded under ltp's own threads.
const bool kSingleThreadedBlas = ltp::UseSingleThreadedBlas();

using namespace ltp;

const LinOperatingPoint& Big() {
  static const LinOperatingPoint op = [] {
    const std::string dir = std::string(LTP_SOURCE_DIR) + "/tests/data/openfast/lin-60-states/";
    return ReadLinOperatingPoint({dir + "Big.0.lin", dir + "Big.1.lin", dir + "Big.2.lin"});
  }();
  return op;
}

// Three azimuths of 200 random damped states, drawn as lin-60-states (see the top).
const LinOperatingPoint& Synthetic200() {
  static const LinOperatingPoint op = [] {
    const int n = 200;
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("ltp-lin-" + std::to_string(n) + "-states");
    std::filesystem::create_directories(dir);
    std::mt19937 random(20261126);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> diagonal(-7.5, -2.5);
    std::vector<std::string> paths;
    for (int k = 0; k < 3; ++k) {
      LinFile file;
      file.title = "Linearized model";
      file.rotor_speed = 1.0;
      file.azimuth = 2 * std::numbers::pi * k / 3;
      file.continuous_states = n;
      for (int i = 0; i < n; ++i) {
        LinChannel state;
        state.derivative_order = 2;
        state.description = "state " + std::to_string(i + 1);
        file.states.push_back(std::move(state));
      }
      file.A.resize(n, n);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) file.A(i, j) = i == j ? diagonal(random) : normal(random);
      paths.push_back((dir / ("Big." + std::to_string(k) + ".lin")).string());
      WriteLinFile(paths.back(), file);
    }
    return ReadLinOperatingPoint(paths);
  }();
  return op;
}

void Mbc3Only(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(Mbc3(Big(), {}));
}
BENCHMARK(Mbc3Only)->Unit(benchmark::kMillisecond);

void SampledFloquet(benchmark::State& state) {
  const Mbc3Result mbc = Mbc3(Big(), {});
  for (auto _ : state) {
    const SampledFloquetResult r = AnalyzeSampledFloquet(Big(), mbc, {});
    if (!r.ok) state.SkipWithError("Floquet analysis failed");
  }
}
BENCHMARK(SampledFloquet)->Unit(benchmark::kMillisecond)->Iterations(1);

void SampledFloquet200(benchmark::State& state) {
  const LinOperatingPoint& op = Synthetic200();
  const Mbc3Result mbc = Mbc3(op, {});
  for (auto _ : state) {
    const SampledFloquetResult r = AnalyzeSampledFloquet(op, mbc, {});
    if (!r.ok) state.SkipWithError("Floquet analysis failed");
  }
}
BENCHMARK(SampledFloquet200)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
