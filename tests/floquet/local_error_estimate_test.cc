// The error estimate from carried local errors (ErrorEstimateMethod::kLocalErrors:
// Bulirsch–Stoer, Taylor series, the Magnus methods; docs/local-error-estimate.md) against
// independent references.
#include <gtest/gtest.h>

#include <complex>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "ltp/integrate/integrator.h"
#include "ltp/models/scene.h"

namespace ltp {
namespace {

// Reference: Runge–Kutta–Fehlberg 7(8) at 1e-13, no estimate — another integrator family,
// whose own error (≲ 1e-12 on these scenes) is below every estimate asserted here.
FloquetResult Reference(const PeriodicSystem& system) {
  FloquetOptions o;
  o.integrator.type = IntegratorType::kRkf78;
  o.integrator.rel_tol = 1e-13;
  o.integrator.abs_tol = 1e-16;
  o.estimate_error = false;
  o.compute_modes = false;
  return AnalyzeFloquet(system, o);
}

// The analysis with options `o` makes one run (no refined run), estimates from its carried local
// errors, and the estimate bounds the error of its exponents against `reference`.
void ExpectOneRunBoundsTheError(const PeriodicSystem& system, const FloquetOptions& o,
                                const FloquetResult& reference, const std::string& where) {
  const FloquetResult r = AnalyzeFloquet(system, o);
  ASSERT_TRUE(r.ok && r.error_estimate) << where;
  EXPECT_EQ(r.error_estimate_method, ErrorEstimateMethod::kLocalErrors) << where;
  // No second run: neither the segment choice nor a fallback note speaks of a refined run.
  for (const Diagnostic& d : r.diagnostics)
    EXPECT_EQ(d.text.find("refined run"), std::string::npos) << where << ": " << d.text;
  const double error =
      MaxExponentMismatch(Exponents(r.modes), Exponents(reference.modes), system.omega());
  EXPECT_LT(error, *r.error_estimate) << where;
}

// Oscillating, growing and decaying, piecewise-constant (meissner: restarts at every jump)
// and two-state-pair scenes at a loose and a tight tolerance, with and without modes: the
// estimate is at least the error of the numbers reported, and is made by one run.
TEST(LocalErrorEstimate, BoundsTheErrorOfTheReportedExponents) {
  const std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>
      cases = {{"mathieu", {}},
               {"mathieu", {{"a", "1"}, {"q", "5"}}},
               {"mathieu", {{"a", "-20"}, {"q", "30"}}},
               {"rotor", {}},
               {"meissner", {}},
               {"jeffcott", {}},
               {"flap", {}}};
  for (const auto& [name, set] : cases) {
    const PeriodicSystem system = LoadScene(name).Build(set);
    const FloquetResult reference = Reference(system);
    ASSERT_TRUE(reference.ok) << name;
    for (double tol : {1e-6, 1e-10})
      for (bool modes : {false, true}) {
        FloquetOptions o;
        o.integrator.type = IntegratorType::kBulirschStoer;
        o.integrator.rel_tol = tol;
        o.compute_modes = modes;
        o.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
        std::ostringstream where;
        where << name << (set.empty() ? "" : " " + set[0].second) << " tol " << tol
              << (modes ? " modes" : "");
        ExpectOneRunBoundsTheError(system, o, reference, where.str());
      }
  }
}

// The carried local errors are a first-order effect of size ~ the tolerance: zero-size unless
// asked for; Runge–Kutta carries none and falls back to the refined run, and says so.
TEST(LocalErrorEstimate, CarriedOnlyWhenAskedAndNotByRungeKutta) {
  const PeriodicSystem system = LoadScene("mathieu").Build({{"a", "1"}, {"q", "5"}});
  IntegratorOptions bs;
  bs.type = IntegratorType::kBulirschStoer;
  bs.rel_tol = 1e-8;
  EXPECT_EQ(StateTransition(system, 0, system.period(), bs).local_error_effect.size(), 0);
  bs.carry_local_errors = true;
  const TransitionResult carried = StateTransition(system, 0, system.period(), bs);
  ASSERT_EQ(carried.local_error_effect.rows(), 2);
  const double relative = carried.local_error_effect.norm() / carried.phi.norm();
  EXPECT_GT(relative, 0);
  EXPECT_LT(relative, 1e-4);
  IntegratorOptions rk = bs;
  rk.type = IntegratorType::kRkf78;
  EXPECT_EQ(StateTransition(system, 0, system.period(), rk).local_error_effect.size(), 0);

  FloquetOptions o;
  o.integrator.type = IntegratorType::kRkf78;
  o.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
  const FloquetResult r = AnalyzeFloquet(system, o);
  EXPECT_EQ(r.error_estimate_method, ErrorEstimateMethod::kRefinedRun);
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kErrorEstimateFallback));
}

