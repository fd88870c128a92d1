#include "analysis_progress.h"

#include <algorithm>
#include <utility>

namespace ltp::internal {

AnalysisProgress::AnalysisProgress(Sink sink, double period)
    : sink_(std::move(sink)), period_(period > 0 ? period : 1) {}

std::function<void(double)> AnalysisProgress::Phase(std::string name) const {
  if (!sink_) return {};
  auto state = std::make_shared<State>();
  return [state, sink = sink_, period = period_, name = std::move(name)](double advanced) {
    std::lock_guard<std::mutex> lock(state->mutex);
    state->done += advanced;
    // The steps' lengths add up to the period only to rounding: within 1e-9 of it is done.
    const double ratio = state->done / period;
    const double fraction = ratio > 1 - 1e-9 ? 1.0 : ratio;
    if (fraction - state->last < 0.005 && fraction < 1) return;
    if (fraction == state->last) return;  // 100 % said once
    state->last = fraction;
    sink(name, fraction);
  };
}

}  // namespace ltp::internal
