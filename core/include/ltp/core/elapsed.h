#pragma once
// Wall time of a whole call, for the elapsed_s fields of results: one clock, one helper.
#include <chrono>

namespace ltp {

/// Seconds since `start` on the steady clock.
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace ltp
