// Tests of FourierMatrix and of the FFT fit (fourier_fit.h). Convention (docs/conventions.md):
//   A(t) = Σ_w A_w e^{j w Ωp t},  A_w = (1/T) ∫_0^T A(t) e^{-j w Ωp t} dt.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>

#include "ltp/core/error.h"
#include "ltp/core/fourier_fit.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_system.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// FourierMatrix

TEST(FourierMatrix, EvaluateMatchesClosedForm) {
  const double period = 0.7, omega = 2 * kPi / period;
  Eigen::MatrixXd a0(2, 2);
  a0 << 1.0, -2.0, 0.5, 3.0;
  Eigen::MatrixXcd a1(2, 2);
  a1 << cd(0.3, -0.1), cd(0, 0.2), cd(-0.4, 0.25), cd(0.1, 0);
  FourierMatrix f(2, 2, 1);
  f.SetHarmonic(0, a0.cast<cd>());
  f.SetHarmonic(1, a1);
  for (double t : {0.0, 0.1, 0.33, 0.69, -1.2}) {
    // Closed form of a real series with one harmonic: A(t) = A0 + 2 Re(A1 e^{jΩt}).
    const Eigen::MatrixXd expected = a0 + 2 * (a1 * std::polar(1.0, omega * t)).real();
    EXPECT_LT((f.Evaluate(t, omega) - expected).norm(), 1e-15) << "t = " << t;
  }
}

TEST(FourierMatrix, SetHarmonicKeepsSeriesReal) {
  FourierMatrix f(1, 2, 2);
  Eigen::MatrixXcd m(1, 2);
  m << cd(1, 2), cd(-3, 0.5);
  f.SetHarmonic(2, m);
  // M_{-w} = conj(M_w) for a real function.
  EXPECT_EQ(f[-2], m.conjugate());
  EXPECT_EQ(f.coefficient(2), m);
  // M_0 of a real function is real: SetHarmonic drops the imaginary part.
  f.SetHarmonic(0, m);
  EXPECT_EQ(f[0].imag().norm(), 0.0);
  EXPECT_EQ(f[0].real(), m.real());
  EXPECT_EQ(f.HermitianDefect(), 0.0);
  // Beyond max_harmonic: zero (const access) or an error (mutable access).
  EXPECT_EQ(f.coefficient(3).norm(), 0.0);
  EXPECT_THROW(f[3], InputError);
  EXPECT_THROW(f.SetHarmonic(-1, m), InputError);
  EXPECT_THROW(f.SetHarmonic(1, Eigen::MatrixXcd::Zero(2, 2)), InputError);
}

TEST(FourierMatrix, HermitianDefectMeasuresAsymmetry) {
  FourierMatrix f(2, 2, 1);
  Eigen::MatrixXcd m = Eigen::MatrixXcd::Zero(2, 2);
  m(0, 1) = cd(0.0, 3.0);
  f[1] = m;  // M_1 set alone: M_{-1} stays 0, so the defect is ||M_1 - conj(0)|| = 3.
  EXPECT_DOUBLE_EQ(f.HermitianDefect(), 3.0);
  f[0](1, 1) = cd(0, -4.0);  // an imaginary M_0 counts too: defect max(3, 4) = 4.
  EXPECT_DOUBLE_EQ(f.HermitianDefect(), 4.0);
  EXPECT_EQ(f.HarmonicNorms().size(), 3u);
}

