// Tests of the periodic Schur eigenvalues (SLICOT MB03VD + MB03BD), of the periodic Schur form
// itself (MB03VD + MB03VY + MB03BD) and of the periodic
// eigenvectors (block-cyclic null vectors). Reference values are either eig of the formed
// product (well-conditioned cases only) or closed forms of factors built from known pieces.
#include "ltp/floquet/periodic_eigen.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "support/compare.h"

namespace ltp {
namespace {

using Complex = std::complex<double>;
using ltp::test::CompareMatrices;
using ltp::test::ExpectLogEigenvaluesNear;
using ltp::test::VectorsEqualUpToPhase;

/// Uniform in [−1, 1) from the raw mt19937 stream (fully specified by the standard, unlike
/// the std distributions), so the test data are the same on every platform.
class Uniform {
 public:
  explicit Uniform(std::uint32_t seed) : engine_(seed) {}
  double operator()() { return engine_() / 2147483648.0 - 1.0; }
  Eigen::MatrixXd Matrix(int n) {
    Eigen::MatrixXd m(n, n);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = (*this)();
    return m;
  }
  /// A random orthogonal matrix (Q of the QR of a random matrix).
  Eigen::MatrixXd Orthogonal(int n) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(Matrix(n));
    return qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
  }

 private:
  std::mt19937 engine_;
};

Eigen::MatrixXd FormProduct(const std::vector<Eigen::MatrixXd>& factors) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(factors[0].rows(), factors[0].cols());
  for (const Eigen::MatrixXd& f : factors) p = f * p;  // Φ_K ⋯ Φ_1
  return p;
}

/// Segment lengths 1 + 0.5 sin(i), scaled to sum to `period`: deliberately unequal.
std::vector<double> UnequalSegments(int k, double period) {
  std::vector<double> dt(k);
  double sum = 0;
  for (int i = 0; i < k; ++i) sum += dt[i] = 1.0 + 0.5 * std::sin(i + 1.0);
  for (double& d : dt) d *= period / sum;
  return dt;
}

/// Factors Φ_i = Q_{i+1} diag(e^{λ_j dt_i}) Q_iᵀ, Q_K = Q_0, with random orthogonal Q_i. By
/// construction Φ_i Q_i e_j = e^{λ_j dt_i} Q_{i+1} e_j, so the product has eigenvalues
/// e^{λ_j T} and eigenvectors Q_0 e_j, and the periodic eigenvectors are v_i = Q_i e_j.
struct StiffProduct {
  std::vector<Eigen::MatrixXd> factors;
  std::vector<Eigen::MatrixXd> q;  // Q_0 … Q_{K−1}
  std::vector<double> dt;
};

StiffProduct MakeStiffProduct(const Eigen::VectorXd& lambda, int k, double period,
                              std::uint32_t seed) {
  const int n = static_cast<int>(lambda.size());
  Uniform random(seed);
  StiffProduct p;
  p.dt = UnequalSegments(k, period);
  for (int i = 0; i < k; ++i) p.q.push_back(random.Orthogonal(n));
  for (int i = 0; i < k; ++i) {
    const Eigen::VectorXd d = (lambda * p.dt[i]).array().exp();
    p.factors.push_back(p.q[(i + 1) % k] * d.asDiagonal() * p.q[i].transpose());
  }
  return p;
}

// ---------------------------------------------------------------------------------------------
// Periodic Schur eigenvalues.
// ---------------------------------------------------------------------------------------------

class PeriodicSchurRandomTest : public ::testing::TestWithParam<int> {};

TEST_P(PeriodicSchurRandomTest, MatchesEigOfFormedProduct) {
  const int k = GetParam();
  Uniform random(1234 + k);
  std::vector<Eigen::MatrixXd> factors;
  for (int i = 0; i < k; ++i) factors.push_back(random.Matrix(4));

  const LogEigenvalues periodic = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(periodic.ok) << periodic.message;
  // Reference: Eigen eig of the product formed in long double. The eigenvalues of these
  // products span up to ~8 decades (K = 8: log|ρ| from 2.6 to −15.7), which already costs a
  // double-precision formed product ~1e-9 on the smallest; the 64-bit mantissa keeps the
  // reference at ~1e-12 (checked: it agrees with the periodic result to 1e-13).
  using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  MatrixLd product = MatrixLd::Identity(4, 4);
  for (const Eigen::MatrixXd& f : factors) product = f.cast<long double>() * product;
  const Eigen::EigenSolver<MatrixLd> solver(product, /*computeEigenvectors=*/false);
  ASSERT_EQ(solver.info(), Eigen::Success);
  std::vector<Complex> reference;
  for (const std::complex<long double>& rho : solver.eigenvalues()) {
    reference.emplace_back(static_cast<double>(std::log(std::abs(rho))),
                           static_cast<double>(std::arg(rho)));
  }
  ExpectLogEigenvaluesNear(periodic.log_values, reference, 1e-10);

  for (std::size_t i = 1; i < periodic.log_values.size(); ++i) {
    EXPECT_GE(periodic.log_values[i - 1].real(), periodic.log_values[i].real()) << "not sorted";
  }
}

INSTANTIATE_TEST_SUITE_P(PeriodicRandomFactors, PeriodicSchurRandomTest,
                         ::testing::Values(1, 3, 8));

