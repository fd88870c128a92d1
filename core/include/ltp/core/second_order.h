#pragma once
// Second-order periodic systems  M(t) p'' + D(t) p' + K(t) p = F(t) u,
//   y = Cd(t) p + Cv(t) p'
// converted to first order (docs/conventions.md):  x = [p; p'],
//   A = [[0, I], [-M⁻¹K, -M⁻¹D]],  B = [[0], [M⁻¹F]],  C = [Cd, Cv],  D = 0.
// M must be invertible for all t: it is checked on a grid (and at every breakpoint); a
// singular, ill-conditioned or non-finite M throws SingularMassError naming the time.
#include <Eigen/Dense>
#include <vector>

#include "ltp/core/periodic_system.h"

namespace ltp {

struct SecondOrderSystem {
  double period = 0;
  int dofs = 0;     ///< number of coordinates q = dim(p); the state has 2·dofs entries
  int inputs = 0;   ///< columns of F
  int outputs = 0;  ///< rows of Cd / Cv
  PeriodicSystem::MatrixFunction M, D, K;  ///< dofs × dofs; D may be empty (no damping)
  PeriodicSystem::MatrixFunction F;        ///< dofs × inputs (may be empty if inputs == 0)
  PeriodicSystem::MatrixFunction Cd, Cv;   ///< outputs × dofs; either may be empty (zero)
  std::vector<double> breakpoints;         ///< times in [0, T) where a coefficient jumps
};

struct SecondOrderOptions {
  /// Number of equally spaced times at which M(t) is checked (plus every breakpoint and both
  /// sides of it). Raise it for a mass matrix that is singular only in a narrow window.
  int check_points = 64;
  /// M counts as singular when its reciprocal condition number (1-norm estimate) is below this.
  double min_rcond = 1e-13;
};

/// Converts to first order. @throws SingularMassError, InputError (sizes, missing M or K).
PeriodicSystem FromSecondOrder(const SecondOrderSystem& system,
                               const SecondOrderOptions& options = {});

/// The same from Fourier coefficients, as finite-element models come (constant M, D, K plus the
/// harmonics of a rotating asymmetry or a periodic bearing; D includes gyroscopic terms Ω·G).
/// Constant M: the first-order system is a Fourier series with the harmonics of D, K, F,
/// exact — the form every analysis uses fastest — with A_w = [[δ_w I... ]] built as
/// A_0 = [[0, I], [−M⁻¹K_0, −M⁻¹D_0]], A_w = [[0, 0], [−M⁻¹K_w, −M⁻¹D_w]], B_w = [[0], [M⁻¹F_w]],
/// C_w = [Cd_w, Cv_w]. Periodic M: M(t)⁻¹ is no finite series, so the function form of
/// FromSecondOrder. Empty D, F, Cd, Cv: no damping, no inputs, zero output parts (at least one
/// of Cd, Cv gives the outputs). @throws SingularMassError, InputError (sizes, non-finite).
PeriodicSystem FromSecondOrderSeries(double period, const FourierMatrix& M, const FourierMatrix& D,
                                     const FourierMatrix& K, const FourierMatrix& F = {},
                                     const FourierMatrix& Cd = {}, const FourierMatrix& Cv = {},
                                     const SecondOrderOptions& options = {});

}  // namespace ltp
