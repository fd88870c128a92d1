#pragma once
// Whether A(t) stays finite and bounded over the period — checked before any analysis, for
// every door a system comes in by (scene files, Python callables): a pole (1/(t − 1), tan t),
// a mass matrix that passes through singular, or a callable that returns NaN makes every
// integrator shrink its steps without end (a NaN from t > 1 on ran 9.7 s into 19 945 lines).
#include <optional>
#include <string>

#include "ltp/core/periodic_system.h"

namespace ltp {

/// nullopt when A(t) is finite and bounded at 256 points of the period and near the largest of
/// them (a ternary search on ‖A‖ down to 1e-12 T: a bounded peak stays near its sampled value,
/// a singularity keeps growing like 1/|t − t*|); otherwise what is wrong and where, one
/// sentence that names t.
std::optional<std::string> UnboundedCoefficients(const PeriodicSystem& system);

}  // namespace ltp
