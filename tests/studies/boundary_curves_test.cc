// Stability boundaries as curves (boundary_curves.h): the undamped Mathieu map's transition
// curves against the characteristic values a_m(q), b_m(q), from q = 0 (the tongues' tips, m²) to
// the map's edge; and D_σ = Π (ρ_k − σ) against closed forms, also where the multipliers would
// overflow. docs/stability-boundaries.md, "Curves by continuation".
#include "ltp/studies/boundary_curves.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <iostream>
#include <numbers>
#include <vector>

#include "ltp/models/scene.h"
#include "ltp/studies/chart.h"

namespace ltp {
namespace {

constexpr double kPi = std::numbers::pi;

// The characteristic values of y'' + (a − 2q cos 2t) y = 0 (DLMF 28.2(v), the convention of
// scipy.special.mathieu_a/b) as eigenvalues of the symmetric tridiagonal matrices of the Fourier
// coefficients' recurrences (DLMF 28.4.5–28.4.8; A_0 scaled by √2 for a_2n): an independent
// route, no Floquet theory. family 0: a_2n, 1: a_2n+1, 2: b_2n+1, 3: b_2n+2; sorted ascending.
std::vector<double> CharacteristicValues(int family, double q, int size = 40) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(size, size);
  for (int r = 0; r < size; ++r) {
    const int order = family == 0 ? 2 * r : family == 3 ? 2 * r + 2 : 2 * r + 1;
    M(r, r) = double(order) * order;
    if (r + 1 < size) M(r, r + 1) = M(r + 1, r) = q;
  }
  if (family == 0 && size > 1) M(0, 1) = M(1, 0) = std::sqrt(2.0) * q;
  if (family == 1) M(0, 0) += q;
  if (family == 2) M(0, 0) -= q;
  const Eigen::VectorXd e = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
  return {e.data(), e.data() + e.size()};
}

// a_m(q) (odd = false) or b_m(q).
double Characteristic(int m, bool b, double q) {
  if (!b) return CharacteristicValues(m % 2 == 0 ? 0 : 1, q)[static_cast<size_t>(m / 2)];
  return CharacteristicValues(m % 2 == 1 ? 2 : 3, q)[static_cast<size_t>((m - 1) / 2)];
}

TEST(MathieuCharacteristicValues, ReferenceAgreesWithScipy) {
  // scipy.special.mathieu_a / mathieu_b (SciPy 1.10), printed with %.15g.
  struct Row {
    double q;
    double a[6], b[5];
  };
  const Row rows[] = {
      {0.5,
       {-0.121765544941083, 1.46676684251606, 4.10090059556048, 9.01760692779751, 16.008364622723,
        25.0052094338271},
       {0.470654354933839, 3.97918921575136, 9.01371983892039, 16.0083104597095, 25.0052090102938}},
      {6.0,
       {-7.36883083202679, 1.21427816442045, 7.87006447477531, 12.4656006833377, 17.6887829545602,
        25.8172719926912},
       {-7.3639110118125, 1.35138115480626, 9.13790584614305, 16.8446016443731, 25.7234106518965}}};
  for (const Row& row : rows)
    for (int m = 0; m <= 5; ++m) {
      EXPECT_NEAR(Characteristic(m, false, row.q), row.a[m], 1e-12) << "a_" << m << " " << row.q;
      if (m > 0) {
        EXPECT_NEAR(Characteristic(m, true, row.q), row.b[m - 1], 1e-12)
            << "b_" << m << " " << row.q;
      }
    }
}

TEST(MultiplierDeterminant, ClosedFormsAndNoOverflow) {
  // A rotation by θ: ρ = e^{±jθ}, det(Φ − I) = 2 − 2 cos θ, det(Φ + I) = 2 + 2 cos θ.
  for (double theta : {1e-9, 0.3, 2.0, 3.1}) {
    const std::vector<std::complex<double>> logs = {{0, theta}, {0, -theta}};
    const CharacteristicValue plus = MultiplierDeterminant(logs, 1),
                              minus = MultiplierDeterminant(logs, -1);
    EXPECT_EQ(plus.sign, 1);
    EXPECT_NEAR(plus.log_abs, std::log(4 * std::pow(std::sin(theta / 2), 2)), 1e-12);
    EXPECT_EQ(minus.sign, 1);
    EXPECT_NEAR(minus.log_abs, std::log(4 * std::pow(std::cos(theta / 2), 2)), 1e-9);
  }
  // Real multipliers e^{±x} (a tongue's inside): (e^x − 1)(e^{−x} − 1) = −4 sinh²(x/2) < 0 for
  // σ = +1; for σ = −1 with −e^{±x}: the same; x = 2000 would overflow any product of ρ's.
  for (double x : {1e-8, 0.5, 2000.0}) {
    const std::vector<std::complex<double>> logs = {{x, 0}, {-x, 0}}, neg = {{x, kPi}, {-x, kPi}};
    // log(4 sinh²(x/2)); for x = 2000 it is x to within e^{−x}.
    const double expected = x < 100 ? std::log(4 * std::pow(std::sinh(x / 2), 2)) : x;
    for (const auto& [l, sigma] : {std::pair{logs, 1}, std::pair{neg, -1}}) {
      const CharacteristicValue v = MultiplierDeterminant(l, sigma);
      EXPECT_EQ(v.sign, -1) << x;
      EXPECT_NEAR(v.log_abs, expected, 1e-9 * std::max(1.0, x)) << x;
    }
  }
  // The error bound: ε Σ_k |ρ_k| Π_{j≠k} |ρ_j − σ| for ρ = (2, 0.5), σ = 1: ε (2·0.5 + 0.5·1).
  const CharacteristicValue v =
      MultiplierDeterminant({{std::log(2.0), 0}, {std::log(0.5), 0}}, 1, 1e-10);
  EXPECT_NEAR(std::exp(v.log_abs_error), 1.5e-10, 1e-13);  // plus the round-off floor
}

TEST(BlockDeterminant, ClosedFormAndBoundHoldsForPerturbations) {
  // det of a permuted triangular matrix: −(2 · −3 · 0.5) = 3, sign +1.
  Eigen::MatrixXd M(3, 3);
  M << 0, -3, 7, 2, 1, 4, 0, 0, 0.5;
  const CharacteristicValue v = BlockDeterminant(M);
  EXPECT_EQ(v.sign, 1);
  EXPECT_NEAR(v.log_abs, std::log(3.0), 1e-15);
  EXPECT_EQ(BlockDeterminant(Eigen::MatrixXd::Zero(2, 2)).sign, 0);
  // The bound against det(M + E) − det M in long double, for E of the given entrywise size:
  // a nonsingular block, and one with two singular values near zero (a double root, where the
  // first-order term alone would be far too small).
  Eigen::MatrixXd near_double(3, 3);
  near_double << 1e-9, 2e-9, 1, -1e-9, 3e-9, 2, 0, 1e-9, 0.4;
  std::srand(7);
  for (const Eigen::MatrixXd& block : {M, near_double}) {
    const Eigen::MatrixXd error = Eigen::MatrixXd::Constant(3, 3, 1e-7);
    const CharacteristicValue bounded = BlockDeterminant(block, &error);
    const auto exact = block.cast<long double>().determinant();
    for (int trial = 0; trial < 200; ++trial) {
      const Eigen::MatrixXd E = error.cwiseProduct(Eigen::MatrixXd::Random(3, 3));
      const long double moved = (block + E).cast<long double>().determinant() - exact;
      EXPECT_LE(std::abs(static_cast<double>(moved)), std::exp(bounded.log_abs_error));
    }
  }
}

// The characteristic value a curve of the undamped Mathieu map follows, by its σ and symmetry:
// the even solutions are a_m (ce_m), the odd ones b_m (se_m); σ = +1 for even m. The curve's
// nearest such value with m ≤ 7.
double Deviation(const BoundaryCurve& c, size_t i) {
  const double q = c.points[i][0], a = c.points[i][1];
  double best = INFINITY;
  for (int m = 0; m <= 7; ++m)
    for (bool b : {false, true}) {
      if ((m == 0 && b) || (m % 2 == 0) != (c.kind == BoundaryKind::kRealPlusOne)) continue;
      if (c.symmetry != BoundarySymmetry::kNone && b != (c.symmetry == BoundarySymmetry::kOdd))
        continue;
      best = std::min(best, std::abs(Characteristic(m, b, q) - a));
    }
  return best;
}

TEST(BoundaryCurves, UndampedMathieuMapAgreesWithCharacteristicValues) {
  // The Ince–Strutt map, coarse: the grid misses the thin tips of the tongues; the
  // curves follow them down to the a axis, a_m(0) = b_m(0) = m². Undamped Mathieu is
  // time-reversible, so each curve is the root of one half-period block (y₁(T/2), y₁'(T/2),
  // y₂(T/2) or y₂'(T/2)) and both edges of every tongue are resolved to the tip.
  const Scene scene = LoadScene("mathieu");
  const ParameterMap base = scene.Resolve({{"c", "0"}});
  const PeriodicSystem system = scene.build(base);
  const Chart chart = ComputeChart(
      scene, base, system, {SweepAxis::Parse("q=0:6:0.2"), SweepAxis::Parse("a=-2:27:0.2")}, {});
  const BoundaryCurves& curves = chart.analysis.curves;
  // a_0; b_m and a_m for m = 1..5 (a_6, b_6 start at 36, beyond the map).
  ASSERT_EQ(curves.curves.size(), 11u);
  EXPECT_TRUE(curves.untraced.empty());
  std::vector<double> tips;
  double worst = 0, widest = 0;
  for (const BoundaryCurve& c : curves.curves) {
    ASSERT_GT(c.points.size(), 10u);
    EXPECT_NE(c.symmetry, BoundarySymmetry::kNone);
    EXPECT_EQ(c.end_notes[0], "reached the map's edge");
    EXPECT_EQ(c.end_notes[1], "reached the map's edge");
    for (size_t i = 0; i < c.points.size(); ++i) {
      const double dev = Deviation(c, i);
      // The promise: the boundary within ±bracket, and every bracket within 1e-8, tips included.
      EXPECT_LE(dev, c.bracket[i]) << "q = " << c.points[i][0];
      EXPECT_LE(c.bracket[i], 1e-8) << "q = " << c.points[i][0];
      EXPECT_FALSE(c.merged[i]) << "q = " << c.points[i][0];
      worst = std::max(worst, dev);
      widest = std::max(widest, c.bracket[i]);
      if (c.points[i][0] == 0) tips.push_back(c.points[i][1]);
    }
  }
  std::cout << "largest deviation " << worst << ", widest bracket " << widest << "\n";
  // Every curve reaches q = 0 at m².
  std::sort(tips.begin(), tips.end());
  const double expected[] = {0, 1, 1, 4, 4, 9, 9, 16, 16, 25, 25};
  ASSERT_EQ(tips.size(), 11u);
  for (size_t k = 0; k < tips.size(); ++k) EXPECT_NEAR(tips[k], expected[k], 1e-10);
}

TEST(BoundaryCurves, DampedMathieuMapTracesTheCharacteristicDeterminant) {
  // With damping the system is time-reversible only after the shear (μ ≠ 0): no half-period
  // factorization, the curves follow D_σ (the tongues' edges no longer meet at their tips).
  const Scene scene = LoadScene("mathieu");
  const ParameterMap base = scene.Resolve({{"c", "0.1"}});
  const PeriodicSystem system = scene.build(base);
  const Chart chart = ComputeChart(
      scene, base, system, {SweepAxis::Parse("q=0:3:0.1"), SweepAxis::Parse("a=-1:5:0.1")}, {});
  ASSERT_FALSE(chart.analysis.curves.curves.empty());
  for (const BoundaryCurve& c : chart.analysis.curves.curves)
    EXPECT_EQ(c.symmetry, BoundarySymmetry::kNone);
}

}  // namespace
}  // namespace ltp
