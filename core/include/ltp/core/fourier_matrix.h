#pragma once
// A real matrix-valued T-periodic function given by a finite Fourier series,
//   M(t) = Σ_{w=-H..H} M_w e^{j w Ωp t},   M_w = (1/T) ∫_0^T M(t) e^{-j w Ωp t} dt,
// with M_{-w} = conj(M_w) because M(t) is real (docs/conventions.md).
#include <Eigen/Dense>
#include <vector>

namespace ltp {

class FourierMatrix {
 public:
  FourierMatrix() = default;
  /// Zero series of the given size with harmonics -max_harmonic..max_harmonic.
  FourierMatrix(int rows, int cols, int max_harmonic);
  /// Constant matrix (only harmonic 0).
  static FourierMatrix Constant(const Eigen::MatrixXd& m);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int max_harmonic() const { return max_harmonic_; }

  /// Coefficient M_w; zero for |w| > max_harmonic (const access only).
  Eigen::MatrixXcd coefficient(int w) const;
  /// Mutable M_w, |w| <= max_harmonic. Setting M_w does *not* set M_{-w}: use SetHarmonic.
  Eigen::MatrixXcd& operator[](int w);
  const Eigen::MatrixXcd& operator[](int w) const;
  /// Sets M_w and M_{-w} = conj(M_w) (real-valued series). w >= 0; M_0 must be real.
  void SetHarmonic(int w, const Eigen::MatrixXcd& m);

  /// Real value M(t); Ωp = 2π/period. Imaginary parts of an inconsistent series are dropped.
  void Evaluate(double t, double omega_p, Eigen::Ref<Eigen::MatrixXd> out) const;
  Eigen::MatrixXd Evaluate(double t, double omega_p) const;

  /// max_w ||M_w - conj(M_{-w})|| (0 for a real function up to round-off).
  double HermitianDefect() const;
  /// Frobenius norm of each harmonic, index w + max_harmonic.
  std::vector<double> HarmonicNorms() const;
  /// The harmonic (block-Toeplitz) matrix at truncation N: block (v, u) = M_{v−u} for
  /// v, u = −N..N, size (2N+1)·rows × (2N+1)·cols. It maps the harmonics −N..N of a signal
  /// x(t) to those of M(t) x(t), dropping what lands beyond ±N. Hill's matrix is this of A minus
  /// blockdiag(j v Ωp I).
  Eigen::MatrixXcd BlockToeplitz(int harmonics) const;

 private:
  int rows_ = 0, cols_ = 0, max_harmonic_ = 0;
  std::vector<Eigen::MatrixXcd> coeffs_;  // index w + max_harmonic_
};

}  // namespace ltp