TEST(PeriodicSchurTest, MultipliersSpanningSixHundredDecades) {
  // λ T = (0.1, −5, −300, −1400) with T = 1: the smallest multiplier e^{−1400} ≈ 1e−608 is far
  // below the smallest double. K = 200 unequal segments keep each factor's dynamic range
  // moderate (e^{−1400 dt} ≥ e^{−11}), as in an integrated stiff system, so every log|ρ| is
  // well conditioned with respect to rounding in the factors.
  const Eigen::Vector4d lambda(0.1, -5.0, -300.0, -1400.0);
  const StiffProduct p = MakeStiffProduct(lambda, 200, 1.0, 77);

  const LogEigenvalues periodic = PeriodicSchurLogEigenvalues(p.factors);
  ASSERT_TRUE(periodic.ok) << periodic.message;
  // Closed form by construction: log ρ_j = λ_j T, all real and positive multipliers.
  const std::vector<Complex> expected = {0.1, -5.0, -300.0, -1400.0};
  ExpectLogEigenvaluesNear(periodic.log_values, expected, 1e-9);
  ASSERT_EQ(periodic.log_values.size(), 4u);
  for (int j = 0; j < 4; ++j) {  // sorted descending, so the order is known here
    EXPECT_NEAR(periodic.log_values[j].real(), lambda[j], 1e-9 * std::abs(lambda[j]));
  }

  // The single-shot route on the formed product cannot see below eps · max|ρ|: its two
  // smallest multipliers are rounding noise (or exact zeros), wrong by far more than 1 in
  // log|ρ|. This documents why the periodic route exists.
  const LogEigenvalues single = SingleShotLogEigenvalues(FormProduct(p.factors));
  ASSERT_TRUE(single.ok) << single.message;
  ASSERT_EQ(single.log_values.size(), 4u);
  EXPECT_NEAR(single.log_values[0].real(), 0.1, 1e-10);  // the dominant one is still fine
  EXPECT_GT(std::abs(single.log_values[3].real() - (-1400.0)), 1.0);
  EXPECT_GT(std::abs(single.log_values[2].real() - (-300.0)), 1.0);
}

TEST(PeriodicSchurTest, ComplexPairOfRotationsTimesScalings) {
  // Φ_i = Q_{i+1} blockdiag(r_i R(θ_i), p_i, q_i) Q_iᵀ with R(θ) a plane rotation. The product
  // is Q_0 blockdiag((Π r_i) R(Σ θ_i), Π p_i, Π q_i) Q_0ᵀ, so in closed form
  //   log ρ = Σ log r_i ± j wrap(Σ θ_i),  Σ log|p_i| + j π (K odd, p_i < 0),  Σ log q_i.
  // Every factor is scaled by about e^{−50}: the pair's modulus e^{−500} underflows in double.
  const int k = 9;
  Uniform random(99);
  std::vector<Eigen::MatrixXd> q;
  for (int i = 0; i < k; ++i) q.push_back(random.Orthogonal(4));
  double log_r = 0, theta = 0, log_p = 0, log_q = 0;
  std::vector<Eigen::MatrixXd> factors;
  for (int i = 0; i < k; ++i) {
    const double lr = -50.0 - 0.3 * i, th = 0.4 + 0.1 * i;
    const double lp = -49.0 + 0.05 * i, lq = -51.5;
    log_r += lr;
    theta += th;
    log_p += lp;
    log_q += lq;
    Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
    block.topLeftCorner<2, 2>() << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    block.topLeftCorner<2, 2>() *= std::exp(lr);
    block(2, 2) = -std::exp(lp);
    block(3, 3) = std::exp(lq);
    factors.push_back(q[(i + 1) % k] * block * q[i].transpose());
  }
  const double wrapped = std::remainder(theta, 2 * std::numbers::pi);
  const std::vector<Complex> expected = {
      {log_p, std::numbers::pi}, {log_r, wrapped}, {log_r, -wrapped}, {log_q, 0.0}};

  const LogEigenvalues periodic = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(periodic.ok) << periodic.message;
  ExpectLogEigenvaluesNear(periodic.log_values, expected, 1e-12);
  // Sorted by log|ρ| descending; the conjugate pair is exact and lists +arg first.
  ASSERT_EQ(periodic.log_values.size(), 4u);
  EXPECT_EQ(periodic.log_values[1], std::conj(periodic.log_values[2]));
  EXPECT_GT(periodic.log_values[1].imag(), 0);
  EXPECT_DOUBLE_EQ(periodic.log_values[0].imag(), std::numbers::pi);  // negative real: +π
}

TEST(PeriodicSchurTest, ZeroMultiplierHasMinusInfinityLog) {
  // diag(2, 0) · diag(3, 5): eigenvalues 6 and 0 (closed form).
  const std::vector<Eigen::MatrixXd> factors = {Eigen::Vector2d(3, 5).asDiagonal(),
                                                Eigen::Vector2d(2, 0).asDiagonal()};
  const LogEigenvalues periodic = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(periodic.ok) << periodic.message;
  ASSERT_EQ(periodic.log_values.size(), 2u);
  EXPECT_NEAR(periodic.log_values[0].real(), std::log(6.0), 1e-15);
  EXPECT_EQ(periodic.log_values[1].real(), -std::numeric_limits<double>::infinity());
}

TEST(PeriodicSchurTest, EmptyAndInvalidInput) {
  const LogEigenvalues empty = PeriodicSchurLogEigenvalues({Eigen::MatrixXd(0, 0)});
  EXPECT_TRUE(empty.ok);
  EXPECT_TRUE(empty.log_values.empty());

  EXPECT_FALSE(PeriodicSchurLogEigenvalues({}).ok);

  Eigen::MatrixXd bad = Eigen::MatrixXd::Identity(3, 3);
  bad(1, 2) = std::numeric_limits<double>::quiet_NaN();
  const LogEigenvalues nan = PeriodicSchurLogEigenvalues({Eigen::MatrixXd::Identity(3, 3), bad});
  EXPECT_FALSE(nan.ok);
  EXPECT_NE(nan.message.find("non-finite"), std::string::npos) << nan.message;

  const LogEigenvalues mismatch =
      PeriodicSchurLogEigenvalues({Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Ones(2, 2)});
  EXPECT_FALSE(mismatch.ok);
}

