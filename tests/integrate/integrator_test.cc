// Tests of StateTransition (ltp/integrate/integrator.h). Every reference value states its
// source: closed forms, Eigen's MatrixFunctions expm (independent of the code under test),
// Liouville's formula, or rkf78 at a much tighter tolerance where no closed form exists.
#include "ltp/integrate/integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

#include "ltp/core/error.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_system.h"

namespace ltp {
namespace {

constexpr double kPi = std::numbers::pi;

double RelErr(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
  return (got - want).norm() / want.norm();
}

IntegratorOptions With(IntegratorType type) {
  IntegratorOptions o;
  o.type = type;
  return o;
}

// Meissner equation y'' + (a + b sign(cos t)) y + c y' = 0, T = 2π, jumps at π/2 and 3π/2.
PeriodicSystem Meissner(double a, double b, double c) {
  PeriodicSystem::Functions f;
  f.A = [a, b, c](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const double k = a + b * (std::cos(t) >= 0 ? 1.0 : -1.0);
    out << 0, 1, -k, -c;
  };
  return PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, std::move(f), {kPi / 2, 3 * kPi / 2});
}

// The same system as a piecewise-constant (sampled) system: exact for kExpm.
PeriodicSystem MeissnerSampled(double a, double b, double c) {
  LtiSystem minus, plus;
  minus.A.resize(2, 2);
  plus.A.resize(2, 2);
  minus.A << 0, 1, -(a - b), -c;
  plus.A << 0, 1, -(a + b), -c;
  return PeriodicSystem::FromSamples(2 * kPi, {kPi / 2, 3 * kPi / 2}, {minus, plus});
}

// Closed-form monodromy of the undamped Meissner equation: the product of the constant-
// coefficient transitions E(ω, τ) = [[cos ωτ, sin ωτ/ω], [−ω sin ωτ, cos ωτ]] (harmonic
// oscillator).
Eigen::Matrix2d MeissnerExact(double a, double b) {
  auto e = [](double w, double tau) {
    Eigen::Matrix2d m;
    m << std::cos(w * tau), std::sin(w * tau) / w, -w * std::sin(w * tau), std::cos(w * tau);
    return m;
  };
  const double wp = std::sqrt(a + b), wm = std::sqrt(a - b);
  return e(wp, kPi / 2) * e(wm, kPi) * e(wp, kPi / 2);
}

// Damped Meissner: each constant piece is exp(A± τ), by Eigen's expm (independent reference).
Eigen::Matrix2d MeissnerDampedReference(double a, double b, double c) {
  Eigen::Matrix2d ap, am;
  ap << 0, 1, -(a + b), -c;
  am << 0, 1, -(a - b), -c;
  const Eigen::Matrix2d half = (ap * (kPi / 2)).exp();
  return half * (am * kPi).exp() * half;
}

// Mathieu oscillator y'' + (a − 2q cos 2t) y = 0, period π.
PeriodicSystem Mathieu(double a, double q) {
  PeriodicSystem::Functions f;
  f.A = [a, q](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out << 0, 1, -(a - 2 * q * std::cos(2 * t)), 0;
  };
  return PeriodicSystem::FromFunctions(kPi, 2, 0, 0, std::move(f));
}

// Random smooth 4×4 system with harmonics 0, ±1, ±2 from a fixed seed.
PeriodicSystem RandomFourier(double period, FourierMatrix* coefficients = nullptr) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  FourierMatrix a(4, 4, 2);
  Eigen::MatrixXcd a0(4, 4);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) a0(i, j) = u(rng);
  a.SetHarmonic(0, a0);
  for (int w = 1; w <= 2; ++w) {
    Eigen::MatrixXcd aw(4, 4);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) aw(i, j) = {0.5 * u(rng), 0.5 * u(rng)};
    a.SetHarmonic(w, aw);
  }
  if (coefficients) *coefficients = a;
  return PeriodicSystem::FromFourier(period, a);
}

// ---------------------------------------------------------------- names and options

TEST(IntegratorNames, RoundTrip) {
  EXPECT_EQ(AllIntegrators().size(), 10u);
  for (IntegratorType t : AllIntegrators()) {
    auto parsed = ParseIntegratorType(ToString(t));
    ASSERT_TRUE(parsed.has_value()) << ToString(t);
    EXPECT_EQ(*parsed, t);
  }
  EXPECT_EQ(ToString(IntegratorType::kCvodeBdf), "cvode");
  EXPECT_EQ(ToString(IntegratorType::kCvodeAdams), "cvode-adams");
  EXPECT_EQ(ParseIntegratorType("magnus6"), IntegratorType::kMagnus6);
  EXPECT_FALSE(ParseIntegratorType("rk4").has_value());
  EXPECT_FALSE(ParseIntegratorType("").has_value());
  // The list the CLI's and Python's "unknown integrator" messages quote.
  EXPECT_EQ(IntegratorNames(),
            "auto, dopri5, rkf78, bs, cvode, cvode-adams, magnus4, magnus6, expm, taylor, "
            "magnus-filon");
}

