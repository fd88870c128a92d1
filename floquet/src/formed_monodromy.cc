#include "ltp/floquet/formed_monodromy.h"

#include <cmath>

#include "ltp/floquet/floquet.h"
#include "time_reversal.h"

namespace ltp {

namespace {

using cd = std::complex<double>;

// The multipliers of a 2×2 Φ(T) with its determinant known exactly (Liouville): the larger
// from the trace without cancellation, the smaller as det / larger — where the formed matrix
// holds only round-off of the larger's size (even an exact 0) — and a complex pair on the
// circle |ρ|² = det.
Eigen::VectorXcd MultipliersFromTraceAndDet(double trace, double det) {
  const double half = trace / 2;
  if (std::abs(half) > 1e150) return Eigen::Vector2cd(trace, det / trace);  // det ≪ trace²
  const double discriminant = half * half - det;
  if (discriminant < 0) {
    const double im = std::sqrt(-discriminant);
    return Eigen::Vector2cd(cd(half, im), cd(half, -im));
  }
  const double larger = half + std::copysign(std::sqrt(discriminant), half);
  return Eigen::Vector2cd(larger, det / larger);
}

}  // namespace

std::optional<std::vector<cd>> FormedLogMultipliers(const PeriodicSystem& system,
                                                    const IntegratorOptions& integrator) {
  const int n = system.states();
  if (n == 0) return std::nullopt;
  const std::optional<internal::TimeReversal> reversal = internal::FindTimeReversal(system);
  const TransitionResult phi =
      reversal ? internal::MonodromyFromHalfPeriod(system, *reversal, integrator)
               : StateTransition(system, 0, system.period(), integrator);
  if (!phi.ok || !phi.phi.allFinite()) return std::nullopt;
  const bool exact_trace_integral =
      system.fourier_A() != nullptr || system.form() == PeriodicSystem::Form::kPiecewiseConstant;
  const double det = n == 2 && exact_trace_integral ? std::exp(IntegralOfTrace(system)) : 0;
  const Eigen::VectorXcd rho = det > 0 && std::isfinite(det)
                                   ? MultipliersFromTraceAndDet(phi.phi.trace(), det)
                                   : Eigen::VectorXcd(phi.phi.eigenvalues());
  std::vector<cd> logs(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    if (!(std::abs(rho(k)) > 0)) return std::nullopt;  // underflow: the full analysis keeps it
    logs[static_cast<size_t>(k)] = std::log(rho(k));
  }
  return logs;
}

bool FormsMonodromyFromHalfPeriod(const PeriodicSystem& system) {
  return internal::FindTimeReversal(system).has_value();
}

}  // namespace ltp
