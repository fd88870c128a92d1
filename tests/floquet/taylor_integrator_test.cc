// The Taylor-series integrator (IntegratorType::kTaylor, integrator_taylor.cc). References:
// closed forms (a commuting system: Φ = exp(∫f · M), by Eigen's expm), Liouville's formula,
// and rkf78 at rel tol 1e-13 on the same A(t) given as a *function* (another integrator and
// another evaluation of A, not the Fourier series the Taylor steps differentiate).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "ltp/core/error.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"
#include "ltp/integrate/integrator.h"
#include "ltp/integrate/integrator_choice.h"
#include "ltp/models/scene.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

double RelErr(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
  return (got - want).norm() / want.norm();
}

IntegratorOptions Taylor(double rel_tol) {
  IntegratorOptions o;
  o.type = IntegratorType::kTaylor;
  o.rel_tol = rel_tol;
  o.abs_tol = 1e-3 * rel_tol;
  return o;
}

IntegratorOptions Reference() {
  IntegratorOptions o;
  o.type = IntegratorType::kRkf78;
  o.rel_tol = 1e-13;
  o.abs_tol = 1e-16;
  return o;
}

// The same system evaluated as a function: what the reference integrates.
PeriodicSystem AsFunction(const PeriodicSystem& fourier) {
  const FourierMatrix a = *fourier.fourier_A();
  const double omega = fourier.omega();
  PeriodicSystem::Functions f;
  f.A = [a, omega](double t, Eigen::Ref<Eigen::MatrixXd> out) { a.Evaluate(t, omega, out); };
  return PeriodicSystem::FromFunctions(fourier.period(), fourier.states(), 0, 0, std::move(f));
}

// f(t) M with f = α + β cos Ωt + γ sin 2Ωt and a constant 3 × 3 M (general form, not
// second-order): every A(t) commutes with every other, so Φ(t1, t0) = exp(F M) with
// F = ∫ f = αΔt + (β/Ω)(sin Ωt1 − sin Ωt0) − (γ/2Ω)(cos 2Ωt1 − cos 2Ωt0).
struct Commuting {
  double alpha = -0.1, beta = 1.3, gamma = 0.6, period = 1.7;
  Eigen::Matrix3d m =
      (Eigen::Matrix3d() << 0.2, 1.1, -0.4, -1.3, -0.3, 0.5, 0.1, -0.6, 0.05).finished();
  double omega() const { return 2 * kPi / period; }
  PeriodicSystem System() const {
    FourierMatrix a(3, 3, 2);
    a.SetHarmonic(0, (alpha * m).cast<cd>());
    a.SetHarmonic(1, (0.5 * beta * m).cast<cd>());       // 2 Re(M₁) cos
    a.SetHarmonic(2, (cd(0, -0.5 * gamma) * m).eval());  // −2 Im(M₂) sin
    return PeriodicSystem::FromFourier(period, a);
  }
  Eigen::Matrix3d Exact(double t0, double t1) const {
    const double w = omega();
    const double f = alpha * (t1 - t0) + beta / w * (std::sin(w * t1) - std::sin(w * t0)) -
                     gamma / (2 * w) * (std::cos(2 * w * t1) - std::cos(2 * w * t0));
    return (f * m).exp();
  }
};

// A random damped 3-degree-of-freedom second-order system [0 I; K(t) D(t)] with harmonics 1
// and 2 (6 states: the dynamic-size, second-order path).
PeriodicSystem RandomSecondOrder() {
  std::mt19937 rng(20261126);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  FourierMatrix a(6, 6, 2);
  for (int w = 0; w <= 2; ++w) {
    Eigen::MatrixXcd m = Eigen::MatrixXcd::Zero(6, 6);
    for (int i = 3; i < 6; ++i)
      for (int j = 0; j < 6; ++j) m(i, j) = w == 0 ? cd(u(rng), 0) : cd(u(rng), u(rng));
    if (w == 0) {
      m.topRightCorner(3, 3) = Eigen::MatrixXcd::Identity(3, 3);
      m.bottomLeftCorner(3, 3) -= 2.0 * Eigen::MatrixXcd::Identity(3, 3);  // stiffness
    }
    a.SetHarmonic(w, m);
  }
  return PeriodicSystem::FromFourier(2.1, a);
}

