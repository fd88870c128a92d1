#include "oscillatory_integrals.h"

#include <array>
#include <cmath>

namespace ltp::internal {

namespace {

// e^z − 1 without the cancellation of exp(z) − 1 for small |z|:
// Re = expm1(x) cos y − 2 sin²(y/2), Im = e^x sin y.
Complex Expm1(Complex z) {
  const double x = z.real(), y = z.imag(), half = std::sin(0.5 * y);
  return {std::expm1(x) * std::cos(y) - 2 * half * half, std::exp(x) * std::sin(y)};
}

// φ1'(z) = Σ_{k≥1} k z^{k−1}/(k+1)! near 0 (the closed form (e^z (z − 1) + 1)/z² cancels there).
Complex Phi1Derivative(Complex z) {
  if (std::abs(z) >= 1) return (std::exp(z) * (z - 1.0) + 1.0) / (z * z);
  Complex sum = 0, power = 1;
  double factorial = 2;  // (k + 1)!
  for (int k = 1; k <= 20; ++k) {
    sum += static_cast<double>(k) * power / factorial;
    power *= z;
    factorial *= k + 2;
  }
  return sum;
}

}  // namespace

Complex Phi1(Complex z) { return z == Complex(0) ? Complex(1) : Expm1(z) / z; }

Complex Phi1DividedDifference(Complex x, Complex y) {
  const Complex d = y - x;
  // Apart, the quotient loses at most ε/|d| relative; close, φ1[x, y] = ∫_0^1 φ1'(x + t d) dt
  // by 5-point Gauss–Legendre, whose error (|d|^10 times φ1's 11th derivative / 10^12) is
  // below round-off for |d| ≤ 1/4.
  if (std::abs(d) > 0.25) return (Phi1(y) - Phi1(x)) / d;
  static constexpr std::array<double, 5> kNodes = {0.046910077030668018, 0.23076534494715845, 0.5,
                                                   0.7692346550528415, 0.95308992296933193};
  static constexpr std::array<double, 5> kWeights = {0.11846344252809471, 0.2393143352496831,
                                                     0.2844444444444445, 0.2393143352496831,
                                                     0.11846344252809471};
  Complex sum = 0;
  for (int i = 0; i < 5; ++i) sum += kWeights[i] * Phi1Derivative(x + kNodes[i] * d);
  return sum;
}

Complex TriangleIntegral(Complex a, Complex b, double h) {
  return h * h * Phi1DividedDifference(a * h, (a + b) * h);
}

}  // namespace ltp::internal
