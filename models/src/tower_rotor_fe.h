#pragma once
// Euler–Bernoulli beam finite elements for the tower-rotor scene (internal): Hermite cubic
// bending elements, linear torsion elements, 4-point Gauss–Legendre quadrature, and the
// assembly of clamped-free beams. Nodes 0..n along the beam; node 0 is clamped, so the global
// DOFs are those of nodes 1..n.
#include <Eigen/Dense>
#include <array>

namespace ltp::internal {

/// 4-point Gauss–Legendre rule on [0, 1]: exact for polynomials of degree <= 7, so for
/// products of two cubics (consistent mass) and for N(s) w'² with quadratic N (geometric
/// stiffness).
struct GaussRule {
  std::array<double, 4> points;
  std::array<double, 4> weights;
};
const GaussRule& Gauss4();

/// Hermite cubic shape functions of an element of length l at ξ = s/l ∈ [0, 1], for the
/// element DOFs [w_1, w_1', w_2, w_2'] (w' = dw/ds): values and derivatives d/ds.
struct HermiteShape {
  Eigen::Vector4d value;
  Eigen::Vector4d slope;
};
HermiteShape Hermite(double xi, double l);

/// Bending element: stiffness EI/l³ [...] and consistent mass ρA l/420 [...] (standard).
Eigen::Matrix4d BendingStiffness(double ei, double l);
Eigen::Matrix4d BendingMass(double rho_a, double l);
/// Geometric stiffness ∫ N(s) N'ᵀN' ds of one element for the axial force
/// N(s) = n0 − n2 s² (s measured from the rotation axis; the element spans [s0, s0 + l]).
Eigen::Matrix4d BendingGeometricStiffness(double n0, double n2, double s0, double l);
/// Linear torsion element: GJ/l [[1, −1], [−1, 1]], ρI_p l/6 [[2, 1], [1, 2]].
Eigen::Matrix2d TorsionStiffness(double gj, double l);
Eigen::Matrix2d TorsionMass(double rho_ip, double l);

/// Adds element matrix `e` at global indices `dofs` (−1 = clamped, skipped).
template <int N>
void Scatter(const Eigen::Matrix<double, N, N>& e, const std::array<int, N>& dofs,
             Eigen::MatrixXd& global) {
  for (int i = 0; i < N; ++i) {
    if (dofs[i] < 0) continue;
    for (int j = 0; j < N; ++j) {
      if (dofs[j] >= 0) global(dofs[i], dofs[j]) += e(i, j);
    }
  }
}

}  // namespace ltp::internal