TEST(SingleShotTest, ClosedFormAndInvalidInput) {
  // Rotation by 2π/3 scaled by 2: eigenvalues 2 e^{±j 2π/3} (closed form); plus −3 and 0.
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  const double th = 2 * std::numbers::pi / 3;
  m.topLeftCorner<2, 2>() << 2 * std::cos(th), -2 * std::sin(th), 2 * std::sin(th),
      2 * std::cos(th);
  m(2, 2) = -3;
  const LogEigenvalues single = SingleShotLogEigenvalues(m);
  ASSERT_TRUE(single.ok) << single.message;
  ASSERT_EQ(single.log_values.size(), 4u);
  EXPECT_NEAR(std::abs(single.log_values[0] - Complex(std::log(3.0), std::numbers::pi)), 0, 1e-14);
  EXPECT_NEAR(std::abs(single.log_values[1] - Complex(std::log(2.0), th)), 0, 1e-14);
  EXPECT_NEAR(std::abs(single.log_values[2] - Complex(std::log(2.0), -th)), 0, 1e-14);
  EXPECT_EQ(single.log_values[3].real(), -std::numeric_limits<double>::infinity());

  EXPECT_FALSE(SingleShotLogEigenvalues(Eigen::MatrixXd::Ones(2, 3)).ok);
  Eigen::MatrixXd inf = Eigen::MatrixXd::Identity(2, 2);
  inf(0, 1) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(SingleShotLogEigenvalues(inf).ok);
  EXPECT_TRUE(SingleShotLogEigenvalues(Eigen::MatrixXd(0, 0)).ok);
}

// ---------------------------------------------------------------------------------------------
// The periodic Schur form itself.
// ---------------------------------------------------------------------------------------------

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// max_k ||Z_{k+1} T_k Z_kᵀ − Φ_k||_F / ||Φ_k||_F and max_k ||Z_kᵀ Z_k − I||_F, recomputed from
/// the definition (the reference is the factors themselves).
struct SchurResiduals {
  double reconstruction = 0, orthogonality = 0;
};
SchurResiduals MeasureSchurForm(const std::vector<Eigen::MatrixXd>& factors,
                                const PeriodicSchurForm& s) {
  const std::size_t k = factors.size();
  const Eigen::Index n = factors[0].rows();
  SchurResiduals r;
  for (std::size_t i = 0; i < k; ++i) {
    const Eigen::MatrixXd back = s.z[(i + 1) % k] * s.t[i] * s.z[i].transpose();
    r.reconstruction = std::max(r.reconstruction, (back - factors[i]).norm() / factors[i].norm());
    r.orthogonality = std::max(
        r.orthogonality, (s.z[i].transpose() * s.z[i] - Eigen::MatrixXd::Identity(n, n)).norm());
  }
  return r;
}

/// The structure SLICOT promises: T_k upper triangular for k < K−1, T_{K−1} quasi-upper-
/// triangular (zero below the subdiagonal, no two consecutive subdiagonal entries), every entry
/// below exactly 0. Each 2×2 block holds a complex pair, diagonal order = log_values order.
void ExpectSchurStructure(const PeriodicSchurForm& s) {
  const int k = static_cast<int>(s.t.size());
  const int n = static_cast<int>(s.t[0].rows());
  ASSERT_EQ(s.quasi_triangular, k - 1);
  ASSERT_EQ(s.log_values.size(), static_cast<std::size_t>(n));
  for (int i = 0; i < k; ++i) {
    const int first_zero = i == k - 1 ? 2 : 1;
    for (int c = 0; c < n; ++c)
      for (int r = c + first_zero; r < n; ++r)
        EXPECT_EQ(s.t[i](r, c), 0.0) << "T_" << i << "(" << r << ", " << c << ")";
  }
  const Eigen::MatrixXd& quasi = s.t[k - 1];
  for (int p = 0; p + 1 < n; ++p) {
    const bool block = quasi(p + 1, p) != 0.0;
    const bool pair =
        s.log_values[p].imag() != 0 && s.log_values[p] == std::conj(s.log_values[p + 1]);
    if (block) {
      EXPECT_TRUE(pair) << "2x2 block at " << p << " but log values " << s.log_values[p] << ", "
                        << s.log_values[p + 1];
      EXPECT_GT(s.log_values[p].imag(), 0) << "the pair lists +arg first";
      if (p + 2 < n) {
        EXPECT_EQ(quasi(p + 2, p + 1), 0.0) << "two consecutive subdiagonal entries";
      }
      ++p;
    }
  }
}

class PeriodicSchurFormRandomTest : public ::testing::TestWithParam<int> {};

