// The built-in scenes. Where the coefficients are a short trigonometric series the system is
// built in Fourier form, so Hill's method and the harmonic transfer function get exact
// coefficients instead of a fit.
#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/models/scene.h"
#include "scene_builders.h"

namespace ltp {
namespace {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;
using std::numbers::pi;

void RequirePositive(const ParameterMap& p, const std::string& scene, const std::string& name) {
  const double value = p.at(name);
  if (!(value > 0)) {
    std::ostringstream message;
    message << "scene '" << scene << "': parameter '" << name << "' must be > 0, got " << value;
    throw InputError(message.str());
  }
}

// y'' + c y' + (a − 2q cos 2t) y = u. With T = π, Ωp = 2 and 2q cos 2t = q e^{jΩp t} + c.c.,
// so A_0 = [[0, 1], [−a, −c]] and A_{±1} = [[0, 0], [q, 0]].
PeriodicSystem BuildMathieu(const ParameterMap& p) {
  const double a = p.at("a"), q = p.at("q"), c = p.at("c");
  FourierMatrix A(2, 2, 1);
  A[0] << 0, 1, -a, -c;
  MatrixXcd a1 = MatrixXcd::Zero(2, 2);
  a1(1, 0) = q;
  A.SetHarmonic(1, a1);
  const FourierMatrix B = FourierMatrix::Constant((MatrixXd(2, 1) << 0, 1).finished());
  const FourierMatrix C = FourierMatrix::Constant((MatrixXd(1, 2) << 1, 0).finished());
  return PeriodicSystem::FromFourier(pi, std::move(A), B, C)
      .WithLabels({.states = {"y", "y_dot"}, .inputs = {"u"}, .outputs = {"y"}});
}

// y'' + c y' + (a + b·sign(cos t)) y = u: the stiffness switches at t = π/2 and 3π/2.
PeriodicSystem BuildMeissner(const ParameterMap& p) {
  const double a = p.at("a"), b = p.at("b"), c = p.at("c");
  PeriodicSystem::Functions f;
  f.A = [a, b, c](double t, Eigen::Ref<MatrixXd> out) {
    const double cos_t = std::cos(t);
    const double sign = cos_t > 0 ? 1.0 : (cos_t < 0 ? -1.0 : 0.0);
    out << 0, 1, -(a + b * sign), -c;
  };
  f.B = [](double, Eigen::Ref<MatrixXd> out) { out << 0, 1; };
  f.C = [](double, Eigen::Ref<MatrixXd> out) { out << 1, 0; };
  return PeriodicSystem::FromFunctions(2 * pi, 2, 1, 1, std::move(f), {pi / 2, 3 * pi / 2})
      .WithLabels({.states = {"y", "y_dot"}, .inputs = {"u"}, .outputs = {"y"}});
}

// Asymmetric shaft seen from the fixed frame: m p'' + c p' + K(t) p = f, p = (x, y), with
// K(t) = R(Ωt) diag(k1, k2) R(Ωt)ᵀ = k0 I + kd [[cos 2Ωt, sin 2Ωt], [sin 2Ωt, −cos 2Ωt]],
// k0 = (k1 + k2)/2, kd = (k1 − k2)/2. T = π/Ω, Ωp = 2Ω; with e = e^{jΩp t},
// cos = (e + e*)/2 and sin = (e − e*)/(2j), so the e-coefficient of K is
// kd/2 [[1, −j], [−j, −1]].
PeriodicSystem BuildJeffcott(const ParameterMap& p) {
  RequirePositive(p, "jeffcott", "m");
  RequirePositive(p, "jeffcott", "Omega");
  const double m = p.at("m"), k1 = p.at("k1"), k2 = p.at("k2"), c = p.at("c");
  const double omega = p.at("Omega");
  const double k0 = (k1 + k2) / 2, kd = (k1 - k2) / 2;
  const std::complex<double> j(0, 1);

  FourierMatrix A(4, 4, 1);
  A[0].setZero();
  A[0].topRightCorner(2, 2).setIdentity();
  A[0].bottomLeftCorner(2, 2) = MatrixXcd::Identity(2, 2) * (-k0 / m);
  A[0].bottomRightCorner(2, 2) = MatrixXcd::Identity(2, 2) * (-c / m);
  MatrixXcd k_plus(2, 2);
  k_plus << 1.0, -j, -j, -1.0;
  MatrixXcd a1 = MatrixXcd::Zero(4, 4);
  a1.bottomLeftCorner(2, 2) = -kd / (2 * m) * k_plus;
  A.SetHarmonic(1, a1);

  MatrixXd b = MatrixXd::Zero(4, 2);
  b.bottomRows(2) = MatrixXd::Identity(2, 2) / m;
  MatrixXd cm = MatrixXd::Zero(2, 4);
  cm.leftCols(2).setIdentity();
  return PeriodicSystem::FromFourier(pi / omega, std::move(A), FourierMatrix::Constant(b),
                                     FourierMatrix::Constant(cm))
      .WithLabels({.states = {"x", "y", "x_dot", "y_dot"},
                   .inputs = {"fx", "fy"},
                   .outputs = {"x", "y"},
                   .whirl_pairs = {{0, 1}}})  // R(Ωt) turns x towards y
      .WithRotorSpeed(omega);
}

std::vector<Scene> MakeBuiltins() {
  std::vector<Scene> scenes;
  scenes.push_back(
      {"mathieu",
       "damped Mathieu oscillator y'' + c y' + (a - 2q cos 2t) y = u; period pi, output y",
       "built-in",
       {{"a", 1.0, "constant stiffness a (1/s^2)"},
        {"q", 0.2, "parametric excitation q: stiffness varies by -2q cos 2t (1/s^2)"},
        {"c", 0.02, "viscous damping c (1/s)"}},
       BuildMathieu,
       {}});
  scenes.push_back(
      {"meissner",
       "Meissner oscillator y'' + c y' + (a + b sign(cos t)) y = u: square-wave stiffness, "
       "period 2 pi, jumps at pi/2 and 3 pi/2",
       "built-in",
       {{"a", 1.0, "mean stiffness a (1/s^2)"},
        {"b", 0.3, "square-wave stiffness amplitude b (1/s^2)"},
        {"c", 0.0, "viscous damping c (1/s)"}},
       BuildMeissner,
       {}});
  scenes.push_back(
      {"jeffcott",
       "Jeffcott rotor with an asymmetric shaft, fixed frame: m p'' + c p' + K(t) p = f, "
       "p = (x, y); period pi/Omega; unstable for sqrt(k1/m) < Omega < sqrt(k2/m) undamped",
       "built-in",
       {{"m", 1.0, "disc mass m (kg), > 0"},
        {"k1", 1.0, "shaft stiffness along its first principal axis k1 (N/m)"},
        {"k2", 1.5, "shaft stiffness along its second principal axis k2 (N/m)"},
        {"c", 0.0, "external (non-rotating) viscous damping c (N s/m)"},
        {"Omega", 1.1, "rotor speed Omega (rad/s), > 0"}},
       BuildJeffcott,
       {}});
  scenes.push_back(RotorScene());
  scenes.push_back(FlapScene());
  scenes.push_back(TowerRotorScene());
  return scenes;
}

}  // namespace

const std::vector<Scene>& BuiltinScenes() {
  static const std::vector<Scene> scenes = MakeBuiltins();
  return scenes;
}

}  // namespace ltp
