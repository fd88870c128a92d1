// The automatic PFRF route (PfrfRoute::kAuto, the default): which route it takes on smooth,
// discontinuous and near-defective systems, and that the values it returns agree with an
// independent route (the step-sine time simulation, or shooting at a tight tolerance) within
// the error estimate it reports.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

#include "ltp/core/scene.h"
#include "ltp/floquet/integrator.h"
#include "ltp/htf/pfrf.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
constexpr double kTwoPi = 2 * test::kPi;

// Largest |H_auto − H_ref| − estimate over the sweep and orders (≤ 0: every value covered),
// with the reference's own accuracy `ref_tol` · max|H| granted.
double WorstUncovered(const PfrfResult& r, const std::vector<PartialFrfs>& ref, double ref_tol) {
  double hmax = 0;
  for (const auto& h : ref)
    for (const auto& m : h) hmax = std::max(hmax, m.cwiseAbs().maxCoeff());
  double worst = -INFINITY;
  for (size_t f = 0; f < ref.size(); ++f)
    for (int z = r.min_order; z <= r.max_order; ++z) {
      const int zi = z - r.min_order;
      const double err = std::abs(r.values[f][zi] - ref[f][zi](0, 0));
      worst = std::max(worst, err - r.error_estimate[f][zi] - ref_tol * hmax);
    }
  return worst;
}

TEST(PfrfRouteChoice, SmoothReliableSystemGoesModalCheckedByHtf) {
  const PeriodicSystem sys = test::MathieuIo(1.5, 0.5, 0.05);
  PfrfOptions o;
  o.frequencies_hz = {0.05, 0.13, 0.21, 0.29};
  o.min_order = -2;
  o.max_order = 2;
  const PfrfResult r = ComputePartialFrf(sys, o);
  ASSERT_TRUE(r.ok);
  ASSERT_EQ(r.routes.size(), 2u);
  EXPECT_EQ(r.routes[0].route, PfrfRoute::kModal);
  EXPECT_EQ(r.routes[1].route, PfrfRoute::kHtf);
  EXPECT_NE(r.route_choice.find("modal checked by htf"), std::string::npos) << r.route_choice;
}

TEST(PfrfRouteChoice, JumpsGetAShootingCheckAndTheValuesMeetTheTimeRoute) {
  // Meissner: the HTF converges only algebraically across the jumps, so the check is shooting.
  // Independent reference: the step-sine time simulation (settled to 1e-11, RKF78 1e-12).
  const PeriodicSystem sys = LoadScene("meissner").Build({{"a", "2"}, {"b", "0.5"}, {"c", "0.05"}});
  PfrfOptions o;
  o.frequencies_hz = {0.03, 0.19, 0.35};
  o.min_order = -2;
  o.max_order = 2;
  o.floquet.integrator.type = IntegratorType::kAuto;
  const PfrfResult r = ComputePartialFrf(sys, o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.routes[0].route, PfrfRoute::kModal);
  ASSERT_EQ(r.routes.size(), 2u);
  EXPECT_EQ(r.routes[1].route, PfrfRoute::kShooting);
  ShootingOptions so;
  so.settle_tol = 1e-11;
  ForcedResponseSolver time(sys, so);
  const double settle = ForcedResponseSolver::SettlingTime(r.floquet, so.settle_tol);
  std::vector<PartialFrfs> ref;
  for (double f : o.frequencies_hz) {
    bool ok = false;
    ref.push_back(time.TimeSimulation(kTwoPi * f, -2, 2, settle, &ok));
    ASSERT_TRUE(ok);
  }
  EXPECT_LE(WorstUncovered(r, ref, 1e-9), 0);
}

TEST(PfrfRouteChoice, NearDefectiveMonodromyFallsBackToHtfAndStaysAccurate) {
  // Undamped Mathieu 1e-9 inside the stable side of the first tongue's boundary a_1(q), where
  // Φ is nearly a Jordan block: the modal model reports itself unreliable (cond Ξ ≈ 3e4), so
  // the automatic route must take the HTF (smooth A) and still match shooting at 1e-13.
  const double q = 0.3;
  auto trace = [&](double a) { return StateTransition(test::MathieuIo(a, q, 0), 0, test::kPi).phi.trace(); };
  double lo = 1.1, hi = 1.6;  // tr Φ(1.1) < −2 (unstable tongue), tr Φ(1.6) > −2
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (trace(mid) < -2 ? lo : hi) = mid;
  }
  const PeriodicSystem sys = test::MathieuIo(hi + 1e-9, q, 0);
  PfrfOptions o;
  o.frequencies_hz = {0.3 / kTwoPi, 0.9 / kTwoPi};  // off the lines ±1 + 2v rad/s
  o.min_order = -3;
  o.max_order = 3;
  const PfrfResult r = ComputePartialFrf(sys, o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.routes[0].route, PfrfRoute::kHtf) << r.route_choice;
  EXPECT_NE(r.route_choice.find("unreliable"), std::string::npos) << r.route_choice;
  ShootingOptions so;
  so.rel_tol = 1e-13;
  so.abs_tol = 1e-16;
  ForcedResponseSolver shooting(sys, so);
  std::vector<PartialFrfs> ref;
  for (double f : o.frequencies_hz) {
    bool ok = false;
    ref.push_back(shooting.Shooting(kTwoPi * f, -3, 3, &ok));
    ASSERT_TRUE(ok);
  }
  EXPECT_LE(WorstUncovered(r, ref, 1e-12), 0);
}

}  // namespace
}  // namespace ltp
