#include "format.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

namespace ltp::cli {

std::string Num(double x, int precision, int width) {
  char buf[64];
  if (std::isnan(x)) {
    std::snprintf(buf, sizeof buf, "%*s", width, "nan");
  } else if (std::isinf(x)) {
    std::snprintf(buf, sizeof buf, "%*s", width, x > 0 ? "inf" : "-inf");
  } else {
    std::snprintf(buf, sizeof buf, "%*.*g", width, precision, x);
  }
  return buf;
}

std::string Num(std::optional<double> x, int precision, int width) {
  if (x) return Num(*x, precision, width);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%*s", width, "n/a");
  return buf;
}

nlohmann::json JsonNumber(std::optional<double> x) { return x ? JsonNumber(*x) : nullptr; }

nlohmann::json JsonNumber(double x) {
  if (std::isfinite(x)) return x;
  if (std::isnan(x)) return "nan";
  return x > 0 ? "inf" : "-inf";
}

nlohmann::json JsonNumbers(const std::vector<double>& x) {
  nlohmann::json a = nlohmann::json::array();
  for (double v : x) a.push_back(JsonNumber(v));
  return a;
}

void AppendCsvNumber(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
    return;
  }
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 12).ptr;
  out.append(buf, end);
}

std::string CsvNumber(std::optional<double> x) {
  std::string s;
  if (x) AppendCsvNumber(s, *x);
  return s;
}

std::string CsvText(std::string s) {
  for (char& c : s)
    if (c == '"' || c == '\n' || c == '\r') c = '\'';
  return "\"" + s + "\"";
}

std::string WorkAhead(double s) {
  const std::string about = s < 120    ? Num(s, 2) + " s"
                            : s < 7200 ? Num(s / 60, 2) + " min"
                                       : Num(s / 3600, 2) + " h";
  return "about " + about + " of CPU work ahead";
}

double ExpClamped(double log_abs) {
  if (log_abs > 709.78) return std::numeric_limits<double>::infinity();
  return std::exp(log_abs);  // underflows to 0 (or a denormal) below e^-745
}

}  // namespace ltp::cli