TEST(FourierMatrix, BlockToeplitzMultipliesHarmonics) {
  // M(t) (2×3, harmonics ±1) times x(t) (3 rows, harmonics ±1) has harmonics ±2: at N = 2 the
  // harmonic matrix maps x's coefficients to those of M x exactly. Reference: the product
  // evaluated pointwise, at times where e^{jwΩt} of w = −2..2 are independent.
  const double period = 1.3, omega = 2 * kPi / period;
  FourierMatrix m(2, 3, 1), x(3, 1, 1);
  m.SetHarmonic(0, (Eigen::MatrixXcd(2, 3) << 1, -2, 0.5, 0.3, 0, 4).finished());
  m.SetHarmonic(
      1, (Eigen::MatrixXcd(2, 3) << cd(0.2, 1), 0, cd(0, -0.7), 1.5, cd(-1, 1), 0.1).finished());
  x.SetHarmonic(0, (Eigen::MatrixXcd(3, 1) << 0.4, -1, 2).finished());
  x.SetHarmonic(1, (Eigen::MatrixXcd(3, 1) << cd(1, 0.5), cd(0, 2), -0.3).finished());
  const int N = 2;
  const Eigen::MatrixXcd t = m.BlockToeplitz(N);
  ASSERT_EQ(t.rows(), 5 * 2);
  ASSERT_EQ(t.cols(), 5 * 3);
  Eigen::VectorXcd xs = Eigen::VectorXcd::Zero(5 * 3);
  for (int u = -1; u <= 1; ++u) xs.segment((u + N) * 3, 3) = x[u];
  const Eigen::VectorXcd ys = t * xs;
  for (double time : {0.0, 0.11, 0.5, 0.77, 1.01}) {
    Eigen::VectorXcd y = Eigen::VectorXcd::Zero(2);
    for (int v = -N; v <= N; ++v)
      y += ys.segment((v + N) * 2, 2) * std::polar(1.0, v * omega * time);
    const Eigen::VectorXd expected = m.Evaluate(time, omega) * x.Evaluate(time, omega);
    EXPECT_LT((y - expected.cast<cd>()).norm(), 1e-14) << time;
  }
  EXPECT_EQ(FourierMatrix().BlockToeplitz(3).size(), 0);
  EXPECT_THROW(m.BlockToeplitz(-1), InputError);
}

// ---------------------------------------------------------------------------------------------
// FitFourier

// A 2×3 real series with harmonics 0..5 (arbitrary complex values, chosen by hand).
FourierMatrix KnownSeries() {
  FourierMatrix f(2, 3, 5);
  for (int w = 0; w <= 5; ++w) {
    Eigen::MatrixXcd m(2, 3);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j)
        m(i, j) = cd(std::cos(1.0 + w + 2 * i + 3 * j), w == 0 ? 0.0 : std::sin(0.5 * w - i + j)) /
                  (1.0 + w);
    f.SetHarmonic(w, m);
  }
  return f;
}

TEST(FourierFit, RecoversFiniteSeriesExactly) {
  const FourierMatrix known = KnownSeries();
  const double period = 0.37, omega = 2 * kPi / period;
  auto fn = [&](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    // Direct sum M_0 + Σ_{w=1..5} 2 Re(M_w e^{jwΩt}): the function whose coefficients are known.
    out = known[0].real();
    for (int w = 1; w <= 5; ++w) out += 2 * (known[w] * std::polar(1.0, w * omega * t)).real();
  };
  const FourierFit fit = FitFourier(fn, 2, 3, period);
  ASSERT_EQ(fit.series.max_harmonic(), 5);  // exactly the harmonics that are there
  for (int w = -5; w <= 5; ++w) EXPECT_LT((fit.series[w] - known[w]).norm(), 1e-13) << "w = " << w;
  EXPECT_EQ(fit.decay, FourierDecay::kFinite);
  EXPECT_TRUE(fit.converged);
  EXPECT_LE(fit.tail, 1e-12);
  EXPECT_EQ(fit.series.HermitianDefect(), 0.0);  // symmetry and real M_0 enforced exactly
}

TEST(FourierFit, BesselCoefficientsOfExpCos) {
  // exp(r cos θ) = Σ_w I_|w|(r) e^{jwθ} (generating function of the modified Bessel functions,
  // Abramowitz & Stegun 9.6.34), so A_w = I_|w|(r) with θ = Ωp t.
  const double r = 2.5, period = 1.3, omega = 2 * kPi / period;
  auto fn = [&](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out(0, 0) = std::exp(r * std::cos(omega * t));
  };
  const FourierFit fit = FitFourier(fn, 1, 1, period);
  EXPECT_TRUE(fit.converged);
  EXPECT_LE(fit.tail, 1e-12);
  EXPECT_EQ(fit.decay, FourierDecay::kExponential);
  EXPECT_GT(fit.decay_rate, 0.5);
  // I_w(2.5) falls below 1e-12 · I_0(2.5) ≈ 3.3e-12 near w = 15 (I_15(2.5) ≈ 5e-13).
  EXPECT_GE(fit.series.max_harmonic(), 13);
  EXPECT_LE(fit.series.max_harmonic(), 18);
  for (int w = -fit.series.max_harmonic(); w <= fit.series.max_harmonic(); ++w) {
    const double expected = std::cyl_bessel_i(static_cast<double>(std::abs(w)), r);
    EXPECT_NEAR(fit.series[w](0, 0).real(), expected, 1e-13) << "w = " << w;
    EXPECT_NEAR(fit.series[w](0, 0).imag(), 0.0, 1e-13) << "w = " << w;
  }
  // I_0(2.5) = 3.28983914405012303570... (mpmath.besseli(0, 2.5)), a check of cyl_bessel_i too.
  EXPECT_NEAR(fit.series[0](0, 0).real(), 3.289839144050123, 1e-13);
}

