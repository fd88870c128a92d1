// Hill's route carries a sampled (.lin) model's sampling error in its estimate too
// (docs/sampled-models.md). Reference: rotating-frame files generated from an isotropic model
// with a 1P gravity term (tests/support/isotropic_rotor_lin.h), analysed by the monodromy route
// in blade coordinates, where the trigonometric model is exact.
#include "ltp/hill/hill_model_error.h"

#include <gtest/gtest.h>

#include <complex>
#include <string>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/hill/hill.h"
#include "ltp/models/scene_input.h"
#include "support/isotropic_rotor_lin.h"

namespace ltp {
namespace {

TEST(ModelError, HillRouteCarriesTheSamplingErrorToo) {
  // The gravity rotor at 3 azimuths: the default (MBC, trigonometric) route folds the 1P term
  // onto a constant, an error the samples cannot show in those coordinates. Hill's own estimate
  // (truncation, 1e-13) knows nothing of it; with the model term it covers the true error.
  // Reference: the trigonometric route in blade coordinates by the monodromy route, exact here
  // (harmonics 0 and ±1 only; the test above checks it against 9 azimuths).
  const auto model = test::MakeIsotropicRotorLin(4, 4, test::EvenAzimuths(3), 1.0, 3, 0.4);
  const std::string dir = test::WriteLinDirectory(model.files, ::testing::TempDir() + "grav-hill");
  const FloquetResult ref = AnalyzeFloquet(LoadSceneInput({dir}, {"mbc=0"}).system);
  std::vector<std::complex<double>> reference;
  for (const FloquetMode& m : ref.modes) reference.push_back(m.exponent);
  const LoadedScene l = LoadSceneInput({dir});
  HillOptions o;
  o.harmonics = 8;
  HillResult h = AnalyzeHill(l.system, o);
  ASSERT_TRUE(h.ok && h.error_estimate);
  std::vector<std::complex<double>> exponents;
  for (const FloquetMode& m : h.modes) exponents.push_back(m.exponent);
  const double error = MaxExponentMismatch(exponents, reference, 1.0);
  EXPECT_LT(*h.error_estimate, error);  // the case: Hill alone under-estimates
  const double elapsed = h.elapsed_s;
  IncludeModelError(l.model_alternatives, FloquetOptions{}, h);
  ASSERT_TRUE(h.model_error && h.error_estimate);
  EXPECT_GE(*h.error_estimate, error);
  EXPECT_GT(h.elapsed_s, elapsed);  // the other models' analyses are part of the call
  if (h.verdict != StabilityVerdict::kMarginal) {
    EXPECT_EQ(h.verdict, ref.verdict);
  }
}

}  // namespace
}  // namespace ltp