void ExpectInvalid(const IntegratorOptions& o, const std::string& field) {
  try {
    o.Validate();
    ADD_FAILURE() << "no InputError for " << field;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("IntegratorOptions::" + field), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("Violated constraint"), std::string::npos) << e.what();
  }
}

TEST(IntegratorOptions, ValidateNamesTheField) {
  IntegratorOptions good;
  EXPECT_NO_THROW(good.Validate());
  IntegratorOptions o;
  o.rel_tol = -1;
  ExpectInvalid(o, "rel_tol");
  o.rel_tol = 1;
  ExpectInvalid(o, "rel_tol");
  o.rel_tol = std::nan("");
  ExpectInvalid(o, "rel_tol");
  o = {};
  o.abs_tol = -1e-3;
  ExpectInvalid(o, "abs_tol");
  o = {};
  o.steps_per_period = -2;
  ExpectInvalid(o, "steps_per_period");
  o = {};
  o.max_steps = 0;
  ExpectInvalid(o, "max_steps");

  o = {};
  o.rel_tol = -1;
  try {
    o.Validate();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "IntegratorOptions::rel_tol = -1. Violated constraint: 1e-15 <= rel_tol < 1 (double "
              "precision delivers no more)");
  }
  o.rel_tol = 1e-300;  // positive, but below what double precision can deliver
  ExpectInvalid(o, "rel_tol");
}

TEST(TransitionInput, BadOptionsAndBackwardIntervalsThrow) {
  const PeriodicSystem sys = Mathieu(1, 0.2);
  IntegratorOptions o;
  o.rel_tol = 2;
  EXPECT_THROW(StateTransition(sys, 0, 1, o), InputError);
  EXPECT_THROW(StateTransition(sys, 1, 0.5), InputError);
  EXPECT_THROW(StateTransition(sys, 0, std::nan("")), InputError);
  const TransitionResult same = StateTransition(sys, 0.7, 0.7);
  EXPECT_TRUE(same.ok);
  EXPECT_TRUE(same.phi.isIdentity());
}

// ---------------------------------------------------------------- every integrator

class IntegratorP : public ::testing::TestWithParam<IntegratorType> {};

// "cvode-adams" → "cvode_adams": test names take no '-'.
std::string TestName(const ::testing::TestParamInfo<IntegratorType>& info) {
  std::string s(ToString(info.param));
  for (char& c : s)
    if (c == '-') c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Integrator, IntegratorP, ::testing::ValuesIn(AllIntegrators()), TestName);

// Every integrator that takes A(t) with jumps (Meissner): all but kTaylor and kMagnusFilon,
// which need a Fourier series (their own tests: taylor_integrator_test.cc, below).
class JumpsP : public ::testing::TestWithParam<IntegratorType> {};

std::vector<IntegratorType> IntegratorsForJumps() {
  std::vector<IntegratorType> types;
  for (IntegratorType t : AllIntegrators())
    if (t != IntegratorType::kTaylor && t != IntegratorType::kMagnusFilon) types.push_back(t);
  return types;
}

INSTANTIATE_TEST_SUITE_P(Integrator, JumpsP, ::testing::ValuesIn(IntegratorsForJumps()), TestName);

TEST_P(IntegratorP, ConstantMatchesExpm) {
  Eigen::Matrix3d a;
  a << -0.3, 1.2, 0.4, -1.1, 0.1, 0.7, 0.2, -0.8, -0.5;
  const double period = 2.5;
  const PeriodicSystem sys = PeriodicSystem::FromFourier(period, FourierMatrix::Constant(a));
  const TransitionResult r = StateTransition(sys, 0, period, With(GetParam()));
  ASSERT_TRUE(r.ok) << r.message;
  // Reference: Eigen's Padé scaling-and-squaring expm.
  const Eigen::MatrixXd want = (a * period).exp();
  EXPECT_LT(RelErr(r.phi, want), 1e-9);
  EXPECT_GT(r.steps, 0);
  EXPECT_GT(r.rhs_evals, 0);
}

TEST_P(JumpsP, MeissnerMatchesClosedForm) {
  const double a = 1, b = 0.3;
  const TransitionResult r = StateTransition(Meissner(a, b, 0), 0, 2 * kPi, With(GetParam()));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_LT(RelErr(r.phi, MeissnerExact(a, b)), 1e-9);
}

// Reference for any [t0, t1] of the damped Meissner system: the product of exp(A± τ) over
// its constant pieces (jumps at π/2 + kπ), by Eigen's expm.
Eigen::Matrix2d MeissnerPieces(double a, double b, double c, double t0, double t1) {
  Eigen::Matrix2d phi = Eigen::Matrix2d::Identity();
  double t = t0;
  while (t < t1) {
    const double next_jump = kPi / 2 + kPi * std::floor((t - kPi / 2) / kPi + 1);
    const double end = std::min(t1, next_jump);
    const double k = a + b * (std::cos(0.5 * (t + end)) >= 0 ? 1.0 : -1.0);
    Eigen::Matrix2d m;
    m << 0, 1, -k, -c;
    phi = (m * (end - t)).exp() * phi;
    t = end;
  }
  return phi;
}

