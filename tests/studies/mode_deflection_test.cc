#include "ltp/studies/mode_deflection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "ltp/core/error.h"
#include "support/throws.h"

namespace ltp {
namespace {

using std::numbers::pi;
using namespace std::complex_literals;

// A unit bar turning about z (node 1 at (cos t, sin t, 0)) whose tip the first of two
// coordinates moves along the direction of turning; the second moves nothing drawn.
StructureGeometry TurningBar(double t) {
  StructureGeometry g;
  g.axes = "test";
  DrawnBody bar{"bar", Eigen::Matrix3Xd::Zero(3, 2), Eigen::MatrixXd::Zero(6, 2)};
  bar.rest.col(1) << std::cos(t), std::sin(t), 0;
  bar.motion.block(3, 0, 3, 1) << -std::sin(t), std::cos(t), 0;
  g.bodies.push_back(bar);
  return g;
}

// One mode λ = −0.1 + 2j with constant ξ = [1, 0.5j, ·, ·] at four sample times over T = 2π.
FloquetResult OneMode() {
  FloquetResult r;
  r.states = 4;
  FloquetMode m;
  m.exponent = -0.1 + 2.0i;
  r.modes = {m};
  for (int s = 0; s < 4; ++s) {
    r.sample_times.push_back(2 * pi * s / 4);
    Eigen::MatrixXcd xi(4, 1);
    xi << 1, 0.5i, 0, 0;
    r.mode_samples.push_back(xi);
  }
  r.mode_descriptions = {"bar 100%"};
  return r;
}

// Closed form: the tip moves by scale · Re(e^{λt}) = scale · e^{−0.1 t} cos 2t along the
// direction of turning; the largest |Re(e^{λt})| over the samples is 1 (t = 0), and the bar's
// size is 1, so scale = amplitude. On the bar as it stands at t = 0, that is a motion along y
// of a bar along x.
TEST(ModeDeflection, FramesAreTheModesFreeMotionOnTheTurningStructure) {
  ModeDeflectionOptions options;
  options.amplitude = 0.2;
  const ModeDeflections d = DeflectModes(TurningBar, OneMode(), {}, options);
  ASSERT_EQ(d.bodies, std::vector<std::string>{"bar"});
  ASSERT_EQ(d.modes.size(), 1u);
  const ModeDeflection& m = d.modes[0];
  EXPECT_EQ(m.description, "bar 100%");
  EXPECT_DOUBLE_EQ(m.scale, 0.2);
  ASSERT_EQ(m.frames.size(), 4u);
  for (const DeflectionFrame& f : m.frames) {
    const Eigen::Vector3d tip(std::cos(f.t), std::sin(f.t), 0);
    EXPECT_LT((f.rest[0].col(1) - tip).norm(), 1e-15);
    const double u = 0.2 * std::exp(-0.1 * f.t) * std::cos(2 * f.t);
    const Eigen::Vector3d along(-std::sin(f.t), std::cos(f.t), 0);
    EXPECT_LT((f.moved[0].col(1) - (tip + u * along)).norm(), 1e-15) << f.t;
    EXPECT_LT((f.standing[0].col(1) - Eigen::Vector3d(1, u, 0)).norm(), 1e-15) << f.t;
    EXPECT_EQ(f.moved[0].col(0), f.rest[0].col(0));  // the root does not move
  }
}

TEST(ModeDeflection, RefusesWhatItCannotDraw) {
  FloquetResult none = OneMode();
  none.mode_samples.clear();
  EXPECT_NE(test::ThrownMessage<InputError>([&] {
              DeflectModes(TurningBar, none);
            }).find("no periodic mode shapes"),
            std::string::npos);
  EXPECT_NE(test::ThrownMessage<InputError>([&] {
              DeflectModes(TurningBar, OneMode(), {1});
            }).find("there is no mode 2 (index 1): the analysis has 1 mode"),
            std::string::npos);
  FloquetResult scalar = OneMode();  // a one-state system cannot drive two coordinates
  for (Eigen::MatrixXcd& xi : scalar.mode_samples) xi.conservativeResize(1, 1);
  EXPECT_NE(test::ThrownMessage<InputError>([&] {
              DeflectModes(TurningBar, scalar);
            }).find("the structure has 2 coordinates but the analysed system only 1 states"),
            std::string::npos);
  const GeometryAt uneven = [](double t) {  // two bodies on different coordinates
    StructureGeometry g = TurningBar(t);
    g.bodies.push_back({"odd", Eigen::Matrix3Xd::Zero(3, 1), Eigen::MatrixXd::Zero(3, 3)});
    return g;
  };
  EXPECT_NE(test::ThrownMessage<InputError>([&] {
              DeflectModes(uneven, OneMode());
            }).find("the drawn body 'odd' does not match the structure's 2 coordinates"),
            std::string::npos);
  ModeDeflectionOptions zero;
  zero.amplitude = 0;
  EXPECT_THROW(DeflectModes(TurningBar, OneMode(), {}, zero), InputError);
}

}  // namespace
}  // namespace ltp
