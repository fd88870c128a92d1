#pragma once
// Internal: locating the jumps of a piecewise-smooth periodic scalar function of time.
#include <functional>
#include <vector>

namespace ltp::internal {

/// Times in [0, period) where `f` jumps, each to within ~1e-14·period, sorted. Scans `grid`
/// equal steps and bisects every step whose change does not shrink like that of a smooth
/// function. Two jumps closer than one grid step can cancel and be missed.
std::vector<double> FindJumps(const std::function<double(double)>& f, double period,
                              int grid = 4096);

}  // namespace ltp::internal
