// Hill's method where its estimate used to fall short: eigenvalues of the truncation edge that
// N vs N+Δ cannot see (an exactly reducible system, closed-form exponents), slowly decaying
// coefficients (the Poisson kernel, against the monodromy route of the closed-form A(t)), and
// the convergence study's per-row estimate. docs/hill-method.md, "Truncation estimate".
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "ltp/hill/hill.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

// The Poisson-kernel oscillator with A(t) in closed form, for the monodromy reference (rkf78 at
// 1e-13: an independent route that never sees the Fourier series).
PeriodicSystem PoissonKernelFunction(double a, double b, double r, double c) {
  PeriodicSystem::Functions f;
  f.A = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const double kernel = (1 - r * r) / (1 - 2 * r * std::cos(t) + r * r);
    out << 0, 1, -(a + b * kernel), -c;
  };
  return PeriodicSystem::FromFunctions(2 * test::kPi, 2, 0, 0, f);
}

// Its exponents and their error estimate.
std::pair<std::vector<cd>, double> MonodromyReference(const PeriodicSystem& s) {
  FloquetOptions o;
  o.integrator.type = IntegratorType::kRkf78;
  o.integrator.rel_tol = 1e-13;
  o.integrator.abs_tol = 1e-15;
  const FloquetResult r = AnalyzeFloquet(s, o);
  EXPECT_TRUE(r.ok);
  EXPECT_LT(r.error_estimate.value(), 1e-11);
  return {Exponents(r.modes), r.error_estimate.value_or(0.0)};
}

TEST(HillEdge, TruncationEdgeEigenvaluesNeverPassAsConverged) {
  // x = R(θ) z, z' = diag(l1, l2) z: exponents exactly l1, l2. The banded solver, searching
  // around A_0's eigenvalues (−0.25 ± j), found only an edge pair −0.25 ± j(N − 0.06) whose Im λ
  // follows N, so N vs N+Δ saw a change of 6e-14, and the pair also satisfied Liouville
  // (Σ Re λ = l1 + l2): "STABLE, estimate 3.2e-13" for max Re λ = 120. Whatever N, the result
  // is now right within its estimate, or has no bound and no stable verdict.
  for (const auto& [l1, l2] : std::vector<std::pair<double, double>>{
           {120, -120.5}, {110, -110}, {-110, 110}, {-120, -0.5}}) {
    const PeriodicSystem s = test::ReducibleRotation(l1, l2, 0.5);
    const std::vector<cd> exact = {cd(l1, 0), cd(l2, 0)};
    for (int N : {8, 12, 16, 32}) {
      for (bool fallback : {true, false}) {
        HillOptions o;
        o.harmonics = N;
        o.solver = HillSolver::kStructured;
        o.structured_fallback = fallback;
        const HillResult h = AnalyzeHill(s, o);
        const double err = MaxExponentMismatch(Exponents(h.modes), exact, s.omega());
        SCOPED_TRACE("l1 = " + std::to_string(l1) + ", N = " + std::to_string(N) +
                     (fallback ? ", dense fallback" : ", structured only"));
        ASSERT_TRUE(h.error_estimate.has_value());
        EXPECT_GE(*h.error_estimate, err) << h.BriefReport();
        if (err > 1e-6) {  // the wrong pair: no bound, and never a verdict
          EXPECT_FALSE(h.ok);
          EXPECT_NE(h.verdict, StabilityVerdict::kStable);
          EXPECT_NE(h.verdict, StabilityVerdict::kUnstable);
        }
        if (fallback) {  // the dense solver sees the whole spectrum and finds l1, l2
          EXPECT_LT(err, 1e-9) << h.BriefReport();
          EXPECT_EQ(h.verdict,
                    std::max(l1, l2) > 0 ? StabilityVerdict::kUnstable : StabilityVerdict::kStable);
        }
      }
    }
  }
}

TEST(HillEdge, StudyRowsCarryTheAnalysisEstimate) {
  // `ltp hill` printed the bare N vs N+Δ change per row: 120 rows wrong with 1e-14 on the
  // reducible system, and on Mathieu q = 2 at N = 1 a change of 0.112 for an error of 1.36.
  // Every row's estimate is now the analysis' own, and covers the row's error (against the
  // closed form and against the monodromy route).
  const PeriodicSystem reducible = test::ReducibleRotation(120, -120.5, 0.5);
  const PeriodicSystem mathieu = test::Mathieu(1, 2, 0.02);
  FloquetResult exact;
  for (double l : {120.0, -120.5}) {
    FloquetMode m;
    m.exponent = l;
    exact.modes.push_back(m);
  }
  FloquetResult mathieu_ref;
  const auto [mathieu_exponents, mathieu_error] = MonodromyReference(mathieu);
  for (const cd& l : mathieu_exponents) {
    FloquetMode m;
    m.exponent = l;
    mathieu_ref.modes.push_back(m);
  }
  for (const auto& [system, reference, name] :
       {std::tuple{reducible, exact, "reducible"}, std::tuple{mathieu, mathieu_ref, "mathieu"}}) {
    const HillStudy study = HillConvergenceStudy(system, 32, reference);
    ASSERT_FALSE(study.rows.empty());
    for (const HillStudyRow& row : study.rows) {
      ASSERT_TRUE(row.max_error.has_value());
      ASSERT_TRUE(row.error_estimate.has_value());
      // Plus the reference's own error estimate (0 for the closed form).
      const double slack = std::string(name) == "mathieu" ? mathieu_error : 0.0;
      EXPECT_GE(*row.error_estimate + slack, *row.max_error) << name << " at N = " << row.harmonics;
    }
    // A fitted law, when there is one, says the error falls.
    if (study.rate_kind) {
      EXPECT_GT(study.rate, 0) << name;
    }
  }
}

TEST(HillTail, SlowGeometricDecayIsCoveredByTheTailFactor) {
  // Coefficients ∝ r^|w| with r = 0.9 (b = −ln r = 0.105): the change from N to N + Δ was
  // 0.96–0.999 of the error at N = 32–64. Against the monodromy route of the closed-form
  // kernel, the estimate now covers the error at every N, and the automatic truncation goes on
  // to the tolerance (it stopped at N = 8 extrapolating a power law to "N ≈ 6029").
  const double a = 0.8, b = 0.2, r = 0.9, c = 0.02;
  const PeriodicSystem fourier = test::PoissonKernel(a, b, r, c);
  const auto [ref, ref_error] = MonodromyReference(PoissonKernelFunction(a, b, r, c));
  for (int N : {16, 24, 32, 48, 64}) {
    HillOptions o;
    o.harmonics = N;
    const HillResult h = AnalyzeHill(fourier, o);
    ASSERT_TRUE(h.ok) << h.BriefReport();
    const double err = MaxExponentMismatch(Exponents(h.modes), ref, fourier.omega());
    EXPECT_GE(h.error_estimate.value() + ref_error, err) << "N = " << N << ": " << h.BriefReport();
  }
  HillOptions o;
  o.harmonics = 4;
  const HillResult h = AnalyzeHillAuto(fourier, o, 1e-10, 256);
  ASSERT_TRUE(h.tolerance_met.has_value());
  EXPECT_TRUE(*h.tolerance_met) << h.diagnostics.back().text;
  EXPECT_LE(h.harmonics, 128);
  EXPECT_LT(MaxExponentMismatch(Exponents(h.modes), ref, fourier.omega()), 1e-9);
}

}  // namespace
}  // namespace ltp