TEST_P(PeriodicSchurFormRandomTest, ReconstructsTheFactorsWithOrthogonalZ) {
  // Random 6×6 factors (complex pairs likely). References: (a) the factors themselves and the
  // definition Z_{k+1} T_k Z_kᵀ = Φ_k, ZᵀZ = I; (b) SLICOT's structure; (c) the eigenvalue-only
  // route PeriodicSchurLogEigenvalues (JOB = 'E', log ρ from ALPHA, BETA and SCAL), a different
  // computation from this one's sums of logs of the Schur form's diagonal.
  const int k = GetParam();
  Uniform random(2024 + k);
  std::vector<Eigen::MatrixXd> factors;
  for (int i = 0; i < k; ++i) factors.push_back(random.Matrix(6));
  const PeriodicSchurForm s = PeriodicSchurDecomposition(factors);
  ASSERT_TRUE(s.ok) << s.message;
  ASSERT_EQ(s.t.size(), static_cast<std::size_t>(k));
  ASSERT_EQ(s.z.size(), static_cast<std::size_t>(k));
  const SchurResiduals r = MeasureSchurForm(factors, s);
  EXPECT_LT(r.reconstruction, 100 * kEps) << "K = " << k;
  EXPECT_LT(r.orthogonality, 100 * kEps) << "K = " << k;
  ExpectSchurStructure(s);

  const LogEigenvalues eig = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(eig.ok) << eig.message;
  ExpectLogEigenvaluesNear(s.log_values, eig.log_values, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(PeriodicRandomFactors, PeriodicSchurFormRandomTest,
                         ::testing::Values(1, 2, 5, 12));

TEST(PeriodicSchurFormTest, PlusMinusThousandWhereTheFormedProductOverflows) {
  // Φ_k = Q_{k+1} diag(e^{1000/K}, e^{−1000/K}) Q_kᵀ with random orthogonal Q_k (Q_K = Q_0):
  // the product is Q_0 diag(e^{1000}, e^{−1000}) Q_0ᵀ in closed form, log ρ = ±1000 exactly.
  // e^{1000} is beyond the double range: the formed product holds inf. K = 200 keeps each
  // factor's range e^{±5}, as in an integrated system: forming Φ_k in double perturbs its small
  // component by about eps e^{10} relative (measured: −1000 to 8e-12 absolute). With K = 20
  // (e^{±50}) that rounding, eps · e^{50}, is larger than e^{−50} itself and the factors no
  // longer hold the small multiplier (both routes then report −inf): a limit of the data.
  const int k = 200;
  const StiffProduct p = MakeStiffProduct(Eigen::Vector2d(1000.0, -1000.0), k, 1.0, 11);
  EXPECT_FALSE(FormProduct(p.factors).allFinite());
  const PeriodicSchurForm s = PeriodicSchurDecomposition(p.factors);
  ASSERT_TRUE(s.ok) << s.message;
  ExpectSchurStructure(s);
  const SchurResiduals r = MeasureSchurForm(p.factors, s);
  EXPECT_LT(r.reconstruction, 100 * kEps);
  EXPECT_LT(r.orthogonality, 100 * kEps);
  ASSERT_EQ(s.log_values.size(), 2u);
  // Schur order (not sorted): whichever comes first, the two are +1000 and −1000, real.
  const Complex high = s.log_values[0].real() > 0 ? s.log_values[0] : s.log_values[1];
  const Complex low = s.log_values[0].real() > 0 ? s.log_values[1] : s.log_values[0];
  EXPECT_LE(std::abs(high - 1000.0), 1e-12 * 1000.0) << high;
  EXPECT_LE(std::abs(low + 1000.0), 1e-12 * 1000.0) << low;
}

TEST(PeriodicSchurFormTest, ComplexPairAndSignsInClosedForm) {
  // Φ_i = Q_{i+1} blockdiag(e^{−600/K} R(θ_i), e^{800/K}, −e^{−900/K}) Q_iᵀ, K = 201 (odd):
  // log ρ = −600 ± j wrap(Σθ_i), 800, −900 + jπ in closed form; e^{800} overflows and e^{−900}
  // underflows in the formed product. The pair must come out as a 2×2 block of T_{K−1}. K = 201
  // keeps each factor's range at e^{8.5} (see the test above for why it matters).
  const int k = 201;
  Uniform random(5151);
  std::vector<Eigen::MatrixXd> q, factors;
  for (int i = 0; i < k; ++i) q.push_back(random.Orthogonal(4));
  double theta = 0;
  for (int i = 0; i < k; ++i) {
    const double th = 0.2 + 0.001 * i;
    theta += th;
    Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
    block.topLeftCorner<2, 2>() << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    block.topLeftCorner<2, 2>() *= std::exp(-600.0 / k);
    block(2, 2) = std::exp(800.0 / k);
    block(3, 3) = -std::exp(-900.0 / k);
    factors.push_back(q[(i + 1) % k] * block * q[i].transpose());
  }
  const double wrapped = std::remainder(theta, 2 * std::numbers::pi);
  const std::vector<Complex> expected = {
      {-600.0, wrapped}, {-600.0, -wrapped}, {800.0, 0.0}, {-900.0, std::numbers::pi}};
  const PeriodicSchurForm s = PeriodicSchurDecomposition(factors);
  ASSERT_TRUE(s.ok) << s.message;
  ExpectSchurStructure(s);
  const SchurResiduals r = MeasureSchurForm(factors, s);
  EXPECT_LT(r.reconstruction, 100 * kEps);
  EXPECT_LT(r.orthogonality, 100 * kEps);
  ExpectLogEigenvaluesNear(s.log_values, expected, 1e-12);
  int blocks = 0;
  for (int p = 0; p + 1 < 4; ++p) blocks += s.t[k - 1](p + 1, p) != 0.0;
  EXPECT_EQ(blocks, 1);
}

TEST(PeriodicSchurFormTest, ZeroEmptyAndInvalidInput) {
  // diag(2, 0) · diag(3, 5): log ρ = log 6 and −inf (closed form), already in Schur form.
  const PeriodicSchurForm zero = PeriodicSchurDecomposition(
      {Eigen::Vector2d(3, 5).asDiagonal(), Eigen::Vector2d(2, 0).asDiagonal()});
  ASSERT_TRUE(zero.ok) << zero.message;
  ASSERT_EQ(zero.log_values.size(), 2u);
  const Complex finite =
      std::isfinite(zero.log_values[0].real()) ? zero.log_values[0] : zero.log_values[1];
  const Complex infinite =
      std::isfinite(zero.log_values[0].real()) ? zero.log_values[1] : zero.log_values[0];
  EXPECT_NEAR(std::abs(finite - std::log(6.0)), 0, 1e-15);
  EXPECT_EQ(infinite.real(), -std::numeric_limits<double>::infinity());

  const PeriodicSchurForm empty = PeriodicSchurDecomposition({Eigen::MatrixXd(0, 0)});
  EXPECT_TRUE(empty.ok);
  EXPECT_TRUE(empty.log_values.empty());
  EXPECT_EQ(empty.t.size(), 1u);
  EXPECT_FALSE(PeriodicSchurDecomposition({}).ok);
  Eigen::MatrixXd bad = Eigen::MatrixXd::Identity(3, 3);
  bad(0, 1) = std::numeric_limits<double>::infinity();
  const PeriodicSchurForm inf = PeriodicSchurDecomposition({bad});
  EXPECT_FALSE(inf.ok);
  EXPECT_NE(inf.message.find("non-finite"), std::string::npos) << inf.message;
  EXPECT_FALSE(
      PeriodicSchurDecomposition({Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Ones(2, 3)})
          .ok);
}

// ---------------------------------------------------------------------------------------------
// Periodic eigenvectors.
// ---------------------------------------------------------------------------------------------

/// max_i ||Φ_i v_i − σ_i v_{i+1}|| / (||Φ_i||_F + |σ_i|), recomputed independently.
double CyclicResidual(const std::vector<Eigen::MatrixXd>& factors, const std::vector<double>& dt,
                      Complex log_rho, const PeriodicEigenvector& vec) {
  const std::size_t k = factors.size();
  double period = 0;
  for (double d : dt) period += d;
  double worst = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Complex sigma = std::exp(log_rho * dt[i] / period);
    const double r = (factors[i] * vec.v[i] - sigma * vec.v[(i + 1) % k]).norm() /
                     (factors[i].norm() + std::abs(sigma));
    worst = std::max(worst, r);
  }
  return worst;
}

double MaxBlockNorm(const PeriodicEigenvector& vec) {
  double m = 0;
  for (const Eigen::VectorXcd& v : vec.v) m = std::max(m, v.norm());
  return m;
}

class PeriodicEigenvectorsRandomTest : public ::testing::TestWithParam<int> {};

TEST_P(PeriodicEigenvectorsRandomTest, CyclicRelationAndEigenvectorOfProduct) {
  const int k = GetParam();
  Uniform random(555 + k);
  std::vector<Eigen::MatrixXd> factors;
  for (int i = 0; i < k; ++i) factors.push_back(random.Matrix(4));
  const std::vector<double> dt = UnequalSegments(k, 2.5);
  const LogEigenvalues eig = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(eig.ok) << eig.message;

  const std::vector<PeriodicEigenvector> vecs =
      ComputePeriodicEigenvectors(factors, dt, eig.log_values);
  ASSERT_EQ(vecs.size(), eig.log_values.size());
  const Eigen::MatrixXd product = FormProduct(factors);
  for (std::size_t j = 0; j < vecs.size(); ++j) {
    ASSERT_EQ(vecs[j].v.size(), static_cast<std::size_t>(k));
    EXPECT_NEAR(MaxBlockNorm(vecs[j]), 1.0, 1e-14);
    EXPECT_LT(vecs[j].residual, 1e-12);
    EXPECT_LT(CyclicResidual(factors, dt, eig.log_values[j], vecs[j]), 1e-12);
    // v_0 is an eigenvector of the formed product (well conditioned here): P v_0 = ρ v_0.
    const Complex rho = std::exp(eig.log_values[j]);
    const Eigen::VectorXcd& v0 = vecs[j].v[0];
    EXPECT_LT((product * v0 - rho * v0).norm(), 1e-11 * product.norm() * v0.norm())
        << "eigenvalue " << j;
  }
}

INSTANTIATE_TEST_SUITE_P(PeriodicRandomFactors, PeriodicEigenvectorsRandomTest,
                         ::testing::Values(1, 3, 8));

// Six random 7 × 7 factors: isolated multipliers of every kind, vectors by the Schur route.
std::vector<Eigen::MatrixXd> SixRandomFactors(std::uint32_t seed) {
  Uniform random(seed);
  std::vector<Eigen::MatrixXd> factors;
  for (int i = 0; i < 6; ++i) factors.push_back(random.Matrix(7));
  return factors;
}

// An analysis that has the periodic Schur form already passes it in: the multipliers from the
// form's diagonal (LogEigenvaluesOf) match the eigenvalue-only route (a different SLICOT job and
// another formula for log ρ) in the same sorted order, and the vectors are those computed
// without it, with their cyclic relation at round-off.
TEST(PeriodicEigenvectorsTest, AGivenSchurFormGivesTheSameMultipliersAndVectors) {
  const std::vector<Eigen::MatrixXd> factors = SixRandomFactors(909);
  const std::vector<double> dt = UnequalSegments(6, 1.5);
  const PeriodicSchurForm form = PeriodicSchurDecomposition(factors);
  ASSERT_TRUE(form.ok) << form.message;
  const LogEigenvalues from_form = LogEigenvaluesOf(form);
  const LogEigenvalues eigenvalue_only = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(from_form.ok && eigenvalue_only.ok);
  ASSERT_EQ(from_form.log_values.size(), eigenvalue_only.log_values.size());
  for (std::size_t j = 0; j < from_form.log_values.size(); ++j)
    EXPECT_LT(std::abs(from_form.log_values[j] - eigenvalue_only.log_values[j]), 1e-12) << j;
  const std::vector<PeriodicEigenvector> given =
      ComputePeriodicEigenvectors(factors, dt, from_form.log_values, 1, &form);
  const std::vector<PeriodicEigenvector> own =
      ComputePeriodicEigenvectors(factors, dt, from_form.log_values, 2);
  for (std::size_t j = 0; j < given.size(); ++j) {
    EXPECT_EQ(given[j].method, PeriodicEigenvectorMethod::kSchur) << j;
    EXPECT_LT(given[j].residual, 1e-12) << j;
    EXPECT_LT(CyclicResidual(factors, dt, from_form.log_values[j], given[j]), 1e-12) << j;
    for (std::size_t i = 0; i < given[j].v.size(); ++i)
      EXPECT_LT((given[j].v[i] - own[j].v[i]).norm(), 1e-13) << j << ", " << i;
  }
  EXPECT_FALSE(LogEigenvaluesOf(PeriodicSchurForm{}).ok);
}

// The factors multiplied in consecutive groups of r, Φ_{r−1}⋯Φ_0 first.
std::vector<Eigen::MatrixXd> Grouped(const std::vector<Eigen::MatrixXd>& factors, int r) {
  std::vector<Eigen::MatrixXd> groups;
  for (std::size_t i = 0; i < factors.size(); i += r) {
    Eigen::MatrixXd product = Eigen::MatrixXd::Identity(factors[i].rows(), factors[i].cols());
    for (std::size_t j = i; j < i + r; ++j) product = factors[j] * product;
    groups.push_back(product);
  }
  return groups;
}

Eigen::VectorXcd Stacked(const PeriodicEigenvector& vec) {
  Eigen::VectorXcd all(static_cast<Eigen::Index>(vec.v.size()) * vec.v[0].size());
  for (std::size_t i = 0; i < vec.v.size(); ++i)
    all.segment(static_cast<Eigen::Index>(i) * vec.v[0].size(), vec.v[0].size()) = vec.v[i];
  return all;
}

// An analysis whose grid was cut finer than its factors need takes the Schur form of the
// factors in groups (floquet.cc, FactorsPerForm); the vectors inside a group then come from the
// factors. They must be the vectors at every factor all the same: against the route through the
// form of every factor, and by their own cyclic residual.
TEST(PeriodicEigenvectorsTest, AFormOfGroupedFactorsGivesTheVectorsAtEveryFactor) {
  const std::vector<Eigen::MatrixXd> factors = SixRandomFactors(913);
  const std::vector<double> dt = UnequalSegments(6, 1.5);
  const LogEigenvalues every = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(every.ok);
  const std::vector<PeriodicEigenvector> own =
      ComputePeriodicEigenvectors(factors, dt, every.log_values, 1);
  for (int r : {2, 3, 6}) {
    const PeriodicSchurForm form = PeriodicSchurDecomposition(Grouped(factors, r));
    ASSERT_TRUE(form.ok) << form.message;
    const LogEigenvalues grouped = LogEigenvaluesOf(form);
    ASSERT_TRUE(grouped.ok);
    const std::vector<double> distance =
        ltp::MatchExponents(every.log_values, grouped.log_values, 2 * std::numbers::pi);
    for (double d : distance) EXPECT_LT(d, 1e-12) << "groups of " << r;
    const std::vector<PeriodicEigenvector> given =
        ComputePeriodicEigenvectors(factors, dt, every.log_values, 2, &form);
    for (std::size_t j = 0; j < given.size(); ++j) {
      EXPECT_EQ(given[j].method, PeriodicEigenvectorMethod::kSchur) << j << ", groups of " << r;
      EXPECT_LT(CyclicResidual(factors, dt, every.log_values[j], given[j]), 1e-12) << j;
      EXPECT_TRUE(VectorsEqualUpToPhase(Stacked(given[j]), Stacked(own[j]), 1e-12))
          << j << ", groups of " << r;
    }
  }
}

// The same through six hundred decades (the closed form of the test below, v_i = Q_i e_j at
// every factor): the factors inside a group carry the vectors without losing the fast-decaying
// ones. An analysis groups factors only while a group stays within the condition limit (1000,
// StartingGrid): here K = 1000, so groups of 2 and 4 span e^{2.8} and e^{5.6}. (At e^{14}, beyond
// the limit, the −1400 mode's residual is 5e-10 and it goes to the inverse iteration instead.)
TEST(PeriodicEigenvectorsTest, GroupedFormKeepsSixHundredDecadesAtEveryFactor) {
  const Eigen::Vector4d lambda(0.1, -5.0, -300.0, -1400.0);
  const StiffProduct p = MakeStiffProduct(lambda, 1000, 1.0, 77);
  const std::vector<Complex> log_rho = {0.1, -5.0, -300.0, -1400.0};
  for (int r : {2, 4}) {
    const PeriodicSchurForm form = PeriodicSchurDecomposition(Grouped(p.factors, r));
    ASSERT_TRUE(form.ok) << form.message;
    const std::vector<PeriodicEigenvector> vecs =
        ComputePeriodicEigenvectors(p.factors, p.dt, log_rho, 1, &form);
    for (int j = 0; j < 4; ++j) {
      EXPECT_EQ(vecs[j].method, PeriodicEigenvectorMethod::kSchur) << j << ", groups of " << r;
      EXPECT_LT(CyclicResidual(p.factors, p.dt, log_rho[j], vecs[j]), 1e-12) << j;
      for (int i : {0, 1, r - 1, 501, 999})
        EXPECT_TRUE(VectorsEqualUpToPhase(vecs[j].v[i], p.q[i].col(j).cast<Complex>(), 1e-10))
            << "mode " << j << ", factor " << i << ", groups of " << r;
    }
  }
}

TEST(PeriodicEigenvectorsTest, SixHundredDecadesMatchClosedForm) {
  // Same construction as MultipliersSpanningSixHundredDecades: v_i = Q_i e_j exactly.
  const Eigen::Vector4d lambda(0.1, -5.0, -300.0, -1400.0);
  const StiffProduct p = MakeStiffProduct(lambda, 200, 1.0, 77);
  const std::vector<Complex> log_rho = {0.1, -5.0, -300.0, -1400.0};

  const std::vector<PeriodicEigenvector> vecs =
      ComputePeriodicEigenvectors(p.factors, p.dt, log_rho);
  ASSERT_EQ(vecs.size(), 4u);
  for (int j = 0; j < 4; ++j) {
    EXPECT_LT(vecs[j].residual, 1e-12) << "mode " << j;
    EXPECT_LT(CyclicResidual(p.factors, p.dt, log_rho[j], vecs[j]), 1e-12) << "mode " << j;
    const Eigen::VectorXcd expected = p.q[0].col(j).cast<Complex>();
    EXPECT_TRUE(VectorsEqualUpToPhase(vecs[j].v[0], expected, 1e-10)) << "mode " << j;
    // All v_i have unit norm by construction (orthogonal Q_i, σ_i = exact step factor).
    EXPECT_NEAR(vecs[j].v[100].norm(), 1.0, 1e-10) << "mode " << j;
    // Isolated multipliers: the periodic Schur route, not the per-mode sparse LU.
    EXPECT_EQ(vecs[j].method, PeriodicEigenvectorMethod::kSchur) << "mode " << j;
  }
}

TEST(PeriodicEigenvectorsTest, ComplexPairAcrossHundredsOfDecadesMatchesClosedForm) {
  // Φ_i = Q_{i+1} blockdiag(e^{a_i} R(θ_i), −e^{b_i}, e^{c_i}) Q_iᵀ, K = 200 unequal segments:
  // R(θ)(1, −j)ᵀ = e^{jθ}(1, −j)ᵀ, so the pair's periodic eigenvectors are v_i ∝ Q_i (e_1 ∓ j e_2)
  // and the real ones v_i ∝ Q_i e_3, Q_i e_4 (closed form, up to one scalar per i). The pair
  // decays by e^{−600} per period against e^{+2} and e^{−1200} for the others: the Schur route
  // has to split the 2×2 block (complex pair) and run the recurrences both ways. K = 200 keeps
  // each factor's range moderate (e^{−1200 dt} ≥ e^{−9}), as in an integrated stiff system.
  const int k = 200;
  Uniform random(4242);
  std::vector<Eigen::MatrixXd> q, factors;
  for (int i = 0; i < k; ++i) q.push_back(random.Orthogonal(4));
  const std::vector<double> dt = UnequalSegments(k, 1.0);
  double theta = 0;
  for (int i = 0; i < k; ++i) {
    const double th = 0.3 + 0.02 * i;
    theta += th;
    Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
    block.topLeftCorner<2, 2>() << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    block.topLeftCorner<2, 2>() *= std::exp(-600.0 * dt[i]);
    block(2, 2) = -std::exp(2.0 * dt[i]);
    block(3, 3) = std::exp(-1200.0 * dt[i]);
    factors.push_back(q[(i + 1) % k] * block * q[i].transpose());
  }
  const double wrapped = std::remainder(theta, 2 * std::numbers::pi);
  // The third block changes sign in every segment; K = 200 is even, so its multiplier is e^{+2}.
  const std::vector<Complex> log_rho = {
      {2.0, 0.0}, {-600.0, wrapped}, {-600.0, -wrapped}, {-1200.0, 0.0}};
  const LogEigenvalues eig = PeriodicSchurLogEigenvalues(factors);
  ASSERT_TRUE(eig.ok) << eig.message;
  ExpectLogEigenvaluesNear(eig.log_values, log_rho, 1e-9);

  const std::vector<PeriodicEigenvector> vecs = ComputePeriodicEigenvectors(factors, dt, log_rho);
  ASSERT_EQ(vecs.size(), 4u);
  const Complex j1(0, 1);
  for (int m = 0; m < 4; ++m) {
    EXPECT_EQ(vecs[m].method, PeriodicEigenvectorMethod::kSchur) << "mode " << m;
    EXPECT_LT(CyclicResidual(factors, dt, log_rho[m], vecs[m]), 1e-12) << "mode " << m;
    for (int i : {0, 77, 199}) {
      Eigen::VectorXcd expected;
      if (m == 0) expected = q[i].col(2).cast<Complex>();
      if (m == 1) expected = (q[i].col(0) - j1 * q[i].col(1)) / std::sqrt(2.0);
      if (m == 2) expected = (q[i].col(0) + j1 * q[i].col(1)) / std::sqrt(2.0);
      if (m == 3) expected = q[i].col(3).cast<Complex>();
      const Eigen::VectorXcd v = vecs[m].v[i] / vecs[m].v[i].norm();
      EXPECT_NEAR(std::abs(expected.dot(v)), 1.0, 1e-12) << "mode " << m << ", segment " << i;
    }
  }
}

TEST(PeriodicEigenvectorsTest, IdentityFactorsGiveIndependentVectors) {
  // Φ_i = I: every ρ = 1 (log ρ = 0), a triple non-defective cluster; any v works, so the
  // returned sets must be made independent: rank [v_0^(1) v_0^(2) v_0^(3)] = 3.
  for (int k : {1, 4}) {
    const std::vector<Eigen::MatrixXd> factors(k, Eigen::MatrixXd::Identity(3, 3));
    const std::vector<double> dt(k, 0.25);
    const std::vector<PeriodicEigenvector> vecs =
        ComputePeriodicEigenvectors(factors, dt, {0.0, 0.0, 0.0});
    ASSERT_EQ(vecs.size(), 3u);
    Eigen::Matrix3cd v0;
    for (int j = 0; j < 3; ++j) {
      EXPECT_LT(vecs[j].residual, 1e-12);
      EXPECT_EQ(vecs[j].method, PeriodicEigenvectorMethod::kInverseIteration);  // a cluster
      v0.col(j) = vecs[j].v[0];
    }
    const Eigen::JacobiSVD<Eigen::Matrix3cd> svd(v0);
    EXPECT_GT(svd.singularValues()(2), 0.1 * svd.singularValues()(0)) << "K = " << k;
  }
}

TEST(PeriodicEigenvectorsTest, CloseButDistinctEigenvaluesGetTheirOwnVectors) {
  // Φ_i = Q_{i+1} diag(e^{λ dt_i}) Q_iᵀ with λ_2 − λ_1 = 1e-9: inside the cluster tolerance,
  // yet each member must converge to its own closed-form vector Q_0 e_j rather than to a
  // common one (which would be ~1 away from one of them). The achievable accuracy is set by
  // the gap: the second-smallest singular value of the lifted matrix is 1.2e-10, so rounding
  // in the factors alone moves the vectors by ~eps/1.2e-10 ≈ 1e-6 (a dense SVD null vector
  // is off by 2e-7 and 6e-7; this routine by 4e-6 and 7e-7). Hence the loose tolerance.
  const Eigen::Vector3d lambda(-1.0, -1.0 + 1e-9, 0.5);
  const StiffProduct p = MakeStiffProduct(lambda, 5, 2.0, 31);
  const std::vector<Complex> log_rho = {2.0 * lambda[0], 2.0 * lambda[1], 2.0 * lambda[2]};
  const std::vector<PeriodicEigenvector> vecs =
      ComputePeriodicEigenvectors(p.factors, p.dt, log_rho);
  for (int j = 0; j < 3; ++j) {
    EXPECT_LT(vecs[j].residual, 1e-12) << "mode " << j;
    EXPECT_TRUE(VectorsEqualUpToPhase(vecs[j].v[0], p.q[0].col(j).cast<Complex>(), 3e-5))
        << "mode " << j;
  }
}

TEST(PeriodicEigenvectorsTest, SingleFactorGivesPlainEigenvectors) {
  // K = 1: v_0 is an eigenvector of Φ_1 itself (diagonal: closed-form eigenvectors e_j).
  const std::vector<Eigen::MatrixXd> factors = {Eigen::Vector3d(2.0, -0.5, 0.1).asDiagonal()};
  const std::vector<Complex> log_rho = {
      std::log(2.0), {std::log(0.5), std::numbers::pi}, std::log(0.1)};
  const std::vector<PeriodicEigenvector> vecs =
      ComputePeriodicEigenvectors(factors, {1.0}, log_rho);
  for (int j = 0; j < 3; ++j) {
    EXPECT_TRUE(VectorsEqualUpToPhase(vecs[j].v[0], Eigen::Vector3cd::Unit(j), 1e-12));
    EXPECT_LT(vecs[j].residual, 1e-14);
  }
}

TEST(PeriodicEigenvectorsTest, DefectiveClusterDoesNotCrash) {
  // Jordan block [[1, 1], [0, 1]]: ρ = 1 twice but one eigenvector e_1. The two returned sets
  // are (nearly) parallel — detected downstream by the mode matrix's condition number.
  const std::vector<Eigen::MatrixXd> factors = {(Eigen::Matrix2d() << 1, 1, 0, 1).finished()};
  const std::vector<PeriodicEigenvector> vecs =
      ComputePeriodicEigenvectors(factors, {1.0}, {0.0, 0.0});
  ASSERT_EQ(vecs.size(), 2u);
  for (const PeriodicEigenvector& vec : vecs) {
    ASSERT_TRUE(vec.v[0].allFinite());
    EXPECT_NEAR(vec.v[0].norm(), 1.0, 1e-14);
    EXPECT_LT(vec.residual, 1e-6);  // an eigenvector of a Jordan block is only ~sqrt(eps) accurate
  }
}

TEST(PeriodicEigenvectorsTest, InvalidInputThrows) {
  const std::vector<Eigen::MatrixXd> factors(2, Eigen::MatrixXd::Identity(2, 2));
  EXPECT_THROW(ComputePeriodicEigenvectors(factors, {1.0}, {0.0}), InputError);
  EXPECT_THROW(ComputePeriodicEigenvectors(factors, {1.0, -1.0}, {0.0}), InputError);
  EXPECT_THROW(ComputePeriodicEigenvectors(factors, {1.0, 1.0},
                                           {Complex(std::numeric_limits<double>::quiet_NaN(), 0)}),
               InputError);
  EXPECT_THROW(ComputePeriodicEigenvectors({}, {}, {0.0}), InputError);
}

}  // namespace
}  // namespace ltp