TEST_P(JumpsP, ConsecutiveFactorsMatchTheirPieces) {
  // Factors across a jump (π/2 inside the first), one starting exactly on a jump (3π/2), and
  // uneven lengths: each must be Φ(t_{i+1}, t_i), and their product the monodromy.
  const double a = 1, b = 0.3, c = 0.2;
  const std::vector<double> times = {0, 2.0, 2.5, 3 * kPi / 2, 5.0, 2 * kPi};
  const std::vector<TransitionResult> f =
      ConsecutiveTransitions(Meissner(a, b, c), times, With(GetParam()));
  ASSERT_EQ(f.size(), times.size() - 1);
  Eigen::MatrixXd product = Eigen::MatrixXd::Identity(2, 2);
  for (size_t i = 0; i < f.size(); ++i) {
    ASSERT_TRUE(f[i].ok) << f[i].message;
    EXPECT_LT(RelErr(f[i].phi, MeissnerPieces(a, b, c, times[i], times[i + 1])), 1e-9)
        << "factor " << i;
    product = f[i].phi * product;
  }
  EXPECT_LT(RelErr(product, MeissnerDampedReference(a, b, c)), 1e-9);
}

TEST_P(JumpsP, IntervalTransitionsWithGapsMatchClosedForm) {
  // Chains broken by gaps and cut across two threads: every factor is still the closed-form
  // product of the Meissner pieces' matrix exponentials over its own interval.
  const double a = 1, b = 0.3, c = 0.2;
  const std::vector<std::pair<double, double>> intervals = {{0, 0.4},   {0.4, 1.0}, {1.0, 2.5},
                                                            {3.0, 3.5}, {3.5, 5.0}, {5.5, 2 * kPi}};
  const std::vector<TransitionResult> f =
      IntervalTransitions(Meissner(a, b, c), intervals, With(GetParam()), 2);
  ASSERT_EQ(f.size(), intervals.size());
  for (size_t i = 0; i < f.size(); ++i) {
    ASSERT_TRUE(f[i].ok) << f[i].message;
    EXPECT_LT(RelErr(f[i].phi, MeissnerPieces(a, b, c, intervals[i].first, intervals[i].second)),
              1e-9)
        << "interval " << i;
  }
}

TEST(IntervalTransitions, BadIntervalFailsItsPassWithoutThrowing) {
  // A backwards interval makes its pass throw inside the parallel region: it must come back
  // as failed results with the reason, and the other chain must be unaffected.
  const std::vector<std::pair<double, double>> intervals = {{0, 1}, {2, 1.5}, {3, 4}};
  const std::vector<TransitionResult> f =
      IntervalTransitions(Meissner(1, 0.3, 0), intervals, {}, 2);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_TRUE(f[0].ok) << f[0].message;
  EXPECT_FALSE(f[1].ok);
  EXPECT_NE(f[1].message.find("strictly increasing"), std::string::npos) << f[1].message;
  EXPECT_TRUE(f[2].ok) << f[2].message;
}

TEST(ConsecutiveTransitions, RejectsTimesThatDoNotIncrease) {
  EXPECT_THROW(ConsecutiveTransitions(Meissner(1, 0.3, 0), {0, 1, 1}), InputError);
  EXPECT_THROW(ConsecutiveTransitions(Meissner(1, 0.3, 0), {0, NAN}), InputError);
  EXPECT_TRUE(ConsecutiveTransitions(Meissner(1, 0.3, 0), {0}).empty());
}

TEST_P(JumpsP, DampedMeissnerMatchesExpmProduct) {
  const double a = 1, b = 0.3, c = 0.2;
  const TransitionResult r = StateTransition(Meissner(a, b, c), 0, 2 * kPi, With(GetParam()));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_LT(RelErr(r.phi, MeissnerDampedReference(a, b, c)), 1e-9);
}

TEST_P(IntegratorP, LiouvilleDeterminant) {
  // Liouville: det Φ(T, 0) = exp(∫_0^T tr A) = exp(T tr A_0) (the harmonics integrate to 0).
  const double period = 1.7;
  FourierMatrix coefficients;
  const PeriodicSystem sys = RandomFourier(period, &coefficients);
  const TransitionResult r = StateTransition(sys, 0, period, With(GetParam()));
  ASSERT_TRUE(r.ok) << r.message;
  const double want = std::exp(period * coefficients[0].real().trace());
  EXPECT_NEAR(r.phi.determinant() / want, 1.0, 1e-9);
}

