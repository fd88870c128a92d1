#pragma once
// Why a sweep runs on the route it does: code branches on this, people read the sentence
// beside it (PfrfResult::route_choice, OrbitSweep::route_choice).

namespace ltp {

enum class RouteReason {
  kAsRequested,       ///< the caller named the route
  kNoDecomposition,   ///< automatic: no Floquet decomposition, so no modal model
  kModalResolved,     ///< automatic: the modal model is resolved, the cheapest per frequency
  kModalUnreliable,   ///< automatic: the modal model reports itself unreliable
  kModalCheckFailed,  ///< automatic: the modal route ran first and its check found it wrong
};

}  // namespace ltp
