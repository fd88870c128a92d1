#pragma once
// Forward and backward whirl of a rotor's modes in the (x, y) planes a model declares
// (SystemLabels::whirl_pairs; the rotor turns from x towards y when its speed is positive).
//
// A mode e^{λt} ξ(t), ξ(t) = Σ_v ξ_v e^{jvΩp t}, together with its complex conjugate moves each
// pair as
//   x + jy = Σ_v [ e^{(λ + jvΩp)t} (X_v + jY_v) + conj(e^{(λ + jvΩp)t}) conj(X_v − jY_v) ],
// X_v, Y_v the pair's entries of ξ_v: for each harmonic, a circle of radius |X_v + jY_v| turning
// at ω_v = Im λ + vΩp and one of radius |X_v − jY_v| turning at −ω_v. A circle whirls forward
// when it turns the way the rotor does. The share is branch-free: another branch of λ renumbers
// the harmonics, not the circles.
#include <Eigen/Dense>
#include <array>
#include <complex>
#include <vector>

#include "ltp/core/periodic_system.h"

namespace ltp {

/// The sense the rotor turns in the whirl planes: −1 when its rotor speed is negative, else +1
/// (also without one).
int RotorSpin(const PeriodicSystem& system);

/// The share (0..1) of a mode's squared circle radii, over every pair and harmonic, that turns
/// with the rotor. `harmonics[v + H]` = ξ_v (one entry per state), v = −H..H; `frequency` = Im λ
/// (rad/s); `omega_p` = 2π/T; `spin` = +1 when the rotor turns from x towards y, −1 the other
/// way. Circles that stand still (ω_v = 0) count for neither. NaN when the mode does not move in
/// those planes (their share of Σ_v ‖ξ_v‖² below 1e-10). @throws InputError when a pair's index is
/// outside the shape.
double ForwardWhirlShare(const std::vector<std::array<int, 2>>& pairs,
                         const std::vector<Eigen::VectorXcd>& harmonics, double frequency,
                         double omega_p, int spin);

/// The ellipse one harmonic traces in a plane: x(t) = Re(X e^{jωt}), y(t) = Re(Y e^{jωt}) is
/// x + jy = A e^{jωt} + B e^{−jωt}, A = (X + jY)/2, B = conj(X − jY)/2 — two circles, one turning
/// each way. The major axis (|A| + |B|) lies where they align, at (arg A + arg B)/2.
struct Orbit {
  double forward = 0, backward = 0;       ///< radii of the circles turning with / against the rotor
  double semi_major = 0, semi_minor = 0;  ///< forward + backward, |forward − backward|
  double tilt = 0;  ///< the major axis from x towards y (rad), (−π/2, π/2]
};
/// `frequency` = ω (rad/s; its sign says which circle turns which way), `spin` as above. A
/// harmonic that stands still (ω = 0) is the point (Re X, Re Y): both radii 0.
Orbit OrbitOf(std::complex<double> X, std::complex<double> Y, double frequency, int spin);

}  // namespace ltp
