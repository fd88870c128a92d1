// Koopman–Hill projection: ψ_v(t) = e^{−jvΩp t} x(t) obeys ψ' = H ψ exactly (infinite H), with
// ψ_v(0) = x(0) for every v and x = ψ_0, so Φ(t) = C e^{H t} W; truncating H gives an
// approximation whose multipliers need no selection among shifted copies.
#include <unsupported/Eigen/MatrixFunctions>

#include "ltp/core/error.h"
#include "ltp/hill/hill.h"

namespace ltp {

Eigen::MatrixXcd KoopmanHillTransition(const FourierMatrix& A, double omega, int harmonics,
                                       double t) {
  const int n = A.rows(), N = harmonics;
  const Eigen::MatrixXcd H = HillMatrix(A, omega, N);
  const Eigen::MatrixXcd E = (H * t).exp();
  // C selects block row 0 (index N); W sums the block columns.
  Eigen::MatrixXcd phi = Eigen::MatrixXcd::Zero(n, n);
  for (int u = 0; u < 2 * N + 1; ++u) phi += E.block(N * n, u * n, n, n);
  return phi;
}

}  // namespace ltp
