#pragma once
// Progress of one Floquet analysis, phase by phase, from the integrators' steps
// (FloquetOptions::on_progress).
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

namespace ltp::internal {

class AnalysisProgress {
 public:
  using Sink = std::function<void(std::string_view phase, double fraction)>;
  /// `sink` empty: every Phase() is empty too, and the integrators call nothing.
  AnalysisProgress(Sink sink, double period);
  /// The step callback (IntegratorOptions::on_advance) of a phase that integrates about one
  /// period: each call adds the time a step advanced and tells the sink the fraction done
  /// (clamped to 1: refinement re-integrates split segments), at most every half percent, one
  /// call at a time whatever thread the step ran on.
  std::function<void(double)> Phase(std::string name) const;

 private:
  struct State {
    std::mutex mutex;
    double done = 0, last = -1;
  };
  Sink sink_;
  double period_ = 1;
};

}  // namespace ltp::internal
