// Periodic eigenvectors from the periodic Schur form (docs/periodic-eigenvectors.md).
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "ltp/floquet/periodic_eigen.h"

namespace ltp::internal {

/// For each log_rho[m] with wanted[m]: the stacked periodic eigenvector (v_0; …; v_{K−1}),
/// Φ_i v_i = σ_i v_{i+1} with σ_i = exp(log_rho[m] · dt_i / Σdt), scaled so that the largest
/// ||v_i|| is about 1. Empty for a mode the Schur route could not deliver (no converged
/// Schur form, no diagonal entry matching log_rho[m], a repeated multiplier, or non-finite
/// numbers): the caller falls back to another method, and checks every returned vector's
/// cyclic residual itself. The modes' recurrences run on `threads` threads (OpenMP). `form`:
/// the factors' periodic Schur decomposition when the caller has it, else computed here — or
/// that of the factors multiplied in consecutive groups of r (K/r factors, Φ_{r−1}⋯Φ_0 first):
/// the vectors at the groups' ends come from it, those inside by the factors.
std::vector<Eigen::VectorXcd> SchurPeriodicEigenvectors(
    const std::vector<Eigen::MatrixXd>& factors, const std::vector<double>& dt,
    const std::vector<std::complex<double>>& log_rho, const std::vector<bool>& wanted,
    int threads = 1, const PeriodicSchurForm* form = nullptr);

}  // namespace ltp::internal
