// Tests of PeriodicSystem (periodic_system.h) and of its conversion to Fourier form.
#include "ltp/core/periodic_system.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/core/fourier_matrix.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Damped Mathieu oscillator p'' + c p' + (a − 2q cos 2t) p = 0 in first-order form:
// A(t) = [[0, 1], [−(a − 2q cos 2t), −c]], T = π, Ωp = 2.
constexpr double kA = 1.3, kQ = 0.4, kC = 0.1, kPeriod = std::numbers::pi;

Eigen::MatrixXd MathieuA(double t) {
  Eigen::MatrixXd a(2, 2);
  a << 0, 1, -(kA - 2 * kQ * std::cos(2 * t)), -kC;
  return a;
}

// Same system from its Fourier coefficients: A_0 = [[0,1],[−a,−c]], A_{±1} = [[0,0],[q,0]]
// (2q cos 2t = q e^{j2t} + q e^{−j2t}).
FourierMatrix MathieuFourier() {
  FourierMatrix f(2, 2, 1);
  Eigen::MatrixXcd a0(2, 2), a1(2, 2);
  a0 << 0, 1, -kA, -kC;
  a1 << 0, 0, kQ, 0;
  f.SetHarmonic(0, a0);
  f.SetHarmonic(1, a1);
  return f;
}

PeriodicSystem MathieuFunctions() {
  PeriodicSystem::Functions fn;
  fn.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) { out = MathieuA(t); };
  return PeriodicSystem::FromFunctions(kPeriod, 2, 0, 0, fn);
}

TEST(PeriodicSystem, FourierAndFunctionFormsAgree) {
  const PeriodicSystem fourier = PeriodicSystem::FromFourier(kPeriod, MathieuFourier());
  const PeriodicSystem function = MathieuFunctions();
  EXPECT_EQ(fourier.form(), PeriodicSystem::Form::kFourier);
  EXPECT_EQ(function.form(), PeriodicSystem::Form::kFunction);
  EXPECT_DOUBLE_EQ(fourier.omega(), 2.0);  // Ωp = 2π/T with T = π
  EXPECT_EQ(fourier.states(), 2);
  EXPECT_EQ(fourier.inputs(), 0);
  EXPECT_EQ(fourier.outputs(), 0);
  for (double t : {0.0, 0.3, 1.0, 2.5, 3.1, -0.7, 10.0}) {
    EXPECT_LT((fourier.A(t) - MathieuA(t)).norm(), 1e-14) << "t = " << t;
    EXPECT_LT((function.A(t) - MathieuA(t)).norm(), 1e-14) << "t = " << t;
  }
  ASSERT_NE(fourier.fourier_A(), nullptr);
  EXPECT_EQ(function.fourier_A(), nullptr);
}

TEST(PeriodicSystem, FromSamplesHoldsAndWraps) {
  const double period = 2.0;
  std::vector<LtiSystem> samples;
  for (double v : {1.0, 2.0, 3.0}) {
    Eigen::MatrixXd a(1, 1), b(1, 1);
    a << v;
    b << 10 * v;
    samples.push_back({a, b, {}, {}});
  }
  const PeriodicSystem sys = PeriodicSystem::FromSamples(period, {0.0, 0.5, 1.2}, samples);
  EXPECT_EQ(sys.form(), PeriodicSystem::Form::kPiecewiseConstant);
  EXPECT_EQ(sys.inputs(), 1);
  EXPECT_EQ(sys.outputs(), 0);
  // Sample k holds on [t_k, t_{k+1}), the last one until t_0 + T.
  EXPECT_EQ(sys.A(0.0)(0, 0), 1.0);
  EXPECT_EQ(sys.A(0.49)(0, 0), 1.0);
  EXPECT_EQ(sys.A(0.5)(0, 0), 2.0);
  EXPECT_EQ(sys.A(1.19)(0, 0), 2.0);
  EXPECT_EQ(sys.A(1.2)(0, 0), 3.0);
  EXPECT_EQ(sys.A(1.99)(0, 0), 3.0);
  EXPECT_EQ(sys.B(0.7)(0, 0), 20.0);
  // Periodic continuation: t and t ± kT give the same sample.
  EXPECT_EQ(sys.A(2.0)(0, 0), 1.0);
  EXPECT_EQ(sys.A(2.6)(0, 0), 2.0);
  EXPECT_EQ(sys.A(-0.1)(0, 0), 3.0);  // −0.1 ≡ 1.9
  EXPECT_EQ(sys.A(-1.6)(0, 0), 1.0);  // −1.6 ≡ 0.4
  EXPECT_EQ(sys.A(-3.3)(0, 0), 2.0);  // −3.3 ≡ 0.7
  EXPECT_EQ(sys.A(41.5)(0, 0), 3.0);  // 41.5 ≡ 1.5
  EXPECT_EQ(sys.breakpoints(), (std::vector<double>{0.0, 0.5, 1.2}));
  EXPECT_EQ(sys.sample_times().size(), 3u);
}

