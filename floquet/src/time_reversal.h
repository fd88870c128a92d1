#pragma once
// Time-reversal symmetry: an involution R (R² = I) and a rate μ with
//   R (A(−t) − μI) R = −(A(t) − μI).
// Hill equations x'' + p(t) x = 0 with p even (undamped Mathieu) have it in [x; x'] coordinates
// with R = diag(I, −I) and μ = 0; with damping c·x' as well, after x = e^{−ct/2} y: μ = −c/2 and
// R = S⁻¹ diag(I, −I) S for the shear S = [[I, 0], [(c/2) I, I]]. Then Φ(−t) = e^{−2μt} R Φ(t) R,
// and with periodicity the monodromy follows from half a period:
//   Φ(T) = e^{μT} R Φ(T/2)⁻¹ R Φ(T/2)   (docs/time-reversal.md).
#include <Eigen/Dense>
#include <optional>

#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"

namespace ltp::internal {

struct TimeReversal {
  Eigen::MatrixXd involution;  ///< R
  double rate = 0;             ///< μ (1/s)
};

/// R and μ for a Fourier-form system with the symmetry (to a few ulps of A): A − μI with
/// μ = tr A_0 / n, seen directly or — for second-order form [[0, I], [·, ·]] — through the shear
/// that removes a scalar damping, has A_0 and the cosine coefficients coupling only states of
/// opposite sign and the sine coefficients only states of the same sign. nullopt for any other
/// system (time functions and samples are not inspected).
std::optional<TimeReversal> FindTimeReversal(const PeriodicSystem& system);

/// Φ(T, 0) from one integration over [0, T/2] — or over [0, T] for a system of more than two
/// states whose Φ(T/2) is too ill-conditioned to invert within a hundredth of the tolerance.
TransitionResult MonodromyFromHalfPeriod(const PeriodicSystem& system, const TimeReversal& reversal,
                                         const IntegratorOptions& integrator);

}  // namespace ltp::internal
