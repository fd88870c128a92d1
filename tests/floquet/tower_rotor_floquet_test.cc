// Floquet analysis of the tower-rotor scene (paper Fig. 2, §5.2: rotor speed 100 1/s).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ltp/floquet/floquet.h"
#include "ltp/models/scene.h"
#include "ltp/models/tower_rotor.h"

namespace ltp {
namespace {

FloquetOptions Options() {
  FloquetOptions options;
  // The automatic segment rule would refine to thousands of segments: the factor condition of
  // [p; p'] states grows like ω_max² (ω_max ≈ 4800 rad/s) even without growth or decay.
  options.segments = 128;
  options.mode_samples = 256;
  return options;
}

// Undamped (zeta = 0) the linearised equations come from a Lagrangian with periodic
// coefficients, so the monodromy is symplectic; a stable rotor then has every exponent on the
// imaginary axis (no energy source: the drive's work averages out). Observed |Re λ| ~ 2e-8 1/s
// with an error estimate ~1e-7 1/s, against |λ| up to 4.8e3 1/s.
TEST(TowerRotorFloquet, UndampedExponentsOnImaginaryAxis) {
  const PeriodicSystem system = LoadScene("tower-rotor").Build({{"zeta", "0"}});
  const FloquetResult result = AnalyzeFloquet(system, Options());
  ASSERT_TRUE(result.ok);
  ASSERT_EQ(static_cast<int>(result.modes.size()), system.states());
  for (const FloquetMode& mode : result.modes) {
    EXPECT_LT(std::abs(mode.exponent.real()), 1e-6) << "mode at " << mode.frequency_hz << " Hz";
  }
  EXPECT_LT(std::abs(result.liouville_residual.value()), 1e-7);
}

// Damped default: stable; the slowest decay is the first cantilever mode, Re λ ≈ −ζ ω_1; the
// cantilever's first bending modes barely move with rotation (compare the mode table).
TEST(TowerRotorFloquet, DampedRotorIsStableAndCantileverModesStay) {
  const PeriodicSystem system = LoadScene("tower-rotor").Build();
  const FloquetResult result = AnalyzeFloquet(system, Options());
  ASSERT_TRUE(result.ok);
  EXPECT_TRUE(result.stable);
  const std::vector<TowerRotorMode> table = TowerRotorModeTable(TowerRotorParams{});
  ASSERT_GE(result.modes.size(), 4u);
  // Modes are sorted by |Im λ|, conjugate pairs adjacent.
  EXPECT_NEAR(std::abs(result.modes[0].frequency_hz), table[0].frequency_hz,
              0.01 * table[0].frequency_hz);
  EXPECT_NEAR(std::abs(result.modes[2].frequency_hz), table[1].frequency_hz,
              0.01 * table[1].frequency_hz);
  EXPECT_NEAR(result.max_real_exponent, -0.01 * 2 * std::numbers::pi * table[0].frequency_hz, 0.05);
}

}  // namespace
}  // namespace ltp
