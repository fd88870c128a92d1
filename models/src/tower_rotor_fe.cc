#include "tower_rotor_fe.h"

#include <cmath>

namespace ltp::internal {

const GaussRule& Gauss4() {
  // Nodes ±sqrt(3/7 ∓ 2/7 sqrt(6/5)) on [−1, 1] with weights (18 ± sqrt(30))/36, mapped to [0, 1].
  static const GaussRule rule = [] {
    const double a = std::sqrt(3.0 / 7 - 2.0 / 7 * std::sqrt(6.0 / 5));
    const double b = std::sqrt(3.0 / 7 + 2.0 / 7 * std::sqrt(6.0 / 5));
    const double wa = (18 + std::sqrt(30.0)) / 36, wb = (18 - std::sqrt(30.0)) / 36;
    GaussRule r;
    r.points = {(1 - b) / 2, (1 - a) / 2, (1 + a) / 2, (1 + b) / 2};
    r.weights = {wb / 2, wa / 2, wa / 2, wb / 2};
    return r;
  }();
  return rule;
}

HermiteShape Hermite(double xi, double l) {
  const double x2 = xi * xi, x3 = x2 * xi;
  HermiteShape h;
  h.value << 1 - 3 * x2 + 2 * x3, l * (xi - 2 * x2 + x3), 3 * x2 - 2 * x3, l * (x3 - x2);
  h.slope << (6 * x2 - 6 * xi) / l, 1 - 4 * xi + 3 * x2, (6 * xi - 6 * x2) / l, 3 * x2 - 2 * xi;
  return h;
}

Eigen::Matrix4d BendingStiffness(double ei, double l) {
  Eigen::Matrix4d k;
  k << 12, 6 * l, -12, 6 * l,               //
      6 * l, 4 * l * l, -6 * l, 2 * l * l,  //
      -12, -6 * l, 12, -6 * l,              //
      6 * l, 2 * l * l, -6 * l, 4 * l * l;
  return k * (ei / (l * l * l));
}

Eigen::Matrix4d BendingMass(double rho_a, double l) {
  Eigen::Matrix4d m;
  m << 156, 22 * l, 54, -13 * l,              //
      22 * l, 4 * l * l, 13 * l, -3 * l * l,  //
      54, 13 * l, 156, -22 * l,               //
      -13 * l, -3 * l * l, -22 * l, 4 * l * l;
  return m * (rho_a * l / 420);
}

Eigen::Matrix4d BendingGeometricStiffness(double n0, double n2, double s0, double l) {
  Eigen::Matrix4d k = Eigen::Matrix4d::Zero();
  const GaussRule& g = Gauss4();
  for (int i = 0; i < 4; ++i) {
    const double s = s0 + g.points[i] * l;
    const HermiteShape h = Hermite(g.points[i], l);
    k += (g.weights[i] * l * (n0 - n2 * s * s)) * h.slope * h.slope.transpose();
  }
  return k;
}

Eigen::Matrix2d TorsionStiffness(double gj, double l) {
  return (Eigen::Matrix2d() << 1, -1, -1, 1).finished() * (gj / l);
}

Eigen::Matrix2d TorsionMass(double rho_ip, double l) {
  return (Eigen::Matrix2d() << 2, 1, 1, 2).finished() * (rho_ip * l / 6);
}

}  // namespace ltp::internal
