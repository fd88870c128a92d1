#include "ltp/htf/frequency_range.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "ltp/core/error.h"
#include "ltp/core/text.h"

namespace ltp {

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

std::vector<double> ParseFrequencyRange(const std::string& text, const std::string& option) {
  const auto parts = SplitAt(text, ':');
  if (parts.size() != 3) throw InputError(option + " must be F0:F1:DF in Hz, got '" + text + "'");
  const double f0 = ParseNumber(parts[0], option + " F0"),
               f1 = ParseNumber(parts[1], option + " F1");
  const double df = ParseNumber(parts[2], option + " DF");
  if (f1 < f0) throw InputError(option + ": F1 must be >= F0, got '" + text + "'");
  if (f1 == f0) return {f0};
  if (!(df > 0)) throw InputError(option + ": DF must be > 0, got '" + text + "'");
  const double count = std::floor((f1 - f0) / df * (1 + 1e-12) + 1e-9) + 1;
  if (count > 1e6) throw InputError(option + ": more than a million frequencies in '" + text + "'");
  std::vector<double> f;
  for (int i = 0; i < static_cast<int>(count); ++i) f.push_back(f0 + i * df);
  return f;
}

std::vector<double> ParseFrequencyList(const std::string& text, const std::string& option) {
  std::vector<double> f;
  for (const std::string& item : SplitAt(text, ',')) {
    if (item.empty()) throw InputError(option + ": an empty item in '" + text + "'");
    const std::vector<double> part = item.find(':') == std::string::npos
                                         ? std::vector<double>{ParseNumber(item, option)}
                                         : ParseFrequencyRange(item, option);
    if (f.size() + part.size() > 1000000)
      throw InputError(option + ": more than a million frequencies in '" + text + "'");
    f.insert(f.end(), part.begin(), part.end());
  }
  return f;
}

std::pair<int, int> ParseOrderRange(const std::string& text, const std::string& option) {
  const auto parts = SplitAt(text, ':');
  if (parts.size() == 1) {
    const int z = ParseInt(parts[0], option);
    return {z, z};
  }
  if (parts.size() != 2) throw InputError(option + " must be ZMIN:ZMAX, got '" + text + "'");
  const int a = ParseInt(parts[0], option), b = ParseInt(parts[1], option);
  if (a > b) throw InputError(option + ": ZMIN must be <= ZMAX, got '" + text + "'");
  if (std::max(std::abs(a), std::abs(b)) > 1000) throw InputError(option + ": beyond ±1000");
  return {a, b};
}

std::pair<double, double> ParseFrequencyBand(const std::string& text, const std::string& option) {
  const std::vector<std::string> parts = SplitAt(text, ':');
  if (parts.size() != 2) throw InputError(option + ": expected F0:F1 (Hz), got '" + text + "'");
  const double f0 = ParseNumber(parts[0], option), f1 = ParseNumber(parts[1], option);
  if (!(f0 >= 0 && f1 > f0))
    throw InputError(option + ": the band needs 0 <= F0 < F1, got '" + text + "'");
  return {f0, f1};
}

}  // namespace ltp