TEST(PeriodicSystem, RejectsBadInput) {
  const FourierMatrix a = MathieuFourier();
  EXPECT_THROW(PeriodicSystem::FromFourier(0.0, a), InputError);
  EXPECT_THROW(PeriodicSystem::FromFourier(-1.0, a), InputError);
  EXPECT_THROW(PeriodicSystem::FromFourier(kNaN, a), InputError);
  EXPECT_THROW(PeriodicSystem::FromFourier(std::numeric_limits<double>::infinity(), a), InputError);

  FourierMatrix nan_coefficient = a;
  nan_coefficient[-1](1, 0) = cd(kNaN, 0);
  EXPECT_THROW(PeriodicSystem::FromFourier(1.0, nan_coefficient), InputError);
  EXPECT_THROW(PeriodicSystem::FromFourier(1.0, FourierMatrix(2, 3, 0)),
               InputError);  // A not square
  EXPECT_THROW(PeriodicSystem::FromFourier(1.0, a, FourierMatrix(3, 1, 0)), InputError);  // B rows

  PeriodicSystem::Functions fn;
  fn.A = [](double, Eigen::Ref<Eigen::MatrixXd> out) { out.setZero(); };
  EXPECT_THROW(PeriodicSystem::FromFunctions(kNaN, 1, 0, 0, fn), InputError);
  EXPECT_THROW(PeriodicSystem::FromFunctions(1.0, 1, 1, 0, fn), InputError);  // B(t) missing
  EXPECT_THROW(PeriodicSystem::FromFunctions(1.0, 1, 0, 0, fn, {1.0}),
               InputError);  // not in [0, T)
  EXPECT_THROW(PeriodicSystem::FromFunctions(1.0, 1, 0, 0, PeriodicSystem::Functions{}),
               InputError);

  const LtiSystem one{Eigen::MatrixXd::Ones(1, 1), {}, {}, {}};
  const LtiSystem two{Eigen::MatrixXd::Ones(2, 2), {}, {}, {}};
  EXPECT_THROW(PeriodicSystem::FromSamples(0.0, {0.0}, {one}), InputError);
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {0.0, 1.0}, {one, one}), InputError);   // t = T
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {-0.1, 0.5}, {one, one}), InputError);  // t < 0
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {0.5, 0.2}, {one, one}), InputError);   // unsorted
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {0.2, 0.2}, {one, one}), InputError);   // repeated
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {0.0, 0.5}, {one}), InputError);  // count mismatch
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {}, {}), InputError);
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {0.0, 0.5}, {one, two}),
               InputError);  // sizes differ
  const LtiSystem not_square{Eigen::MatrixXd::Ones(1, 2), {}, {}, {}};
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {0.0}, {not_square}), InputError);
  LtiSystem nan_sample = one;
  nan_sample.A(0, 0) = kNaN;
  EXPECT_THROW(PeriodicSystem::FromSamples(1.0, {0.0}, {nan_sample}), InputError);
}

TEST(PeriodicSystem, WithLabelsChecksSizes) {
  const PeriodicSystem sys = PeriodicSystem::FromFourier(kPeriod, MathieuFourier());
  const PeriodicSystem named = sys.WithLabels({.states = {"p", "v"}});
  EXPECT_EQ(named.labels().states, (std::vector<std::string>{"p", "v"}));
  EXPECT_TRUE(sys.labels().states.empty());  // the original is unchanged
  EXPECT_THROW(sys.WithLabels({.states = {"p"}}), InputError);
  EXPECT_THROW(sys.WithLabels({.inputs = {"u"}}), InputError);  // the system has no inputs
}

TEST(PeriodicSystem, WithLabelsOnATemporaryLeavesOtherOwnersAlone) {
  // Sole owner: relabelled in place (the same representation, no copy).
  PeriodicSystem sole = PeriodicSystem::FromFourier(kPeriod, MathieuFourier());
  const FourierMatrix* representation = sole.fourier_A();
  const PeriodicSystem named = std::move(sole).WithLabels({.states = {"p", "v"}});
  EXPECT_EQ(named.fourier_A(), representation);
  EXPECT_EQ(named.labels().states, (std::vector<std::string>{"p", "v"}));
  // Shared: copied, the other owner keeps its labels.
  const PeriodicSystem kept = named;
  PeriodicSystem shared = named;
  const PeriodicSystem renamed = std::move(shared).WithLabels({.states = {"x", "x_dot"}});
  EXPECT_EQ(renamed.labels().states, (std::vector<std::string>{"x", "x_dot"}));
  EXPECT_EQ(kept.labels().states, (std::vector<std::string>{"p", "v"}));
  EXPECT_NE(renamed.fourier_A(), kept.fourier_A());
  PeriodicSystem bad = PeriodicSystem::FromFourier(kPeriod, MathieuFourier());
  EXPECT_THROW(std::move(bad).WithLabels({.states = {"p"}}), InputError);
}