TEST(TaylorIntegrator, CommutingSystemMatchesItsClosedFormAtEachTolerance) {
  const Commuting c;
  const PeriodicSystem sys = c.System();
  for (double tol : {1e-6, 1e-9, 1e-12}) {
    for (const auto& [t0, t1] : std::vector<std::pair<double, double>>{
             {0, c.period}, {0.3, 2.9}, {1.0, 1.05}, {0, 4 * c.period}}) {
      const TransitionResult r = StateTransition(sys, t0, t1, Taylor(tol));
      ASSERT_TRUE(r.ok) << r.message;
      // The step rule holds each step's truncation to the tolerance; over a few steps the
      // global error stays within a small multiple of it.
      EXPECT_LT(RelErr(r.phi, c.Exact(t0, t1)), 10 * tol)
          << "tol " << tol << " [" << t0 << ", " << t1 << "]";
      EXPECT_GT(r.steps, 0);
      EXPECT_GT(r.rhs_evals, r.steps);
    }
  }
}

TEST(TaylorIntegrator, MathieuMatchesAnotherIntegratorFromStableToStronglyUnstable) {
  // Second-order form, fixed size 2 (the stability maps' case), across a tongue: a = 1, q = 0.2
  // is stable; a = 1, q = 6 grows by ~e^{4} per period; a = −2, q = 8 by ~e^{9}.
  for (const auto& [a, q] : std::vector<std::pair<double, double>>{{1, 0.2}, {1, 6}, {-2, 8}}) {
    const PeriodicSystem sys = test::Mathieu(a, q);
    const Eigen::MatrixXd want = StateTransition(AsFunction(sys), 0, kPi, Reference()).phi;
    for (double tol : {1e-6, 1e-10}) {
      const TransitionResult r = StateTransition(sys, 0, kPi, Taylor(tol));
      ASSERT_TRUE(r.ok) << r.message;
      EXPECT_LT(RelErr(r.phi, want), 10 * tol) << "a " << a << " q " << q << " tol " << tol;
    }
  }
}

TEST(TaylorIntegrator, LargerSecondOrderSystemMatchesAnotherIntegrator) {
  const PeriodicSystem sys = RandomSecondOrder();
  const double T = sys.period();
  const Eigen::MatrixXd want = StateTransition(AsFunction(sys), 0, T, Reference()).phi;
  const TransitionResult r = StateTransition(sys, 0, T, Taylor(1e-10));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_LT(RelErr(r.phi, want), 1e-9);
  // Liouville: det Φ(T, 0) = exp(T tr A₀) (the harmonics integrate to zero).
  const double det = std::exp(T * sys.fourier_A()->coefficient(0).real().trace());
  EXPECT_NEAR(r.phi.determinant() / det, 1.0, 1e-9);
}

// A random system of `q` degrees of freedom with harmonics 1 … H, in one of the three shapes
// the stepper tells apart (ShapeOfSeries): general first order (2q states), second order with
// the harmonics in stiffness and damping, second order with constant damping. Frequencies up
// to 12 rad/s. The states are then scaled by S = diag(2^-6 … 2^5) (A → S⁻¹AS), as the analysis
// balances them, so the second-order form's upper-right block is diagonal, not I.
// Φ over one period by Taylor series at 1e-7 and 1e-10 within 10 × tol of the reference run.
void ExpectTaylorMatchesTheReferenceOverAPeriod(const PeriodicSystem& sys) {
  const double T = sys.period();
  const Eigen::MatrixXd want = StateTransition(AsFunction(sys), 0, T, Reference()).phi;
  for (double tol : {1e-7, 1e-10}) {
    const TransitionResult r = StateTransition(sys, 0, T, Taylor(tol));
    ASSERT_TRUE(r.ok) << r.message;
    EXPECT_LT(RelErr(r.phi, want), 10 * tol) << "tol " << tol;
  }
}

