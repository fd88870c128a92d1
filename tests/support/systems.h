#pragma once
// Analytic test systems with known Floquet structure, built directly (not through scenes) so
// floquet tests do not depend on the scene parser.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "ltp/core/periodic_system.h"

namespace ltp::test {

constexpr double kPi = std::numbers::pi;

/// Damped Mathieu y'' + c y' + (a − 2q cos 2t) y = 0, period π, exact Fourier form:
/// A_0 = [[0,1],[−a,−c]], A_{±1} = [[0,0],[q,0]] (2q cos 2t = q e^{j2t} + q e^{−j2t}, Ωp = 2).
/// `omega_p` ≠ 2 rescales time: the excitation becomes 2q cos Ωp t, period 2π/Ωp.
// x'' + 0.02 x' + w²(1 + 0.1 cos t) x = 0 over 2π: T·ρ ≈ 2π w radians per period (the work
// estimate's tests: how fast the fastest motion is sets the work).
inline PeriodicSystem FastOscillator(double w) {
  FourierMatrix a(2, 2, 1);
  a[0] << 0, 1, -w * w, -0.02;
  a[1] << 0, 0, -0.05 * w * w, 0;
  a[-1] = a[1];
  return PeriodicSystem::FromFourier(2 * std::numbers::pi, a);
}

inline PeriodicSystem Mathieu(double a, double q, double c = 0, double omega_p = 2) {
  FourierMatrix A(2, 2, 1);
  Eigen::MatrixXcd a0(2, 2), a1 = Eigen::MatrixXcd::Zero(2, 2);
  a0 << 0, 1, -a, -c;
  a1(1, 0) = q;
  A.SetHarmonic(0, a0);
  A.SetHarmonic(1, a1);
  return PeriodicSystem::FromFourier(2 * kPi / omega_p, A);  // 2π/2 = π exactly
}

/// The same with input u (B = [0; 1]) and output y (C = [1, 0]): y'' + c y' + (a − 2q cos 2t) y =
/// u.
inline PeriodicSystem MathieuIo(double a, double q, double c) {
  const PeriodicSystem s = Mathieu(a, q, c);
  return PeriodicSystem::FromFourier(
      s.period(), *s.fourier_A(),
      FourierMatrix::Constant((Eigen::MatrixXd(2, 1) << 0, 1).finished()),
      FourierMatrix::Constant((Eigen::MatrixXd(1, 2) << 1, 0).finished()));
}

/// `dofs` damped Mathieu oscillators with stiffnesses k_i = 1 + 0.37 i, coupled to their
/// neighbours by springs 0.2, damping `damping`, parametric excitation 2·excitation·k_i cos 2t:
/// a rotor-size (n = 2·dofs) smooth periodic system with harmonics ±1, period π.
inline PeriodicSystem MathieuChain(int dofs, double damping = 0.05, double excitation = 0.1) {
  const int n = 2 * dofs;
  FourierMatrix A(n, n, 1);
  Eigen::MatrixXcd a0 = Eigen::MatrixXcd::Zero(n, n), a1 = Eigen::MatrixXcd::Zero(n, n);
  for (int i = 0; i < dofs; ++i) {
    a0(i, dofs + i) = 1;
    const double k = 1.0 + 0.37 * i;
    a0(dofs + i, i) = -k - (i > 0) * 0.2 - (i + 1 < dofs) * 0.2;
    if (i > 0) a0(dofs + i, i - 1) = 0.2;
    if (i + 1 < dofs) a0(dofs + i, i + 1) = 0.2;
    a0(dofs + i, dofs + i) = -damping;
    a1(dofs + i, i) = excitation * k;
  }
  A.SetHarmonic(0, a0);
  A.SetHarmonic(1, a1);
  return PeriodicSystem::FromFourier(kPi, A);
}

/// Meissner y'' + c y' + (a + b·sign(cos t)) y = 0, period 2π, jumps at π/2 and 3π/2.
inline PeriodicSystem Meissner(double a, double b, double c = 0) {
  PeriodicSystem::Functions f;
  f.A = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const double s = std::cos(t) >= 0 ? 1.0 : -1.0;
    out << 0, 1, -(a + b * s), -c;
  };
  return PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f, {kPi / 2, 3 * kPi / 2});
}

/// Closed-form Meissner monodromy: Φ = E₊(π/2) E₋(π) E₊(π/2), E±(τ) = expm([[0,1],[−(a±b),−c]] τ).
/// For c = 0 and a > b, E(ω,τ) = [[cos ωτ, sin ωτ/ω], [−ω sin ωτ, cos ωτ]], ω = √(a ± b).
inline Eigen::Matrix2d MeissnerMonodromy(double a, double b, double c = 0) {
  auto E = [&](double k, double tau) -> Eigen::Matrix2d {
    if (c == 0 && k > 0) {
      const double w = std::sqrt(k);
      Eigen::Matrix2d e;
      e << std::cos(w * tau), std::sin(w * tau) / w, -w * std::sin(w * tau), std::cos(w * tau);
      return e;
    }
    Eigen::Matrix2d m;
    m << 0, 1, -k, -c;
    return (m * tau).exp();
  };
  return E(a + b, kPi / 2) * E(a - b, kPi) * E(a + b, kPi / 2);
}

