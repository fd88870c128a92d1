#include "progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace ltp::cli {

ProgressBar::ProgressBar(std::string label, bool enabled)
    : label_(std::move(label)), enabled_(enabled), terminal_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() { Clear(); }

void ProgressBar::Clear() {
  if (shown_) std::cerr << "\r" << std::string(110, ' ') << "\r" << std::flush;
  shown_ = false;
}

void ProgressBar::Update(double done, double total, std::string_view unit, std::string_view phase) {
  if (!enabled_ || !(total > 0)) return;
  const auto now = Clock::now();
  if (first_done_ < 0 || phase != phase_) {  // the ETA's rate is measured within a phase
    phase_ = std::string(phase);
    phase_start_ = now;
    first_done_ = done;
  }
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < 0.5 || (now - last_ < std::chrono::milliseconds(100) && done < total)) return;
  last_ = now;
  const double fraction = std::clamp(done / total, 0.0, 1.0);
  const double rate = (done - first_done_) /
                      std::max(std::chrono::duration<double>(now - phase_start_).count(), 1e-9);
  if (!terminal_) {
    const double eta = rate > 0 ? (total - done) / rate : 0;
    if (!announced_ && elapsed >= 2 && eta > 10) {
      std::ostringstream s;
      s << std::fixed << std::setprecision(0) << "ltp: " << label_
        << (phase.empty() ? "" : " (" + std::string(phase) + ")") << ": about " << eta << " s more";
      if (!unit.empty())
        s << " for " << static_cast<long>(total - done) << " " << unit << " (" << done << " in "
          << elapsed << " s)";
      std::cerr << s.str() << "\n" << std::flush;
      announced_ = true;
    }
    return;
  }
  const int width = 30, filled = static_cast<int>(width * fraction);
  std::ostringstream s;
  s << "\r  " << label_;
  if (!phase.empty()) s << " (" << phase << ")";
  s << " [" << std::string(filled, '#') << std::string(width - filled, '.') << "] " << std::setw(3)
    << static_cast<int>(100 * fraction) << "%";
  if (!unit.empty())
    s << "  " << static_cast<long>(done) << "/" << static_cast<long>(total) << " " << unit;
  s << std::fixed << std::setprecision(1) << "  " << elapsed << " s";
  if (rate > 0 && done < total) s << ", ETA " << (total - done) / rate << " s";
  s << "   ";
  std::cerr << s.str() << std::flush;
  shown_ = true;
}

}  // namespace ltp::cli
