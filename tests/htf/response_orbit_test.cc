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

}  // namespace
}  // namespace ltp