/// Jeffcott rotor with an asymmetric shaft, fixed frame: m p'' + c p' + K(t) p = 0,
/// K(t) = R(Ωt) diag(k1,k2) R(Ωt)ᵀ, period π/Ω, exact Fourier form (Ωp = 2Ω).
inline PeriodicSystem Jeffcott(double m, double k1, double k2, double c, double omega) {
  const double k0 = (k1 + k2) / 2, dk = (k1 - k2) / 2;
  // K(t) = k0 I + dk [[cos 2Ωt, sin 2Ωt],[sin 2Ωt, −cos 2Ωt]];
  // cos = (e + e*)/2, sin = (e − e*)/(2j)  →  K_1 = dk/2 [[1, −j],[−j, −1]].
  using cd = std::complex<double>;
  FourierMatrix A(4, 4, 1);
  Eigen::MatrixXcd a0 = Eigen::MatrixXcd::Zero(4, 4), a1 = Eigen::MatrixXcd::Zero(4, 4);
  a0(0, 2) = a0(1, 3) = 1;
  a0(2, 0) = a0(3, 1) = -k0 / m;
  a0(2, 2) = a0(3, 3) = -c / m;
  Eigen::Matrix2cd k1m;
  k1m << cd(1, 0), cd(0, -1), cd(0, -1), cd(-1, 0);
  a1.block(2, 0, 2, 2) = -dk / 2 / m * k1m;
  A.SetHarmonic(0, a0);
  A.SetHarmonic(1, a1);
  return PeriodicSystem::FromFourier(kPi / omega, A);
}

/// The same rotor in the rotating frame is time-invariant: q = R(Ωt)ᵀ p gives
/// M_r = mI, D_r = 2mΩJ + cI, K_r = diag(k1,k2) − mΩ²I + cΩJ, J = [[0,−1],[1,0]].
struct JeffcottRotatingFrame {
  Eigen::Matrix2d D, K;
  Eigen::Matrix4d A;  ///< [[0, I], [−K/m, −D/m]]
};
inline JeffcottRotatingFrame JeffcottRotating(double m, double k1, double k2, double c,
                                              double omega) {
  Eigen::Matrix2d J;
  J << 0, -1, 1, 0;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  JeffcottRotatingFrame f;
  f.D = 2 * m * omega * J + c * I;
  f.K << k1 - m * omega * omega, 0, 0, k2 - m * omega * omega;
  f.K += c * omega * J;
  f.A.setZero();
  f.A.block(0, 2, 2, 2) = I;
  f.A.block(2, 0, 2, 2) = -f.K / m;
  f.A.block(2, 2, 2, 2) = -f.D / m;
  return f;
}

/// Its eigenvalues s relate to the fixed-frame Floquet exponents by λ = s ± jΩ, so
/// Re λ = Re s exactly: an independent closed-form reference for the real parts.
inline Eigen::VectorXcd JeffcottRotatingEigenvalues(double m, double k1, double k2, double c,
                                                    double omega) {
  return JeffcottRotating(m, k1, k2, c, omega).A.eigenvalues();
}

/// Uncoupled Fourier-form blocks of one period: the exponents are the union of the blocks'.
inline PeriodicSystem BlockDiagonal(const std::vector<PeriodicSystem>& blocks) {
  int n = 0, h = 0;
  for (const PeriodicSystem& b : blocks) {
    n += b.states();
    h = std::max(h, b.fourier_A()->max_harmonic());
  }
  FourierMatrix A(n, n, h);
  for (int w = 0; w <= h; ++w) {
    Eigen::MatrixXcd aw = Eigen::MatrixXcd::Zero(n, n);
    int at = 0;
    for (const PeriodicSystem& b : blocks) {
      const int m = b.states();
      aw.block(at, at, m, m) = b.fourier_A()->coefficient(w);
      at += m;
    }
    A.SetHarmonic(w, aw);
  }
  return PeriodicSystem::FromFourier(blocks.front().period(), A);
}

/// A Lyapunov-reducible 2-state system with exponents exactly l1 and l2 (closed form):
/// x = R(θ(t)) z, z' = diag(l1, l2) z, θ = t + e sin t, so
/// A(t) = R(θ) diag(l1, l2) R(θ)ᵀ + θ'(t) J, J = [[0, −1], [1, 0]]; 2π-periodic because θ
/// advances by 2π per period. Its frozen eigenvalues sit near l1 and l2 at every t, while A_0's
/// are near (l1 + l2)/2 ± j: large |l1 − l2| puts the exponents far from where a search around
/// A_0 looks (the scene of the same name in the robustness reproducers).
inline PeriodicSystem ReducibleRotation(double l1, double l2, double e) {
  PeriodicSystem::Functions f;
  f.A = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const double th = t + e * std::sin(t), dth = 1 + e * std::cos(t);
    const double c = std::cos(th), s = std::sin(th);
    out(0, 0) = l1 * c * c + l2 * s * s;
    out(0, 1) = (l1 - l2) * c * s - dth;
    out(1, 0) = (l1 - l2) * c * s + dth;
    out(1, 1) = l1 * s * s + l2 * c * c;
  };
  return PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f);
}

