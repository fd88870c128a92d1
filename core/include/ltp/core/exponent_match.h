#pragma once
// Comparing Floquet exponents as solutions. λ is defined modulo jΩp (docs/conventions.md), so two
// exponents describe the same solution when their real parts agree and their imaginary parts
// differ by a multiple of Ωp. Every comparison of exponents in ltp — between routes, against
// references, across sweep points — goes through these functions.
#include <complex>
#include <vector>

namespace ltp {

/// hypot(Re a − Re b, (Im a − Im b) modulo Ωp). Equal infinite real parts (a multiplier that is
/// exactly 0 has log|ρ| = −∞) are at real distance 0; any other non-finite input gives +inf.
/// `omega` = 2π compares log multipliers.
double ExponentDistance(std::complex<double> a, std::complex<double> b, double omega);

/// One-to-one matching of `values` to `reference`, globally closest pair first (robust for
/// close exponents): match[i] = index into `reference`, or -1 when the reference ran out.
std::vector<int> MatchExponentIndices(const std::vector<std::complex<double>>& values,
                                      const std::vector<std::complex<double>>& reference,
                                      double omega);

/// The distances of that matching: out[i] for values[i] (+inf when unmatched).
std::vector<double> MatchExponents(const std::vector<std::complex<double>>& values,
                                   const std::vector<std::complex<double>>& reference,
                                   double omega);

/// The largest distance of that matching; +inf when the two sets differ in size, 0 when both
/// are empty.
double MaxExponentMismatch(const std::vector<std::complex<double>>& values,
                           const std::vector<std::complex<double>>& reference, double omega);

}  // namespace ltp
