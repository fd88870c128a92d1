// D_σ from multipliers and the determinant of a half-period block: the functions whose roots
// are stability boundaries (boundary_curves.h), with their error bounds.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "ltp/studies/boundary_curves.h"

namespace ltp {

namespace {

using cd = std::complex<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// log|e^z − 1| and the phase of e^z − 1, without cancellation or overflow: for Re z ≤ 0,
// e^z − 1 = expm1(x) cos y − 2 sin²(y/2) + j e^x sin y; for Re z > 0, e^z − 1 = −e^z (e^{−z} − 1).
std::pair<double, cd> LogExpm1(cd z) {
  if (z.real() > 0) {
    const auto [log_abs, phase] = LogExpm1(-z);
    return {z.real() + log_abs, -phase * std::polar(1.0, z.imag())};
  }
  const double x = z.real(), y = z.imag(), s = std::sin(0.5 * y);
  const double re = std::expm1(x) * std::cos(y) - 2 * s * s, im = std::exp(x) * std::sin(y);
  const double mag = std::hypot(re, im);
  return {std::log(mag), mag > 0 ? cd(re / mag, im / mag) : cd(1, 0)};
}

double LogSumExp(double a, double b) {
  if (a == -kInf) return b;
  if (b == -kInf) return a;
  const double m = std::max(a, b);
  return m + std::log(std::exp(a - m) + std::exp(b - m));
}

}  // namespace

std::string_view ToString(BoundarySymmetry symmetry) {
  switch (symmetry) {
    case BoundarySymmetry::kNone:
      return "none";
    case BoundarySymmetry::kEven:
      return "even";
    case BoundarySymmetry::kOdd:
      return "odd";
  }
  return "?";
}

std::string_view ToString(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::kRealPlusOne:
      return "real multiplier +1";
    case BoundaryKind::kRealMinusOne:
      return "real multiplier -1";
    case BoundaryKind::kComplex:
      return "complex pair";
  }
  return "?";
}

CharacteristicValue MultiplierDeterminant(const std::vector<cd>& log_multipliers, int sigma,
                                          double log_error) {
  // ρ − σ = σ (σρ − 1) = σ (e^{L'} − 1), L' = log ρ (+ jπ for σ = −1), imaginary part wrapped.
  const size_t n = log_multipliers.size();
  std::vector<double> log_factor(n);
  cd phase = sigma < 0 && n % 2 ? cd(-1, 0) : cd(1, 0);
  CharacteristicValue v;
  v.log_abs = 0;
  for (size_t k = 0; k < n; ++k) {
    const cd L = log_multipliers[k];
    const double y =
        std::remainder(L.imag() + (sigma < 0 ? std::numbers::pi : 0.0), 2 * std::numbers::pi);
    const auto [log_abs, factor_phase] = LogExpm1(cd(L.real(), y));
    log_factor[k] = log_abs;
    v.log_abs += log_abs;
    phase *= factor_phase;
  }
  v.sign = v.log_abs == -kInf ? 0 : (phase.real() >= 0 ? 1 : -1);
  if (n == 0) v.sign = 1;
  if (log_error > 0) {
    // Round-off: D_σ formed from O(1) factors carries an absolute error of a few ε_machine
    // times its larger factors even where the first-order bound below vanishes (two
    // multipliers both near σ, a tongue's tip: there the error is second order in Φ's).
    double floor = std::log(8 * n * std::numeric_limits<double>::epsilon());
    for (size_t k = 0; k < n; ++k) floor += std::max(0.0, log_factor[k]);
    v.log_abs_error = floor;
    // Σ_k |ρ_k| ε Π_{j≠k} |ρ_j − σ|, each term summed in logs (a factor may be exactly 0).
    for (size_t k = 0; k < n; ++k) {
      double term = log_multipliers[k].real() + std::log(log_error);
      for (size_t j = 0; j < n; ++j)
        if (j != k) term += log_factor[j];
      v.log_abs_error = LogSumExp(v.log_abs_error, term);
    }
  }
  return v;
}

CharacteristicValue BlockDeterminant(const Eigen::MatrixXd& block, const Eigen::MatrixXd* error) {
  CharacteristicValue v;
  const Eigen::Index m = block.rows();
  v.sign = 1;
  v.log_abs = 0;
  if (m > 0) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(block);
    v.sign = lu.permutationP().determinant() > 0 ? 1 : -1;
    for (Eigen::Index i = 0; i < m; ++i) {
      const double u = lu.matrixLU()(i, i);
      if (u < 0) v.sign = -v.sign;
      v.log_abs += std::log(std::abs(u));
    }
    if (v.log_abs == -kInf) v.sign = 0;
  }
  if (error == nullptr || m == 0) return v;
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(block).singularValues();
  const double e =
      error->norm() + 8 * double(m) * std::numeric_limits<double>::epsilon() * sigma(0);
  // Σ_k s_{m−k} e^k with everything scaled by s = max(σmax, e) ≥ each term's base.
  const double scale = std::max(sigma(0), e);
  if (!(scale > 0)) return v;
  std::vector<double> symmetric(static_cast<size_t>(m) + 1, 0.0);  // s_j of σ / scale
  symmetric[0] = 1;
  for (Eigen::Index i = 0; i < m; ++i)
    for (size_t j = static_cast<size_t>(m); j > 0; --j)
      symmetric[j] += sigma(i) / scale * symmetric[j - 1];
  double sum = 0, power = 1;
  for (size_t k = 1; k <= static_cast<size_t>(m); ++k) {
    power *= e / scale;
    sum += symmetric[static_cast<size_t>(m) - k] * power;
  }
  v.log_abs_error = double(m) * std::log(scale) + std::log(sum);
  return v;
}

}  // namespace ltp