TEST(FourierFit, MaxHarmonicsCapsTheSeriesAndReportsTheTail) {
  const double r = 2.5, period = 2 * kPi;
  auto fn = [&](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out(0, 0) = std::exp(r * std::cos(t));
  };
  FourierFitOptions options;
  options.max_harmonics = 3;
  const FourierFit fit = FitFourier(fn, 1, 1, period, options);
  EXPECT_EQ(fit.series.max_harmonic(), 3);
  EXPECT_FALSE(fit.converged);
  // Exact dropped norm relative to max|A_w| = I_0(r): sqrt(2 Σ_{w>3} I_w(r)²) / I_0(r).
  double sum = 0;
  for (int w = 4; w < 60; ++w) sum += std::pow(std::cyl_bessel_i(static_cast<double>(w), r), 2);
  const double exact = std::sqrt(2 * sum) / std::cyl_bessel_i(0.0, r);
  EXPECT_NEAR(fit.tail, exact, 1e-10 * exact);
}

TEST(FourierFit, SquareWaveHasAlgebraicTail) {
  // sign(cos t): A_w = (2/(πw)) sin(wπ/2) for w != 0, A_0 = 0 (elementary integral of the
  // square wave; ±1 on alternating quarter periods around t = 0).
  auto coefficient = [](int w) { return w == 0 ? 0.0 : 2 / (kPi * w) * std::sin(w * kPi / 2); };
  auto fn = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out(0, 0) = std::cos(t) >= 0 ? 1.0 : -1.0;
  };
  FourierFitOptions options;
  options.max_samples = 1 << 14;
  const FourierFit fit = FitFourier(fn, 1, 1, 2 * kPi, options);
  for (int w = 0; w <= 7; ++w) {
    // A jump costs O(1/S) accuracy in general; these jumps fall between samples, so better.
    EXPECT_NEAR(fit.series[w](0, 0).real(), coefficient(w), 1e-6) << "w = " << w;
    EXPECT_NEAR(fit.series[w](0, 0).imag(), 0.0, 1e-6) << "w = " << w;
  }
  EXPECT_EQ(fit.decay, FourierDecay::kAlgebraic);
  EXPECT_NEAR(fit.decay_rate, 1.0, 0.1);  // |A_w| ~ 1/w
  EXPECT_FALSE(fit.converged);
  EXPECT_EQ(fit.samples, options.max_samples);
  // Exact relative ℓ2 tail: sqrt(Σ_{|w|>H} |A_w|²) / max|A_w|, with max|A_w| = |A_1| = 2/π and
  // Σ_{odd w>H} 1/w² = π²/8 − Σ_{odd w<=H} 1/w² (Σ_{odd w} 1/w² = π²/8).
  const int h = fit.series.max_harmonic();
  double odd_sum = kPi * kPi / 8;
  for (int w = 1; w <= h; w += 2) odd_sum -= 1.0 / (static_cast<double>(w) * w);
  const double exact = std::sqrt(2 * 4 / (kPi * kPi) * odd_sum) / (2 / kPi);
  EXPECT_GT(exact, 1e-3);
  EXPECT_GE(fit.tail, 0.5 * exact);  // honest: not hidden
  EXPECT_LE(fit.tail, 4.0 * exact);  // and not absurdly pessimistic
}

TEST(FourierFit, ZeroAndEmptyFunctions) {
  auto zero = [](double, Eigen::Ref<Eigen::MatrixXd> out) { out.setZero(); };
  const FourierFit z = FitFourier(zero, 2, 2, 1.0);
  EXPECT_EQ(z.series.max_harmonic(), 0);
  EXPECT_EQ(z.series[0].norm(), 0.0);
  EXPECT_TRUE(z.converged);
  EXPECT_EQ(z.decay, FourierDecay::kFinite);
  const FourierFit e = FitFourier(zero, 3, 0, 1.0);
  EXPECT_EQ(e.series.rows(), 3);
  EXPECT_EQ(e.series.cols(), 0);
  EXPECT_TRUE(e.converged);
}