enum class Shape { kFirstOrder, kSecondOrder, kConstantDamping };
PeriodicSystem RandomLargeSystem(int q, int harmonics, Shape shape) {
  std::mt19937 rng(20261129);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const int n = 2 * q;
  Eigen::VectorXd scale(n);
  for (int i = 0; i < n; ++i) scale(i) = std::ldexp(1.0, i % 12 - 6);
  FourierMatrix a(n, n, harmonics);
  for (int w = 0; w <= harmonics; ++w) {
    Eigen::MatrixXcd m = Eigen::MatrixXcd::Zero(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) m(i, j) = w == 0 ? cd(u(rng), 0) : cd(u(rng), u(rng)) / double(w);
    if (shape != Shape::kFirstOrder) {
      m.topRows(q).setZero();
      if (w == 0) {
        m.topRightCorner(q, q).setIdentity();
        for (int i = 0; i < q; ++i) m(q + i, i) -= std::pow(12.0 * (i + 1) / q, 2);
      }
      if (w > 0 && shape == Shape::kConstantDamping) m.bottomRightCorner(q, q).setZero();
      if (w > 0) m.bottomLeftCorner(q, q) *= 4.0;
    }
    a.SetHarmonic(w, (scale.cwiseInverse().asDiagonal() * m * scale.asDiagonal()).eval());
  }
  return PeriodicSystem::FromFourier(1.9, a);
}

TEST(TaylorIntegrator, LargeSystemsOfEveryShapeMatchAnotherIntegrator) {
  // n = 40 (BLAS products, the weighted sums of the terms as one product) in each shape; the
  // products per order say which shape the stepper recognised: 1 + 2H in first-order form,
  // (1 + 2H)/2 in second-order form, (1 + H)/2 with constant damping.
  struct Case {
    Shape shape;
    int harmonics;
    double products_per_order;
  };
  for (const Case& c : {Case{Shape::kFirstOrder, 2, 5}, Case{Shape::kSecondOrder, 2, 2.5},
                        Case{Shape::kConstantDamping, 3, 2}}) {
    SCOPED_TRACE(testing::Message()
                 << "shape " << static_cast<int>(c.shape) << ", H " << c.harmonics);
    const PeriodicSystem sys = RandomLargeSystem(20, c.harmonics, c.shape);
    EXPECT_EQ(MeasureSystemTraits(sys).series_products_per_order, c.products_per_order);
    ExpectTaylorMatchesTheReferenceOverAPeriod(sys);
  }
}

// The finite-element shaft's pattern at a size rkf78 can check: 20 degrees of freedom at 30 to
// 3000 rad/s, constant light damping, and a stiffness that varies by 10 % at Ω = 2π/0.2 s — a
// harmonic 100 times slower than the fastest mode. There the weighted sums X_w = Σ_j c_j Φ_{k−j}
// keep only their first terms (the weights fall like (Ω)^j/j!, the terms like ρ^{−j}): the
// stepper leaves the rest out when together they are below half an ulp of the largest
// (SummedTerms). A threshold of 1e-8 instead of the ulp fails this test at 1e-10 (error 1e-8),
// where LargeSystemsOfEveryShapeMatchAnotherIntegrator, whose harmonics are as fast as its
// modes, still passes.
PeriodicSystem FastModesSlowHarmonic() {
  std::mt19937 rng(20261130);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const int q = 20, n = 2 * q;
  Eigen::MatrixXd k0 = Eigen::MatrixXd::Zero(q, q), k1(q, q);
  for (int i = 0; i < q; ++i) k0(i, i) = std::pow(30.0 * std::pow(100.0, i / (q - 1.0)), 2);
  for (int i = 0; i < q; ++i)  // a symmetric coupling and a variation of 10 % of the stiffness
    for (int j = 0; j <= i; ++j) {
      const double scale = std::sqrt(k0(i, i) * k0(j, j));
      k1(i, j) = k1(j, i) = 0.1 * scale * (i == j ? 1.0 : u(rng) * 0.2);
      if (i != j) k0(i, j) = k0(j, i) = 0.05 * scale * u(rng);
    }
  FourierMatrix a(n, n, 1);
  Eigen::MatrixXcd mean = Eigen::MatrixXcd::Zero(n, n), first = mean;
  mean.topRightCorner(q, q).setIdentity();
  mean.bottomLeftCorner(q, q) = -k0.cast<cd>();
  for (int i = 0; i < q; ++i) mean(q + i, q + i) = -1.0;
  first.bottomLeftCorner(q, q) = -0.5 * k1.cast<cd>();  // cos Ωt: half at ±1
  a.SetHarmonic(0, mean);
  a.SetHarmonic(1, first);
  return PeriodicSystem::FromFourier(0.2, a);
}

TEST(TaylorIntegrator, FastModesWithASlowHarmonicMatchAnotherIntegrator) {
  const PeriodicSystem sys = FastModesSlowHarmonic();
  EXPECT_EQ(MeasureSystemTraits(sys).series_products_per_order, 1);  // constant damping, H = 1
  ExpectTaylorMatchesTheReferenceOverAPeriod(sys);
}

