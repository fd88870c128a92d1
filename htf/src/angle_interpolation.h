#pragma once
// The rotor's phase between the times it is known at. Internal to ltp::htf.
#include <vector>

namespace ltp::internal {

/// θ at t from the cubic through the (up to) four points (tau, theta) around it; beyond the
/// ends, the cubic through the first or last four (tau increasing).
double InterpolateAngle(const std::vector<double>& tau, const std::vector<double>& theta, double t);

}  // namespace ltp::internal
