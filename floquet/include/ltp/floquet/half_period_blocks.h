#pragma once
// The characteristic determinants of an undamped time-reversible system, factored over half a
// period (docs/stability-boundaries.md, "Tips"). With the symmetry of docs/time-reversal.md for
// μ = 0 and a diagonal involution R with as many +1 as −1 states (x'' + K(t)x = 0 with K even in
// t, in [x; x'] coordinates), and Φh = Φ(T/2) in R's blocks [[P, Q], [U, W]] (R's +1 states
// first):
//   det(Φ(T) − I) = (−4)^p det Q det U / det Φh,   det(Φ(T) + I) = 4^p det P det W / det Φh,
// det Φh > 0. A root of det U (σ = +1) or det P (σ = −1) carries a solution with
// x(−t) = R x(t) ("even"), one of det Q or det W a solution with x(−t) = −R x(t) ("odd"). The two
// edges of a parametric-resonance tongue are simple roots of different factors, where
// det(Φ(T) ∓ I) has a double root at the tongue's tip.
#include <Eigen/Dense>
#include <optional>

#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"

namespace ltp {

/// Φ(T/2) in the involution's blocks: rows and columns of R's +1 states first.
struct HalfPeriodBlocks {
  Eigen::MatrixXd P, Q, U, W;
  /// The block whose determinant vanishes where a multiplier crosses σ (+1 or −1) with a
  /// solution of that symmetry: σ = +1: U (even), Q (odd); σ = −1: P (even), W (odd).
  const Eigen::MatrixXd& Factor(int sigma, bool even) const;
};

/// Whether the factorization applies (no integration): a Fourier-form system with the
/// time-reversal symmetry, μ = 0, R diagonal with as many +1 as −1 states.
bool HasHalfPeriodBlocks(const PeriodicSystem& system);

/// The blocks of Φ(T/2) from one integration over [0, T/2]. nullopt when the factorization does
/// not apply or the integration fails.
std::optional<HalfPeriodBlocks> ComputeHalfPeriodBlocks(const PeriodicSystem& system,
                                                        const IntegratorOptions& integrator);

}  // namespace ltp
