// `ltp mbc` on a 60-state OpenFAST set (tests/data/openfast/lin-60-states, 3 azimuths): the MBC3
// table and the Floquet analysis of the same samples, as the command runs them.
//
//   build/benchmarks/openfast_benchmark --benchmark_repetitions=3
//
// Mbc3Only        the MBC3 table (azimuth averaging in multi-blade coordinates)
// SampledFloquet  the Floquet analysis of the samples: monodromy, error estimate, and the
//                 periodic eigenvectors of all 60 modes (docs/periodic-eigenvectors.md)
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "ltp/floquet/sampled_floquet.h"
#include "ltp/floquet/threads.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"

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

}  // namespace

BENCHMARK_MAIN();
