#pragma once
// A real T-periodic matrix function in real form, for inner loops that evaluate it many times:
//   M(t) = M_0 + Σ_{w=1..H} (C_w cos wΩt + S_w sin wΩt),
// C_w = 2 Re M_w and S_w = −2 Im M_w for a Hermitian series (both halves are summed, so a
// slightly non-Hermitian one evaluates to its real part), stored as flat column-major blocks
// [M_0 | C_1 | S_1 | … | C_H | S_H] with trailing zero harmonics dropped. An evaluation reads
// contiguous memory and turns one phasor instead of reading complex coefficients by halves.
#include <Eigen/Dense>
#include <vector>

#include "ltp/core/fourier_matrix.h"

namespace ltp {

class RealFourierSeries {
 public:
  RealFourierSeries() = default;
  explicit RealFourierSeries(const FourierMatrix& m);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int harmonics() const { return harmonics_; }  ///< H after dropping trailing zeros
  /// The blocks [M_0 | C_1 | S_1 | …], each rows × cols column-major.
  const double* data() const { return blocks_.data(); }

  /// M(t); Ωp = 2π/period. cos/sin of wΩt by rotation from those of Ωt (error ~w ulps).
  void Evaluate(double t, double omega_p, Eigen::Ref<Eigen::MatrixXd> out) const;

 private:
  int rows_ = 0, cols_ = 0, harmonics_ = 0;
  std::vector<double> blocks_;
};

}  // namespace ltp
