#pragma once
// Fourier coefficients of uniformly sampled periodic matrix functions (internal to ltp::htf).
#include <Eigen/Dense>
#include <chrono>
#include <complex>
#include <vector>

namespace ltp::internal {

/// Samples f(t_s), t_s = sT/S (S = samples.size(), all of one size) → coefficients
/// c_v = (1/S) Σ_s f(t_s) e^{−j2π vs/S} for v = −H..H, H = S/2 − 1 (the Nyquist bin is dropped:
/// its sign is ambiguous). Index v + H.
std::vector<Eigen::MatrixXcd> SampledFourier(const std::vector<Eigen::MatrixXcd>& samples);

/// Largest Frobenius norm among harmonics |v| > H/2 divided by the largest of all (0 if all 0).
double UpperHalfRatio(const std::vector<Eigen::MatrixXcd>& coef);

/// Smallest power of two >= x (x >= 1).
int NextPowerOfTwo(int x);

}  // namespace ltp::internal