/// y'' + c y' + (a + b P_r(t)) y = 0 with the Poisson kernel
/// P_r(t) = (1 − r²)/(1 − 2r cos t + r²) = 1 + 2 Σ_{k>=1} r^k cos kt, given by its exact
/// Fourier coefficients (harmonic k of A: −b r^k in the lower-left entry) up to r^k < 1e-20:
/// coefficients that decay only geometrically, slowly for r near 1.
inline PeriodicSystem PoissonKernel(double a, double b, double r, double c) {
  const int M = static_cast<int>(std::ceil(std::log(1e-20) / std::log(r)));
  FourierMatrix A(2, 2, M);
  Eigen::MatrixXcd a0(2, 2);
  a0 << 0, 1, -(a + b), -c;
  A.SetHarmonic(0, a0);
  for (int k = 1; k <= M; ++k) {
    Eigen::MatrixXcd ak = Eigen::MatrixXcd::Zero(2, 2);
    ak(1, 0) = -b * std::pow(r, k);  // e^{jkt} and e^{−jkt} each carry r^k of 2 r^k cos kt
    A.SetHarmonic(k, ak);
  }
  return PeriodicSystem::FromFourier(2 * kPi, A);
}

/// A Lyapunov-reducible system with prescribed real exponents: x = R(t) z, z' = Λ z, with
/// R(t) = Q exp(S t) Qᵀ orthogonal and 2π-periodic (S skew with rates 1 and 2), so
/// A(t) = R(t) Λ R(t)ᵀ + Q S Qᵀ has Floquet exponents exactly diag(Λ) (closed form).
inline PeriodicSystem Reducible4(const Eigen::Vector4d& lambda) {
  Eigen::Matrix4d S = Eigen::Matrix4d::Zero();
  S(0, 1) = -1;
  S(1, 0) = 1;
  S(2, 3) = -2;
  S(3, 2) = 2;
  // A fixed orthogonal mixing so that no coordinate is decoupled.
  Eigen::Matrix4d M;
  M << 1, 2, 0, -1, 0.5, -1, 3, 1, 2, 0, 1, 1, -1, 1, 1, 2;
  const Eigen::Matrix4d Q = Eigen::HouseholderQR<Eigen::Matrix4d>(M).householderQ();
  const Eigen::Matrix4d skew = Q * S * Q.transpose();
  const Eigen::Matrix4d L = lambda.asDiagonal();
  PeriodicSystem::Functions f;
  f.A = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const Eigen::Matrix4d R = Q * (S * t).exp() * Q.transpose();
    out = R * L * R.transpose() + skew;
  };
  return PeriodicSystem::FromFunctions(2 * kPi, 4, 0, 0, f);
}

/// The oscillator z'' + c z' + k z = u, y = c0 [z; z'] + d u, in coordinates x = R(Ωt) z rotating
/// at Ω = rate: A(t) = R A0 Rᵀ + ΩJ, B(t) = R B0, C(t) = c0 Rᵀ, D = d (J = [[0, −1], [1, 0]]).
/// The matrices are periodic with harmonics up to 2, but y depends on u exactly as through the
/// LTI G(s) = (c0₀ + c0₁ s)/(s² + cs + k) + d: H_0 = G, every other H_z = 0. With the default
/// output y = z, ‖G‖∞ = 1/(c √(k − c²/4)) (c² < 2k) and ‖G‖₂² = 1/(2ck).
inline PeriodicSystem RotatingOscillator(double k, double c, double rate,
                                         const Eigen::RowVector2d& c0 = {1, 0}, double d = 0) {
  const Eigen::Matrix2d a0 = (Eigen::Matrix2d() << 0, 1, -k, -c).finished();
  const Eigen::Vector2d b0(0, 1);
  auto rotation = [rate](double t) {
    const double th = rate * t;
    return (Eigen::Matrix2d() << std::cos(th), -std::sin(th), std::sin(th), std::cos(th))
        .finished();
  };
  PeriodicSystem::Functions f;
  f.A = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const Eigen::Matrix2d r = rotation(t);
    out = r * a0 * r.transpose() + rate * (Eigen::Matrix2d() << 0, -1, 1, 0).finished();
  };
  f.B = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) { out = rotation(t) * b0; };
  f.C = [=](double t, Eigen::Ref<Eigen::MatrixXd> out) { out = c0 * rotation(t).transpose(); };
  if (d != 0) f.D = [d](double, Eigen::Ref<Eigen::MatrixXd> out) { out.setConstant(d); };
  return PeriodicSystem::FromFunctions(2 * kPi / rate, 2, 1, 1, f);
}

}  // namespace ltp::test
