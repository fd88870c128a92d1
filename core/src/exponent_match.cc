#include "ltp/core/exponent_match.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace ltp {

double ExponentDistance(std::complex<double> a, std::complex<double> b, double omega) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double re = std::isinf(a.real()) && a.real() == b.real() ? 0.0 : a.real() - b.real();
  const double im = std::remainder(a.imag() - b.imag(), omega);
  const double d = std::hypot(re, im);
  return std::isnan(d) ? kInf : d;
}

std::vector<int> MatchExponentIndices(const std::vector<std::complex<double>>& values,
                                      const std::vector<std::complex<double>>& reference,
                                      double omega) {
  std::vector<std::pair<double, std::pair<int, int>>> pairs;
  pairs.reserve(values.size() * reference.size());
  for (size_t i = 0; i < values.size(); ++i)
    for (size_t j = 0; j < reference.size(); ++j)
      pairs.push_back({ExponentDistance(values[i], reference[j], omega),
                       {static_cast<int>(i), static_cast<int>(j)}});
  // Distances that differ only by round-off count as equal, and equal ones go in index order.
  // Exact ties are structural: an exponent on the strip edge (Im λ = Ωp/2, a negative real
  // multiplier) is exactly as far from a reference as from its conjugate, so without the
  // quantum the last bit of Im λ — any change of summation order — decided which of the two it
  // took, and every later choice with it.
  double scale = 1;
  for (const auto* set : {&values, &reference})
    for (const std::complex<double>& z : *set)
      if (std::isfinite(std::abs(z))) scale = std::max(scale, std::abs(z));
  const double quantum = 1e-10 * scale;
  for (auto& pair : pairs)
    if (std::isfinite(pair.first)) pair.first = std::round(pair.first / quantum);
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<int> match(values.size(), -1);
  std::vector<bool> used(reference.size(), false);
  for (const auto& [d, ij] : pairs)
    if (match[ij.first] < 0 && !used[ij.second]) {
      match[ij.first] = ij.second;
      used[ij.second] = true;
    }
  return match;
}

std::vector<double> MatchExponents(const std::vector<std::complex<double>>& values,
                                   const std::vector<std::complex<double>>& reference,
                                   double omega) {
  const std::vector<int> match = MatchExponentIndices(values, reference, omega);
  std::vector<double> out(values.size(), std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < values.size(); ++i)
    if (match[i] >= 0) out[i] = ExponentDistance(values[i], reference[match[i]], omega);
  return out;
}

double MaxExponentMismatch(const std::vector<std::complex<double>>& values,
                           const std::vector<std::complex<double>>& reference, double omega) {
  if (values.size() != reference.size()) return std::numeric_limits<double>::infinity();
  double worst = 0;
  for (double d : MatchExponents(values, reference, omega)) worst = std::max(worst, d);
  return worst;
}

}  // namespace ltp
