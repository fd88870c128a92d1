// Stability charts: the 400 × 400 Mathieu map (a ∈ [−2, 10] step 0.03, q ∈ [0, 8] step 0.02,
// c = 0.02: 401 × 401 points) on all cores, and the same analysis written the usual way in
// Python (benchmarks/peers/mathieu_map_scipy.py: solve_ivp DOP853 + eigvals) two ways — one
// solve per point on an evenly spread subset of 400 points, and the whole map vectorised in
// blocks of 4010 points — against ltp on that subset (the median of 25 passes), in the same
// process so the ratios are measured under the same machine load. Counters: per-point times, the
// ratios, and the largest difference of max log|ρ| between the two (both aim at 1e-8).
//
//   build/benchmarks/chart_benchmark
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "ltp/core/elapsed.h"
#include "ltp/models/scene.h"
#include "ltp/studies/chart.h"
#include "ltp/studies/chart_options.h"
#include "ltp/studies/sweep.h"

namespace {

// `ltp chart` map defaults at rel tol 1e-10: the integrator `type` (Map::integrator, the
// library's ChartIntegrator choice, is Taylor series for this Fourier scene) keeps max log|ρ|
// within 3.8e-9 of an rkf78 run at 1e-13 on 6 561 points of this map (Bulirsch–Stoer at 1e-10:
// 5.6e-9; docs/taylor-integrator.md).
ltp::SweepOptions MapOptions(int threads, ltp::IntegratorType type) {
  ltp::SweepOptions o;
  o.modes = false;
  o.check_every = 0;
  o.threads = threads;
  o.floquet.integrator.type = type;
  o.floquet.integrator.rel_tol = 1e-10;
  o.floquet.integrator.abs_tol = 1e-13;
  return o;
}

struct Map {
  ltp::Scene scene = ltp::LoadScene("mathieu");
  ltp::ParameterMap base = scene.Resolve({{"c", "0.02"}});
  ltp::SweepGrid grid = ltp::MakeSweepGrid(
      scene, {ltp::SweepAxis::Parse("a=-2:10:0.03"), ltp::SweepAxis::Parse("q=0:8:0.02")});
  // What `ltp chart` integrates this map with.
  ltp::IntegratorType integrator = ltp::ChartIntegrator({}, /*map=*/true, scene.build(base));
};

// `type`: empty = the chart's own choice (Map::integrator).
double RunMap(const Map& m, const std::vector<size_t>& indices, int threads,
              std::vector<double>* values = nullptr,
              std::optional<ltp::IntegratorType> type = std::nullopt) {
  std::mutex mutex;
  if (values) values->assign(indices.size(), NAN);
  std::vector<size_t> position(m.grid.size());
  for (size_t i = 0; i < indices.size(); ++i) position[indices[i]] = i;
  const auto start = std::chrono::steady_clock::now();
  ltp::RunSweep(m.scene, m.base, m.grid, indices, MapOptions(threads, type.value_or(m.integrator)),
                [&](ltp::SweepPoint&& p) {
                  if (!values) return;
                  std::lock_guard<std::mutex> lock(mutex);
                  (*values)[position[p.index]] = p.max_log_multiplier;
                });
  return ltp::SecondsSince(start);
}

void BM_MathieuMap400(benchmark::State& state) {
  const Map m;
  std::vector<size_t> all(m.grid.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  double seconds = 0;
  const auto type = static_cast<ltp::IntegratorType>(state.range(0));
  for (auto _ : state) {
    seconds = RunMap(m, all, 0, nullptr, type);
    state.SetIterationTime(seconds);
  }
  state.SetLabel(std::string(ltp::ToString(type)));
  state.counters["points"] = static_cast<double>(all.size());
  state.counters["us_per_point_wall"] = 1e6 * seconds / static_cast<double>(all.size());
}
// `ltp chart tower-rotor --sweep Omega=20:200:20`: a Campbell diagram of the paper's system,
// ten rotor speeds with modes, mode tracking, the diagram and the refined unstable intervals, at
// the chart's defaults (every point of a 1-D sweep checked by the error estimate), on all cores.
void BM_TowerRotorCampbell(benchmark::State& state) {
  const ltp::Scene scene = ltp::LoadScene("tower-rotor");
  const ltp::ParameterMap base = scene.Resolve({});
  const ltp::PeriodicSystem system = scene.build(base);
  size_t points = 0, lines = 0;
  for (auto _ : state) {
    const ltp::Chart chart =
        ltp::ComputeChart(scene, base, system, {ltp::SweepAxis::Parse("Omega=20:200:20")}, {});
    points = chart.points.size();
    lines = chart.analysis.campbell.lines.size();
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["lines"] = static_cast<double>(lines);
}
BENCHMARK(BM_TowerRotorCampbell)->Iterations(1)->Unit(benchmark::kSecond);

BENCHMARK(BM_MathieuMap400)
    ->Arg(static_cast<int>(ltp::IntegratorType::kTaylor))
    ->Arg(static_cast<int>(ltp::IntegratorType::kBulirschStoer))
    ->Arg(static_cast<int>(ltp::IntegratorType::kRkf78))
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

void BM_VersusScipy(benchmark::State& state) {
  const Map m;
  const std::string script = std::string(LTP_SOURCE_DIR) + "/benchmarks/peers/mathieu_map_scipy.py";
  const int count = 400;
  // Arg 0: one solve_ivp per point (the usual way); 1: the whole map vectorised, ten q-rows per
  // solve_ivp (what a numerical analyst writes; its per-point time is over the whole map).
  const bool vectorised = state.range(0) == 1;
  for (auto _ : state) {
    FILE* p = popen(("/usr/bin/python3 " + script + " " + std::to_string(count) + " 0.02 " +
                     (vectorised ? "vectorised" : "loop") + " 2>&1")
                        .c_str(),
                    "r");
    std::string out;
    std::array<char, 65536> buf;
    while (p && fgets(buf.data(), buf.size(), p)) out += buf.data();
    const int status = p ? pclose(p) : -1;
    if (status != 0) {
      state.SkipWithError(("SciPy peer unavailable: " + out).c_str());
      return;
    }
    const auto peer = nlohmann::json::parse(out);
    // The same points (same index rule as the script), one thread and all threads.
    const size_t total = m.grid.size(), stride = total / count;
    std::vector<size_t> indices;
    for (size_t i = 0; i < total && indices.size() < static_cast<size_t>(count); i += stride)
      indices.push_back(i);
    std::vector<double> values;
    RunMap(m, indices, 1, &values);
    // 400 points are about a millisecond of ltp's work, within the machine's scheduling noise:
    // the median of 25 passes over them, on one thread and on all.
    const auto median_pass = [&](int threads) {
      std::vector<double> t;
      for (int pass = 0; pass < 25; ++pass) t.push_back(RunMap(m, indices, threads));
      std::nth_element(t.begin(), t.begin() + 12, t.end());
      return t[12];
    };
    const double one_thread = median_pass(1);
    const double all_threads = median_pass(0);
    double worst = 0;
    for (size_t i = 0; i < indices.size(); ++i)
      worst = std::max(worst, std::abs(values[i] - peer["results"][i][2].get<double>()));
    const double scipy = peer["per_point_s"].get<double>();
    const double ltp1 = one_thread / static_cast<double>(indices.size());
    const double ltpn = all_threads / static_cast<double>(indices.size());
    state.SetIterationTime(one_thread);
    state.SetLabel(std::string(ltp::ToString(m.integrator)) +
                   (vectorised ? " vs SciPy vectorised" : " vs SciPy per point"));
    state.counters["scipy_us_per_point"] = 1e6 * scipy;
    state.counters["ltp_us_per_point_1thread"] = 1e6 * ltp1;
    state.counters["ltp_us_per_point_all_threads"] = 1e6 * ltpn;
    state.counters["ratio_1thread"] = scipy / ltp1;
    state.counters["ratio_all_threads"] = scipy / ltpn;
    state.counters["max_abs_diff_log_rho"] = worst;
  }
}
BENCHMARK(BM_VersusScipy)
    ->Arg(0)
    ->Arg(1)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
