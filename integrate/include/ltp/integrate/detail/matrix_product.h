#pragma once
// out = a · b for the n × n products that dominate a large system's integration (A(t)Φ in the
// adaptive steppers, exp(hA)Φ in the exponential ones). From the work of a kBlasColumns-square
// product on (m·k·n ≥ 16³, tall products too) they go to BLAS's dgemm: OpenBLAS picks AVX2/AVX-512
// kernels for the CPU at run time, while ltp (and the Eigen products inside it) is compiled for
// baseline x86-64, i.e. SSE2. Measured on the 60-state OpenFAST set: `ltp mbc` 0.92 → 0.63 s, the
// same table (docs/speed-notes.md).
#include <Eigen/Core>

namespace ltp::internal {

/// The size whose square product's work (kBlasColumns³ multiply-adds) MultiplyInto sends to BLAS
/// (below it Eigen's own product is faster).
inline constexpr int kBlasColumns = 16;

/// out = a · b + beta · out; out must not overlap a or b.
void MultiplyInto(const Eigen::Ref<const Eigen::MatrixXd>& a,
                  const Eigen::Ref<const Eigen::MatrixXd>& b, Eigen::Ref<Eigen::MatrixXd> out,
                  double beta = 0);
/// The same for complex matrices (zgemm): the periodic eigenvectors' Schur bases.
void MultiplyInto(const Eigen::Ref<const Eigen::MatrixXcd>& a,
                  const Eigen::Ref<const Eigen::MatrixXcd>& b, Eigen::Ref<Eigen::MatrixXcd> out);

}  // namespace ltp::internal