// The Magnus methods choosing their steps by doubling keep the loop's last coarse pass beside
// the reported one: its offset is the carried local error, at no extra work, and `auto` takes
// it for them. On the smooth scenes at a loose and a tight tolerance the estimate bounds the
// error of the reported numbers against the RKF78 reference; fixed steps have no coarse pass
// and fall back to the refined run with a note.
TEST(LocalErrorEstimate, MagnusMethodsKeepTheirCoarsePass) {
  const std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>
      cases = {{"mathieu", {}},
               {"mathieu", {{"a", "1"}, {"q", "5"}}},
               {"rotor", {}},
               {"jeffcott", {{"c", "0.05"}}},
               {"flap", {}}};
  for (const auto& [name, set] : cases) {
    const PeriodicSystem system = LoadScene(name).Build(set);
    const FloquetResult reference = Reference(system);
    ASSERT_TRUE(reference.ok) << name;
    for (IntegratorType type :
         {IntegratorType::kMagnus4, IntegratorType::kMagnus6, IntegratorType::kMagnusFilon}) {
      // Magnus–Filon needs a Fourier series whose mean has an eigenbasis (Mathieu's does).
      if (type == IntegratorType::kMagnusFilon && name != "mathieu") continue;
      for (double tol : {1e-6, 1e-10}) {
        FloquetOptions o;
        o.integrator.type = type;
        o.integrator.rel_tol = tol;
        std::ostringstream where;
        where << name << (set.empty() ? "" : " " + set[0].second) << " " << ToString(type)
              << " tol " << tol;
        ExpectOneRunBoundsTheError(system, o, reference, where.str());
      }
    }
  }
  FloquetOptions fixed;
  fixed.integrator.type = IntegratorType::kMagnus6;
  fixed.integrator.steps_per_period = 64;
  fixed.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
  const FloquetResult r = AnalyzeFloquet(LoadScene("mathieu").Build({}), fixed);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.error_estimate_method, ErrorEstimateMethod::kRefinedRun);
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kErrorEstimateFallback));
}

// Taylor series keep the product of their order-p sums beside the reported order-(p + 4) one on
// the same steps: the estimate is the order-p product's distance, so it covers the error of the
// reported numbers (against the RKF78 reference) by a wide margin, as a refined run's does.
// Mathieu in Fourier form, a = 1.3, q = 0.2 (with light damping), at 1e-6 so that the error of
// the reported numbers stands clear of the reference's.
TEST(LocalErrorEstimate, TaylorSeriesCarryTheirLowerOrderProduct) {
  FourierMatrix a(2, 2, 1);
  a[0] << 0, 1, -1.3, -0.05;
  a[1] << 0, 0, -0.2, 0;
  a[-1] = a[1];
  const PeriodicSystem system = PeriodicSystem::FromFourier(2 * 3.141592653589793, a);
  const FloquetResult ref = Reference(system);
  for (IntegratorType type : {IntegratorType::kTaylor, IntegratorType::kAuto}) {
    FloquetOptions o;
    o.integrator.type = type;
    o.integrator.rel_tol = 1e-6;
    o.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
    const FloquetResult r = AnalyzeFloquet(system, o);
    ASSERT_TRUE(r.ok && r.error_estimate);
    ASSERT_EQ(r.integrator, IntegratorType::kTaylor);  // auto's choice on this system
    EXPECT_EQ(r.error_estimate_method, ErrorEstimateMethod::kLocalErrors);
    EXPECT_FALSE(HasCode(r.diagnostics, DiagnosticCode::kErrorEstimateFallback));
    const double error =
        MaxExponentMismatch(Exponents(r.modes), Exponents(ref.modes), system.omega());
    EXPECT_GE(*r.error_estimate, error);
    EXPECT_LT(*r.error_estimate, 1e-3);  // of the order of the tolerance, not a blanket bound
    std::cerr << "taylor local errors: error " << error << " estimate " << *r.error_estimate
              << "\n";
  }
}