TEST(PeriodicSystem, ToFourierSystemReproducesFunctionForm) {
  // Mathieu A(t) plus a time-varying input and output matrix, all with period π.
  PeriodicSystem::Functions fn;
  fn.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) { out = MathieuA(t); };
  fn.B = [](double t, Eigen::Ref<Eigen::MatrixXd> out) { out << 0, 1 + 0.5 * std::sin(2 * t); };
  fn.C = [](double t, Eigen::Ref<Eigen::MatrixXd> out) { out << std::exp(std::cos(2 * t)), 0; };
  const PeriodicSystem sys =
      PeriodicSystem::FromFunctions(kPeriod, 2, 1, 1, fn)
          .WithLabels({.states = {"p", "v"}, .inputs = {"force"}, .outputs = {"disp"}})
          .WithRotorSpeed(2.0);
  FourierFitOptions options;
  options.tol = 1e-13;
  const PeriodicSystem fourier = ToFourierSystem(sys, options);
  EXPECT_EQ(fourier.form(), PeriodicSystem::Form::kFourier);
  ASSERT_NE(fourier.fourier_A(), nullptr);
  EXPECT_EQ(fourier.fourier_A()->max_harmonic(), 1);  // 2q cos 2t: exactly one harmonic
  EXPECT_EQ(fourier.fourier_B()->max_harmonic(), 1);
  EXPECT_EQ(fourier.labels().inputs, (std::vector<std::string>{"force"}));
  EXPECT_EQ(fourier.labels().outputs, (std::vector<std::string>{"disp"}));
  ASSERT_TRUE(fourier.rotor_speed().has_value());
  EXPECT_EQ(*fourier.rotor_speed(), 2.0);
  for (double t : {0.0, 0.4, 1.7, 3.0, -2.2}) {
    EXPECT_LT((fourier.A(t) - sys.A(t)).norm(), 1e-13) << "t = " << t;
    EXPECT_LT((fourier.B(t) - sys.B(t)).norm(), 1e-13) << "t = " << t;
    // C has infinitely many harmonics; max |C_w| = I_0(1) ≈ 1.27, so a relative tail of 1e-13
    // bounds the error at a few 1e-13.
    EXPECT_LT((fourier.C(t) - sys.C(t)).norm(), 1e-12) << "t = " << t;
    EXPECT_EQ(fourier.D(t).norm(), 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// Snapshots

TEST(Snapshot, MathieuFrozenAtZero) {
  const PeriodicSystem sys = PeriodicSystem::FromFourier(kPeriod, MathieuFourier());
  const LtiSystem frozen = sys.Snapshot(0.0);
  // At t = 0, cos 2t = 1: A = [[0, 1], [−(a − 2q), −c]] = [[0, 1], [−0.5, −0.1]].
  Eigen::Matrix2d expected_a;
  expected_a << 0, 1, -0.5, -0.1;
  EXPECT_LT((frozen.A - expected_a).norm(), 1e-15);
  // Eigenvalues of [[0,1],[−k,−c]]: λ² + cλ + k = 0, λ = (−c ± sqrt(c² − 4k))/2 with k = a − 2q
  // = 0.5: c² − 4k = 0.01 − 2 = −1.99, so λ = −0.05 ± j sqrt(1.99)/2
  // = −0.05 ± 0.7053367989832942 j (sqrt(1.99) = 1.41067359796658844..., by hand / mpmath).
  Eigen::EigenSolver<Eigen::MatrixXd> eig(frozen.A);
  std::vector<cd> ev(eig.eigenvalues().begin(), eig.eigenvalues().end());
  std::sort(ev.begin(), ev.end(), [](cd x, cd y) { return x.imag() < y.imag(); });
  EXPECT_NEAR(ev[0].real(), -0.05, 1e-14);
  EXPECT_NEAR(ev[0].imag(), -0.7053367989832942, 1e-14);
  EXPECT_NEAR(ev[1].real(), -0.05, 1e-14);
  EXPECT_NEAR(ev[1].imag(), 0.7053367989832942, 1e-14);
  EXPECT_EQ(frozen.B.rows(), 2);  // no inputs, outputs
  EXPECT_EQ(frozen.B.cols(), 0);
  EXPECT_EQ(frozen.C.rows(), 0);
}

TEST(Snapshot, AtAngleNeedsRotorSpeed) {
  const PeriodicSystem sys = PeriodicSystem::FromFourier(kPeriod, MathieuFourier());
  EXPECT_THROW(sys.SnapshotAtAngle(1.0), InputError);
  EXPECT_THROW(sys.WithRotorSpeed(kNaN), InputError);
  // Rotor speed 4 rad/s: angle 2 rad is t = 0.5.
  const PeriodicSystem rotor = sys.WithRotorSpeed(4.0);
  EXPECT_LT((rotor.SnapshotAtAngle(2.0).A - MathieuA(0.5)).norm(), 1e-14);
}

}  // namespace
}  // namespace ltp

