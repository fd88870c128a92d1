// G (jωI + H)⁻¹ B at many ω from one reduction (Laub's method for frequency responses): H is
// balanced by a diagonal similarity D of powers of two (exact), then reduced once to upper
// Hessenberg form Qᴴ D⁻¹HD Q = 𝐻 (LAPACK zgebal, zgehrd); each ω then costs one O(n²)
// Hessenberg solve (jωI + 𝐻) y = Qᴴ D⁻¹ B, and G x = (G D Q) y. Backward stable like the
// direct solve; the reduction (≈ 10/3 n³) pays once a sweep has more frequencies than it
// costs in direct factorizations.
//
// The Hessenberg solve is Gaussian elimination with adjacent-row pivoting, written here on a
// row-major copy of 𝐻: SLICOT's MB02SZ/MB02RZ (and LAPACK's band LU with one subdiagonal) do
// the same elimination on column-major storage, where every row operation strides across all
// columns; there a tower-rotor point (size 550) took ~3 ms, here 0.7 ms (benchmarks/
// tower_rotor_benchmark HtfPoint/1; the banded LU HtfPoint/0 takes ~9 ms).
#pragma once

#include <Eigen/Dense>
#include <complex>

namespace ltp::internal {

class ShiftedHessenbergSolver {
 public:
  /// h: n × n; b: n × m right-hand sides; g: r × n output rows.
  ShiftedHessenbergSolver(Eigen::MatrixXcd h, const Eigen::MatrixXcd& b, const Eigen::MatrixXcd& g);

  /// out = rows first … first + count − 1 of G (sI + H)⁻¹ B (count × m), s = jω on the
  /// frequency axis. False when sI + H is exactly singular or the reduction failed; out is then
  /// unspecified. Safe to call from several threads at once.
  bool Solve(std::complex<double> s, int first, int count, Eigen::MatrixXcd& out) const;

  bool ok() const { return ok_; }
  int size() const { return static_cast<int>(hessenberg_.rows()); }

 private:
  /// 𝐻 by rows (entries below the first subdiagonal are never read).
  Eigen::Matrix<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> hessenberg_;
  Eigen::MatrixXcd qb_;  ///< Qᴴ D⁻¹ B
  Eigen::MatrixXcd gq_;  ///< G D Q
  bool ok_ = false;
};

}  // namespace ltp::internal
