#include "frf_args.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>

namespace ltp::cli {

double PhaseDeg(double re, double im) { return std::atan2(im, re) * 180 / std::numbers::pi; }

Progress::Progress(std::string label) : label_(std::move(label)), active_(isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  if (shown_) std::cerr << "\r" << std::string(label_.size() + 24, ' ') << "\r" << std::flush;
}

void Progress::operator()(int done, int total) {
  if (!active_ || total <= 0) return;
  const int percent = static_cast<int>(100.0 * done / total);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  shown_ = true;
  std::cerr << "\r" << label_ << " " << done << "/" << total << " (" << percent << "%)"
            << std::flush;
}

}  // namespace ltp::cli
