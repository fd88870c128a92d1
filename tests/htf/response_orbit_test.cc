// Response orbits (response_orbit.h) of the Jeffcott rotor against its rotating frame, where it
// is time-invariant: the fixed-frame force (cos ωt, sin ωt) = R(Ωt)(cos νt, sin νt), ν = ω − Ω,
// is a rotating-frame force Re((1, −j) e^{jνt}); the rotating-frame response Re(Q e^{jνt}),
// Q = (K_r + jν D_r − ν² M)⁻¹ (1, −j), is turned back by R(Ωt): x + jy = ½(Q₁ + jQ₂) e^{jωt} +
// ½ conj(Q₁ − jQ₂) e^{j(2Ω − ω)t}. So order 0 is one circle of radius |Q₁ + jQ₂|/2 turning at ω,
// order −1 (ω − 2Ω) one of radius |Q₁ − jQ₂|/2 turning at 2Ω − ω, and every other order is 0.
#include "ltp/htf/response_orbit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "ltp/core/error.h"
#include "ltp/models/scene.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

Eigen::Vector2cd RotatingFrameResponse(double m, double k1, double k2, double c, double Omega,
                                       double nu) {
  const test::JeffcottRotatingFrame f = test::JeffcottRotating(m, k1, k2, c, Omega);
  const Eigen::Matrix2cd G =
      f.K.cast<cd>() + cd(0, nu) * f.D.cast<cd>() - nu * nu * m * Eigen::Matrix2cd::Identity();
  return G.inverse() * Eigen::Vector2cd(1, cd(0, -1));
}

TEST(ResponseOrbits, JeffcottUnbalanceEqualsTheRotatingFrame) {
  const double m = 1, k1 = 1, k2 = 1.5, c = 0.05, Omega = 0.5;
  const Scene scene = LoadScene("jeffcott");
  const HarmonicTransferFunction htf(
      scene.build({{"m", m}, {"k1", k1}, {"k2", k2}, {"c", c}, {"Omega", Omega}}));
  const Eigen::Vector2cd unbalance(1, cd(0, -1));  // fx = cos ωt, fy = sin ωt
  // ω = 0.7: order −1 turns at 2Ω − ω = 0.3 (forward); ω = 1.3: at −0.3 (backward);
  // ω = Ω: synchronous unbalance, a static load in the rotating frame (order −1 at −Ω).
  for (double omega : {0.7, 1.3, 0.5}) {
    const Eigen::Vector2cd Q = RotatingFrameResponse(m, k1, k2, c, Omega, omega - Omega);
    const double r0 = std::abs(Q(0) + cd(0, 1) * Q(1)) / 2;
    const double r1 = std::abs(Q(0) - cd(0, 1) * Q(1)) / 2;
    for (OperatorRoute route : {OperatorRoute::kModal, OperatorRoute::kHill}) {
      const std::vector<ResponseOrbit> orbits =
          ResponseOrbits(htf, omega, unbalance, 0, 1, -2, 2, route);
      ASSERT_EQ(orbits.size(), 5u);
      for (const ResponseOrbit& o : orbits) {
        EXPECT_NEAR(o.frequency, omega + 2 * Omega * o.order, 1e-15);
        const double expected_forward =
            o.order == 0 ? r0 : (o.order == -1 && 2 * Omega - omega > 0 ? r1 : 0);
        const double expected_backward = o.order == -1 && 2 * Omega - omega < 0 ? r1 : 0;
        EXPECT_NEAR(o.orbit.forward, expected_forward, 1e-8) << omega << " z = " << o.order;
        EXPECT_NEAR(o.orbit.backward, expected_backward, 1e-8) << omega << " z = " << o.order;
        EXPECT_NEAR(o.orbit.semi_major, expected_forward + expected_backward, 1e-8);
        EXPECT_NEAR(o.orbit.semi_minor, expected_forward + expected_backward, 1e-8);  // circles
      }
    }
  }
  EXPECT_THROW(ResponseOrbits(htf, 0.7, unbalance, 0, 2, 0, 0), InputError);
  EXPECT_THROW(ResponseOrbits(htf, 0.7, Eigen::VectorXcd::Ones(3), 0, 1, 0, 0), InputError);
}

