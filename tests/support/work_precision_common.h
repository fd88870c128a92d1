#pragma once
// Shared pieces of the work–precision study (benchmarks/work_precision_benchmark.cc) and the
// failure map (tests/support/failure_map.h, also run by tests/htf/failure_map_test.cc); kept
// with the test support, which the benchmarks include as well:
// exponent errors modulo jΩp, and median CPU / wall timing of repeated runs.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "ltp/hill/hill.h"

namespace ltp::wp {

using cd = std::complex<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Largest error of `got` against `ref` (both sets of exponents, 1/s), modulo jΩ, matched
/// one-to-one (ltp's MatchExponents). +inf when fewer exponents were computed than the
/// reference has, or any is not finite.
inline double ExponentError(const std::vector<cd>& got, const std::vector<cd>& ref, double omega) {
  if (got.size() < ref.size()) return kInf;
  for (const cd& g : got)
    if (!std::isfinite(g.real()) || !std::isfinite(g.imag())) return kInf;
  double worst = 0;
  for (double d : ltp::MatchExponents(ref, got, omega)) worst = std::max(worst, d);
  return worst;
}

/// Exponents from log-multipliers of a period `period`.
inline std::vector<cd> FromLogMultipliers(const std::vector<cd>& logs, double period) {
  std::vector<cd> e;
  for (const cd& l : logs) e.push_back(l / period);
  return e;
}

/// Hill's error estimate as `ltp floquet --method hill` reports it (+inf when none was computed).
inline double HillEstimate(const HillResult& h) { return h.error_estimate.value_or(kInf); }

inline double CpuNow() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
inline double WallNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Timing {
  double cpu_s = 0, wall_s = 0;  ///< medians
  int repeats = 0;
};

inline double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

/// Runs `fn` at least once and repeats it (up to `max_repeats`) while the total stays under
/// `budget_s`; returns the median CPU and wall time. CPU time is the whole process's (all
/// threads), so a parallel method is not flattered.
inline Timing TimeIt(const std::function<void()>& fn, int max_repeats, double budget_s) {
  std::vector<double> cpu, wall;
  double spent = 0;
  while (static_cast<int>(cpu.size()) < max_repeats) {
    const double c0 = CpuNow(), w0 = WallNow();
    fn();
    cpu.push_back(CpuNow() - c0);
    wall.push_back(WallNow() - w0);
    spent += wall.back();
    if (cpu.size() >= 3 && spent > budget_s) break;
    if (cpu.size() >= 1 && spent > 3 * budget_s) break;  // one slow run is all we can afford
  }
  return {Median(cpu), Median(wall), static_cast<int>(cpu.size())};
}

}  // namespace ltp::wp
