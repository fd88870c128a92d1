// The paper's system (built-in scene tower-rotor, 22 states, Ωp = 100 rad/s): the jobs of the
// speed issues, side by side in one run so that their ratios are meaningful on a shared machine.
//
//   build/benchmarks/tower_rotor_benchmark --benchmark_repetitions=5
//   --benchmark_report_aggregates_only
//
// FloquetFull            `ltp floquet tower-rotor`: modes, error estimate (two integrations)
// FloquetFull/256        the same with the 256 mode samples (= segments) the sample rule chose
//                        before the samples were demodulated by the averaged system's branch
// MonodromyOnly          one integration, multipliers only (estimate and modes off): the
//                        floor of this route at rel_tol 1e-10 with this integrator
// Pfrf/Modal, Pfrf/Auto `ltp pfrf tower-rotor --input Fz_tip --output z_tip --freq 0:450:0.6
//                        --orders -4:4` (751 × 9 values), Floquet analysis and checks
//                        included; route modal, and auto
// Pfrf/Htf               the same with the HTF as the primary route (modal as the check)
// Snapshot               `ltp snapshot tower-rotor --angle 90 --compare --freq 0:450:0.6`
// ModalSweep             the modal route's sweep alone (751 × 9 values of one channel, one
//                        thread) after the model is built
// HtfPoint/0 and /1      one HTF evaluation at the automatic truncation: banded LU (0) against
//                        the Hessenberg solve after one reduction (1); HtfReduction the
//                        reduction itself (what a sweep pays once per truncation)
#include <benchmark/benchmark.h>

#include <cmath>
#include <tuple>
#include <utility>

#include "ltp/core/channel.h"
#include "ltp/floquet/floquet.h"
#include "ltp/htf/pfrf.h"
#include "ltp/htf/snapshot.h"
#include "ltp/integrate/threads.h"
#include "ltp/models/scene.h"

namespace {

// As the ltp command runs: OpenBLAS single-threaded under ltp's own threads.
const bool kSingleThreadedBlas = ltp::UseSingleThreadedBlas();

using namespace ltp;

const PeriodicSystem& TowerRotor() {
  static const PeriodicSystem system = LoadScene("tower-rotor").Build();
  return system;
}

// The demo's channel: force at the blade tip (Fz_tip) to its displacement (z_tip).
std::pair<int, int> DemoChannel() {
  const auto& labels = TowerRotor().labels();
  return {ResolveChannel("Fz_tip", labels.inputs, TowerRotor().inputs(), "input", "input"),
          ResolveChannel("z_tip", labels.outputs, TowerRotor().outputs(), "output", "output")};
}

FloquetOptions CliFloquetOptions() {
  FloquetOptions o;
  o.integrator.type = IntegratorType::kAuto;  // the CLI's default
  return o;
}

void FloquetFull(benchmark::State& state) {
  FloquetOptions o = CliFloquetOptions();
  o.mode_samples = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const FloquetResult r = AnalyzeFloquet(TowerRotor(), o);
    if (!r.ok) state.SkipWithError("Floquet analysis failed");
    state.counters["evals"] = static_cast<double>(r.rhs_evals);
    state.counters["estimate"] = r.error_estimate.value_or(std::nan(""));
  }
}
BENCHMARK(FloquetFull)->Arg(0)->Arg(256)->Unit(benchmark::kMillisecond)->Iterations(3);

void MonodromyOnly(benchmark::State& state) {
  FloquetOptions o = CliFloquetOptions();
  o.estimate_error = false;
  o.compute_modes = false;
  for (auto _ : state) {
    const FloquetResult r = AnalyzeFloquet(TowerRotor(), o);
    if (!r.ok) state.SkipWithError("Floquet analysis failed");
    state.counters["evals"] = static_cast<double>(r.rhs_evals);
  }
}
BENCHMARK(MonodromyOnly)->Unit(benchmark::kMillisecond)->Iterations(3);

void Pfrf(benchmark::State& state, PfrfRoute route) {
  PfrfOptions o;
  for (int i = 0; i <= 750; ++i) o.frequencies_hz.push_back(0.6 * i);
  o.primary = route;
  std::tie(o.input, o.output) = DemoChannel();
  o.floquet = CliFloquetOptions();
  o.modal.integrator.type = IntegratorType::kAuto;
  for (auto _ : state) {
    const PfrfResult r = ComputePartialFrf(TowerRotor(), o);
    if (!r.ok) state.SkipWithError("sweep failed");
    state.counters["rel_disagreement"] = r.max_relative_disagreement;
  }
}
BENCHMARK_CAPTURE(Pfrf, Modal, PfrfRoute::kModal)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(Pfrf, Auto, PfrfRoute::kAuto)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(Pfrf, Htf, PfrfRoute::kHtf)->Unit(benchmark::kMillisecond)->Iterations(1);

// `ltp snapshot tower-rotor --angle 90 --compare --freq 0:450:0.6` on the demo's channel: the
// frozen FRF, and the summed partials by the modal route checked by the HTF.
void Snapshot(benchmark::State& state) {
  SnapshotOptions o;
  for (int i = 0; i <= 750; ++i) o.frequencies_hz.push_back(0.6 * i);
  o.angle_deg = 90;
  o.compare = true;
  std::tie(o.input, o.output) = DemoChannel();
  for (auto _ : state) {
    const SnapshotResult r = ComputeSnapshotFrf(TowerRotor(), o);
    benchmark::DoNotOptimize(r.summed.data());
    state.counters["disagreement"] = r.max_summed_disagreement;
  }
}
BENCHMARK(Snapshot)->Unit(benchmark::kMillisecond)->Iterations(1);

std::vector<double> SweepOmegas() {
  std::vector<double> w;
  for (int i = 0; i <= 750; ++i) w.push_back(2 * 3.141592653589793 * 0.6 * i);
  return w;
}

HtfSolver TowerRotorHtf() {
  HtfSolver htf(TowerRotor());
  const std::vector<double> w = SweepOmegas();
  htf.ChooseTruncation(-4, 4, {w.front(), w[w.size() / 2], w.back()});
  return htf;
}

void HtfPoint(benchmark::State& state) {
  HtfSolver htf = TowerRotorHtf();
  if (state.range(0) == 1 && !htf.PrepareSweep(1000)) state.SkipWithError("not reduced");
  const std::vector<double> w = SweepOmegas();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(htf.Evaluate(w[i], -4, 4));
    i = (i + 37) % w.size();
  }
  state.counters["N"] = htf.harmonics();
}
BENCHMARK(HtfPoint)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The modal route's sweep alone, after the model is built: 751 frequencies × orders −4…4 of
// the demo's channel (Fz_tip → z_tip), one thread.
void ModalSweep(benchmark::State& state) {
  const ModalModel model = BuildModalModel(TowerRotor(), AnalyzeFloquet(TowerRotor()));
  const auto [input, output] = DemoChannel();
  const std::vector<double> w = SweepOmegas();
  const ModalChannel channel(model, output, input);
  for (auto _ : state)
    for (double x : w) benchmark::DoNotOptimize(channel.Evaluate(x, -4, 4));
  state.counters["V"] = model.harmonics;
}
BENCHMARK(ModalSweep)->Unit(benchmark::kMillisecond);

void HtfReduction(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    HtfSolver htf = TowerRotorHtf();
    state.ResumeTiming();
    if (!htf.PrepareSweep(1000)) state.SkipWithError("not reduced");
  }
}
BENCHMARK(HtfReduction)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