namespace ltp {
namespace {

// WithStateScaling: z = S⁻¹ x, so A_z = S⁻¹ A S, B_z = S⁻¹ B, C_z = C S, D unchanged — checked
// entry by entry against the definition, for each of the three forms.
void ExpectScaledLike(const PeriodicSystem& original, const PeriodicSystem& scaled,
                      const Eigen::VectorXd& s) {
  const Eigen::MatrixXd S = s.asDiagonal(), Si = s.cwiseInverse().asDiagonal();
  for (double t : {0.1, 1.3, 2.9}) {
    EXPECT_LT((scaled.A(t) - Si * original.A(t) * S).norm(),
              1e-15 * (Si * original.A(t) * S).norm());
    if (original.inputs() > 0) EXPECT_EQ(scaled.B(t), Si * original.B(t));
    if (original.outputs() > 0) EXPECT_EQ(scaled.C(t), original.C(t) * S);
  }
  EXPECT_EQ(scaled.form(), original.form());
  EXPECT_EQ(scaled.breakpoints(), original.breakpoints());
  EXPECT_EQ(scaled.labels().states, original.labels().states);
  EXPECT_EQ(scaled.rotor_speed(), original.rotor_speed());
}

TEST(StateScaling, EveryFormIsTheSimilarityTransform) {
  const Eigen::Vector2d s(0x1p-20, 0x1p+12);
  SystemLabels labels;
  labels.states = {"y", "y'"};
  const PeriodicSystem fourier =
      PeriodicSystem::FromFourier(kPeriod, MathieuFourier()).WithLabels(labels).WithRotorSpeed(2);
  ExpectScaledLike(fourier, fourier.WithStateScaling(s), s);
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) { out = MathieuA(t); };
  f.B = [](double, Eigen::Ref<Eigen::MatrixXd> out) { out << 0, 1; };
  f.C = [](double t, Eigen::Ref<Eigen::MatrixXd> out) { out << 1, std::sin(t); };
  f.D = [](double, Eigen::Ref<Eigen::MatrixXd> out) { out << 0.5; };
  const PeriodicSystem functions = PeriodicSystem::FromFunctions(kPeriod, 2, 1, 1, f, {1.0});
  const PeriodicSystem scaled = functions.WithStateScaling(s);
  ExpectScaledLike(functions, scaled, s);
  EXPECT_EQ(scaled.D(0.3), functions.D(0.3));
  LtiSystem held{MathieuA(0.0), Eigen::MatrixXd::Ones(2, 1), Eigen::MatrixXd::Ones(1, 2),
                 Eigen::MatrixXd::Zero(1, 1)};
  const PeriodicSystem samples = PeriodicSystem::FromSamples(kPeriod, {0.0, 1.0}, {held, held});
  ExpectScaledLike(samples, samples.WithStateScaling(s), s);
  EXPECT_THROW(fourier.WithStateScaling(Eigen::Vector3d::Ones()), InputError);
  EXPECT_THROW(fourier.WithStateScaling(Eigen::Vector2d(1, 0)), InputError);
  EXPECT_THROW(fourier.WithStateScaling(Eigen::Vector2d(1, kNaN)), InputError);
}

}  // namespace
}  // namespace ltp

namespace ltp {
namespace {

TEST(FromFourier, AMissingOrEmptyIsAnInputErrorNotACrash) {
  // Python's from_fourier(1.0, None) and from_fourier(1.0, np.zeros((0, 0))) reached here and
  // read a coefficient the empty series does not have (segmentation fault).
  EXPECT_THROW(PeriodicSystem::FromFourier(1.0, FourierMatrix()), InputError);
  EXPECT_THROW(PeriodicSystem::FromFourier(1.0, FourierMatrix::Constant(Eigen::MatrixXd(0, 0))),
               InputError);
}

}  // namespace
}  // namespace ltp
