// The rotor in multi-blade coordinates (equations in ltp/models/rotor_mbc.h).
#include "ltp/models/rotor_mbc.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "ltp/core/error.h"

namespace ltp {
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;

// T for the whole coordinate vector: blade block T(ψ) (or its ψ-derivative), hub identity
// (zero for derivatives).
MatrixXd FullTransform(int blades, double psi, int order) {
  const int q = blades + 2;
  MatrixXd t = MatrixXd::Zero(q, q);
  t.topLeftCorner(blades, blades) = MbcTransform(blades, psi, order);
  if (order == 0) t.bottomRightCorner(2, 2).setIdentity();
  return t;
}

struct Transformed {
  MatrixXd M, D, K, F;
};

// The transformed second-order matrices at time t (they do not depend on t when MBC applies).
Transformed TransformAt(const RotorParameters& r, double t) {
  const RotorMatrices m = RotorSecondOrderMatrices(r, t);
  const double psi = r.omega * t, w = r.omega;
  const MatrixXd T = FullTransform(r.blades, psi, 0);
  const MatrixXd T1 = w * FullTransform(r.blades, psi, 1);      // dT/dt
  const MatrixXd T2 = w * w * FullTransform(r.blades, psi, 2);  // d²T/dt²
  const Eigen::PartialPivLU<MatrixXd> inverse(T);
  return {inverse.solve(m.M * T), inverse.solve(2 * m.M * T1 + m.D * T),
          inverse.solve(m.M * T2 + m.D * T1 + m.K * T), inverse.solve(m.F)};
}

double RelativeChange(const MatrixXd& a, const MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

}  // namespace

std::optional<std::string> MbcNotApplicable(const RotorParameters& rotor) {
  std::ostringstream why;
  if (rotor.blades < 3) {
    why << "multi-blade coordinates do not apply to a " << rotor.blades
        << "-bladed rotor: there is no cyclic pair, so its equations stay periodic in any "
           "blade-based coordinates; use Floquet analysis";
    return why.str();
  }
  if (!rotor.IdenticalBlades()) {
    why << "multi-blade coordinates do not apply: blade 1 is mistuned (mistune_k = "
        << rotor.mistune_k << ", mistune_c = " << rotor.mistune_c
        << "), so the MBC equations keep periodic coefficients";
    if (rotor.IsotropicSupport()) {
      why << " (the support is isotropic, so the rotor is time-invariant in the rotating "
             "frame instead)";
    } else {
      why << " and, with an anisotropic support, no frame makes them constant";
    }
    why << "; use Floquet analysis";
    return why.str();
  }
  return std::nullopt;
}

MbcRotorSystem RotorInMultiBladeCoordinates(const RotorParameters& rotor) {
  rotor.Validate();
  if (const auto reason = MbcNotApplicable(rotor)) throw InputError(*reason);
  const int q = rotor.blades + 2;
  MbcRotorSystem s;
  s.blades = rotor.blades;
  s.rotor_speed = rotor.omega;
  s.coordinates = MbcCoordinateNames(rotor.blades);
  s.coordinates.push_back("x");
  s.coordinates.push_back("y");

  const Transformed at0 = TransformAt(rotor, 0);
  s.M = at0.M;
  s.D = at0.D;
  s.K = at0.K;
  s.F = at0.F;
  s.Cd = MatrixXd::Zero(2, q);
  s.Cd(0, q - 2) = s.Cd(1, q - 1) = 1;
  // The matrices must not depend on the azimuth: check at a few irregular ones.
  const double period = 2 * pi / rotor.omega;
  for (double fraction : {0.137, 0.291, 0.5, 0.618, 0.853}) {
    const Transformed at = TransformAt(rotor, fraction * period);
    s.constancy_defect =
        std::max({s.constancy_defect, RelativeChange(at.M, at0.M), RelativeChange(at.D, at0.D),
                  RelativeChange(at.K, at0.K), RelativeChange(at.F, at0.F)});
  }

  const Eigen::PartialPivLU<MatrixXd> mass(s.M);
  s.A = MatrixXd::Zero(2 * q, 2 * q);
  s.A.topRightCorner(q, q).setIdentity();
  s.A.bottomLeftCorner(q, q) = -mass.solve(s.K);
  s.A.bottomRightCorner(q, q) = -mass.solve(s.D);
  s.B = MatrixXd::Zero(2 * q, 2);
  s.B.bottomRows(q) = mass.solve(s.F);
  const Eigen::VectorXcd values = s.A.eigenvalues();
  s.eigenvalues.assign(values.data(), values.data() + values.size());
  std::sort(s.eigenvalues.begin(), s.eigenvalues.end(),
            [](const std::complex<double>& a, const std::complex<double>& b) {
              return a.imag() != b.imag() ? a.imag() < b.imag() : a.real() < b.real();
            });
  return s;
}

}  // namespace ltp
