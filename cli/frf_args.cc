#include "frf_args.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>

#include "ltp/core/error.h"

namespace ltp::cli {

namespace {

double ParseNumber(const std::string& s, const std::string& what) {
  try {
    size_t used = 0;
    const double x = std::stod(s, &used);
    if (used != s.size() || !std::isfinite(x)) throw std::invalid_argument("");
    return x;
  } catch (const std::exception&) {
    throw InputError(what + ": '" + s + "' is not a finite number");
  }
}

std::vector<std::string> Split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t at = s.find(sep, start);
    parts.push_back(s.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  return parts;
}

int ParseInt(const std::string& s, const std::string& what) {
  try {
    size_t used = 0;
    const long v = std::stol(s, &used);
    if (used != s.size() || v < -100000 || v > 100000) throw std::invalid_argument("");
    return static_cast<int>(v);
  } catch (const std::exception&) {
    throw InputError(what + ": '" + s + "' is not an integer");
  }
}

}  // namespace

std::vector<double> ParseFrequencyRange(const std::string& text) {
  const auto parts = Split(text, ':');
  if (parts.size() != 3) throw InputError("--freq must be F0:F1:DF in Hz, got '" + text + "'");
  const double f0 = ParseNumber(parts[0], "--freq F0"), f1 = ParseNumber(parts[1], "--freq F1");
  const double df = ParseNumber(parts[2], "--freq DF");
  if (f1 < f0) throw InputError("--freq: F1 must be >= F0, got '" + text + "'");
  if (f1 == f0) return {f0};
  if (!(df > 0)) throw InputError("--freq: DF must be > 0, got '" + text + "'");
  const double count = std::floor((f1 - f0) / df * (1 + 1e-12) + 1e-9) + 1;
  if (count > 1e6) throw InputError("--freq: more than a million frequencies in '" + text + "'");
  std::vector<double> f;
  for (int i = 0; i < static_cast<int>(count); ++i) f.push_back(f0 + i * df);
  return f;
}

std::pair<int, int> ParseOrderRange(const std::string& text) {
  const auto parts = Split(text, ':');
  if (parts.size() == 1) {
    const int z = ParseInt(parts[0], "--orders");
    return {z, z};
  }
  if (parts.size() != 2) throw InputError("--orders must be ZMIN:ZMAX, got '" + text + "'");
  const int a = ParseInt(parts[0], "--orders"), b = ParseInt(parts[1], "--orders");
  if (a > b) throw InputError("--orders: ZMIN must be <= ZMAX, got '" + text + "'");
  if (std::max(std::abs(a), std::abs(b)) > 1000) throw InputError("--orders: beyond ±1000");
  return {a, b};
}

int ResolveChannel(const std::string& text, const std::vector<std::string>& names, int count,
                   const std::string& what) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == text) return static_cast<int>(i);
  bool digits = !text.empty();
  for (char c : text) digits = digits && c >= '0' && c <= '9';
  if (digits && text.size() < 8) {
    const int i = std::stoi(text);
    if (i < count) return i;
  }
  std::string valid;
  for (int i = 0; i < count; ++i)
    valid += (i ? ", " : "") + std::to_string(i) +
             (i < static_cast<int>(names.size()) && !names[i].empty() ? " (" + names[i] + ")" : "");
  throw InputError("--" + what + " '" + text + "' is not one of the system's " + what + "s: " +
                   (count ? valid : std::string("none")));
}

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
  std::cerr << "\r" << label_ << " " << done << "/" << total << " (" << percent << "%)" << std::flush;
}

}  // namespace ltp::cli
