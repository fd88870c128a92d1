#pragma once
// Least-squares fit of spectral lines with known phases to a sampled signal:
//   y(t_n) ≈ c + Σ_l (A_l e^{jφ_l(t_n)} + c.c.) + noise,
// the step-sine estimator of identify.cc on measured angles (φ = ωt + zθ(t)): it needs neither
// whole periods nor a uniform grid nor a constant speed, and reduces to the DFT bins of eq. 47
// when those hold (the columns are then orthogonal). Internal to ltp::htf.
#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <vector>

namespace ltp::internal {

/// The radius that circular Gaussian noise of variance σ² exceeds with probability 5 %:
/// P(|e| > r) = e^{−r²/σ²}, so r = sqrt(ln 20)·σ — every 95 % bound of identification.
inline const double kBoundFactor = std::sqrt(std::log(20.0));

struct LineFit {
  std::vector<std::complex<double>> amplitude;  ///< A_l (NaN when not determined)
  /// E|δA_l|² = (var a_l + var b_l)/4 from σ²(XᵀX)⁻¹, a_l, b_l the cosine and sine coefficients.
  std::vector<double> variance;
  /// false: the line's columns lie in the span of the others (two lines at one frequency).
  std::vector<bool> determined;
  double noise_variance = 0;  ///< σ² = |residual|² / (samples − rank)
  long dof = 0;               ///< samples − rank
};

/// A change of y confined to rows first … first + values.size() − 1.
struct RowPerturbation {
  Eigen::Index first = 0;
  Eigen::VectorXd values;
};

/// `phases` is samples × lines (φ_l(t_n), rad). A constant c is always fitted.
LineFit FitLines(const Eigen::VectorXd& y, const Eigen::MatrixXd& phases);

/// The lines' least-squares basis, factored once (the SVD of the columns scaled to unit norm):
/// y fitted with it, and the fit's linear response to changes of y without a second
/// factorisation. With a known complex gain per sample and line, y ≈ c + Σ_l (A_l g_l(t_n)
/// e^{jφ_l} + c.c.) — records stacked whose lines are driven by different measured inputs
/// (g = U_r), one A_l = H for all; `gains` has the shape of `phases` (empty: all 1).
class LineBasis {
 public:
  LineBasis(const Eigen::MatrixXd& phases, const Eigen::MatrixXcd& gains);
  LineFit Fit(const Eigen::VectorXd& y) const;
  /// δA_l for each change of y (errors of the gains, say): [change][line], one product each.
  std::vector<std::vector<std::complex<double>>> Response(
      const std::vector<RowPerturbation>& changes) const;

 private:
  // The coefficients (constant, then cos and sin per line, scaled) for U_rᵀ·y of the rows.
  Eigen::VectorXd Coefficients(const Eigen::VectorXd& projected) const;
  Eigen::Index lines_ = 0, rank_ = 0;
  Eigen::MatrixXd columns_;  // scaled to unit norm
  Eigen::VectorXd scale_;
  // Divide and conquer: on 441 lines × 12 288 samples (broadband on an angle) 10 s where
  // one-sided Jacobi took 92 s, the same numbers to 1e-14; small fits fall back to Jacobi.
  Eigen::BDCSVD<Eigen::MatrixXd> svd_;
};

/// A rate r in lines of phases φ_l(t) = base_l(t) + m_l · r · t, fitted with their amplitudes
/// by Gauss–Newton from r0 (the column ∂y/∂r = Σ_l m_l t (−a_l sin φ_l + b_l cos φ_l)).
struct FittedRate {
  double rate = 0;
  double standard_error = 0;  ///< of `rate`, from σ²(JᵀJ)⁻¹ at the optimum (NaN: none)
};
FittedRate FitLineRate(const std::vector<double>& time, const Eigen::VectorXd& y,
                       const Eigen::MatrixXd& base, const std::vector<double>& multiplier,
                       double r0);

/// The frequency (rad/s) of the largest line in u's spectrum (the DFT on the record's median
/// step, DC left out): where FitSineFrequency starts when no frequency was written.
double StrongestLine(const std::vector<double>& time, const Eigen::VectorXd& u);

/// The frequency ω (rad/s) of the sine in u(t) nearest ω0: the best of a scan over ±2 bins of
/// the record (2π/L) seeds FitLineRate with the one line ωt (machine precision on a clean sine).
FittedRate FitSineFrequency(const std::vector<double>& time, const Eigen::VectorXd& u,
                            double omega0);

}  // namespace ltp::internal
