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
#include <vector>

namespace ltp {

/// The share (0..1) of a mode's squared circle radii, over every pair and harmonic, that turns
/// with the rotor. `harmonics[v + H]` = ξ_v (one entry per state), v = −H..H; `frequency` = Im λ
/// (rad/s); `omega_p` = 2π/T; `spin` = +1 when the rotor turns from x towards y, −1 the other
/// way. Circles that stand still (ω_v = 0) count for neither. NaN when the mode does not move in
/// those planes (their share of Σ_v ‖ξ_v‖² below 1e-10). @throws InputError when a pair's index is
/// outside the shape.
double ForwardWhirlShare(const std::vector<std::array<int, 2>>& pairs,
                         const std::vector<Eigen::VectorXcd>& harmonics, double frequency,
                         double omega_p, int spin);

}  // namespace ltp
