#pragma once
// What `ltp pfrf` and `ltp snapshot` share beyond the library's parsers of frequency and order
// ranges (ltp/htf/frequency_range.h) and channels (ltp/core/channel.h): the phase of the CSV
// columns and progress on a terminal.
#include <string>

namespace ltp::cli {

/// Phase in degrees, (−180, 180].
double PhaseDeg(double re, double im);
/// A progress line "\r<label> done/total" on stderr, only when stderr is a terminal.
class Progress {
 public:
  explicit Progress(std::string label);
  ~Progress();
  void operator()(int done, int total);

 private:
  std::string label_;
  bool active_ = false, shown_ = false;
  int last_percent_ = -1;
};

}  // namespace ltp::cli