// Under `auto` the estimate follows the integrator it chose: held samples get the exact
// exponential, which carries no local errors, so the refined run is used without a note (the
// result says which estimate it is).
TEST(LocalErrorEstimate, AutoChoiceWithoutLocalErrorsTakesTheRefinedRunQuietly) {
  Eigen::MatrixXd a0(2, 2), a1(2, 2);
  a0 << 0, 1, -1.5, -0.1;
  a1 << 0, 1, -1.1, -0.1;
  const PeriodicSystem system =
      PeriodicSystem::FromSamples(2.0, {0.0, 1.0}, {LtiSystem{a0, {}, {}, {}}, {a1, {}, {}, {}}});
  FloquetOptions o;
  o.integrator.type = IntegratorType::kAuto;
  o.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
  const FloquetResult r = AnalyzeFloquet(system, o);
  ASSERT_TRUE(r.ok);
  ASSERT_EQ(r.integrator, IntegratorType::kExpm);  // the case: auto's choice carries none
  EXPECT_EQ(r.error_estimate_method, ErrorEstimateMethod::kRefinedRun);
  EXPECT_FALSE(HasCode(r.diagnostics, DiagnosticCode::kErrorEstimateFallback));
}

// FloquetResult::grid_segments, the starting grid for a similar system (the other models of a
// sampled set start there): the first run's K halved only while merged factors stay within the
// condition limit by the bound cond(Φ_b Φ_a) ≤ cond Φ_b · cond Φ_a. The same system started
// from it (no modes, so no samples to put on grid points) needs no refinement, and its
// exponents agree with the first analysis within the two estimates; a scene with slow growth
// merges down further than one whose factors grow fast.
TEST(StartingGrid, TheSameSystemStartedFromItNeedsNoRefinement) {
  const std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>>
      cases = {{"mathieu", {}}, {"mathieu", {{"a", "-20"}, {"q", "30"}}}, {"rotor", {}}};
  std::vector<int> starts;
  for (const auto& [name, set] : cases) {
    const PeriodicSystem system = LoadScene(name).Build(set);
    FloquetOptions o;
    o.integrator.type = IntegratorType::kBulirschStoer;
    o.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
    const FloquetResult first = AnalyzeFloquet(system, o);
    ASSERT_TRUE(first.ok && first.error_estimate) << name;
    ASSERT_GE(first.grid_segments, 1) << name;
    EXPECT_EQ(first.segments % first.grid_segments, 0) << name;
    starts.push_back(first.grid_segments);
    o.compute_modes = false;
    o.initial_segments = first.grid_segments;
    const FloquetResult again = AnalyzeFloquet(system, o);
    ASSERT_TRUE(again.ok && again.error_estimate) << name;
    EXPECT_EQ(again.segments, first.grid_segments) << name << ": refined from its start";
    EXPECT_LT(MaxExponentMismatch(Exponents(again.modes), Exponents(first.modes), system.omega()),
              *again.error_estimate + *first.error_estimate)
        << name;
  }
  EXPECT_LT(starts[0], starts[1]) << "mathieu merges further than mathieu a = -20, q = 30";
}

}  // namespace
}  // namespace ltp
