// The `flap` scene: flapping of a rigid articulated rotor blade in forward flight, uniform
// inflow, no reverse-flow region (W. Johnson, "Helicopter Theory" (1980), §5.x / §12.1:
// β'' + γ M_β̇ β' + (ν² + γ M_β) β with M_β̇ = 1/8 + (μ/6) sin ψ, M_β = (μ/6) cos ψ +
// (μ²/8) sin 2ψ; also D. A. Peters & K. H. Hohenemser, J. AHS 16(2), 1971):
//
//   β'' + (γ/8)(1 + (4/3) μ sin ψ) β' + (ν² + (γ/8)((4/3) μ cos ψ + μ² sin 2ψ)) β = u,
//
// ' = d/dψ, ψ = Ωt, u the flap moment divided by I_b Ω². In time t (d/dt = Ω d/dψ):
//   β̈ + Ω(γ/8)(1 + (4/3)μ sin Ωt) β̇ + Ω²(ν² + (γ/8)((4/3)μ cos Ωt + μ² sin 2Ωt)) β = Ω² u,
// period 2π/Ω. Exact Fourier form (Ωp = Ω; cos = (e + e*)/2, sin = (e − e*)/(2j)):
//   A_0 = [[0, 1], [−Ω²ν², −Ωγ/8]],
//   A_1 = [[0, 0], [−Ω²γμ/12, jΩγμ/12]],   A_2 = [[0, 0], [jΩ²γμ²/16, 0]].
#include <complex>
#include <numbers>
#include <sstream>

#include "ltp/core/error.h"
#include "scene_builders.h"

namespace ltp {
namespace {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;
using std::numbers::pi;

PeriodicSystem BuildFlap(const ParameterMap& p) {
  const double gamma = p.at("gamma"), mu = p.at("mu"), nu = p.at("nu"), w = p.at("Omega");
  const std::pair<const char*, double> checks[] = {{"Omega", w}, {"gamma", gamma}};
  for (const auto& [name, value] : checks) {
    if (!(value > 0)) {
      std::ostringstream message;
      message << "scene 'flap': parameter '" << name << "' must be > 0, got " << value;
      throw InputError(message.str());
    }
  }
  if (!(mu >= 0)) {
    std::ostringstream message;
    message << "scene 'flap': parameter 'mu' must be >= 0, got " << mu;
    throw InputError(message.str());
  }
  const std::complex<double> j(0, 1);
  FourierMatrix A(2, 2, 2);
  MatrixXcd a0(2, 2), a1 = MatrixXcd::Zero(2, 2), a2 = MatrixXcd::Zero(2, 2);
  a0 << 0, 1, -w * w * nu * nu, -w * gamma / 8;
  a1(1, 0) = -w * w * gamma * mu / 12;
  a1(1, 1) = j * (w * gamma * mu / 12);
  a2(1, 0) = j * (w * w * gamma * mu * mu / 16);
  A.SetHarmonic(0, a0);
  A.SetHarmonic(1, a1);
  A.SetHarmonic(2, a2);
  const FourierMatrix B = FourierMatrix::Constant((MatrixXd(2, 1) << 0, w * w).finished());
  const FourierMatrix C = FourierMatrix::Constant((MatrixXd(1, 2) << 1, 0).finished());
  return PeriodicSystem::FromFourier(2 * pi / w, std::move(A), B, C)
      .WithLabels({.states = {"beta", "beta_dot"}, .inputs = {"u"}, .outputs = {"beta"}})
      .WithRotorSpeed(w);
}

}  // namespace

Scene FlapScene() {
  return {"flap",
          "rotor blade flapping in forward flight (uniform inflow, no reverse flow): "
          "beta'' + (gamma/8)(1 + 4/3 mu sin psi) beta' + (nu^2 + (gamma/8)(4/3 mu cos psi + "
          "mu^2 sin 2psi)) beta = u, psi = Omega t; period 2 pi/Omega",
          "built-in",
          {{"gamma", 8.0, "Lock number gamma (-), > 0"},
           {"mu", 0.3, "advance ratio mu (-), >= 0"},
           {"nu", 1.0, "rotating flap frequency nu (per rev, -); 1 = centrally hinged"},
           {"Omega", 1.0, "rotor speed Omega (rad/s), > 0; 1 = time in radians of azimuth"}},
          BuildFlap,
          {}};
}

}  // namespace ltp
