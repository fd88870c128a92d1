// EstimateSource (ltp/floquet/estimate_source.h): the words a result line uses name what the
// analysis did, for each integrator and estimate method. The reference is the analysis itself:
// its resolved error_estimate_method and integrator, and whether it made a refined run.
#include "ltp/floquet/estimate_source.h"

#include <gtest/gtest.h>

#include <string>

#include "ltp/models/scene.h"

namespace ltp {
namespace {

std::string SourceOf(IntegratorType type, ErrorEstimateMethod method) {
  FloquetOptions o;
  o.integrator.type = type;
  o.integrator.rel_tol = 1e-8;
  o.error_estimate_method = method;
  o.compute_modes = false;
  const FloquetResult r = AnalyzeFloquet(LoadScene("mathieu").Build({{"a", "1"}, {"q", "2"}}), o);
  EXPECT_TRUE(r.ok) << r.failure;
  return std::string(EstimateSource(r.error_estimate_method, r.integrator));
}

bool Has(const std::string& text, const char* words) {
  return text.find(words) != std::string::npos;
}

TEST(EstimateSource, NamesWhatEachIntegratorCarried) {
  EXPECT_TRUE(Has(SourceOf(IntegratorType::kTaylor, ErrorEstimateMethod::kAuto), "order-p"));
  EXPECT_TRUE(Has(SourceOf(IntegratorType::kBulirschStoer, ErrorEstimateMethod::kLocalErrors),
                  "local errors"));
  EXPECT_TRUE(
      Has(SourceOf(IntegratorType::kMagnus6, ErrorEstimateMethod::kAuto), "half the steps"));
  EXPECT_TRUE(
      Has(SourceOf(IntegratorType::kMagnusFilon, ErrorEstimateMethod::kAuto), "half the steps"));
}

TEST(EstimateSource, ARefinedRunSaysSoWhateverTheIntegrator) {
  // Bulirsch–Stoer under `auto` and an integrator that carries nothing take the refined run.
  EXPECT_TRUE(Has(SourceOf(IntegratorType::kBulirschStoer, ErrorEstimateMethod::kAuto), "refined"));
  EXPECT_TRUE(Has(SourceOf(IntegratorType::kRkf78, ErrorEstimateMethod::kLocalErrors), "refined"));
  EXPECT_TRUE(Has(SourceOf(IntegratorType::kTaylor, ErrorEstimateMethod::kRefinedRun), "refined"));
  EXPECT_EQ(EstimateSourceBrief(ErrorEstimateMethod::kRefinedRun, IntegratorType::kTaylor), "");
}

}  // namespace
}  // namespace ltp
