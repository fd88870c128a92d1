#pragma once
// What the modes beyond a cut-off do to the exponents below it, to second order in the
// periodic part (docs/model-sizes.md, "Modes below a frequency").
#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "ltp/core/periodic_system.h"

namespace ltp::internal {

/// For each of `exponents` (of modes of the mean Ā = `mean` with |λ| ≤ cutoff): |δλ| with
/// δλ_i = Σ_{|λ_f| > cutoff} Σ_{m≠0} Q_{−m}[i,f] Q_m[f,i] / (λ_i + jmΩp − λ_f), Q_m = V⁻¹A_mV in
/// Ā's eigenvectors — the second-order perturbation of Hill's matrix by the harmonics A_m
/// coupling mode i to the modes left out. +inf when a denominator vanishes (a resonance: no
/// perturbation series) or Ā has no eigenvectors. A's harmonics: exact for a Fourier series,
/// an FFT fit (at most 64 harmonics) otherwise.
std::vector<double> TruncationTail(const PeriodicSystem& system, const Eigen::MatrixXd& mean,
                                   double cutoff,
                                   const std::vector<std::complex<double>>& exponents);

}  // namespace ltp::internal