TEST_P(JumpsP, MultiPeriodIsPowerOfMonodromy) {
  const PeriodicSystem sys = Meissner(1, 0.3, 0.1);
  const double period = sys.period();
  const TransitionResult one = StateTransition(sys, 0, period, With(GetParam()));
  const TransitionResult three = StateTransition(sys, 0, 3 * period, With(GetParam()));
  ASSERT_TRUE(one.ok) << one.message;
  ASSERT_TRUE(three.ok) << three.message;
  EXPECT_LT(RelErr(three.phi, one.phi * one.phi * one.phi), 1e-9);
}

TEST_P(JumpsP, ShiftedPeriodIsSimilarToMonodromy) {
  // Periodicity: Φ(t0 + T, t0) Φ(t0, 0) = Φ(t0 + T, T) Φ(T, 0) = Φ(t0, 0) Φ(T, 0).
  // t0 = 2 lies between the breakpoints π/2 and 3π/2, so the interval crosses both copies.
  const PeriodicSystem sys = Meissner(1, 0.3, 0.1);
  const double period = sys.period(), t0 = 2.0;
  const IntegratorOptions o = With(GetParam());
  const TransitionResult head = StateTransition(sys, 0, t0, o);
  const TransitionResult mono = StateTransition(sys, 0, period, o);
  const TransitionResult shifted = StateTransition(sys, t0, t0 + period, o);
  ASSERT_TRUE(head.ok && mono.ok && shifted.ok);
  EXPECT_LT(RelErr(shifted.phi * head.phi, head.phi * mono.phi), 1e-9);
}

TEST_P(IntegratorP, OverflowIsReportedNotThrown) {
  // exp(1000 · 10) overflows a double.
  const PeriodicSystem sys =
      PeriodicSystem::FromFourier(10, FourierMatrix::Constant(1000 * Eigen::Matrix2d::Identity()));
  TransitionResult r;
  ASSERT_NO_THROW(r = StateTransition(sys, 0, 10, With(GetParam())));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.message, "state transition is not finite (overflow?)");
}

// ---------------------------------------------------------------- specific integrators

TEST(TransitionExpm, SampledMeissnerIsExact) {
  const double a = 1, b = 0.3;
  const TransitionResult r =
      StateTransition(MeissnerSampled(a, b, 0), 0, 2 * kPi, With(IntegratorType::kExpm));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(r.message.empty()) << r.message;
  EXPECT_LT(RelErr(r.phi, MeissnerExact(a, b)), 1e-13);
  EXPECT_EQ(r.steps, 3);  // [0, π/2), [π/2, 3π/2), [3π/2, 2π)

  const TransitionResult damped =
      StateTransition(MeissnerSampled(a, b, 0.2), 0, 2 * kPi, With(IntegratorType::kExpm));
  EXPECT_LT(RelErr(damped.phi, MeissnerDampedReference(a, b, 0.2)), 1e-13);
}

TEST(TransitionExpm, SmoothSystemUsesMidpointRule) {
  const TransitionResult r = StateTransition(Mathieu(1, 0.2), 0, kPi, With(IntegratorType::kExpm));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.message,
            "expm on a non-piecewise-constant system: exponential midpoint rule, 2nd order");
  EXPECT_GT(r.steps_per_period, 0);
  ASSERT_TRUE(r.error_estimate.has_value());
  EXPECT_GE(*r.error_estimate, 0);
  EXPECT_LE(*r.error_estimate, 1e-10);
}

TEST(TransitionFixedStep, AutoResolutionReportsItsEstimate) {
  const PeriodicSystem sys = Mathieu(1, 0.4);
  IntegratorOptions ref;
  ref.type = IntegratorType::kRkf78;
  ref.rel_tol = 1e-13;
  ref.abs_tol = 1e-15;
  const Eigen::MatrixXd want = StateTransition(sys, 0, kPi, ref).phi;
  for (IntegratorType type : {IntegratorType::kMagnus4, IntegratorType::kMagnus6}) {
    IntegratorOptions o = With(type);
    o.rel_tol = 1e-8;
    const TransitionResult r = StateTransition(sys, 0, kPi, o);
    ASSERT_TRUE(r.ok) << r.message;
    EXPECT_GT(r.steps_per_period, 0);
    ASSERT_TRUE(r.error_estimate.has_value());
    EXPECT_LE(*r.error_estimate, 1e-8);
    // The Richardson difference bounds the error of the finer result (it is ~2^p−1 times it).
    EXPECT_LT(RelErr(r.phi, want), 1e-8);
  }
}

TEST(TransitionFixedStep, ShortIntervalsStillConverge) {
  // Regression: on an interval of T/32, 8 and 16 steps per period both round to one step;
  // the automatic loop must still refine (it doubles the steps of every piece).
  const PeriodicSystem sys = Mathieu(1.3, 0.7);
  const double period = sys.period();
  IntegratorOptions ref = With(IntegratorType::kRkf78);  // reference: rkf78 at rel_tol 1e-13
  ref.rel_tol = 1e-13;
  ref.abs_tol = 1e-15;
  const Eigen::MatrixXd want = StateTransition(sys, 0, period, ref).phi;
  for (IntegratorType type :
       {IntegratorType::kMagnus4, IntegratorType::kMagnus6, IntegratorType::kExpm}) {
    IntegratorOptions o = With(type);
    o.rel_tol = 1e-9;
    Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(2, 2);
    const int segments = 32;
    for (int k = 0; k < segments; ++k) {
      const TransitionResult r =
          StateTransition(sys, k * period / segments, (k + 1) * period / segments, o);
      ASSERT_TRUE(r.ok) << r.message;
      ASSERT_TRUE(r.error_estimate.has_value()) << ToString(type);
      EXPECT_GT(*r.error_estimate, 0) << ToString(type);
      phi = r.phi * phi;
    }
    EXPECT_LT(RelErr(phi, want), 1e-8) << ToString(type);
  }
}

