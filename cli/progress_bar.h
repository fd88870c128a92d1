#pragma once
// The one progress bar of the commands: a line on stderr, redrawn at most 10 times a second,
// with the elapsed time and an ETA; nothing for work that ends within half a second (no
// flicker). When stderr is not a terminal (a log, a batch job) no bar is drawn, but work whose
// ETA after 2 s is above 10 s says so in one line, so a long job is never silent.
#include <chrono>
#include <string>
#include <string_view>

namespace ltp::cli {

class ProgressBar {
 public:
  /// `enabled` = false: never drawn (e.g. --json, or an MPI rank other than 0).
  explicit ProgressBar(std::string label, bool enabled = true);
  ~ProgressBar();  ///< clears the line if it was drawn
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// `done` of `total` units (`unit` names them: "points", "frequencies"; empty: a percentage
  /// only); `phase` is shown after the label and the bar restarts with a new one. The ETA is
  /// the phase's, from its rate since its first update (so resumed work counted in that
  /// `done` does not make it optimistic); the time shown is the whole call's.
  void Update(double done, double total, std::string_view unit = {}, std::string_view phase = {});
  void Clear();

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  bool enabled_ = false, terminal_ = false, shown_ = false, announced_ = false;
  Clock::time_point start_ = Clock::now(), last_{}, phase_start_{};
  std::string phase_;
  double first_done_ = -1;
};

}  // namespace ltp::cli
