// When SLICOT MB03BD does not converge (INFO > 0; forced here through the test hook, since the
// failure cannot be produced on demand), the analysis falls back instead of failing: periodic
// Schur of the regrouped product, then single-shot eigenvalues with their lost accuracy in the
// estimate (docs/sampled-models.md). References: constant systems, whose Floquet exponents are
// the eigenvalues of A in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "periodic_schur_testing.h"

namespace ltp {
namespace {

// x'' + 2ζω x' + ω² x = 0 plus a decoupled first-order state x' = −d x: exponents
// −ζω ± jω√(1−ζ²) and −d.
PeriodicSystem Constant(double omega, double zeta, double d) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3, 3);
  a(0, 1) = 1;
  a(1, 0) = -omega * omega;
  a(1, 1) = -2 * zeta * omega;
  a(2, 2) = -d;
  return PeriodicSystem::FromFourier(2.0, FourierMatrix::Constant(a));
}

std::vector<std::complex<double>> Exact(double omega, double zeta, double d) {
  const double wd = omega * std::sqrt(1 - zeta * zeta);
  return {{-zeta * omega, wd}, {-zeta * omega, -wd}, {-d, 0}};
}

double Error(const FloquetResult& r, const std::vector<std::complex<double>>& exact) {
  std::vector<std::complex<double>> e;
  for (const FloquetMode& m : r.modes) e.push_back(m.exponent);
  return MaxExponentMismatch(e, exact, 2 * std::acos(-1.0) / r.period);
}

// The analysis over 8 segments with the next `failures` periodic Schur calls failing.
FloquetResult AnalyzeWithSchurFailures(const PeriodicSystem& system, int failures) {
  FloquetOptions o;
  o.segments = 8;
  internal::InjectPeriodicSchurFailures(failures);
  const FloquetResult r = AnalyzeFloquet(system, o);
  internal::InjectPeriodicSchurFailures(0);
  return r;
}

TEST(MultiplierFallback, RegroupedPeriodicSchur) {
  const FloquetResult r = AnalyzeWithSchurFailures(Constant(1.3, 0.05, 0.7), 1);
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kMultipliersRegrouped))
      << r.diagnostics.front().text;
  EXPECT_EQ(r.multiplier_method, MultiplierMethod::kPeriodicSchur);
  EXPECT_LE(Error(r, Exact(1.3, 0.05, 0.7)), *r.error_estimate);
  EXPECT_EQ(r.verdict, StabilityVerdict::kStable);
}

TEST(MultiplierFallback, SingleShotWithItsErrorInTheEstimate) {
  const FloquetResult r = AnalyzeWithSchurFailures(Constant(1.3, 0.05, 0.7), 2);
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kMultipliersSingleShot));
  EXPECT_EQ(r.multiplier_method, MultiplierMethod::kSingleShot);
  EXPECT_LE(Error(r, Exact(1.3, 0.05, 0.7)), *r.error_estimate);
  EXPECT_EQ(r.verdict, StabilityVerdict::kStable);
}

TEST(MultiplierFallback, SingleShotOnAStiffSystemIsUndecidedNotWrong) {
  // d = 200: |ρ| = e^{−400} next to e^{−0.13}, far below eps · max|ρ|: single shot cannot
  // resolve that exponent, so the estimate is +inf and the verdict undecided.
  const FloquetResult r = AnalyzeWithSchurFailures(Constant(1.3, 0.05, 200), 2);
  ASSERT_TRUE(r.error_estimate.has_value());
  EXPECT_LE(Error(r, Exact(1.3, 0.05, 200)), *r.error_estimate);
  EXPECT_NE(r.verdict, StabilityVerdict::kUnstable);
}

// With carried local errors (Taylor series) the moved factors' eigenvalues are found beside the
// multipliers' form; after a fallback to single shot they are found the same way again. One
// thread, so that the injected failures fall on the multipliers' route, not on the moved one.
TEST(MultiplierFallback, LocalErrorsFollowTheSingleShotFallback) {
  FloquetOptions o;
  o.segments = 8;
  o.threads = 1;
  o.compute_modes = false;  // the multipliers from MultiplierLogs, where the failures are injected
  o.integrator.type = IntegratorType::kTaylor;
  internal::InjectPeriodicSchurFailures(2);
  const FloquetResult r = AnalyzeFloquet(Constant(1.3, 0.05, 0.7), o);
  internal::InjectPeriodicSchurFailures(0);
  ASSERT_TRUE(r.ok) << r.failure;
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kMultipliersSingleShot));
  EXPECT_EQ(r.error_estimate_method, ErrorEstimateMethod::kLocalErrors);
  EXPECT_LE(Error(r, Exact(1.3, 0.05, 0.7)), *r.error_estimate);
  EXPECT_EQ(r.verdict, StabilityVerdict::kStable);
}

}  // namespace
}  // namespace ltp
