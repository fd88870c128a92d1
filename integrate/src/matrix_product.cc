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

// out = a · b through `gemm` (dgemm_ or zgemm_) from kBlasColumns columns on, else Eigen.
template <typename Scalar, typename Gemm>
void Multiply(Gemm gemm, const Eigen::Ref<const Eigen::Matrix<Scalar, -1, -1>>& a,
              const Eigen::Ref<const Eigen::Matrix<Scalar, -1, -1>>& b,
              Eigen::Ref<Eigen::Matrix<Scalar, -1, -1>> out) {
#ifndef LTP_EIGEN_ONLY
  if (b.cols() >= kBlasColumns) {
    const char no = 'N';
    const Scalar one = 1, zero = 0;
    const int m = static_cast<int>(a.rows()), n = static_cast<int>(b.cols());
    const int k = static_cast<int>(a.cols());
    const int lda = static_cast<int>(a.outerStride()), ldb = static_cast<int>(b.outerStride());
    const int ldc = static_cast<int>(out.outerStride());
    gemm(&no, &no, &m, &n, &k, &one, a.data(), &lda, b.data(), &ldb, &zero, out.data(), &ldc);
    return;
  }
#else
  (void)gemm;
#endif
  out.noalias() = a * b;
}

}  // namespace

void MultiplyInto(const Eigen::Ref<const Eigen::MatrixXd>& a,
                  const Eigen::Ref<const Eigen::MatrixXd>& b, Eigen::Ref<Eigen::MatrixXd> out) {
  Multiply<double>(dgemm_, a, b, out);
}

void MultiplyInto(const Eigen::Ref<const Eigen::MatrixXcd>& a,
                  const Eigen::Ref<const Eigen::MatrixXcd>& b, Eigen::Ref<Eigen::MatrixXcd> out) {
  Multiply<std::complex<double>>(zgemm_, a, b, out);
}

}  // namespace ltp::internal
