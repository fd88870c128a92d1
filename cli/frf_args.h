#pragma once
// Options shared by `ltp pfrf` and `ltp snapshot`: frequency ranges, order ranges, channels
// by index or name, progress on a terminal, and the CSV number format.
#include <string>
#include <utility>
#include <vector>

namespace ltp::cli {

/// "F0:F1:DF" (Hz) → F0, F0+DF, ... <= F1 (equal ends: one frequency). @throws InputError.
std::vector<double> ParseFrequencyRange(const std::string& text);
/// "-4:4" or "0" → (min, max). @throws InputError.
std::pair<int, int> ParseOrderRange(const std::string& text);
/// A channel given by index from 0 or by name among `names`. @throws InputError naming the
/// valid choices.
int ResolveChannel(const std::string& text, const std::vector<std::string>& names, int count,
                   const std::string& what);
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
