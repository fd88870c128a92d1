#include "ltp/integrate/detail/matrix_product.h"

#include <complex>

// BLAS, Fortran interface (OpenBLAS here).
extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const double* alpha, const double* a, const int* lda,
                       const double* b, const int* ldb, const double* beta, double* c,
                       const int* ldc);
extern "C" void zgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const std::complex<double>* alpha,
                       const std::complex<double>* a, const int* lda, const std::complex<double>* b,
                       const int* ldb, const std::complex<double>* beta, std::complex<double>* c,
                       const int* ldc);

namespace ltp::internal {

namespace {

// out = a · b + beta · out through `gemm` (dgemm_ or zgemm_) from the work of a square product of
// kBlasColumns on (tall products too: the Taylor stepper's weighted sums of its terms), else
// Eigen.
template <typename Scalar, typename Gemm>
void Multiply(Gemm gemm, const Eigen::Ref<const Eigen::Matrix<Scalar, -1, -1>>& a,
              const Eigen::Ref<const Eigen::Matrix<Scalar, -1, -1>>& b,
              Eigen::Ref<Eigen::Matrix<Scalar, -1, -1>> out, Scalar beta) {
#ifndef LTP_EIGEN_ONLY
  constexpr double kBlasWork = double(kBlasColumns) * kBlasColumns * kBlasColumns;
  if (double(a.rows()) * double(a.cols()) * double(b.cols()) >= kBlasWork) {
    const char no = 'N';
    const Scalar one = 1;
    const int m = static_cast<int>(a.rows()), n = static_cast<int>(b.cols());
    const int k = static_cast<int>(a.cols());
    const int lda = static_cast<int>(a.outerStride()), ldb = static_cast<int>(b.outerStride());
    const int ldc = static_cast<int>(out.outerStride());
    gemm(&no, &no, &m, &n, &k, &one, a.data(), &lda, b.data(), &ldb, &beta, out.data(), &ldc);
    return;
  }
#else
  (void)gemm;
#endif
  if (beta == Scalar(0)) {
    out.noalias() = a * b;
  } else {
    out *= beta;
    out.noalias() += a * b;
  }
}

}  // namespace

void MultiplyInto(const Eigen::Ref<const Eigen::MatrixXd>& a,
                  const Eigen::Ref<const Eigen::MatrixXd>& b, Eigen::Ref<Eigen::MatrixXd> out,
                  double beta) {
  Multiply<double>(dgemm_, a, b, out, beta);
}

void MultiplyInto(const Eigen::Ref<const Eigen::MatrixXcd>& a,
                  const Eigen::Ref<const Eigen::MatrixXcd>& b, Eigen::Ref<Eigen::MatrixXcd> out) {
  Multiply<std::complex<double>>(zgemm_, a, b, out, 0);
}

}  // namespace ltp::internal
