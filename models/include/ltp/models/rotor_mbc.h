#pragma once
// The rotor scene (ltp/models/rotor.h) in multi-blade coordinates (transform T(t) in
// ltp/core/multiblade.h). With p = T(t) q (hub coordinates unchanged) the rotor equations
// M p'' + D p' + K p = F u become, after premultiplying by T⁻¹,
//
//   M̃ = T⁻¹ M T,   D̃ = T⁻¹(2 M Ṫ + D T),   K̃ = T⁻¹(M T̈ + D Ṫ + K T),   F̃ = T⁻¹ F,
//
// which are constant for N >= 3 identical blades on any (even anisotropic) support. Since T(t)
// is 2π/Ω-periodic, the eigenvalues s of the constant system are the Floquet exponents modulo
// jΩ. Only the cyclic pair ζ_1c, ζ_1s couples with the hub (Σ_i cos nψ_i sin ψ_i = 0 unless
// n ≡ ±1 mod N); the collective, the differential and the higher cyclics are isolated blades:
// s = λ_blade for ζ_0 and ζ_d, s = λ_blade ± jnΩ for the pair (ζ_nc, ζ_ns).
//
// MBC does not give constant coefficients for N = 2 (no cyclic pair: the two blades' motion
// stays periodic in any blade-based coordinates) or for dissimilar blades; those need Floquet
// analysis. (With an isotropic support such rotors are time-invariant in the rotating frame
// instead; that transform is not provided here.)
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/multiblade.h"
#include "ltp/models/rotor.h"

namespace ltp {

/// The rotor in multi-blade coordinates q = (MBC blade coordinates, x, y): constant matrices.
struct MbcRotorSystem {
  int blades = 0;
  double rotor_speed = 0;                ///< Ω (rad/s)
  std::vector<std::string> coordinates;  ///< names of q
  Eigen::MatrixXd M, D, K, F, Cd;        ///< M q'' + D q' + K q = F u,  y = Cd q
  Eigen::MatrixXd A, B;                  ///< first order, state (q, q')
  /// Eigenvalues of A (1/s), sorted by imaginary part then real part. They equal the rotor's
  /// Floquet exponents modulo jΩ.
  std::vector<std::complex<double>> eigenvalues;
  /// max over sampled azimuths of the change of the transformed matrices relative to ψ = 0,
  /// divided by their norm: round-off when MBC applies (a built-in check of the transform).
  double constancy_defect = 0;
};

/// Why MBC cannot make this rotor time-invariant, or nullopt when it can (N >= 3 identical
/// blades).
std::optional<std::string> MbcNotApplicable(const RotorParameters& rotor);

/// The rotor in multi-blade coordinates. @throws InputError with MbcNotApplicable's reason.
MbcRotorSystem RotorInMultiBladeCoordinates(const RotorParameters& rotor);

}  // namespace ltp