TEST(TransitionFixedStep, UnreachableToleranceFailsWithLastResult) {
  // Expm midpoint rule (2nd order) cannot reach 1e-15 within 2^20 steps per period.
  IntegratorOptions o = With(IntegratorType::kExpm);
  o.rel_tol = 1e-15;
  const TransitionResult r = StateTransition(Mathieu(1, 0.4), 0, kPi, o);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("did not reach rel_tol"), std::string::npos) << r.message;
  EXPECT_EQ(r.steps_per_period, 1 << 20);
  EXPECT_TRUE(r.phi.allFinite());
}

TEST(TransitionFixedStep, RoundOffPlateauStopsTheDoubling) {
  // A fast oscillator (ω = 100 rad/s, 314 radians per period): Magnus 6 converges quickly, then
  // each doubling only adds expm round-off. At rel_tol 1e-15 the loop used to run to 2^20 steps
  // per period; now it stops at the plateau, ok, with the plateau as its estimate — and the
  // result matches rkf78 at 1e-13 (independent reference) to within a few times that estimate.
  const PeriodicSystem sys = Mathieu(100.0 * 100.0, 20.0);
  IntegratorOptions o = With(IntegratorType::kMagnus6);
  o.rel_tol = 1e-15;
  const TransitionResult r = StateTransition(sys, 0, kPi, o);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_NE(r.message.find("round-off plateau"), std::string::npos) << r.message;
  EXPECT_LT(r.steps_per_period, 1 << 20);
  ASSERT_TRUE(r.error_estimate.has_value());
  EXPECT_LT(*r.error_estimate, 1e-9);
  IntegratorOptions ref = With(IntegratorType::kRkf78);
  ref.rel_tol = 1e-13;
  ref.abs_tol = 1e-16;
  const TransitionResult want = StateTransition(sys, 0, kPi, ref);
  ASSERT_TRUE(want.ok);
  EXPECT_LT(RelErr(r.phi, want.phi), 10 * *r.error_estimate + 1e-11)
      << r.message << "; " << r.steps_per_period << " steps per period";
}

// Observed order log2(err(N)/err(2N)) of a fixed-step Magnus method on the Mathieu system.
// `fourier`: the same system as a Fourier series (A_{±1} = [[0, 0], [q, 0]] at Ωp = 2).
double ObservedOrder(IntegratorType type, int steps, bool fourier = false) {
  FourierMatrix series(2, 2, 1);
  series.SetHarmonic(0, (Eigen::Matrix2cd() << 0, 1, -1.3, 0).finished());
  series.SetHarmonic(1, (Eigen::Matrix2cd() << 0, 0, 0.6, 0).finished());
  const PeriodicSystem sys =
      fourier ? PeriodicSystem::FromFourier(kPi, std::move(series)) : Mathieu(1.3, 0.6);
  IntegratorOptions ref;
  ref.type = IntegratorType::kRkf78;  // reference: rkf78 at rel_tol 1e-13
  ref.rel_tol = 1e-13;
  ref.abs_tol = 1e-15;
  const TransitionResult want = StateTransition(sys, 0, kPi, ref);
  EXPECT_TRUE(want.ok) << want.message;
  IntegratorOptions o = With(type);
  o.steps_per_period = steps;
  const double coarse = RelErr(StateTransition(sys, 0, kPi, o).phi, want.phi);
  o.steps_per_period = 2 * steps;
  const double fine = RelErr(StateTransition(sys, 0, kPi, o).phi, want.phi);
  EXPECT_GT(fine, 1e-11) << "error too close to the reference's own accuracy";
  return std::log2(coarse / fine);
}

TEST(MagnusOrder, Magnus4IsFourthOrder) {
  EXPECT_NEAR(ObservedOrder(IntegratorType::kMagnus4, 16), 4, 0.3);
}

TEST(MagnusOrder, Magnus6IsSixthOrder) {
  EXPECT_NEAR(ObservedOrder(IntegratorType::kMagnus6, 8), 6, 0.4);
}

TEST(MagnusOrder, ExpmMidpointIsSecondOrder) {
  EXPECT_NEAR(ObservedOrder(IntegratorType::kExpm, 64), 2, 0.2);
}

