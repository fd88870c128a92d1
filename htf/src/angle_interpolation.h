#pragma once
// The rotor's phase between the times it is known at, and where a late channel sees it.
// Internal to ltp::htf.
#include <vector>

namespace ltp::internal {

/// θ at t from the cubic through the (up to) four points (tau, theta) around it; beyond the
/// ends, the cubic through the first or last four (tau increasing).
double InterpolateAngle(const std::vector<double>& tau, const std::vector<double>& theta, double t);

/// A channel sampled `delay` late holds at t what the system did at t − delay: its lines'
/// times and the system's phase there (exact for θ = 2πt/T; a measured θ interpolated).
struct DelayedClock {
  std::vector<double> time, theta;
};
DelayedClock Delayed(const std::vector<double>& time, const std::vector<double>& theta,
                     bool measured, double T, double delay);

}  // namespace ltp::internal
