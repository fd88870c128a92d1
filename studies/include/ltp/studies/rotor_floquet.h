#pragma once
// Floquet multipliers of a system with cyclic symmetry from 1/N of its period.
//
// If P A(t + τ) P⁻¹ = A(t) with τ = T/N and P^N = I (a rotor with N identical blades and P the
// blade relabelling, see ltp/models/rotor.h), then w(t) = P z(t + τ) solves the same equation as
// z(t), which gives
//
//   Φ(T, 0) = G^N,   G = P Φ(τ, 0).
//
// Only [0, τ] is integrated. The eigenvalues μ of G satisfy μ^N = ρ; log(μ)/τ are exponents
// modulo jNΩ (Ω = 2π/T), a finer classification than the full-period exponents (mod jΩ).
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"
#include "ltp/models/rotor.h"

namespace ltp {

struct SectorFloquetResult {
  bool ok = false;  ///< false: the integrator failed (see message)
  std::string message;
  int sectors = 0;             ///< N
  double sector_time = 0;      ///< τ = T/N (s)
  Eigen::MatrixXd sector_map;  ///< G = P Φ(τ, 0)
  Eigen::MatrixXd monodromy;   ///< Φ(T, 0) = G^N (entries may under/overflow when stiff)
  /// log ρ = N log μ (real part exact even when ρ under/overflows), arg wrapped to (−π, π].
  std::vector<std::complex<double>> log_multipliers;
  /// log(μ)/τ on the principal branch: Im in (−NΩ/2, NΩ/2]; equal to the full-period
  /// exponents modulo jΩ.
  std::vector<std::complex<double>> exponents;
  double max_real_exponent = 0;  ///< max Re λ (1/s)
  /// max over sampled t of ||P A(t + τ) P⁻¹ − A(t)|| / ||A(t)||: the symmetry that was assumed.
  double symmetry_defect = 0;
  long rhs_evals = 0;
  double elapsed_s = 0;
};

/// Full-period multipliers from one sector, for any system with P A(t + T/N) P⁻¹ = A(t).
/// @throws InputError when N < 1, P is not a matching square matrix with P^N = I, or the
/// symmetry does not hold (checked at sampled times to 1e-9 relative).
SectorFloquetResult CyclicFloquet(const PeriodicSystem& system, int sectors,
                                  const Eigen::MatrixXd& shift,
                                  const IntegratorOptions& options = {});

/// The rotor of ltp/models/rotor.h integrated over 1/N revolution.
/// @throws InputError when the blades are not identical (mistune_k or mistune_c != 1: the
/// coefficients then repeat only after a full revolution; use AnalyzeFloquet).
SectorFloquetResult RotorSectorFloquet(const RotorParameters& rotor,
                                       const IntegratorOptions& options = {});

}  // namespace ltp