TEST(FourierFit, RejectsBadInput) {
  auto one = [](double, Eigen::Ref<Eigen::MatrixXd> out) { out.setOnes(); };
  FourierFitOptions ok;
  EXPECT_THROW(FitFourier(one, -1, 1, 1.0), InputError);
  EXPECT_THROW(FitFourier(one, 1, 1, 0.0), InputError);
  EXPECT_THROW(FitFourier(one, 1, 1, std::numeric_limits<double>::quiet_NaN()), InputError);
  FourierFitOptions bad = ok;
  bad.tol = 0;
  EXPECT_THROW(FitFourier(one, 1, 1, 1.0, bad), InputError);
  bad = ok;
  bad.max_samples = 24;  // not a power of two
  EXPECT_THROW(FitFourier(one, 1, 1, 1.0, bad), InputError);
  bad.max_samples = 8;  // below 16
  EXPECT_THROW(FitFourier(one, 1, 1, 1.0, bad), InputError);

  auto nan_at_half = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out.setOnes();
    if (t > 0.5) out(0, 0) = std::numeric_limits<double>::quiet_NaN();
  };
  try {
    FitFourier(nan_at_half, 1, 1, 1.0);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("function value is not finite at t ="), std::string::npos)
        << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// ToFourier / ToFourierSystem

TEST(FourierFit, ToFourierCopiesFourierFormExactly) {
  const FourierMatrix known = KnownSeries();  // 2×3: use it as B of a 2-state system
  FourierMatrix a(2, 2, 1);
  a.SetHarmonic(0, Eigen::MatrixXcd::Identity(2, 2) * -1.0);
  a.SetHarmonic(1, Eigen::MatrixXcd::Constant(2, 2, cd(0.1, 0.2)));
  const PeriodicSystem sys = PeriodicSystem::FromFourier(2.0, a, known);
  const SystemFourier f = ToFourier(sys);
  EXPECT_EQ(f.A.series.max_harmonic(), 1);
  EXPECT_EQ(f.A.series[1], a[1]);
  EXPECT_EQ(f.B.series[-5], known[-5]);
  for (const FourierFit* fit : {&f.A, &f.B, &f.C, &f.D}) {
    EXPECT_TRUE(fit->converged);
    EXPECT_EQ(fit->tail, 0.0);
    EXPECT_EQ(fit->decay, FourierDecay::kFinite);
  }
  EXPECT_EQ(f.C.series.rows(), 0);  // no outputs
  EXPECT_EQ(f.C.series.cols(), 2);
}

TEST(FourierFit, ToFourierOfPiecewiseConstantSystem) {
  // A = a1 on [0, T/2), a2 on [T/2, T): A_0 = (a1 + a2)/2, and for w != 0
  // A_w = (1/T)[a1 ∫_0^{T/2} + a2 ∫_{T/2}^T] e^{-jwΩt} dt = (a1 − a2)/(jπw) for odd w, 0 for even
  // w.
  const double period = 3.0;
  Eigen::MatrixXd a1(1, 1), a2(1, 1);
  a1 << 2.0;
  a2 << -1.0;
  const PeriodicSystem sys = PeriodicSystem::FromSamples(
      period, {0.0, period / 2}, {LtiSystem{a1, {}, {}, {}}, LtiSystem{a2, {}, {}, {}}});
  FourierFitOptions options;
  options.max_samples = 1 << 12;
  const SystemFourier f = ToFourier(sys, options);
  EXPECT_NEAR(f.A.series[0].real()(0, 0), 0.5, 1e-9);
  for (int w = 1; w <= 6; ++w) {
    const cd expected = w % 2 ? cd(3.0) / (cd(0, 1) * (kPi * w)) : cd(0.0);
    EXPECT_LT(std::abs(f.A.series[w](0, 0) - expected), 1e-5) << "w = " << w;
  }
  EXPECT_EQ(f.A.decay, FourierDecay::kAlgebraic);
  EXPECT_FALSE(f.A.converged);
  EXPECT_EQ(f.B.series.rows(), 1);  // no inputs: empty of the right shape
  EXPECT_EQ(f.B.series.cols(), 0);
}

}  // namespace
}  // namespace ltp
