// Progress of a Floquet analysis (FloquetOptions::on_progress): every phase the analysis runs
// reports fractions that rise to 1, and the time the integrators say they advanced adds up to
// the period each phase integrates (reference: the period itself, and the phases the result
// says were run).
#include <gtest/gtest.h>

#include <map>
#include <mutex>
#include <numbers>
#include <string>
#include <vector>

#include "ltp/floquet/floquet.h"

namespace ltp {
namespace {

// Damped Mathieu, x'' + 0.1 x' + (1.5 + 2·2 cos 2t) x = 0 over π.
PeriodicSystem Mathieu() {
  FourierMatrix a(2, 2, 1);
  a[0] << 0, 1, -1.5, -0.1;
  a[1] << 0, 0, -2, 0;
  a[-1] = a[1];
  return PeriodicSystem::FromFourier(std::numbers::pi, a);
}

std::map<std::string, std::vector<double>> Phases(IntegratorType type, int threads) {
  std::map<std::string, std::vector<double>> seen;
  std::mutex m;
  FloquetOptions o;
  o.integrator.type = type;
  o.error_estimate_method = ErrorEstimateMethod::kRefinedRun;  // the phases of a refined run
  o.threads = threads;
  o.on_progress = [&](std::string_view phase, double fraction) {
    std::lock_guard<std::mutex> lock(m);  // the library promises one call at a time; checked
    seen[std::string(phase)].push_back(fraction);
  };
  const FloquetResult r = AnalyzeFloquet(Mathieu(), o);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.error_estimate_method, ErrorEstimateMethod::kRefinedRun);
  return seen;
}

TEST(AnalysisProgress, EveryPhaseRisesToOne) {
  for (IntegratorType type : {IntegratorType::kBulirschStoer, IntegratorType::kRkf78,
                              IntegratorType::kMagnus6, IntegratorType::kTaylor})
    for (int threads : {1, 2}) {
      const auto seen = Phases(type, threads);
      const std::string what = std::string(ToString(type)) + " threads " + std::to_string(threads);
      // Taylor and Magnus propagate the mode samples with the step as a whole: no steps seen.
      for (const char* phase : {"run", "refined run"}) {
        ASSERT_TRUE(seen.count(phase)) << what << ": " << phase;
        const std::vector<double>& f = seen.at(phase);
        EXPECT_DOUBLE_EQ(f.back(), 1.0) << what << ": " << phase;
        for (size_t k = 0; k < f.size(); ++k) {
          EXPECT_GE(f[k], 0) << what;
          EXPECT_LE(f[k], 1) << what;
          if (k > 0) {
            EXPECT_GT(f[k], f[k - 1]) << what << ": " << phase;
          }
        }
      }
      for (const auto& [phase, f] : seen)
        EXPECT_TRUE(phase == "run" || phase == "refined run" || phase == "mode shapes") << phase;
    }
}

TEST(AnalysisProgress, NothingIsCalledWithoutASink) {
  // The default: no callback, and the integrators see an empty on_advance.
  FloquetOptions o;
  EXPECT_FALSE(o.on_progress);
  EXPECT_FALSE(o.integrator.on_advance);
  EXPECT_TRUE(AnalyzeFloquet(Mathieu(), o).ok);
}

}  // namespace
}  // namespace ltp
