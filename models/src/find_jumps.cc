#include "find_jumps.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace ltp::internal {
namespace {

// Bisects [a, b] towards the half that changes more. A smooth function's change halves with
// every step and soon drops below half of the original; a jump keeps it down to `width`.
std::optional<double> Refine(const std::function<double(double)>& f, double a, double fa, double b,
                             double fb, double width) {
  const double change = std::abs(fb - fa);
  while (b - a > width) {
    const double mid = a + (b - a) / 2;
    if (mid <= a || mid >= b) break;  // no more doubles in between
    const double fm = f(mid);
    if (std::abs(fm - fa) >= std::abs(fb - fm)) {
      b = mid;
      fb = fm;
    } else {
      a = mid;
      fa = fm;
    }
    if (!(std::abs(fb - fa) >= 0.5 * change)) return std::nullopt;
  }
  return a + (b - a) / 2;
}

}  // namespace

std::vector<double> FindJumps(const std::function<double(double)>& f, double period, int grid) {
  std::vector<double> times(grid + 1), values(grid + 1);
  double scale = 0;
  for (int i = 0; i <= grid; ++i) {
    times[i] = period * i / grid;
    values[i] = f(times[i]);
    if (std::isfinite(values[i])) scale = std::max(scale, std::abs(values[i]));
  }
  // Changes at round-off level are noise, not jumps.
  const double threshold = 1e-9 * scale;
  const double width = 1e-14 * period, snap = 1e-10 * period;
  std::vector<double> jumps;
  for (int i = 0; i < grid; ++i) {
    const double change = std::abs(values[i + 1] - values[i]);
    if (!(change > threshold)) continue;
    if (auto t = Refine(f, times[i], values[i], times[i + 1], values[i + 1], width)) {
      // A jump at T is the jump at 0 of the next period.
      jumps.push_back(*t < snap || *t > period - snap ? 0.0 : *t);
    }
  }
  std::sort(jumps.begin(), jumps.end());
  jumps.erase(std::unique(jumps.begin(), jumps.end()), jumps.end());
  return jumps;
}

}  // namespace ltp::internal