TEST(TaylorIntegrator, JeffcottRotorMatchesAnotherIntegrator) {
  // 4 states, second-order form with constant damping: the fixed-size path whose harmonics
  // multiply only the upper half of Φ (stiffness K(t) rotating, damping constant).
  const Scene scene = LoadScene("jeffcott");
  const PeriodicSystem sys = scene.build(scene.Resolve({{"c", "0.05"}}));
  const double T = sys.period();
  const Eigen::MatrixXd want = StateTransition(AsFunction(sys), 0, 3 * T, Reference()).phi;
  for (double tol : {1e-7, 1e-11}) {
    const TransitionResult r = StateTransition(sys, 0, 3 * T, Taylor(tol));
    ASSERT_TRUE(r.ok) << r.message;
    EXPECT_LT(RelErr(r.phi, want), 10 * tol) << "tol " << tol;
  }
}

TEST(TaylorIntegrator, ConsecutiveFactorsAreEachTheirIntervalsTransition) {
  const Commuting c;
  const std::vector<double> times = {0, 0.2, 0.21, 1.5, 3.4};
  const std::vector<TransitionResult> f = ConsecutiveTransitions(c.System(), times, Taylor(1e-11));
  ASSERT_EQ(f.size(), times.size() - 1);
  for (size_t i = 0; i < f.size(); ++i) {
    ASSERT_TRUE(f[i].ok) << f[i].message;
    EXPECT_LT(RelErr(f[i].phi, c.Exact(times[i], times[i + 1])), 1e-10) << "factor " << i;
  }
  // The short factor [0.2, 0.21] is one step, ended early: fewer terms than the full order
  // ⌈−ln 1e-11⌉ = 26, at 1 + 2H = 5 products each.
  EXPECT_EQ(f[1].steps, 1);
  EXPECT_LT(f[1].rhs_evals, 26 * 5);
}

TEST(TaylorIntegrator, FloquetAnalysisMatchesBulirschStoer) {
  // Both routes of the whole analysis (segments, periodic Schur, error estimate) on a Mathieu
  // point inside the first tongue: the exponents agree within the two estimates.
  const PeriodicSystem sys = test::Mathieu(1, 0.3);
  FloquetOptions o;
  o.integrator = Taylor(1e-10);
  const FloquetResult t = AnalyzeFloquet(sys, o);
  o.integrator.type = IntegratorType::kBulirschStoer;
  const FloquetResult b = AnalyzeFloquet(sys, o);
  ASSERT_TRUE(t.ok && b.ok);
  EXPECT_EQ(t.integrator, IntegratorType::kTaylor);
  ASSERT_TRUE(t.error_estimate && b.error_estimate);
  EXPECT_NEAR(t.max_real_exponent, b.max_real_exponent, *t.error_estimate + *b.error_estimate);
  EXPECT_LT(*t.error_estimate, 1e-8);
}

TEST(TaylorIntegrator, RefusesASystemWhoseAIsNotAFourierSeries) {
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) { out << 0, 1, -(1 + std::cos(t)), 0; };
  const PeriodicSystem sys = PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, std::move(f));
  try {
    StateTransition(sys, 0, 1, Taylor(1e-8));
    FAIL() << "taylor accepted A(t) given as a function";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs A(t) as a Fourier series"), std::string::npos)
        << e.what();
  }
}

TEST(TaylorIntegrator, StepBudgetAndOverflowFailWithoutThrowing) {
  IntegratorOptions o = Taylor(1e-10);
  o.max_steps = 2;
  const TransitionResult few = StateTransition(test::Mathieu(1, 0.2), 0, 100 * kPi, o);
  EXPECT_FALSE(few.ok);
  EXPECT_NE(few.message.find("max_steps"), std::string::npos) << few.message;
  // exp(1000 · 10) overflows a double.
  const PeriodicSystem growing =
      PeriodicSystem::FromFourier(10, FourierMatrix::Constant(1000 * Eigen::Matrix2d::Identity()));
  TransitionResult r;
  ASSERT_NO_THROW(r = StateTransition(growing, 0, 10, Taylor(1e-10)));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.message, "state transition is not finite (overflow?)");
}

}  // namespace
}  // namespace ltp
