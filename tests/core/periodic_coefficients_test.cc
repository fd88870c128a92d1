// NonPeriodicCoefficients: a function A(t) whose own period is not the one given is refused
// before any analysis. References: the functions' exact periods (closed forms).
#include "ltp/core/periodic_coefficients.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace ltp {
namespace {

constexpr double kPi = std::numbers::pi;

// x'' + (1 + 0.4 f(t)) x = 0 with f given.
template <class F>
PeriodicSystem HillWith(double period, F f, std::vector<double> breakpoints = {}) {
  PeriodicSystem::Functions fn;
  fn.A = [f](double t, Eigen::Ref<Eigen::MatrixXd> out) { out << 0, 1, -(1 + 0.4 * f(t)), -0.02; };
  return PeriodicSystem::FromFunctions(period, 2, 0, 0, fn, std::move(breakpoints));
}

TEST(PeriodicCoefficients, FunctionsWithTheGivenPeriodPass) {
  EXPECT_FALSE(NonPeriodicCoefficients(HillWith(2 * kPi, [](double t) { return std::cos(t); })));
  // A shorter period divides T: still T-periodic.
  EXPECT_FALSE(
      NonPeriodicCoefficients(HillWith(2 * kPi, [](double t) { return std::cos(4 * t); })));
  // A sawtooth evaluated at t mod T jumps at t = 0 ≡ T: periodic.
  EXPECT_FALSE(
      NonPeriodicCoefficients(HillWith(2.0, [](double t) { return std::fmod(t, 2.0); }, {0.0})));
  // Periods far from 1 (the check is relative to T and to ‖A‖).
  EXPECT_FALSE(NonPeriodicCoefficients(
      HillWith(1e-4, [](double t) { return std::sin(2 * kPi * t / 1e-4); })));
  EXPECT_FALSE(
      NonPeriodicCoefficients(HillWith(1e6, [](double t) { return std::sin(2 * kPi * t / 1e6); })));
}

// A period of 1e7 or 1e8 of the coefficients' own (π) is off from the true multiple by its
// rounding, and t + T by another ulp: cos(2(t + T)) − cos 2t ≈ 1e-9 of ‖A‖ at 1e7·π, 3e-8 at
// 1e8·π — round-off of T, not a wrong period (was refused); a period off by 1e-12 of itself
// (many ulps) still is.
TEST(PeriodicCoefficients, AHugeMultipleOfTheOwnPeriodPasses) {
  for (const double multiple : {1e7, 1e8})
    EXPECT_FALSE(NonPeriodicCoefficients(HillWith(multiple * kPi, [](double t) {
      return std::cos(2 * t);
    }))) << multiple;
  EXPECT_TRUE(NonPeriodicCoefficients(
      HillWith(1e7 * kPi * (1 + 1e-12), [](double t) { return std::cos(2 * t); })));
}

TEST(PeriodicCoefficients, AMismatchedPeriodOrARampIsRefusedWithWhereAndHowMuch) {
  // cos t with T = 6.2832 (2π rounded): |cos(t + T) − cos t| ≈ 7.3e-6 |sin t|.
  const auto rounded =
      NonPeriodicCoefficients(HillWith(6.2832, [](double t) { return std::cos(t); }));
  ASSERT_TRUE(rounded);
  EXPECT_NE(rounded->find("not periodic with the period T = 6.2832"), std::string::npos)
      << *rounded;
  // sin t over π: sin(t + π) = −sin t.
  EXPECT_TRUE(NonPeriodicCoefficients(HillWith(kPi, [](double t) { return std::sin(t); })));
  // A ramp written for one period.
  const auto ramp = NonPeriodicCoefficients(HillWith(2.0, [](double t) { return t; }, {0.0}));
  ASSERT_TRUE(ramp);
  EXPECT_NE(ramp->find("t mod T"), std::string::npos) << *ramp;
}

TEST(PeriodicCoefficients, FourierSeriesAreNotEvaluated) {
  FourierMatrix a(2, 2, 0);
  a[0] << 0, 1, -1, 0;
  EXPECT_FALSE(NonPeriodicCoefficients(PeriodicSystem::FromFourier(1.0, a)));
}

}  // namespace
}  // namespace ltp