// The sweep over a list of frequencies on one set-up, against the same rotating-frame closed
// form: every value, the sense of each order (order −1 turns at 2Ω − ω: forward below ω = 2Ω,
// backward above), and the routes' agreement as the estimate.
TEST(ResponseOrbitSweep, JeffcottListEqualsTheRotatingFrame) {
  const double m = 1, k1 = 1, k2 = 1.5, c = 0.05, Omega = 0.5;
  const HarmonicTransferFunction htf(
      LoadScene("jeffcott").build({{"m", m}, {"k1", k1}, {"k2", k2}, {"c", c}, {"Omega", Omega}}));
  const std::vector<double> omegas = {0.7, 1.3, 0.2};
  const OrbitSweep r = ResponseOrbitSweep(htf, omegas, UnbalanceInput(2, 0, 1, +1), 0, 1);
  ASSERT_TRUE(r.ok) << r.failure;
  EXPECT_EQ(r.route, OperatorRoute::kModal);
  ASSERT_TRUE(r.check_route.has_value());
  EXPECT_EQ(*r.check_route, OperatorRoute::kHill);
  ASSERT_EQ(r.orbits.size(), 3u);
  ASSERT_EQ(r.error_estimate.size(), 3u);
  // Routes: modal and Hill agree to round-off on this two-harmonic system (measured ~1e-15).
  EXPECT_LT(r.max_relative_disagreement, 1e-9);
  for (size_t i = 0; i < omegas.size(); ++i) {
    const double omega = omegas[i];
    const Eigen::Vector2cd Q = RotatingFrameResponse(m, k1, k2, c, Omega, omega - Omega);
    ASSERT_EQ(r.orbits[i].size(), 5u);
    for (size_t k = 0; k < 5; ++k) {
      const ResponseOrbit& o = r.orbits[i][k];
      const double r0 = o.order == 0 ? std::abs(Q(0) + cd(0, 1) * Q(1)) / 2 : 0;
      const double r1 = o.order == -1 ? std::abs(Q(0) - cd(0, 1) * Q(1)) / 2 : 0;
      const bool backward = o.order == -1 && 2 * Omega - omega < 0;
      EXPECT_NEAR(o.orbit.forward, backward ? 0 : r0 + r1, 1e-8) << omega << " z " << o.order;
      EXPECT_NEAR(o.orbit.backward, backward ? r1 : 0, 1e-8) << omega << " z " << o.order;
      const OrbitSense want = o.order == 0 || o.order == -1
                                  ? (backward ? OrbitSense::kBackward : OrbitSense::kForward)
                                  : OrbitSense::kStill;
      EXPECT_EQ(r.sense[i][k], want) << omega << " z " << o.order;
      EXPECT_LT(r.error_estimate[i][k], 1e-9);
    }
  }
}

// An isotropic shaft (k1 = k2 = k) is time-invariant: m p'' + c p' + k p = f. A unit unbalance
// (fx, fy) = (cos ωt, sin ωt) gives x + jy = e^{jωt}/(k − mω² + jcω) (closed form): a pure
// forward circle of radius 1/|k − mω² + jcω| at order 0, nothing at any other order, and no
// backward circle but round-off.
TEST(ResponseOrbitSweep, IsotropicRotorUnbalanceIsAForwardCircle) {
  const double m = 2, k = 3, c = 0.1, Omega = 0.8;
  const HarmonicTransferFunction htf(
      LoadScene("jeffcott").build({{"m", m}, {"k1", k}, {"k2", k}, {"c", c}, {"Omega", Omega}}));
  const std::vector<double> omegas = {0.3, std::sqrt(k / m), 2.0};
  OrbitSweepOptions options;
  options.min_order = -3;
  options.max_order = 3;
  for (OperatorRoute route : {OperatorRoute::kModal, OperatorRoute::kHill}) {
    options.route = route;
    const OrbitSweep r =
        ResponseOrbitSweep(htf, omegas, UnbalanceInput(2, 0, 1, +1), 0, 1, options);
    ASSERT_TRUE(r.ok) << r.failure;
    for (size_t i = 0; i < omegas.size(); ++i) {
      const double w = omegas[i];
      const double radius = 1 / std::abs(cd(k - m * w * w, c * w));
      for (size_t q = 0; q < r.orbits[i].size(); ++q) {
        const ResponseOrbit& o = r.orbits[i][q];
        const double want = o.order == 0 ? radius : 0;
        EXPECT_NEAR(o.orbit.forward, want, 1e-10 * radius) << w << " z " << o.order;
        EXPECT_NEAR(o.orbit.backward, 0, 1e-12 * radius) << w << " z " << o.order;
        EXPECT_NEAR(o.orbit.semi_minor, want, 1e-10 * radius);  // a circle
        EXPECT_EQ(r.sense[i][q], o.order == 0 ? OrbitSense::kForward : OrbitSense::kStill);
      }
    }
  }
}

