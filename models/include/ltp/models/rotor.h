#pragma once
// An N-bladed rotor with lead-lag hinges on a flexible two-direction support: the classic
// ground-resonance model of Coleman & Feingold (NACA Report 1351, 1958), in the form of
// W. Johnson, "Helicopter Theory" (1980), §12.4 and R. L. Bielawa, "Rotary Wing Structural
// Dynamics and Aeroelasticity", ch. on ground resonance.
//
// Coordinates p = (ζ_1 … ζ_N, x, y): ζ_i is the in-plane hinge angle of blade i, positive in
// the direction of rotation (lead); x, y are the hub displacements in the fixed frame. Blade i
// sits at azimuth ψ_i = Ωt + 2π(i−1)/N. Per blade: hinge offset e, first moment S_b = ∫ m r dr
// and inertia I_b = ∫ m r² dr about the hinge, lag spring K_ζ, lag damper C_ζ. The support
// has masses M_x, M_y (hub, fuselage and all blades), stiffnesses k_x, k_y, dampers c_x, c_y.
//
// Derivation (Lagrange; a blade element at distance r from the hinge is at
// (x, y) + e(cos ψ_i, sin ψ_i) + r(cos(ψ_i + ζ_i), sin(ψ_i + ζ_i))), linearised in ζ, x, y:
//
//   blade i:  I_b ζ̈_i + C_ζ ζ̇_i + (K_ζ + e S_b Ω²) ζ_i + S_b(−ẍ sin ψ_i + ÿ cos ψ_i) = 0
//   hub x:    M_x ẍ + c_x ẋ + k_x x − S_b Σ_i (ζ̈_i sin ψ_i + 2Ω ζ̇_i cos ψ_i − Ω² ζ_i sin ψ_i) = f_x
//   hub y:    M_y ÿ + c_y ẏ + k_y y + S_b Σ_i (ζ̈_i cos ψ_i − 2Ω ζ̇_i sin ψ_i − Ω² ζ_i cos ψ_i) = f_y
//
// (the hub equations are d²/dt² of the x/y momentum M_x x + S_b Σ cos(ψ_i + ζ_i); the
// constant terms S_b Ω² Σ cos ψ_i vanish for evenly spaced blades). The non-rotating lag
// frequency is ν_ζ² = (K_ζ + e S_b Ω²)/I_b: centrifugal stiffening e S_b Ω². M(t) is symmetric
// and D(t) = Ṁ(t) + G(t) with G skew (gyroscopic), so the undamped rotor is Hamiltonian.
//
// Period. The coefficients repeat after T = 2π/Ω. With identical blades they also repeat
// after τ = T/N up to a cyclic relabelling of the blades, because ψ_i(t + τ) = ψ_{i+1}(t):
// if z(t) solves z' = A(t) z, so does w(t) = P z(t + τ) with (P z)_{i+1} = z_i (blades,
// cyclically; hub entries unchanged), i.e. P A(t + τ) P⁻¹ = A(t). Hence
// P Φ(t + τ, 0) = Φ(t, 0) P Φ(τ, 0); with X_k = P^k Φ(kτ, 0) this reads X_k = X_{k−1} G,
// G = P Φ(τ, 0), and since P^N = I:
//
//   Φ(T, 0) = (P Φ(τ, 0))^N.
//
// Only 1/N of the revolution needs integrating (floquet/rotor_floquet.h does it). The
// eigenvalues μ of G satisfy μ^N = ρ, so log(μ)/τ gives the exponents modulo jNΩ instead of
// modulo jΩ.
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>

#include "ltp/core/periodic_system.h"
#include "ltp/models/scene.h"

