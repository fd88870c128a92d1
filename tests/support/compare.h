#pragma once
// Comparison helpers for tests: matrices, vectors up to a phase, and sets of log-eigenvalues
// matched without regard to order.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <sstream>
#include <vector>

#include "ltp/core/exponent_match.h"

namespace ltp::test {

/// Distance of two logarithms of multipliers, log ρ = log|ρ| + j arg ρ: ltp's exponent distance
/// with arguments compared modulo 2π. Two zero multipliers (log|ρ| = −inf) are at distance 0;
/// a zero and a nonzero one at +inf.
inline double LogEigenvalueDistance(std::complex<double> a, std::complex<double> b) {
  return ltp::ExponentDistance(a, b, 2 * std::numbers::pi);
}

/// Matches `actual` to `expected` as sets (ltp's one-to-one matching, globally closest pair
/// first) and adds a gtest failure for every pair farther apart than
/// tol · max(1, |log|ρ_expected||) — a relative tolerance on log|ρ| for large |log|ρ||, an
/// absolute one near |ρ| = 1. Sizes must agree.
inline void ExpectLogEigenvaluesNear(const std::vector<std::complex<double>>& actual,
                                     const std::vector<std::complex<double>>& expected,
                                     double tol) {
  ASSERT_EQ(actual.size(), expected.size()) << "different numbers of eigenvalues";
  const std::vector<int> match = ltp::MatchExponentIndices(actual, expected, 2 * std::numbers::pi);
  for (std::size_t i = 0; i < actual.size(); ++i) {
    const std::complex<double> e = expected[match[i]];
    const double d = LogEigenvalueDistance(actual[i], e);
    const double scale = std::max(1.0, std::abs(e.real()));
    EXPECT_LE(d, tol * scale) << "log-eigenvalue " << actual[i] << " matched to expected " << e
                              << " (distance " << d << ", allowed " << tol * scale << ")";
  }
}

/// Passes when a and b have the same size and max|a − b| <= tol · max(1, max|b|); the failure
/// message names the worst entry.
template <typename A, typename B>
::testing::AssertionResult CompareMatrices(const Eigen::MatrixBase<A>& a,
                                           const Eigen::MatrixBase<B>& b, double tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure()
           << "size " << a.rows() << "x" << a.cols() << " vs " << b.rows() << "x" << b.cols();
  }
  if (a.size() == 0) return ::testing::AssertionSuccess();
  Eigen::Index r = 0, c = 0;
  const double worst = (a - b).cwiseAbs().maxCoeff(&r, &c);
  const double allowed = tol * std::max(1.0, static_cast<double>(b.cwiseAbs().maxCoeff()));
  if (!(worst <= allowed)) {
    return ::testing::AssertionFailure()
           << "max |a - b| = " << worst << " at (" << r << ", " << c << "): " << a(r, c) << " vs "
           << b(r, c) << ", allowed " << allowed;
  }
  return ::testing::AssertionSuccess();
}

/// Passes when a = e^{jφ} b · (||a|| / ||b||) for some phase φ, i.e. the two vectors span the
/// same complex line: || a/||a|| − e^{jφ} b/||b|| || <= tol with the best φ.
inline ::testing::AssertionResult VectorsEqualUpToPhase(const Eigen::VectorXcd& a,
                                                        const Eigen::VectorXcd& b, double tol) {
  if (a.size() != b.size()) {
    return ::testing::AssertionFailure() << "sizes " << a.size() << " vs " << b.size();
  }
  if (a.norm() == 0 || b.norm() == 0) {
    return ::testing::AssertionFailure() << "zero vector";
  }
  const Eigen::VectorXcd ua = a / a.norm(), ub = b / b.norm();
  const std::complex<double> overlap = ub.dot(ua);  // ub^H ua
  const std::complex<double> phase =
      std::abs(overlap) > 0 ? overlap / std::abs(overlap) : std::complex<double>(1.0);
  const double distance = (ua - phase * ub).norm();
  if (!(distance <= tol)) {
    return ::testing::AssertionFailure() << "distance up to phase " << distance << " > " << tol;
  }
  return ::testing::AssertionSuccess();
}

}  // namespace ltp::test
