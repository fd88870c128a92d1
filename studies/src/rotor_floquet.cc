// Full-period Floquet multipliers from one sector of a cyclically symmetric system
// (derivation in ltp/studies/rotor_floquet.h and ltp/models/rotor.h).
#include "ltp/studies/rotor_floquet.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"

namespace ltp {

using Eigen::MatrixXd;
using cd = std::complex<double>;

SectorFloquetResult CyclicFloquet(const PeriodicSystem& system, int sectors, const MatrixXd& shift,
                                  const IntegratorOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int n = system.states();
  if (sectors < 1) throw InputError("CyclicFloquet: the number of sectors must be >= 1");
  if (shift.rows() != n || shift.cols() != n)
    throw InputError("CyclicFloquet: the shift matrix must be " + std::to_string(n) + "x" +
                     std::to_string(n));
  MatrixXd power = MatrixXd::Identity(n, n);
  for (int k = 0; k < sectors; ++k) power = shift * power;
  if (!power.isIdentity(1e-12))
    throw InputError("CyclicFloquet: the shift matrix P must satisfy P^N = I");

  SectorFloquetResult r;
  r.sectors = sectors;
  r.sector_time = system.period() / sectors;
  // The assumed symmetry P A(t + τ) P⁻¹ = A(t), checked at a few irregular times.
  const MatrixXd shift_inverse = shift.partialPivLu().inverse();
  for (double fraction : {0.0, 0.173, 0.419, 0.711}) {
    const double t = fraction * system.period();
    const MatrixXd a = system.A(t);
    const MatrixXd conjugated = shift * system.A(t + r.sector_time) * shift_inverse;
    r.symmetry_defect =
        std::max(r.symmetry_defect, (conjugated - a).norm() / std::max(1.0, a.norm()));
  }
  if (!(r.symmetry_defect <= 1e-9)) {
    std::ostringstream message;
    message << "CyclicFloquet: the system is not symmetric under the given shift over T/" << sectors
            << " (relative defect " << r.symmetry_defect << ")";
    throw InputError(message.str());
  }

  const TransitionResult phi = StateTransition(system, 0, r.sector_time, options);
  r.rhs_evals = phi.rhs_evals;
  if (!phi.ok) {
    r.message = phi.message;
    r.elapsed_s = SecondsSince(start);
    return r;
  }
  r.sector_map = shift * phi.phi;
  r.monodromy = MatrixXd::Identity(n, n);
  for (int k = 0; k < sectors; ++k) r.monodromy = r.sector_map * r.monodromy;

  const Eigen::EigenSolver<MatrixXd> eig(r.sector_map, false);
  r.max_real_exponent = -std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k) {
    const cd log_mu = std::log(eig.eigenvalues()(k));
    r.exponents.push_back(log_mu / r.sector_time);
    double arg = std::remainder(sectors * log_mu.imag(), 2 * std::numbers::pi);
    if (arg <= -std::numbers::pi) arg += 2 * std::numbers::pi;
    r.log_multipliers.emplace_back(sectors * log_mu.real(), arg);
    r.max_real_exponent = std::max(r.max_real_exponent, r.exponents.back().real());
  }
  r.ok = true;
  r.elapsed_s = SecondsSince(start);
  return r;
}

SectorFloquetResult RotorSectorFloquet(const RotorParameters& rotor,
                                       const IntegratorOptions& options) {
  rotor.Validate();
  if (!rotor.IdenticalBlades()) {
    std::ostringstream message;
    message << "the blades are not identical (mistune_k = " << rotor.mistune_k
            << ", mistune_c = " << rotor.mistune_c
            << "): the coefficients repeat only after a full revolution, so 1/N of it "
               "cannot be used; use the full-period Floquet analysis";
    throw InputError(message.str());
  }
  return CyclicFloquet(BuildRotorSystem(rotor), rotor.blades, RotorBladeShift(rotor.blades),
                       options);
}

}  // namespace ltp
