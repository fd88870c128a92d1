#include "ltp/core/whirl.h"

#include <cmath>
#include <complex>
#include <limits>

#include "ltp/core/error.h"

namespace ltp {

int RotorSpin(const PeriodicSystem& system) {
  return system.rotor_speed().value_or(1.0) < 0 ? -1 : 1;
}

double ForwardWhirlShare(const std::vector<std::array<int, 2>>& pairs,
                         const std::vector<Eigen::VectorXcd>& harmonics, double frequency,
                         double omega_p, int spin) {
  const std::complex<double> j(0, 1);
  const int H = (static_cast<int>(harmonics.size()) - 1) / 2;
  // A circle turning at less than this is standing still (a real exponent's harmonic 0).
  const double still = 1e-12 * (std::abs(frequency) + std::abs(omega_p));
  double forward = 0, total = 0, everything = 0;
  for (int v = -H; v <= H; ++v) {
    const Eigen::VectorXcd& xi = harmonics[static_cast<size_t>(v + H)];
    everything += xi.squaredNorm();
    const double w = frequency + v * omega_p;
    if (std::abs(w) <= still) continue;
    for (const auto& [x, y] : pairs) {
      if (x < 0 || y < 0 || x >= xi.size() || y >= xi.size())
        throw InputError("ForwardWhirlShare: a whirl pair's state index is outside the shape");
      const double plus = std::norm(xi(x) + j * xi(y)), minus = std::norm(xi(x) - j * xi(y));
      // The first circle turns at +w, the second at −w; forward is the rotor's sense.
      forward += (w * spin > 0) ? plus : minus;
      total += plus + minus;
    }
  }
  // Twice the whirl planes' share of ξ's energy; below 1e-10 (amplitudes 1e-5 of the shape's)
  // the mode does not move there: a collective lag mode leaves the hub still, and the share of
  // its round-off is noise.
  if (!(total > 2e-10 * everything)) return std::numeric_limits<double>::quiet_NaN();
  return forward / total;
}

Orbit OrbitOf(std::complex<double> X, std::complex<double> Y, double frequency, int spin) {
  const std::complex<double> j(0, 1);
  Orbit o;
  if (frequency == 0) return o;
  const std::complex<double> a = 0.5 * (X + j * Y), b = 0.5 * std::conj(X - j * Y);
  const bool a_forward = frequency * spin > 0;  // a turns at +ω
  o.forward = std::abs(a_forward ? a : b);
  o.backward = std::abs(a_forward ? b : a);
  o.semi_major = std::abs(a) + std::abs(b);
  o.semi_minor = std::abs(std::abs(a) - std::abs(b));
  double tilt = 0.5 * (std::arg(a) + std::arg(b));
  const double pi = std::acos(-1.0);
  while (tilt > pi / 2) tilt -= pi;
  while (tilt <= -pi / 2) tilt += pi;
  o.tilt = tilt;
  return o;
}

}  // namespace ltp