TEST(MagnusOrder, MagnusFilonIsFourthOrder) {
  // Ω1 + Ω2 exact: local error O(h^5) for a smooth A(t) as for Magnus 4.
  EXPECT_NEAR(ObservedOrder(IntegratorType::kMagnusFilon, 16, true), 4, 0.5);
}

// ---------------------------------------------------------------- Magnus–Filon

// Axis-wise damped oscillators x'' + c x' + k_x x = 0, y'' + c y' + k_y y = 0 (z = (x, y, x', y'),
// velocities scaled)
// seen from axes turning at Ω: w = R(Ωt) z with R = blockdiag(r, r), r the plane rotation, so
// A(t) = R A0 Rᵀ + Ω blockdiag(J, J) — harmonics 0 and ±2, the periodic part (k_x − k_y)/2 — and
// Φ(2π/Ω, 0) = e^{A0 T}, the damped oscillator's closed form per axis. The mean's eigenvalues
// −c/2 ± jω_d ± jΩ differ by exactly 2jΩ: the second harmonic meets them in resonance.
struct TurningOscillators {
  PeriodicSystem system;
  Eigen::Matrix4d monodromy;
};

TurningOscillators MakeTurningOscillators(double kx, double ky, double c, double rate) {
  // Velocities over w0 = √((k_x + k_y)/2) as states: entries of A about w0, not w0², so that
  // round-off (ε‖A‖T) stays below the tolerances tested, as in the analyses' balanced states.
  const double w0 = std::sqrt((kx + ky) / 2);
  Eigen::Matrix4d a0 = Eigen::Matrix4d::Zero();
  a0.topRightCorner<2, 2>() = w0 * Eigen::Matrix2d::Identity();
  a0(2, 0) = -kx / w0;
  a0(3, 1) = -ky / w0;
  a0(2, 2) = a0(3, 3) = -c;
  const double period = 2 * kPi / rate;
  auto a_of = [&](double t) {
    const double cs = std::cos(rate * t), sn = std::sin(rate * t);
    Eigen::Matrix4d r = Eigen::Matrix4d::Zero(), j = Eigen::Matrix4d::Zero();
    for (int b = 0; b < 4; b += 2) {
      r.block<2, 2>(b, b) << cs, -sn, sn, cs;
      j.block<2, 2>(b, b) << 0, -rate, rate, 0;
    }
    return Eigen::Matrix4d(r * a0 * r.transpose() + j);
  };
  // Harmonics 0..2 from 8 samples: exact, as aliases start at harmonic 6.
  FourierMatrix a(4, 4, 2);
  for (int w = 0; w <= 2; ++w) {
    Eigen::MatrixXcd sum = Eigen::MatrixXcd::Zero(4, 4);
    for (int s = 0; s < 8; ++s)
      sum += a_of(s * period / 8).cast<std::complex<double>>() *
             std::polar(1.0 / 8, -w * 2 * kPi * s / 8);
    if (w == 0) sum = sum.real().cast<std::complex<double>>();
    a.SetHarmonic(w, sum);
  }
  auto axis = [&](double k) {  // e^{A T} of x'' + c x' + k x = 0
    const double sigma = c / 2, wd = std::sqrt(k - sigma * sigma), cs = std::cos(wd * period),
                 sn = std::sin(wd * period), e = std::exp(-sigma * period);
    return Eigen::Matrix2d{{e * (cs + sigma / wd * sn), e * sn / wd},
                           {-e * k / wd * sn, e * (cs - sigma / wd * sn)}};
  };
  Eigen::Matrix4d phi = Eigen::Matrix4d::Zero();
  const Eigen::Matrix2d px = axis(kx), py = axis(ky);
  const Eigen::Vector2d unit(1, 1 / w0);  // (x, x') → (x, x'/w0)
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      phi(2 * i, 2 * j) = unit(i) * px(i, j) / unit(j);
      phi(2 * i + 1, 2 * j + 1) = unit(i) * py(i, j) / unit(j);
    }
  return {PeriodicSystem::FromFourier(period, std::move(a)), phi};
}

TEST(MagnusFilon, FastTurningOscillatorsMatchTheClosedFormInFewSteps) {
  // 300 rad/s against Ω = 1: 300 oscillations per period; periodic part δk = 0.9 (1e-5 of k).
  const double k = 300.0 * 300.0, delta = 1e-5;
  const TurningOscillators t = MakeTurningOscillators(k * (1 + delta), k * (1 - delta), 0.6, 1);
  const TransitionResult r =
      StateTransition(t.system, 0, t.system.period(), With(IntegratorType::kMagnusFilon));
  ASSERT_TRUE(r.ok) << r.message;
  const double err = RelErr(r.phi, t.monodromy);
  EXPECT_LT(err, 1e-9);
  ASSERT_TRUE(r.error_estimate.has_value());
  EXPECT_LE(err, *r.error_estimate + 1e-12);  // 1e-12: round-off, which doubling cannot see
  // The steps follow the periodic part, not the 300 oscillations: rkf78 at the same tolerance
  // does its arithmetic many times over (both counters count n×n products).
  EXPECT_LE(r.steps_per_period, 512);
  const TransitionResult explicit_run =
      StateTransition(t.system, 0, t.system.period(), With(IntegratorType::kRkf78));
  ASSERT_TRUE(explicit_run.ok);
  // rkf78's global error over 300 oscillations is above its tolerance (2e-8 measured).
  EXPECT_LT(RelErr(explicit_run.phi, t.monodromy), 1e-7);
  EXPECT_LT(10 * r.rhs_evals, explicit_run.rhs_evals)
      << r.rhs_evals << " products against " << explicit_run.rhs_evals;
}

