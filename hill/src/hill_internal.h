#pragma once
// Pieces shared by the hill*.cc files (not part of the public API).
#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/fourier_matrix.h"
#include "ltp/floquet/work_estimate.h"
#include "ltp/hill/hill.h"

namespace ltp::hill_internal {

using cd = std::complex<double>;

/// Eigenpairs of a Hill matrix: all of them (dense) or a subset (structured).
struct Eigenpairs {
  std::vector<cd> values;
  Eigen::MatrixXcd vectors;      ///< column i belongs to values[i]
  std::vector<double> residual;  ///< relative residual per pair
  bool ok = false;
  std::vector<Diagnostic> notes;
};

/// Block bandwidth of the Hill matrix: harmonics of A that actually couple blocks.
int BlockBandwidth(const FourierMatrix& A, int harmonics);

/// Estimate of ||H_N||: Σ_w ||A_w|| + N Ωp (for relative residuals).
double HillNormEstimate(const FourierMatrix& A, double omega, int harmonics);

/// y = H_N x without forming H_N (block Toeplitz part plus the diagonal).
Eigen::VectorXcd HillMultiply(const FourierMatrix& A, double omega, int harmonics,
                              const Eigen::VectorXcd& x);

/// Seconds of one complex n×n product per n³ on this machine now (a 128³ product timed).
double ComplexProductSecondsPerCube();

/// What one Hill analysis of n states at N costs with `o.solver` (dense or structured, not
/// auto): the solves at N and N + Δ, at `seconds_per_cube` per product-cube
/// (docs/model-sizes.md, "Cost before the work").
WorkEstimate HillWork(int n, int N, const HillOptions& o, double seconds_per_cube);

/// The rule for a job `w` described by `job` ("Hill's method at N = 40"): InputError when even
/// its fewest seconds exceed o.max_work_seconds (the message ends with `advice`); a line in
/// `notes` and o.on_long_work when its estimate exceeds o.announce_work_seconds.
void WeighHillWork(const WorkEstimate& w, const std::string& job, const HillOptions& o,
                   const char* advice, std::vector<Diagnostic>& notes);

/// Throws ResourceError when the dense (2N+1)n matrix would exceed max_bytes.
void CheckDenseMemory(int n, int harmonics, double max_bytes);

/// Throws ResourceError when the LAPACK band storage of H_N would exceed 2 GiB.
void CheckBandMemory(int n, int block_bandwidth, int harmonics);

/// LU of H_N − σI in LAPACK band storage (zgbtrf), reused for many solves.
class BandedShiftInvert {
 public:
  BandedShiftInvert(const FourierMatrix& A, double omega, int harmonics);
  /// Factors H_N − σI; false when exactly singular (the caller perturbs σ).
  bool Factor(cd shift);
  /// x ← (H_N − σI)⁻¹ x.
  void Solve(Eigen::Ref<Eigen::VectorXcd> x) const;
  int size() const { return size_; }
  int bandwidth() const { return kl_; }

 private:
  const FourierMatrix& a_;
  double omega_;
  int harmonics_, n_, size_, kl_, ldab_;
  std::vector<cd> ab_;
  std::vector<int> ipiv_;
};

Eigenpairs SolveDense(const FourierMatrix& A, double omega, int harmonics);
/// Eigenpairs near the shifts (clustered); every pair is also re-centred on block 0.
Eigenpairs SolveStructured(const FourierMatrix& A, double omega, int harmonics,
                           const std::vector<cd>& shifts);

/// Block energies of an eigenvector, normalised to sum 1 (index v + N).
std::vector<double> BlockEnergies(const Eigen::VectorXcd& x, int n, int harmonics);

struct Selection {
  std::vector<int> chosen;         ///< indices into the eigenpairs, one per physical exponent
  std::vector<HillModeInfo> info;  ///< parallel to chosen
  std::vector<Diagnostic> diagnostics;
  int passed = 0;  ///< how many chosen met the rule's pass condition
};

Selection SelectPhysical(const Eigenpairs& pairs, int n, int harmonics, double omega,
                         HillSelectionRule rule, double ambiguity_threshold);

}  // namespace ltp::hill_internal
