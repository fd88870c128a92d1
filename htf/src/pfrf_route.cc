#include "pfrf_route.h"

#include <algorithm>
#include <cmath>

#include "ltp/core/error.h"

namespace ltp::internal {

std::unique_ptr<PfrfRouteSolver> MakeRouteSolver(PfrfRoute route, const PeriodicSystem& system,
                                                 const PfrfOptions& options, PfrfResult& result) {
  switch (route) {
    case PfrfRoute::kModal:
      return MakeModalRoute(system, options, result);
    case PfrfRoute::kHtf:
      return MakeHtfRoute(system, options, result);
    case PfrfRoute::kShooting:
    case PfrfRoute::kTime:
      return MakeForcedResponseRoute(route, system, options, result);
    case PfrfRoute::kAuto:
      break;
  }
  throw InputError("pfrf: route auto must be resolved before the sweep");
}

double LargestFinite(const std::vector<std::complex<double>>& values) {
  double largest = 0;
  for (const auto& v : values)
    if (std::isfinite(std::abs(v))) largest = std::max(largest, std::abs(v));
  return largest;
}

}  // namespace ltp::internal
