#pragma once
// Eigenvalues of a product of matrices Φ = Φ_K ⋯ Φ_2 Φ_1 without forming the product, via
// the periodic Schur decomposition (SLICOT MB03BD), returned as logarithms so that
// multipliers far outside the double range (ρ = e^{-1000 T}) keep their exact log|ρ|.
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

namespace ltp {

struct LogEigenvalues {
  /// log ρ_k = log|ρ_k| + j arg ρ_k, arg in (−π, π]. Zero eigenvalues: log|ρ| = −inf.
  std::vector<std::complex<double>> log_values;
  bool ok = false;
  std::string message;
};

/// Eigenvalues of factors[K-1] ⋯ factors[0] (all n×n) by periodic Schur (SLICOT MB03BD, JOB =
/// 'E': eigenvalues only, no Schur vectors), as logarithms. Sorted by log|ρ| descending.
LogEigenvalues PeriodicSchurLogEigenvalues(const std::vector<Eigen::MatrixXd>& factors);

/// The real periodic Schur decomposition of the product Φ = factors[K-1] ⋯ factors[0] (all
/// n×n), by the same SLICOT computation as PeriodicSchurLogEigenvalues (MB03VD, MB03VY, MB03BD
/// with JOB = 'S', COMPQ = 'U'; backward stable, O(K n³), the product is never formed):
///
///   Z_{k+1}ᵀ Φ_k Z_k = T_k,   k = 0 … K-1,   Z_K = Z_0,
///
/// so Z_0ᵀ Φ Z_0 = T_{K-1} ⋯ T_0. SLICOT's convention, in this time order: T_{K-1} (the last
/// factor, leftmost in the product; SLICOT's Hessenberg factor H = 1) is quasi-upper-triangular
/// (a 2×2 diagonal block for each complex pair, in the same rows and columns in every T_k), every
/// other T_k is upper triangular. The entries below that structure are exactly zero. A 2×2 block
/// is SLICOT's JOB = 'S' form, not the standardised one (its 2×2 products are not made diagonal).
struct PeriodicSchurForm {
  std::vector<Eigen::MatrixXd> z;  ///< Z_0 … Z_{K-1}, orthogonal n×n
  std::vector<Eigen::MatrixXd> t;  ///< T_0 … T_{K-1}, n×n; T_{K-1} quasi-upper-triangular
  /// The index of the quasi-triangular factor: always K-1 (the others are upper triangular).
  int quasi_triangular = 0;
  /// log ρ in the order of the Schur form's diagonal (not sorted): for a 1×1 position l,
  /// Σ_k log T_k(l,l) (sums of logs, so nothing overflows; a zero entry gives −inf); for a 2×2
  /// block, the conjugate pair with the positive arg first, log|ρ| = ½ Σ_k log|det B_k| and arg
  /// from the block's product normalised as it is formed. arg in (−π, π].
  std::vector<std::complex<double>> log_values;
  bool ok = false;
  /// Why ok is false (bad factors, or SLICOT's INFO); when ok, empty or SLICOT's warning.
  std::string message;
};
PeriodicSchurForm PeriodicSchurDecomposition(const std::vector<Eigen::MatrixXd>& factors);

/// The form's log ρ sorted as PeriodicSchurLogEigenvalues sorts its own (ok and message copied):
/// the multipliers of an analysis that needs the form for its mode shapes anyway, without a
/// second periodic QZ of the same factors.
LogEigenvalues LogEigenvaluesOf(const PeriodicSchurForm& form);

/// The same from the formed product with a plain eigen-solver (single shot), for comparison:
/// inaccurate for every |ρ| below about eps · max|ρ|.
LogEigenvalues SingleShotLogEigenvalues(const Eigen::MatrixXd& product);

/// Periodic eigenvectors of the cyclic product, one per given eigenvalue: for each log_rho,
/// vectors v_0 … v_{K-1} with
///   Φ_i v_i = σ_i v_{i+1}  (v_K = v_0),  σ_i = exp(log_rho · dt_i / T),  T = Σ dt_i,
/// where dt_i are the segment lengths. With log_rho = λT these are the periodic mode shape
/// ξ(t_i) at the segment boundaries t_i = dt_0 + … + dt_{i-1}. Nothing is propagated through
/// the product, so the vectors stay accurate when multipliers span hundreds of decades: an
/// isolated multiplier's vector comes from the periodic Schur form by cyclic back-substitution
/// (O(K n³) for all modes), kept when its residual is at round-off; the others (repeated or
/// clustered multipliers, or a Schur vector that failed its residual) are null vectors of the
/// block-cyclic matrix by inverse iteration with a sparse LU. Eigenvalues that coincide (a
/// cluster) get vectors made independent by block inverse iteration; a defective cluster then
/// shows up as a large condition number of the mode matrix, not as a crash. Method and
/// measured residual are reported per vector (docs/periodic-eigenvectors.md).
/// Each vector set is normalised to max_i ||v_i|| = 1.
enum class PeriodicEigenvectorMethod { kSchur, kInverseIteration };
struct PeriodicEigenvector {
  std::vector<Eigen::VectorXcd> v;  ///< K vectors of length n
  double residual = 0;              ///< max_i ||Φ_i v_i − σ_i v_{i+1}|| / (||Φ_i|| + |σ_i|)
  PeriodicEigenvectorMethod method = PeriodicEigenvectorMethod::kInverseIteration;
};
/// `threads`: OpenMP threads over the modes. `form`: the periodic Schur decomposition of these
/// factors when the caller has it (ok); otherwise it is computed here.
std::vector<PeriodicEigenvector> ComputePeriodicEigenvectors(
    const std::vector<Eigen::MatrixXd>& factors, const std::vector<double>& dt,
    const std::vector<std::complex<double>>& log_rho, int threads = 1,
    const PeriodicSchurForm* form = nullptr);

}  // namespace ltp