TEST(MagnusFilon, StrongVariationStillMeetsTheClosedFormAndAnotherIntegrator) {
  // Slow modes and a 20 % anisotropy: more steps, the same closed form to the tolerance.
  const TurningOscillators t = MakeTurningOscillators(4.4, 3.6, 0.05, 1);
  IntegratorOptions o = With(IntegratorType::kMagnusFilon);
  o.rel_tol = 1e-11;
  const TransitionResult r = StateTransition(t.system, 0, t.system.period(), o);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_LT(RelErr(r.phi, t.monodromy), 1e-10);
  // Over half a period from t = 0.3 (phases of the harmonics at a step start that is not 0):
  // rkf78 at 1e-13 as the reference.
  IntegratorOptions ref = With(IntegratorType::kRkf78);
  ref.rel_tol = 1e-13;
  ref.abs_tol = 1e-16;
  const TransitionResult half = StateTransition(t.system, 0.3, 0.3 + t.system.period() / 2, o);
  const TransitionResult want = StateTransition(t.system, 0.3, 0.3 + t.system.period() / 2, ref);
  ASSERT_TRUE(half.ok && want.ok);
  EXPECT_LT(RelErr(half.phi, want.phi), 1e-10);
}

// The second Magnus term skips pairs of harmonics whose terms are below the decomposition's own
// round-off (the turning oscillators' first harmonic is the samples' rounding, ~1e-16). A small
// but real first harmonic (1 % of the anisotropy's 0.4) is not round-off: its pairs are kept, so
// the transition meets rkf78 at 1e-13 to the tolerance in the steps of a fourth-order method.
TEST(MagnusFilon, SmallHarmonicsAreKeptRoundOffOnesSkipped) {
  TurningOscillators t = MakeTurningOscillators(4.4, 3.6, 0.05, 1);
  FourierMatrix a = *t.system.fourier_A();
  Eigen::MatrixXcd first(4, 4);
  first << 0, 0, 0, 0, 0, 0, 0, 0, 0.004, -0.002, 0.001, 0.003, 0.002, 0.004, -0.003, 0.001;
  a.SetHarmonic(1, first);
  const PeriodicSystem system = PeriodicSystem::FromFourier(t.system.period(), std::move(a));
  IntegratorOptions o = With(IntegratorType::kMagnusFilon);
  o.rel_tol = 1e-11;
  IntegratorOptions ref = With(IntegratorType::kRkf78);
  ref.rel_tol = 1e-13;
  ref.abs_tol = 1e-16;
  const TransitionResult r = StateTransition(system, 0.3, 0.3 + system.period(), o);
  const TransitionResult want = StateTransition(system, 0.3, 0.3 + system.period(), ref);
  ASSERT_TRUE(r.ok && want.ok) << r.message;
  EXPECT_LT(RelErr(r.phi, want.phi), 1e-10);
  // Fourth order with every pair that counts: 2048 steps per period. Without the small
  // harmonic's pairs the method is second order in them and the doubling went to 131 072.
  EXPECT_LE(r.steps_per_period, 4096);
}

TEST(MagnusFilon, DeclinesAMeanWithoutAWellConditionedEigenbasis) {
  // A_0 = [[0, 1], [0, 0]] is a Jordan block (a free rigid-body state): no eigenbasis at all.
  FourierMatrix a(2, 2, 1);
  a.SetHarmonic(0, (Eigen::Matrix2cd() << 0, 1, 0, 0).finished());
  a.SetHarmonic(1, (Eigen::Matrix2cd() << 0, 0, -0.15, 0).finished());
  const PeriodicSystem sys = PeriodicSystem::FromFourier(2 * kPi, std::move(a));
  TransitionResult r;
  ASSERT_NO_THROW(r = StateTransition(sys, 0, 2 * kPi, With(IntegratorType::kMagnusFilon)));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("magnus-filon does not apply"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("eigenvector condition"), std::string::npos) << r.message;
}

TEST(MagnusFilon, NeedsAFourierSeries) {
  EXPECT_THROW(StateTransition(Meissner(1, 0.3, 0.1), 0, 1, With(IntegratorType::kMagnusFilon)),
               InputError);
}

