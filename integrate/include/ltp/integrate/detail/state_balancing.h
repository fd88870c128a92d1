#pragma once
// Diagonal state scaling that balances A(t): LAPACK dgebal (scaling only, powers of two, so
// exact in floating point) applied to a magnitude of A over the period. Norms measured in the
// balanced states do not depend on the units the states were written in (metres against
// micro-radians, N/m stiffness of 1e13), and integrators whose error control compares entries
// of Φ see comparable columns (docs/model-sizes.md).
#include <Eigen/Dense>

#include "ltp/core/periodic_system.h"

namespace ltp::internal {

/// Σ_w |A_w| entrywise for a Fourier series, Σ_s |A(t_s)| over 16 sample times otherwise.
Eigen::MatrixXd MagnitudeOfA(const PeriodicSystem& system);

/// dgebal's scales d of `magnitude` (D⁻¹ M D balanced, D = diag(d)); all ones when it is not
/// finite or LAPACK fails.
Eigen::VectorXd BalancingScales(Eigen::MatrixXd magnitude);

/// ‖D⁻¹ X D‖_F for D = diag(scale).
double BalancedNorm(const Eigen::MatrixXd& x, const Eigen::VectorXd& scale);
double BalancedNorm(const Eigen::MatrixXcd& x, const Eigen::VectorXd& scale);

/// The scales AnalyzeFloquet rescales the states by, or an empty vector when their spread
/// max/min is at most kBalanceSpread (the states are analysed as given).
Eigen::VectorXd StateBalancing(const PeriodicSystem& system);

/// Spread of balancing scales below which a system is analysed in its own states: within three
/// decades an integrator's error control and the factors' conditioning see every state.
inline constexpr double kBalanceSpread = 1024;

}  // namespace ltp::internal
