// The cost before the work (work_estimate.h): the estimate against the evaluations the analysis
// then counts (another route: the integrators' own tally), a refusal that needs no timing to be
// certain, and the announcement hook.
#include "ltp/floquet/work_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "ltp/core/error.h"
#include "ltp/floquet/floquet.h"
#include "ltp/integrate/integrator_choice.h"
#include "support/systems.h"
#include "support/throws.h"

namespace ltp {
namespace {

using test::FastOscillator;

// Analyses FastOscillator(w) with `type` at `tol` and checks that the estimate brackets the
// evaluations it counted, each weighed as `weight` evaluations' worth.
void ExpectEstimateBrackets(double w, IntegratorType type, double tol, double weight) {
  const PeriodicSystem system = FastOscillator(w);
  FloquetOptions o;
  o.integrator.type = type;
  o.integrator.rel_tol = tol;
  const FloquetResult r = AnalyzeFloquet(system, o);
  ASSERT_TRUE(r.ok);
  IntegratorOptions weighed = o.integrator;  // as the analysis weighs itself: which estimate ran
  weighed.carry_local_errors = r.error_estimate_method == ErrorEstimateMethod::kLocalErrors;
  const WorkEstimate e =
      EstimateFloquetWork(MeasureSystemTraits(system), weighed, 1, r.segments, 1e-7);
  const double counted = weight * static_cast<double>(r.rhs_evals);
  const std::string what = "w = " + std::to_string(w) + " " + std::string(ToString(type)) +
                           " tol " + std::to_string(tol);
  EXPECT_GE(counted, e.fewest_evaluations) << what;
  EXPECT_LE(counted, 3 * e.evaluations) << what;
  EXPECT_GE(counted, e.evaluations / 3) << what;
}

TEST(WorkEstimate, BracketsTheEvaluationsTheAnalysisCounts) {
  for (double w : {30.0, 300.0, 3000.0})
    for (IntegratorType type :
         {IntegratorType::kBulirschStoer, IntegratorType::kRkf78, IntegratorType::kCvodeBdf})
      for (double tol : {1e-6, 1e-10}) {
        if (type == IntegratorType::kCvodeBdf && w > 300) continue;  // seconds: a BDF method
        // CVODE's right-hand sides are weighed as 10 evaluations each (its vector work, timed
        // on the tower-rotor scene): the count is what is compared here.
        ExpectEstimateBrackets(w, type, tol, type == IntegratorType::kCvodeBdf ? 10 : 1);
      }
}

// The low-order exponential methods on a varying A(t) take steps that grow as (1/tol)^(1/order):
// the exponential midpoint rule ran 130 s on the tower-rotor scene at 1e-10 against an upper
// bound of under a second. Their tally counts the nodes; each step's exponential adds about 12
// products, which the estimate counts as evaluations.
TEST(WorkEstimate, LowOrderExponentialStepsAreCounted) {
  for (double w : {30.0, 300.0})
    for (IntegratorType type : {IntegratorType::kMagnus4, IntegratorType::kExpm})
      for (double tol : {1e-6, 1e-8})
        ExpectEstimateBrackets(w, type, tol, 1 + 12.0 / (type == IntegratorType::kMagnus4 ? 2 : 1));
}

// Breakpoints restart the adaptive integrators: at 10^3 and 10^4 of them the restarts are most of
// the work, and the estimate counts them (10^5 from a Python callable took 16–22 s unannounced).
TEST(WorkEstimate, RestartsAtBreakpointsAreCounted) {
  for (const int cuts : {1000, 10000}) {
    PeriodicSystem::Functions fn;
    fn.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
      out << 0, 1, -(1 - 0.4 * std::cos(2 * t)), -0.3;
    };
    std::vector<double> breakpoints;
    for (int k = 0; k < cuts; ++k) breakpoints.push_back(std::numbers::pi * k / cuts);
    const PeriodicSystem system =
        PeriodicSystem::FromFunctions(std::numbers::pi, 2, 0, 0, fn, breakpoints);
    FloquetOptions o;
    o.integrator.type = IntegratorType::kBulirschStoer;
    const FloquetResult r = AnalyzeFloquet(system, o);
    ASSERT_TRUE(r.ok);
    const double pieces = static_cast<double>(system.breakpoints().size()) + 1;
    const WorkEstimate e =
        EstimateFloquetWork(MeasureSystemTraits(system), o.integrator, pieces, r.segments, 1e-7);
    const double counted = static_cast<double>(r.rhs_evals);
    EXPECT_GE(counted, e.fewest_evaluations) << cuts;
    EXPECT_LE(counted, 3 * e.evaluations) << cuts;
    EXPECT_GE(counted, e.evaluations / 3) << cuts;
  }
}

// Fixed steps set the count themselves: the estimate brackets the integrators' tally, and a
// step count no machine finishes in time is refused before the first step (--steps 1e8 on a
// 2-state system ran silently for minutes).
TEST(WorkEstimate, FixedStepsAreCountedAndRefusedUpFront) {
  for (IntegratorType type : {IntegratorType::kMagnus4, IntegratorType::kMagnus6}) {
    FloquetOptions o;
    o.integrator.type = type;
    o.integrator.steps_per_period = 4000;
    const PeriodicSystem system = FastOscillator(30);
    const FloquetResult r = AnalyzeFloquet(system, o);
    ASSERT_TRUE(r.ok);
    const WorkEstimate e =
        EstimateFloquetWork(MeasureSystemTraits(system), o.integrator, 1, r.segments, 1e-7);
    const double counted = static_cast<double>(r.rhs_evals);
    EXPECT_GE(counted, e.fewest_evaluations) << ToString(type);
    EXPECT_LE(counted, 3 * e.evaluations) << ToString(type);
    EXPECT_GE(counted, e.evaluations / 3) << ToString(type);
  }
  FloquetOptions o;
  o.integrator.type = IntegratorType::kMagnus4;
  o.integrator.steps_per_period = 100000000;
  o.max_work_seconds = 0.01;  // 2e8 evaluations: beyond it at even 50 ps each
  EXPECT_THROW(AnalyzeFloquet(FastOscillator(30), o), InputError);
  o.integrator.steps_per_period = 200000000;  // beyond what the refined run's doubling keeps
  EXPECT_THROW(AnalyzeFloquet(FastOscillator(30), o), InputError);
}

TEST(WorkEstimate, AnAnalysisBeyondTheLimitIsRefusedWithTheEstimate) {
  // 2e9 radians per period: even a fifth of the typical count at a nanosecond each is a minute.
  FloquetOptions o;
  o.max_work_seconds = 1;
  const std::string m =
      test::ThrownMessage<InputError>([&] { AnalyzeFloquet(FastOscillator(3e8), o); });
  EXPECT_NE(m.find("would take at least"), std::string::npos) << m;
  EXPECT_NE(m.find("max_work_seconds"), std::string::npos) << m;
}

TEST(WorkEstimate, ALongAnalysisIsAnnouncedBeforeItStarts) {
  FloquetOptions o;
  o.announce_work_seconds = 0;  // announce everything
  int calls = 0;
  WorkEstimate seen;
  o.on_long_work = [&](const WorkEstimate& w) {
    ++calls;
    seen = w;
  };
  const FloquetResult r = AnalyzeFloquet(FastOscillator(300), o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(calls, 1);
  EXPECT_GT(seen.evaluations, 0);
  // The announcement counts periodic Schur on the factors too (a 400-state scene spent 15 of
  // 18.5 s there and was not announced).
  EXPECT_NE(seen.basis.find("periodic Schur"), std::string::npos) << seen.basis;
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kWorkEstimate));
  // The default threshold (10 CPU s) keeps a small job quiet.
  const FloquetResult quiet = AnalyzeFloquet(FastOscillator(300), FloquetOptions{});
  EXPECT_FALSE(HasCode(quiet.diagnostics, DiagnosticCode::kWorkEstimate));
}

}  // namespace
}  // namespace ltp
