#pragma once
// The rigid-body mode of a free rotation angle, for both routes (monodromy and Hill).
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"

namespace ltp::internal {

/// A state labelled rigid-body (SystemLabels::rigid_body_states, a free rotation angle) owns one
/// exponent that is 0 in theory: among the modes whose shape at t = 0 (column k of
/// `shapes_at_zero`; no columns: all modes) lies mostly in that state, the exponent nearest 0 is
/// flagged (FloquetMode::rigid_body) and left out of the verdict. Nearest 0, not largest
/// share: a slow real mode of the rotor speed also lies mostly in the angle (its angle
/// amplitude is the speed amplitude divided by λ). Returns one line per flagged mode.
std::vector<std::string> FlagRigidBodyModes(const SystemLabels& labels,
                                            const Eigen::MatrixXcd& shapes_at_zero,
                                            std::vector<FloquetMode>& modes);

/// max Re λ over the modes not flagged rigid-body (0 when none is left).
double MaxRealExponent(const std::vector<FloquetMode>& modes);

}  // namespace ltp::internal
