#include "ltp/core/bounded_coefficients.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace ltp {
namespace {

std::string NotANumber(double t, double period) {
  std::ostringstream s;
  s.precision(10);
  s << "A(t) is not a number at t = " << t << " (of the period " << period
    << "): the coefficients must be finite over the whole period";
  return s.str();
}

}  // namespace

std::optional<std::string> UnboundedCoefficients(const PeriodicSystem& system) {
  const int n = system.states();
  if (n == 0) return std::nullopt;
  const double T = system.period();
  Eigen::MatrixXd a(n, n);
  bool not_a_number = false;
  double nan_at = 0;
  auto norm_at = [&](double t) {
    system.EvalA(t, a);
    const double v = a.norm();
    if (std::isnan(v) && !not_a_number) {
      not_a_number = true;
      nan_at = t;
    }
    return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
  };
  constexpr int kSamples = 256;
  int worst = 0;
  double worst_norm = -1;
  for (int s = 0; s < kSamples; ++s) {
    const double v = norm_at((s + 0.5) * T / kSamples);
    if (v > worst_norm) {
      worst_norm = v;
      worst = s;
    }
  }
  if (not_a_number) return NotANumber(nan_at, T);
  double lo = std::max(0.0, (worst - 0.5) * T / kSamples),
         hi = std::min(T, (worst + 1.5) * T / kSamples);
  double peak = worst_norm, at = (worst + 0.5) * T / kSamples;
  while (std::isfinite(peak) && hi - lo > 1e-12 * T) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    const double v1 = norm_at(m1), v2 = norm_at(m2);
    if (v1 >= v2) {
      hi = m2;
      if (v1 > peak) peak = v1, at = m1;
    } else {
      lo = m1;
      if (v2 > peak) peak = v2, at = m2;
    }
  }
  if (not_a_number) return NotANumber(nan_at, T);
  if (!std::isfinite(peak) || peak > 1e6 * std::max(worst_norm, 1e-300)) {
    std::ostringstream s;
    s.precision(10);
    s << "A(t) is unbounded near t = " << at << " (‖A‖ grows from " << worst_norm << " to " << peak
      << " approaching it): a pole in the coefficients or a mass matrix that is "
      << "singular there; no integrator can cross it";
    return s.str();
  }
  return std::nullopt;
}

}  // namespace ltp
