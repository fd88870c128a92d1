// Step 4 of the Floquet analysis: periodic mode shapes on a uniform sample grid, each mode's
// branch (which of the exponents λ + j m Ωp it is), and the mode matrix's conditioning.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"
#include "ltp/floquet/periodic_eigen.h"
#include "ltp/integrate/detail/segment_grid.h"

namespace ltp::internal {

struct ModeShapes {
  std::vector<FloquetMode> modes;         ///< one per log multiplier, in their order
  std::vector<double> kappa;              ///< eigenvalue condition numbers (inf: unknown)
  std::vector<double> sample_times;       ///< the uniform samples t_s = s T / S
  std::vector<Eigen::MatrixXcd> samples;  ///< ξ(t_s), column k for log multiplier k
  std::vector<Eigen::MatrixXcd> fourier;  ///< harmonics −H … H of ξ on the chosen branches
  int harmonics = 0;                      ///< H
  double condition = 0;                   ///< of the mode matrix, best sample time
  long rhs_evals = 0;
  std::vector<Diagnostic> diagnostics;
};

/// The mode shapes of the multipliers exp(log_rho) of the factors on `grid`, at `samples`
/// uniform times (grid points where the grid has them, else propagated from the last grid
/// point with `integrator`; for an A(t) that is `constant`, as powers of one transition). The
/// periodic eigenvectors use `threads` threads, and `form`, the grid factors' periodic Schur
/// decomposition, when the caller has it.
ModeShapes ComputeModeShapes(const PeriodicSystem& system, const SegmentGrid& grid,
                             const std::vector<std::complex<double>>& log_rho, int samples,
                             const IntegratorOptions& integrator, int threads, bool constant,
                             const PeriodicSchurForm* form = nullptr);

/// Each mode's FloquetMode::forward_whirl from r.mode_fourier (in the system's states), when
/// `system` declares whirl pairs; the rotor turns the way its rotor speed's sign says (+ when it
/// has none).
void AssignWhirl(const PeriodicSystem& system, FloquetResult& r);

}  // namespace ltp::internal