TEST(TransitionStiff, BdfTakesFarFewerStepsThanDopri5) {
  // A(t) = [[-1000, 1], [0, -1 + 0.5 cos t]]: one fast decaying mode; explicit methods are
  // limited by stability (h ≲ 3.3/1000), BDF only by accuracy.
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out << -1000, 1, 0, -1 + 0.5 * std::cos(t);
  };
  const PeriodicSystem sys = PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, std::move(f));
  // Reference: rkf78 at a tight tolerance (no closed form for the coupling entry Φ_01).
  IntegratorOptions ref = With(IntegratorType::kRkf78);
  ref.rel_tol = 1e-13;
  ref.abs_tol = 1e-16;
  const TransitionResult want = StateTransition(sys, 0, 2 * kPi, ref);
  ASSERT_TRUE(want.ok) << want.message;
  // Φ_11 has a closed form: exp(∫ −1 + 0.5 cos t) = e^{−2π} over one period.
  EXPECT_NEAR(want.phi(1, 1) / std::exp(-2 * kPi), 1, 1e-10);

  // At an engineering tolerance the explicit method is stability-bound (~2000 steps whatever
  // rel_tol), BDF accuracy-bound; at very tight tolerances BDF (order <= 5) loses that edge.
  IntegratorOptions loose = With(IntegratorType::kCvodeBdf);
  loose.rel_tol = 1e-4;
  const TransitionResult bdf = StateTransition(sys, 0, 2 * kPi, loose);
  loose.type = IntegratorType::kDopri5;
  const TransitionResult dopri = StateTransition(sys, 0, 2 * kPi, loose);
  ASSERT_TRUE(bdf.ok) << bdf.message;
  ASSERT_TRUE(dopri.ok) << dopri.message;
  EXPECT_LT(bdf.steps, dopri.steps / 5) << "bdf " << bdf.steps << ", dopri5 " << dopri.steps;
  EXPECT_LT(RelErr(bdf.phi, want.phi), 1e-4);
  EXPECT_LT(RelErr(dopri.phi, want.phi), 1e-4);

  // At default options both succeed and agree with the reference.
  for (IntegratorType type : {IntegratorType::kCvodeBdf, IntegratorType::kDopri5}) {
    const TransitionResult r = StateTransition(sys, 0, 2 * kPi, With(type));
    ASSERT_TRUE(r.ok) << r.message;
    EXPECT_LT(RelErr(r.phi, want.phi), 1e-8) << ToString(type);
  }
}

TEST(TransitionLimits, TinyMaxStepsFailsWithoutThrowing) {
  const PeriodicSystem sys = Mathieu(1, 0.4);
  for (IntegratorType type : {IntegratorType::kDopri5, IntegratorType::kRkf78,
                              IntegratorType::kCvodeBdf, IntegratorType::kCvodeAdams}) {
    IntegratorOptions o = With(type);
    o.max_steps = 5;
    TransitionResult r;
    ASSERT_NO_THROW(r = StateTransition(sys, 0, 10 * kPi, o)) << ToString(type);
    EXPECT_FALSE(r.ok) << ToString(type);
    EXPECT_FALSE(r.message.empty()) << ToString(type);
    EXPECT_LE(r.steps, 5) << ToString(type);
  }
}

TEST(TransitionLimits, UserExceptionsFromAPropagate) {
  // A failing A(t) is the user's error, not a numerical outcome: it must reach the caller,
  // also through the C frames of CVODE.
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    if (t > 0.5) throw InputError("A(t) undefined");
    out.setZero();
  };
  const PeriodicSystem sys = PeriodicSystem::FromFunctions(1, 2, 0, 0, std::move(f));
  for (IntegratorType type : AllIntegrators()) {
    // These refuse an A(t) that is not a Fourier series before calling it.
    if (type == IntegratorType::kTaylor || type == IntegratorType::kMagnusFilon) continue;
    EXPECT_THROW(StateTransition(sys, 0, 1, With(type)), InputError) << ToString(type);
  }
}

// The reference run of an error estimate: a hundredth of both tolerances, rel_tol not below
// 1e-15, and a fixed step count doubled so that a fixed-step method takes other steps (the same
// steps would agree to round-off and estimate nothing).
TEST(RefinedIntegratorOptions, TighterTolerancesAndOtherSteps) {
  IntegratorOptions o;
  o.type = IntegratorType::kMagnus4;
  o.rel_tol = 1e-10;
  o.abs_tol = 1e-13;
  o.steps_per_period = 300;
  const IntegratorOptions fine = RefinedIntegratorOptions(o);
  EXPECT_EQ(fine.type, IntegratorType::kMagnus4);
  EXPECT_DOUBLE_EQ(fine.rel_tol, 1e-12);
  EXPECT_DOUBLE_EQ(fine.abs_tol, 1e-15);
  EXPECT_EQ(fine.steps_per_period, 600);
  o.rel_tol = 1e-14;
  o.steps_per_period = 0;  // automatic stays automatic
  EXPECT_DOUBLE_EQ(RefinedIntegratorOptions(o).rel_tol, 1e-15);
  EXPECT_EQ(RefinedIntegratorOptions(o).steps_per_period, 0);
}

}  // namespace
}  // namespace ltp