namespace ltp {

struct RotorParameters {
  int blades = 4;                                 ///< N >= 2
  double omega = 1.0;                             ///< rotor speed Ω (rad/s), > 0
  double hinge_offset = 0.3;                      ///< e (m), >= 0
  double first_moment = 0.27;                     ///< S_b (kg m), >= 0
  double inertia = 1.0;                           ///< I_b (kg m²), > 0
  double lag_stiffness = 0.0;                     ///< K_ζ (N m/rad), >= 0
  double lag_damping = 0.19;                      ///< C_ζ (N m s/rad), >= 0
  double mass_x = 7.4, mass_y = 3.0;              ///< M_x, M_y (kg), support + hub + blades
  double stiffness_x = 2.86, stiffness_y = 2.86;  ///< k_x, k_y (N/m), >= 0
  double damping_x = 2.35, damping_y = 1.18;      ///< c_x, c_y (N s/m), >= 0
  double mistune_k = 1.0;                         ///< factor on blade 1's lag spring K_ζ, >= 0
  double mistune_c = 1.0;                         ///< factor on blade 1's lag damper C_ζ, >= 0

  /// @throws InputError naming the parameter (N not an integer >= 2, Ω <= 0, I_b <= 0, negative
  /// stiffness/damping, a mass matrix that is not positive definite: M_x, M_y must exceed
  /// c_N S_b²/I_b, c_2 = 2, c_N = N/2 for N >= 3 — always true physically, as M_x includes the
  /// blades' mass N m_b and m_b I_b >= S_b²).
  void Validate() const;
  /// True when all blades are identical (mistune_k = mistune_c = 1).
  bool IdenticalBlades() const;
  /// True when the support is the same in x and y (M, k and c).
  bool IsotropicSupport() const;
  /// K_ζ + e S_b Ω² (N m/rad): the lag stiffness including centrifugal stiffening.
  double EffectiveLagStiffness() const;
};

/// Reads the scene parameters (names as in the `rotor` scene: blades, Omega, e, S_b, I_b,
/// K_zeta, C_zeta, Mx, My, kx, ky, cx, cy, mistune_k, mistune_c) and validates them.
/// @throws InputError.
RotorParameters RotorParametersFrom(const ParameterMap& p);

/// The second-order matrices at time t: M p'' + D p' + K p = F u, y = Cd p, with
/// p = (ζ_1 … ζ_N, x, y), u = (f_x, f_y), y = (x, y).
struct RotorMatrices {
  Eigen::MatrixXd M, D, K, F, Cd;
};
RotorMatrices RotorSecondOrderMatrices(const RotorParameters& rotor, double t);

/// The rotor as a PeriodicSystem with period 2π/Ω, state (p, p'), labelled, with rotor speed Ω.
/// For N >= 3 M(t)⁻¹ is a trigonometric polynomial (its Schur complement on the hub is the
/// constant diag(M_x, M_y) − N S_b²/(2 I_b) I), so A(t) is built in exact Fourier form
/// (harmonics up to 3Ω, coefficients from an alias-free DFT); for N = 2 M(t)⁻¹ is not a finite
/// series and the system is built from time functions. @throws InputError.
PeriodicSystem BuildRotorSystem(const RotorParameters& rotor);

/// The state permutation P of the blade relabelling (see the header comment):
/// (P z)_{i+1} = z_i for the blade angles and rates (cyclically), hub entries unchanged.
/// Size 2(N + 2).
Eigen::MatrixXd RotorBladeShift(int blades);

/// The closed-form exponents of one blade on a fixed hub, the upper one:
/// λ = −C/(2I) + j √(K'/I − (C/2I)²), K' = K_ζ + e S_b Ω² (real pair when overdamped: the
/// larger one is returned). With identical blades the collective lag mode
/// ζ_0 = (1/N) Σ ζ_i never moves the hub (Σ sin ψ_i = Σ cos ψ_i = 0), so this λ is an exact
/// Floquet exponent (mod jΩ) for every N >= 2 and any support.
std::complex<double> IsolatedBladeLagExponent(const RotorParameters& rotor);

}  // namespace ltp
