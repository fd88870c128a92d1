// Systems written in badly scaled states (units far apart) are analysed in balanced states and
// reported in the given ones (integrate/include/ltp/integrate/detail/state_balancing.h,
// docs/model-sizes.md). References: the same system in well-scaled states (exponents are invariant
// under x = S z) and, for the constant system, its closed-form eigenvalues.
#include "ltp/integrate/detail/state_balancing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

TEST(StateBalancing, BadlyScaledMathieuGivesTheWellScaledResult) {
  // x = S y with S = diag(2^-30, 2^20): A_x = S A_y S⁻¹ has entries from 1e-9 to 1e15.
  const PeriodicSystem well = test::Mathieu(1.5, 0.5, 0.05);
  const Eigen::Vector2d s(0x1p-30, 0x1p+20);
  const PeriodicSystem bad = well.WithStateScaling(s.cwiseInverse());
  EXPECT_EQ(internal::StateBalancing(well).size(), 0);  // analysed as given
  EXPECT_EQ(internal::StateBalancing(bad).size(), 2);
  const FloquetResult a = AnalyzeFloquet(well), b = AnalyzeFloquet(bad);
  ASSERT_TRUE(a.ok && b.ok) << b.BriefReport();
  EXPECT_LT(MaxExponentMismatch(Exponents(b.modes), Exponents(a.modes), well.omega()), 1e-12);
  EXPECT_LT(*b.error_estimate, 1e-8);
  EXPECT_EQ(b.verdict, a.verdict);
  // Monodromy and mode shapes come back in the given states: Φ_x = S Φ_y S⁻¹, ξ_x = S ξ_y.
  const Eigen::Matrix2d expected = s.asDiagonal() * a.monodromy * s.cwiseInverse().asDiagonal();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(b.monodromy(i, j), expected(i, j), 1e-9 * std::abs(expected(i, j)));
  ASSERT_FALSE(b.mode_samples.empty());
  for (int k = 0; k < 2; ++k) {
    const cd ratio_a = a.mode_samples[0](0, k) / a.mode_samples[0](1, k);
    const cd ratio_b = b.mode_samples[0](0, k) / b.mode_samples[0](1, k);
    EXPECT_LT(std::abs(ratio_b - ratio_a * (s[0] / s[1])), 1e-9 * std::abs(ratio_b));
  }
}

TEST(StateBalancing, ConstantSystemInFarApartUnitsMeetsItsEigenvalues) {
  // A = [[0, 1e9], [−1e-9, −0.1]]: eigenvalues of λ² + 0.1 λ + 1 = 0, −0.05 ± j √0.9975
  // (closed form). Unbalanced, the periodic eigenvector step failed ("log_rho must be
  // finite") and single-shot multipliers under-estimated their error.
  Eigen::MatrixXd a(2, 2);
  a << 0, 1e9, -1e-9, -0.1;
  const PeriodicSystem s = PeriodicSystem::FromFourier(1.0, FourierMatrix::Constant(a));
  const FloquetResult r = AnalyzeFloquet(s);
  ASSERT_TRUE(r.ok) << r.BriefReport();
  const std::vector<cd> exact = {{-0.05, std::sqrt(0.9975)}, {-0.05, -std::sqrt(0.9975)}};
  const double err = MaxExponentMismatch(Exponents(r.modes), exact, s.omega());
  EXPECT_LT(err, 1e-12);
  EXPECT_GE(*r.error_estimate, err);
}

}  // namespace
}  // namespace ltp