// The default Jeffcott rotor (m = 1, k = 1 and 1.5, c = 0, Ω = 1.1 inside the anisotropy's
// instability band 1 < Ω² < 1.5) is unstable by `ltp floquet` (max Re λ = 0.111 1/s): its orbits
// are formal periodic solutions, and the sweep says so; the damped rotor of the test above says
// nothing.
TEST(ResponseOrbitSweep, AnUnstableRotorsOrbitsAreNamedAsNoSteadyState) {
  auto says_unsteady = [](const OrbitSweep& r) {
    return HasCode(r.diagnostics, DiagnosticCode::kSystemUnstable);
  };
  const HarmonicTransferFunction unstable(
      LoadScene("jeffcott").build({{"m", 1}, {"k1", 1}, {"k2", 1.5}, {"c", 0}, {"Omega", 1.1}}));
  const OrbitSweep u =
      ResponseOrbitSweep(unstable, {0.6}, UnbalanceInput(2, 0, 1, +1), 0, 1, OrbitSweepOptions{});
  EXPECT_TRUE(says_unsteady(u));
  const HarmonicTransferFunction stable(
      LoadScene("jeffcott").build({{"m", 2}, {"k1", 3}, {"k2", 3}, {"c", 0.1}, {"Omega", 0.8}}));
  const OrbitSweep s =
      ResponseOrbitSweep(stable, {0.6}, UnbalanceInput(2, 0, 1, +1), 0, 1, OrbitSweepOptions{});
  EXPECT_FALSE(says_unsteady(s));
}

TEST(ResponseOrbitSweep, ADisagreementBeyondTheLimitFailsTheSweep) {
  const HarmonicTransferFunction htf(
      LoadScene("jeffcott").build({{"m", 1}, {"k1", 1}, {"k2", 1.5}, {"c", 0.05}, {"Omega", 0.5}}));
  OrbitSweepOptions options;
  options.max_relative_disagreement = 1e-300;  // below any round-off: the check must fail it
  const OrbitSweep r = ResponseOrbitSweep(htf, {0.7}, UnbalanceInput(2, 0, 1, 1), 0, 1, options);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kRoutesDisagree)) << r.failure;
  options.check = false;  // nothing to disagree with: ok, no estimates
  const OrbitSweep u = ResponseOrbitSweep(htf, {0.7}, UnbalanceInput(2, 0, 1, 1), 0, 1, options);
  EXPECT_TRUE(u.ok);
  EXPECT_FALSE(u.check_route.has_value());
  EXPECT_TRUE(u.error_estimate.empty());
  EXPECT_THROW(ResponseOrbitSweep(htf, {}, UnbalanceInput(2, 0, 1, 1), 0, 1), InputError);
  options.min_order = 1;
  options.max_order = 0;
  EXPECT_THROW(ResponseOrbitSweep(htf, {0.7}, UnbalanceInput(2, 0, 1, 1), 0, 1, options),
               InputError);
}

// The unbalance turns with the rotor: (cos ωt, sin ωt) = Re((1, −j) e^{jωt}) for a rotor turning
// from x towards y, (cos ωt, −sin ωt) = Re((1, j) e^{jωt}) the other way.
TEST(UnbalanceInput, WeightsAndErrors) {
  const Eigen::VectorXcd u = UnbalanceInput(3, 2, 0, +1);
  EXPECT_EQ(u(2), cd(1, 0));
  EXPECT_EQ(u(0), cd(0, -1));
  EXPECT_EQ(u(1), cd(0, 0));
  EXPECT_EQ(UnbalanceInput(2, 0, 1, -1)(1), cd(0, 1));
  EXPECT_THROW(UnbalanceInput(2, 0, 0, 1), InputError);
  EXPECT_THROW(UnbalanceInput(1, 0, 1, 1), InputError);
  EXPECT_THROW(UnbalanceInput(2, -1, 1, 1), InputError);
}

// The sense against the uncertainty of the radii (OrbitSense's definition, by hand).
TEST(OrbitSense, ForwardBackwardLineStill) {
  const auto orbit = [](double f, double b) {
    Orbit o;
    o.forward = f;
    o.backward = b;
    return o;
  };
  EXPECT_EQ(SenseOf(orbit(1, 0.5), 0.1), OrbitSense::kForward);
  EXPECT_EQ(SenseOf(orbit(0.5, 1), 0.1), OrbitSense::kBackward);
  EXPECT_EQ(SenseOf(orbit(1, 0.95), 0.1), OrbitSense::kStraight);
  EXPECT_EQ(SenseOf(orbit(0.05, 0.01), 0.1), OrbitSense::kStill);
  EXPECT_EQ(SenseOf(orbit(0, 0), 0), OrbitSense::kStill);
  EXPECT_EQ(ToString(OrbitSense::kForward), "FW");
  EXPECT_EQ(ToString(OrbitSense::kBackward), "BW");
}

}  // namespace
}  // namespace ltp
