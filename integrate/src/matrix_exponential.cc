#include "ltp/integrate/detail/matrix_exponential.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <type_traits>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "ltp/integrate/detail/matrix_product.h"

// LAPACK, Fortran interface: LU with partial pivoting and the solve, B overwritten by A⁻¹B.
extern "C" void dgesv_(const int* n, const int* nrhs, double* a, const int* lda, int* ipiv,
                       double* b, const int* ldb, int* info);
extern "C" void zgesv_(const int* n, const int* nrhs, std::complex<double>* a, const int* lda,
                       int* ipiv, std::complex<double>* b, const int* ldb, int* info);
// Diagonal scaling by powers of two (job 'S'): A overwritten by D⁻¹AD, scale = D's diagonal.
extern "C" void dgebal_(const char* job, const int* n, double* a, const int* lda, int* ilo,
                        int* ihi, double* scale, int* info);

namespace ltp::internal {

namespace {

// Higham (2005), Table 2.3: the largest 1-norm for which the degree-m Padé approximant of e^A
// is accurate to the unit round-off of double precision, m = 3, 5, 7, 9.
constexpr std::array<double, 4> kTheta = {1.495585217958292e-2, 2.539398330063230e-1,
                                          9.504178996162932e-1, 2.097847961257068e0};
constexpr double kTheta13 = 5.371920351148152e0;
// Coefficients b_0…b_m of the degree-m numerator p(x) = Σ b_k x^k (the denominator is p(−x)).
constexpr std::array<double, 4> kB3 = {120, 60, 12, 1};
constexpr std::array<double, 6> kB5 = {30240, 15120, 3360, 420, 30, 1};
constexpr std::array<double, 8> kB7 = {17297280, 8648640, 1995840, 277200, 25200, 1512, 56, 1};
constexpr std::array<double, 10> kB9 = {17643225600, 8821612800, 2075673600, 302702400, 30270240,
                                        2162160,     110880,     3960,       90,        1};
constexpr std::array<double, 14> kB13 = {64764752532480000.0,
                                         32382376266240000.0,
                                         7771770303897600.0,
                                         1187353796428800.0,
                                         129060195264000.0,
                                         10559470521600.0,
                                         670442572800.0,
                                         33522128640.0,
                                         1323241920.0,
                                         40840800.0,
                                         960960.0,
                                         16380.0,
                                         182.0,
                                         1.0};

template <typename Scalar>
using Mat = Eigen::Matrix<Scalar, -1, -1>;

// out = (V − U)⁻¹ (V + U): the Padé approximant from its odd part U and even part V.
template <typename Scalar>
void PadeQuotient(Mat<Scalar>& u, Mat<Scalar>& v, Eigen::Ref<Mat<Scalar>> out) {
  out = v + u;
  v -= u;
#ifndef LTP_EIGEN_ONLY
  const int n = static_cast<int>(v.rows()), lda = static_cast<int>(v.outerStride());
  const int ldb = static_cast<int>(out.outerStride());
  std::vector<int> pivots(static_cast<size_t>(n));
  int info = 0;
  if constexpr (std::is_same_v<Scalar, double>)
    dgesv_(&n, &n, v.data(), &lda, pivots.data(), out.data(), &ldb, &info);
  else
    zgesv_(&n, &n, v.data(), &lda, pivots.data(), out.data(), &ldb, &info);
  if (info == 0) return;
  // A singular denominator (only for a non-finite a): let the answer be non-finite, as Eigen's.
  out.setConstant(Scalar(std::numeric_limits<double>::quiet_NaN()));
#else
  out = v.partialPivLu().solve(out).eval();
#endif
}

// U and V of the degree-m approximant (m ≤ 9) from the even powers a², a⁴, ….
template <typename Scalar, size_t N>
void LowDegree(const Eigen::Ref<const Mat<Scalar>>& a, const std::array<double, N>& b,
               Mat<Scalar>& u, Mat<Scalar>& v) {
  const Eigen::Index n = a.rows();
  Mat<Scalar> power = Mat<Scalar>::Identity(n, n), a2(n, n), next(n, n);
  MultiplyInto(a, a, a2);
  Mat<Scalar> odd = b[1] * power;
  v = b[0] * power;
  for (size_t k = 2; k < N; k += 2) {
    MultiplyInto(power, a2, next);
    power.swap(next);
    v += b[k] * power;
    odd += b[k + 1] * power;
  }
  MultiplyInto(a, odd, u);
}

// U and V of the degree-13 approximant (Higham's evaluation: six products).
template <typename Scalar>
void Degree13(const Eigen::Ref<const Mat<Scalar>>& a, Mat<Scalar>& u, Mat<Scalar>& v) {
  const Eigen::Index n = a.rows();
  const auto& b = kB13;
  Mat<Scalar> a2(n, n), a4(n, n), a6(n, n), inner(n, n), product(n, n);
  MultiplyInto(a, a, a2);
  MultiplyInto(a2, a2, a4);
  MultiplyInto(a4, a2, a6);
  const Mat<Scalar> identity = Mat<Scalar>::Identity(n, n);
  inner = b[13] * a6 + b[11] * a4 + b[9] * a2;
  MultiplyInto(a6, inner, product);
  inner = product + b[7] * a6 + b[5] * a4 + b[3] * a2 + b[1] * identity;
  MultiplyInto(a, inner, u);
  inner = b[12] * a6 + b[10] * a4 + b[8] * a2;
  MultiplyInto(a6, inner, product);
  v = product + b[6] * a6 + b[4] * a4 + b[2] * a2 + b[0] * identity;
}

int Squarings(double norm) {
  return std::isfinite(norm) ? std::max(0, static_cast<int>(std::ceil(std::log2(norm / kTheta13))))
                             : 0;
}

template <typename Scalar>
void Exp(const Eigen::Ref<const Mat<Scalar>>& a, Eigen::Ref<Mat<Scalar>> out, bool balance);

// e^A = D e^{D⁻¹AD} D⁻¹ with D a diagonal of powers of two (LAPACK's balancing, exact), where
// that saves squarings: a stiff second-order form [0 I; −K −C] has ‖hA‖₁ ≈ hω² where its
// spectral radius is hω (the 250-state turbine's Magnus steps: 1e5 against about 100, 15
// squarings against 6, 40 % of each exponential's products). Al-Mohy and Higham (SIAM J. Matrix
// Anal. Appl. 31, 2009) balance likewise only where the norm falls. False when it would not.
bool ExpBalanced(const Eigen::Ref<const Mat<double>>& a, double norm, Eigen::Ref<Mat<double>> out) {
#ifdef LTP_EIGEN_ONLY
  (void)a, (void)norm, (void)out;
  return false;
#else
  Mat<double> b = a;
  const int n = static_cast<int>(b.rows()), lda = static_cast<int>(b.outerStride());
  int ilo = 0, ihi = 0, info = 0;
  Eigen::VectorXd scale(n);
  const char job = 'S';
  dgebal_(&job, &n, b.data(), &lda, &ilo, &ihi, scale.data(), &info);
  if (info != 0) return false;
  const double balanced = b.cwiseAbs().colwise().sum().maxCoeff();
  if (!(Squarings(balanced) < Squarings(norm))) return false;
  Exp<double>(b, out, /*balance=*/false);
  out = scale.asDiagonal() * out * scale.cwiseInverse().asDiagonal();
  return true;
#endif
}

template <typename Scalar>
void Exp(const Eigen::Ref<const Mat<Scalar>>& a, Eigen::Ref<Mat<Scalar>> out, bool balance) {
  const Eigen::Index n = a.rows();
  // Small matrices: Eigen's own (the same algorithm; BLAS calls cost more than they save).
  if (n < kBlasColumns) {
    out = a.exp();
    return;
  }
  const double norm = a.cwiseAbs().colwise().sum().maxCoeff();  // the 1-norm
  if constexpr (std::is_same_v<Scalar, double>)
    if (balance && norm > kTheta13 && ExpBalanced(a, norm, out)) return;
  Mat<Scalar> u(n, n), v(n, n);
  for (size_t i = 0; i < kTheta.size(); ++i)
    if (norm <= kTheta[i]) {
      switch (i) {  // the degree m = 2i + 3
        case 0:
          LowDegree<Scalar>(a, kB3, u, v);
          break;
        case 1:
          LowDegree<Scalar>(a, kB5, u, v);
          break;
        case 2:
          LowDegree<Scalar>(a, kB7, u, v);
          break;
        default:
          LowDegree<Scalar>(a, kB9, u, v);
          break;
      }
      PadeQuotient<Scalar>(u, v, out);
      return;
    }
  // Scale into degree 13's range, then square back.
  const int squarings = Squarings(norm);
  const Mat<Scalar> scaled = a * std::ldexp(1.0, -squarings);
  Degree13<Scalar>(scaled, u, v);
  PadeQuotient<Scalar>(u, v, out);
  for (int k = 0; k < squarings; ++k) {
    MultiplyInto(out, out, u);
    out = u;
  }
}

}  // namespace

void ExpInto(const Eigen::Ref<const Eigen::MatrixXd>& a, Eigen::Ref<Eigen::MatrixXd> out) {
  Exp<double>(a, out, /*balance=*/true);
}

bool ExpBalances() {
#ifdef LTP_EIGEN_ONLY
  return false;
#else
  return true;
#endif
}

void ExpInto(const Eigen::Ref<const Eigen::MatrixXcd>& a, Eigen::Ref<Eigen::MatrixXcd> out) {
  Exp<std::complex<double>>(a, out, /*balance=*/false);
}

}  // namespace ltp::internal
