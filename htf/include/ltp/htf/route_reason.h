#pragma once
// Why a sweep runs on the route it does: code branches on this, people read the sentence
// beside it (PfrfResult::route_choice, OrbitSweep::route_choice).

#include <string_view>

namespace ltp {

enum class RouteReason {
  kAsRequested,       ///< the caller named the route
  kNoDecomposition,   ///< automatic: no Floquet decomposition, so no modal model
  kModalResolved,     ///< automatic: the modal model is resolved, the cheapest per frequency
  kModalUnreliable,   ///< automatic: the modal model reports itself unreliable
  kModalCheckFailed,  ///< automatic: the modal route ran first and its check found it wrong
};

/// The reason's name for machines (JSON, Python): "as_requested", "no_decomposition",
/// "modal_resolved", "modal_unreliable", "modal_check_failed".
constexpr std::string_view CodeName(RouteReason reason) {
  switch (reason) {
    case RouteReason::kAsRequested:
      return "as_requested";
    case RouteReason::kNoDecomposition:
      return "no_decomposition";
    case RouteReason::kModalResolved:
      return "modal_resolved";
    case RouteReason::kModalUnreliable:
      return "modal_unreliable";
    case RouteReason::kModalCheckFailed:
      return "modal_check_failed";
  }
  return "unknown";
}

}  // namespace ltp
