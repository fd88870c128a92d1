#pragma once
// Every point of a sweep grid, in grid order (RunSweep hands them over as they complete).
#include <mutex>
#include <vector>

#include "ltp/studies/sweep.h"

namespace ltp::test {

inline std::vector<SweepPoint> SweepAll(const Scene& scene, const ParameterMap& base,
                                        const SweepGrid& grid, const SweepOptions& options) {
  std::vector<size_t> all(grid.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::vector<SweepPoint> points(grid.size());
  std::mutex m;
  RunSweep(scene, base, grid, all, options, [&](SweepPoint&& p) {
    std::lock_guard<std::mutex> lock(m);
    points[p.index] = std::move(p);
  });
  return points;
}

}  // namespace ltp::test
