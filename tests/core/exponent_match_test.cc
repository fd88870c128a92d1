// The one-to-one matching of Floquet exponents (core/exponent_match.h) on hand-made sets whose
// right answer is known by construction.
#include "ltp/core/exponent_match.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <vector>

namespace ltp {
namespace {

using cd = std::complex<double>;

TEST(ExponentMatch, ClosestPairsFirstModuloOmega) {
  const double omega = 2.0;
  // 0.1 + 2.05j is 0.1 + 0.05j modulo jΩ: it belongs to the first reference.
  const std::vector<cd> values = {{-1.0, 0.3}, {0.1, 2.05}};
  const std::vector<cd> reference = {{0.1, 0.0}, {-1.0, 0.31}};
  const std::vector<int> match = MatchExponentIndices(values, reference, omega);
  EXPECT_EQ(match, (std::vector<int>{1, 0}));
  EXPECT_NEAR(ExponentDistance(values[1], reference[0], omega), 0.05, 1e-15);
}

TEST(ExponentMatch, StripEdgeTiesDoNotHangOnTheLastBit) {
  // An exponent on the strip edge, Im λ = Ωp/2 (a negative real multiplier), is exactly as far
  // from a reference r as from conj(r) — distances (x − r) and (x − conj r) modulo jΩp mirror
  // each other. Which of the two it takes must not depend on a last-bit change of Im λ (the
  // summation order of a BLAS kernel): ties go by index, so the first listed reference wins.
  const double omega = 3.0;
  const cd r(-2.0, 0.4);
  const std::vector<cd> reference = {r, std::conj(r)};
  for (double nudge : {-1.0, 0.0, 1.0}) {
    const double im = omega / 2 + nudge * std::numeric_limits<double>::epsilon() * omega;
    const std::vector<cd> values = {{-2.2, im}, {-2.2, -im}};
    const std::vector<int> match = MatchExponentIndices(values, reference, omega);
    EXPECT_EQ(match, (std::vector<int>{0, 1})) << "nudge " << nudge;
  }
}

TEST(ExponentMatch, DistinctDistancesStillDecide) {
  // Two candidates 1e-6 apart in distance: far above round-off, so the closer one wins whatever
  // the index order.
  const std::vector<cd> values = {{0.0, 0.0}};
  const std::vector<cd> reference = {{1.0 + 1e-6, 0.0}, {1.0, 0.0}};
  EXPECT_EQ(MatchExponentIndices(values, reference, 100.0), (std::vector<int>{1}));
}

}  // namespace
}  // namespace ltp
