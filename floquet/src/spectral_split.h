#pragma once
// The slow spectral subspace of a constant matrix: the modes a reduced analysis keeps
// (docs/model-sizes.md, "Modes below a frequency").
#include <Eigen/Dense>
#include <complex>
#include <vector>

namespace ltp::internal {

/// Ā's invariant subspace of the eigenvalues with |λ| ≤ `cutoff`, and its complement.
/// right (n × k) is an orthonormal basis U of the subspace (leading Schur vectors after
/// reordering); left (n × k) is W with WᵀU = I whose rows span the matching left invariant
/// subspace, so WᵀĀU = T₁₁ and x ↦ Wᵀx is the spectral projection: the reduced system
/// q' = Wᵀ A(t) U q is exact for A = Ā and decoupled from the other modes up to the periodic
/// part's coupling.
struct SpectralSplit {
  Eigen::MatrixXd right, left;
  std::vector<std::complex<double>> kept, dropped;  ///< eigenvalues of Ā
  /// Largest entry of the Sylvester solution that decouples the blocks: large when kept and
  /// dropped eigenvalues are close (an ill-conditioned split).
  double coupling = 0;
  bool ok = false;  ///< false when LAPACK failed (a matrix with non-finite entries)
};

/// Ā's real Schur form Ā = Q T Qᵀ (LAPACK dgees), computed once for any number of splits;
/// ok = false for non-finite entries or a LAPACK failure.
struct RealSchurForm {
  Eigen::MatrixXd t, q;
  bool ok = false;
};
RealSchurForm SchurOfMean(const Eigen::MatrixXd& mean);

SpectralSplit SplitAtModulus(const RealSchurForm& schur, double cutoff);

}  // namespace ltp::internal
