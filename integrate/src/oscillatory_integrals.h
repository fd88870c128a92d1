#pragma once
// Exact integrals of exponentials over a step, the weights of the Magnus–Filon integrator
// (docs/magnus-filon.md): evaluated so that they keep full relative accuracy for arguments near
// zero (a step short against an oscillation) and near each other (resonant pairs of modes).
#include <complex>

namespace ltp::internal {

using Complex = std::complex<double>;

/// φ1(z) = (e^z − 1)/z, φ1(0) = 1: ∫_0^1 e^{zs} ds.
Complex Phi1(Complex z);

/// The divided difference φ1[x, y] = (φ1(y) − φ1(x))/(y − x), φ1'(x) at y = x.
Complex Phi1DividedDifference(Complex x, Complex y);

/// ∫_0^h e^{a s1} ∫_0^{s1} e^{b s2} ds2 ds1 = h² φ1[ah, (a + b)h].
Complex TriangleIntegral(Complex a, Complex b, double h);

}  // namespace ltp::internal
