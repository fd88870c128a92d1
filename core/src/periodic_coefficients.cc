#include "ltp/core/periodic_coefficients.h"

#include <cmath>
#include <numbers>
#include <sstream>

namespace ltp {

std::optional<std::string> NonPeriodicCoefficients(const PeriodicSystem& system) {
  const int n = system.states();
  if (n == 0 || system.form() != PeriodicSystem::Form::kFunction) return std::nullopt;
  const double T = system.period();
  // Fractions k·φ mod 1: no two differ by a simple fraction, so a function with a shorter
  // period than T is not mistaken for one that is periodic, and no point falls on t = 0.
  constexpr int kPoints = 7;
  constexpr double kRelative = 1e-9;
  const double phi = std::numbers::phi - 1;
  // A period that is a large multiple of the coefficients' own (1e7·π for cos 2t) is off from
  // it by its rounding, and t + T by another ulp of T: A(t + T) then differs from A(t) by what
  // A changes over a few ulps of T. What A changes over 64 of them is allowed.
  const double drift_step = 64 * (std::nextafter(T, 2 * T) - T);
  Eigen::MatrixXd a(n, n), shifted(n, n), drifted(n, n);
  double scale = 0, worst = 0, worst_t = 0;
  for (int k = 1; k <= kPoints; ++k) {
    const double t = std::fmod(k * phi, 1.0) * T;
    bool near_breakpoint = false;
    for (double b : system.breakpoints())
      near_breakpoint = near_breakpoint || std::abs(t - b) < 1e-6 * T;
    if (near_breakpoint) continue;
    system.EvalA(t, a);
    system.EvalA(t + T, shifted);
    if (!a.allFinite() || !shifted.allFinite()) continue;  // UnboundedCoefficients says so
    scale = std::max({scale, a.norm(), shifted.norm()});
    system.EvalA(t + T + drift_step, drifted);
    const double d = (shifted - a).norm();
    if (drifted.allFinite() && d <= (drifted - shifted).norm()) continue;  // rounding of T
    if (d > worst) worst = d, worst_t = t;
  }
  if (!(worst > kRelative * scale)) return std::nullopt;
  std::ostringstream s;
  s.precision(6);
  s << "A(t) is not periodic with the period T = " << T << ": ‖A(t + T) − A(t)‖ = " << worst
    << " at t = " << worst_t << " (" << worst / scale
    << " of max ‖A‖); give the period of the coefficients, or evaluate a function written for "
       "one period at t mod T";
  return s.str();
}

}  // namespace ltp
