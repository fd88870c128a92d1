// Forward and backward whirl shares (ltp/core/whirl.h) against circles written by hand.
#include "ltp/core/whirl.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "ltp/core/error.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

// One harmonic (H = 0) of a 4-state shape with the pair (x, y) = states (0, 1).
std::vector<Eigen::VectorXcd> Shape(cd x, cd y) {
  Eigen::VectorXcd xi = Eigen::VectorXcd::Zero(4);
  xi << x, y, 0.3, -0.2;  // rates: not in the pair
  return {xi};
}

TEST(ForwardWhirlShare, CirclesAndEllipses) {
  const cd j(0, 1);
  const std::vector<std::array<int, 2>> pair = {{0, 1}};
  // x = cos ωt, y = sin ωt (X = 1, Y = −j): x + jy = e^{jωt}, a forward circle for ω > 0.
  EXPECT_DOUBLE_EQ(ForwardWhirlShare(pair, Shape(1, -j), 2.0, 1.0, 1), 1.0);
  // The same shape at −ω (the conjugate mode's view: x + jy = e^{−jωt}) whirls backward; so
  // does the forward circle when the rotor turns from y towards x.
  EXPECT_DOUBLE_EQ(ForwardWhirlShare(pair, Shape(1, -j), -2.0, 1.0, 1), 0.0);
  EXPECT_DOUBLE_EQ(ForwardWhirlShare(pair, Shape(1, -j), 2.0, 1.0, -1), 0.0);
  // A line x = cos ωt, y = 0: two equal circles, half and half.
  EXPECT_DOUBLE_EQ(ForwardWhirlShare(pair, Shape(1, 0), 2.0, 1.0, 1), 0.5);
  // An ellipse x = 3 cos ωt, y = sin ωt: radii (3 + 1)/2 forward, (3 − 1)/2 backward:
  // 4/(4 + 1).
  EXPECT_NEAR(ForwardWhirlShare(pair, Shape(3, -j), 2.0, 1.0, 1), 0.8, 1e-15);
  // Harmonics: v = −1, 0, 1 with ω = 0.4, Ωp = 1 turn at −0.6, 0.4, 1.4: a forward circle on
  // v = −1 whirls backward.
  std::vector<Eigen::VectorXcd> three = {Shape(1, -j)[0], Shape(0, 0)[0], Shape(2, -2.0 * j)[0]};
  three[1].head(2).setZero();
  EXPECT_NEAR(ForwardWhirlShare(pair, three, 0.4, 1.0, 1), 16.0 / 20.0, 1e-15);
  // No motion in the plane, and a circle that stands still (a real exponent's harmonic 0).
  EXPECT_TRUE(std::isnan(ForwardWhirlShare(pair, Shape(0, 0), 2.0, 1.0, 1)));
  EXPECT_TRUE(std::isnan(ForwardWhirlShare(pair, Shape(1, -j), 0.0, 1.0, 1)));
  EXPECT_THROW(ForwardWhirlShare({{0, 7}}, Shape(1, 0), 2.0, 1.0, 1), InputError);
}

TEST(OrbitOf, CirclesEllipsesAndLines) {
  const cd j(0, 1);
  const double pi = std::acos(-1.0);
  // x = cos ωt, y = sin ωt: a forward circle of radius 1.
  Orbit o = OrbitOf(1, -j, 2.0, 1);
  EXPECT_NEAR(o.forward, 1, 1e-15);
  EXPECT_NEAR(o.backward, 0, 1e-15);
  EXPECT_NEAR(o.semi_minor, 1, 1e-15);
  // x = 3 cos ωt, y = sin ωt: axes 3 (along x) and 1; circles 2 forward, 1 backward.
  o = OrbitOf(3, -j, 2.0, 1);
  EXPECT_NEAR(o.semi_major, 3, 1e-15);
  EXPECT_NEAR(o.semi_minor, 1, 1e-15);
  EXPECT_NEAR(o.forward, 2, 1e-15);
  EXPECT_NEAR(o.backward, 1, 1e-15);
  EXPECT_NEAR(o.tilt, 0, 1e-15);
  // x = y = cos(ωt + 0.4): a line at 45°, length √2 each way; forward and backward equal.
  o = OrbitOf(std::polar(1.0, 0.4), std::polar(1.0, 0.4), -1.5, 1);
  EXPECT_NEAR(o.semi_major, std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(o.semi_minor, 0, 1e-15);
  EXPECT_NEAR(o.tilt, pi / 4, 1e-15);
  EXPECT_NEAR(o.forward, o.backward, 1e-15);
  // x = sin ωt, y = 2 cos ωt (X = −j, Y = 2): axes 2 (along y) and 1, turning from y to x
  // (backward), radii 1.5 and 0.5.
  o = OrbitOf(-j, 2, 1.0, 1);
  EXPECT_NEAR(o.semi_major, 2, 1e-15);
  EXPECT_NEAR(o.semi_minor, 1, 1e-15);
  EXPECT_NEAR(std::abs(o.tilt), pi / 2, 1e-15);
  EXPECT_NEAR(o.backward, 1.5, 1e-15);
  EXPECT_NEAR(o.forward, 0.5, 1e-15);
}

}  // namespace
}  // namespace ltp
