// The `rotor` scene: N lead-lag blades on a flexible support (ground resonance). Equations and
// sources are in ltp/models/rotor.h.
#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/second_order.h"
#include "ltp/models/rotor.h"
#include "scene_builders.h"

namespace ltp {
namespace {

using Eigen::MatrixXcd;
using Eigen::MatrixXd;
using std::numbers::pi;

[[noreturn]] void Reject(const std::string& name, double value, const std::string& rule) {
  std::ostringstream message;
  message << "scene 'rotor': parameter '" << name << "' " << rule << ", got " << value;
  throw InputError(message.str());
}

// Largest eigenvalue of B Bᵀ/S_b² over t, where B (2 × N) holds the blade–hub inertia coupling
// (rows −sin ψ_i, cos ψ_i): N/2 for N >= 3 (Σ cos 2ψ_i = 0), 2 for N = 2 (rank one, |B|² = 2).
double CouplingFactor(int blades) { return blades == 2 ? 2.0 : blades / 2.0; }

// A(t) = [[0, I], [−M⁻¹K, −M⁻¹D]] and B(t) = [[0], [M⁻¹F]] of the rotor.
void FirstOrder(const RotorParameters& r, double t, Eigen::Ref<MatrixXd> a,
                Eigen::Ref<MatrixXd> b) {
  const RotorMatrices m = RotorSecondOrderMatrices(r, t);
  const int q = static_cast<int>(m.M.rows());
  const Eigen::LDLT<MatrixXd> mass(m.M);  // symmetric positive definite (Validate)
  a.setZero();
  a.topRightCorner(q, q).setIdentity();
  a.bottomLeftCorner(q, q) = -mass.solve(m.K);
  a.bottomRightCorner(q, q) = -mass.solve(m.D);
  b.setZero();
  b.bottomRows(q) = mass.solve(m.F);
}

// Fourier coefficients of a trigonometric polynomial in Ωt of degree < samples/2 from
// `samples` equally spaced values (alias-free DFT, exact up to round-off); trailing harmonics
// at round-off level are dropped.
FourierMatrix ExactSeries(const std::vector<MatrixXd>& values) {
  const int samples = static_cast<int>(values.size());
  const int rows = static_cast<int>(values[0].rows()), cols = static_cast<int>(values[0].cols());
  const int top = samples / 2 - 1;
  std::vector<MatrixXcd> c(top + 1, MatrixXcd::Zero(rows, cols));
  double largest = 0;
  for (int w = 0; w <= top; ++w) {
    for (int k = 0; k < samples; ++k)
      c[w] += values[k].cast<std::complex<double>>() *
              std::polar(1.0 / samples, -2 * pi * w * k / samples);
    largest = std::max(largest, c[w].cwiseAbs().maxCoeff());
  }
  int harmonics = 0;
  for (int w = 0; w <= top; ++w)
    if (c[w].cwiseAbs().maxCoeff() > 1e-13 * largest) harmonics = w;
  FourierMatrix series(rows, cols, harmonics);
  series.SetHarmonic(0, c[0].real().cast<std::complex<double>>());
  for (int w = 1; w <= harmonics; ++w) series.SetHarmonic(w, c[w]);
  return series;
}

SystemLabels RotorLabels(int blades) {
  SystemLabels labels;
  std::vector<std::string> coordinates;
  for (int i = 1; i <= blades; ++i) coordinates.push_back("zeta" + std::to_string(i));
  coordinates.push_back("x");
  coordinates.push_back("y");
  labels.states = coordinates;
  for (const std::string& c : coordinates) labels.states.push_back(c + "_dot");
  labels.inputs = {"fx", "fy"};
  labels.outputs = {"x", "y"};
  labels.blades = blades;
  for (int b = 0; b < blades; ++b)
    labels.blade_states.push_back(b);           // zeta_b (rates are left out anyway)
  labels.whirl_pairs = {{blades, blades + 1}};  // the hub's (x, y)
  return labels;
}

PeriodicSystem BuildRotor(const ParameterMap& p) {
  return BuildRotorSystem(RotorParametersFrom(p));
}

}  // namespace

void RotorParameters::Validate() const {
  if (!(blades >= 2)) Reject("blades", blades, "must be an integer >= 2");
  if (blades > 200) Reject("blades", blades, "must be at most 200");
  if (!(omega > 0) || !std::isfinite(omega)) Reject("Omega", omega, "must be > 0");
  if (!(inertia > 0)) Reject("I_b", inertia, "must be > 0");
  const std::pair<const char*, double> non_negative[] = {
      {"e", hinge_offset},     {"S_b", first_moment}, {"K_zeta", lag_stiffness},
      {"C_zeta", lag_damping}, {"kx", stiffness_x},   {"ky", stiffness_y},
      {"cx", damping_x},       {"cy", damping_y},     {"mistune_k", mistune_k},
      {"mistune_c", mistune_c}};
  for (const auto& [name, value] : non_negative)
    if (!(value >= 0) || !std::isfinite(value)) Reject(name, value, "must be finite and >= 0");
  // M(t) is positive definite iff its Schur complement diag(M_x, M_y) − B Bᵀ/I_b is; the
  // largest eigenvalue of B Bᵀ is CouplingFactor(N)·S_b².
  const double bound = CouplingFactor(blades) * first_moment * first_moment / inertia;
  const std::pair<const char*, double> masses[] = {{"Mx", mass_x}, {"My", mass_y}};
  for (const auto& [name, value] : masses) {
    if (!(value > bound * (1 + 1e-12)) || !std::isfinite(value)) {
      std::ostringstream rule;
      rule << "must exceed " << CouplingFactor(blades) << " S_b^2/I_b = " << bound
           << " or the mass matrix is singular (it includes the blades' mass N m_b, and "
              "m_b I_b >= S_b^2)";
      Reject(name, value, rule.str());
    }
  }
}

bool RotorParameters::IdenticalBlades() const { return mistune_k == 1 && mistune_c == 1; }

bool RotorParameters::IsotropicSupport() const {
  return mass_x == mass_y && stiffness_x == stiffness_y && damping_x == damping_y;
}

double RotorParameters::EffectiveLagStiffness() const {
  return lag_stiffness + hinge_offset * first_moment * omega * omega;
}

RotorParameters RotorParametersFrom(const ParameterMap& p) {
  RotorParameters r;
  const double blades = p.at("blades");
  if (!(blades >= 2) || blades > 200 || std::round(blades) != blades)
    Reject("blades", blades, "must be an integer from 2 to 200");
  r.blades = static_cast<int>(blades);
  r.omega = p.at("Omega");
  r.hinge_offset = p.at("e");
  r.first_moment = p.at("S_b");
  r.inertia = p.at("I_b");
  r.lag_stiffness = p.at("K_zeta");
  r.lag_damping = p.at("C_zeta");
  r.mass_x = p.at("Mx");
  r.mass_y = p.at("My");
  r.stiffness_x = p.at("kx");
  r.stiffness_y = p.at("ky");
  r.damping_x = p.at("cx");
  r.damping_y = p.at("cy");
  r.mistune_k = p.at("mistune_k");
  r.mistune_c = p.at("mistune_c");
  r.Validate();
  return r;
}

RotorMatrices RotorSecondOrderMatrices(const RotorParameters& r, double t) {
  const int n = r.blades, q = n + 2, x = n, y = n + 1;
  const double s = r.first_moment, w = r.omega;
  RotorMatrices m;
  m.M = MatrixXd::Zero(q, q);
  m.D = MatrixXd::Zero(q, q);
  m.K = MatrixXd::Zero(q, q);
  for (int i = 0; i < n; ++i) {
    const double psi = w * t + 2 * pi * i / n;
    const double sin_psi = std::sin(psi), cos_psi = std::cos(psi);
    const double k_factor = i == 0 ? r.mistune_k : 1.0;
    const double c_factor = i == 0 ? r.mistune_c : 1.0;
    // Blade i: I ζ̈ + C ζ̇ + (K + e S Ω²) ζ + S(−ẍ sin ψ + ÿ cos ψ) = 0.
    m.M(i, i) = r.inertia;
    m.M(i, x) = -s * sin_psi;
    m.M(i, y) = s * cos_psi;
    m.D(i, i) = c_factor * r.lag_damping;
    m.K(i, i) = k_factor * r.lag_stiffness + r.hinge_offset * s * w * w;
    // Hub x: −S(ζ̈ sin ψ + 2Ω ζ̇ cos ψ − Ω² ζ sin ψ); hub y: S(ζ̈ cos ψ − 2Ω ζ̇ sin ψ − Ω² ζ cos ψ).
    m.M(x, i) = -s * sin_psi;
    m.D(x, i) = -2 * w * s * cos_psi;
    m.K(x, i) = w * w * s * sin_psi;
    m.M(y, i) = s * cos_psi;
    m.D(y, i) = -2 * w * s * sin_psi;
    m.K(y, i) = -w * w * s * cos_psi;
  }
  m.M(x, x) = r.mass_x;
  m.M(y, y) = r.mass_y;
  m.D(x, x) = r.damping_x;
  m.D(y, y) = r.damping_y;
  m.K(x, x) = r.stiffness_x;
  m.K(y, y) = r.stiffness_y;
  m.F = MatrixXd::Zero(q, 2);
  m.F(x, 0) = m.F(y, 1) = 1;
  m.Cd = MatrixXd::Zero(2, q);
  m.Cd(0, x) = m.Cd(1, y) = 1;
  return m;
}

PeriodicSystem BuildRotorSystem(const RotorParameters& rotor) {
  rotor.Validate();
  const int q = rotor.blades + 2, n = 2 * q;
  const double period = 2 * pi / rotor.omega;
  MatrixXd c = MatrixXd::Zero(2, n);
  c(0, rotor.blades) = c(1, rotor.blades + 1) = 1;

  std::optional<PeriodicSystem> system;
  if (rotor.blades >= 3) {
    // A(t) has harmonics up to 3Ω (M⁻¹: 2, K and D: 1); 16 samples alias nothing.
    constexpr int kSamples = 16;
    std::vector<MatrixXd> a(kSamples, MatrixXd(n, n)), b(kSamples, MatrixXd(n, 2));
    for (int k = 0; k < kSamples; ++k) FirstOrder(rotor, period * k / kSamples, a[k], b[k]);
    system = PeriodicSystem::FromFourier(period, ExactSeries(a), ExactSeries(b),
                                         FourierMatrix::Constant(c));
  } else {
    auto r = std::make_shared<const RotorParameters>(rotor);
    SecondOrderSystem s;
    s.period = period;
    s.dofs = q;
    s.inputs = 2;
    s.outputs = 2;
    s.M = [r](double t, Eigen::Ref<MatrixXd> out) { out = RotorSecondOrderMatrices(*r, t).M; };
    s.D = [r](double t, Eigen::Ref<MatrixXd> out) { out = RotorSecondOrderMatrices(*r, t).D; };
    s.K = [r](double t, Eigen::Ref<MatrixXd> out) { out = RotorSecondOrderMatrices(*r, t).K; };
    s.F = [r](double t, Eigen::Ref<MatrixXd> out) { out = RotorSecondOrderMatrices(*r, t).F; };
    s.Cd = [r](double t, Eigen::Ref<MatrixXd> out) { out = RotorSecondOrderMatrices(*r, t).Cd; };
    system = FromSecondOrder(s);
  }
  return system->WithLabels(RotorLabels(rotor.blades)).WithRotorSpeed(rotor.omega);
}

MatrixXd RotorBladeShift(int blades) {
  if (blades < 2) throw InputError("RotorBladeShift: need at least 2 blades");
  const int q = blades + 2;
  MatrixXd p = MatrixXd::Zero(2 * q, 2 * q);
  for (int half = 0; half < 2; ++half) {
    const int o = half * q;
    for (int i = 0; i < blades; ++i) p(o + (i + 1) % blades, o + i) = 1;
    p(o + blades, o + blades) = p(o + blades + 1, o + blades + 1) = 1;
  }
  return p;
}

std::complex<double> IsolatedBladeLagExponent(const RotorParameters& rotor) {
  const double decay = rotor.lag_damping / (2 * rotor.inertia);
  const double d = rotor.EffectiveLagStiffness() / rotor.inertia - decay * decay;
  if (d >= 0) return {-decay, std::sqrt(d)};
  return {-decay + std::sqrt(-d), 0.0};
}

// Defaults: magnitudes modelled on the classic four-bladed ground-resonance example of
// C. E. Hammond, "An application of Floquet theory to prediction of mechanical instability",
// J. AHS 19(4), 1974 (articulated rotor, no lag spring, one damper may be inoperative), scaled
// to I_b = 1 and a time unit of 1/(20 rad/s) and rounded; not a verified reproduction of that
// paper's data. Support modes √(kx/Mx) = 0.62 and √(ky/My) = 0.98 rad/s, lag frequency
// ν_ζ = √(e S_b/I_b) = 0.28/rev: coincidences Ω(1 − ν_ζ) = ω at Ω ≈ 0.87 and 1.37 rad/s.
Scene RotorScene() {
  return {"rotor",
          "ground resonance: N lead-lag blades (hinge offset e) on a support with masses Mx, "
          "My, springs kx, ky and dampers cx, cy (Coleman & Feingold); blade 1 may be "
          "mistuned; period 2 pi/Omega (identical blades: T/N up to relabelling)",
          "built-in",
          {{"blades", 4, "number of blades N (integer >= 2)"},
           {"Omega", 1.0, "rotor speed Omega (rad/s), > 0"},
           {"e", 0.3, "lag hinge offset from the shaft e (m)"},
           {"S_b", 0.27, "blade first moment about the lag hinge S_b (kg m)"},
           {"I_b", 1.0, "blade moment of inertia about the lag hinge I_b (kg m^2), > 0"},
           {"K_zeta", 0.0, "lag spring K_zeta (N m/rad)"},
           {"C_zeta", 0.19, "lag damper C_zeta (N m s/rad)"},
           {"Mx", 7.4, "support mass in x, incl. hub and blades M_x (kg)"},
           {"My", 3.0, "support mass in y, incl. hub and blades M_y (kg)"},
           {"kx", 2.86, "support stiffness in x k_x (N/m)"},
           {"ky", 2.86, "support stiffness in y k_y (N/m)"},
           {"cx", 2.35, "support damping in x c_x (N s/m)"},
           {"cy", 1.18, "support damping in y c_y (N s/m)"},
           {"mistune_k", 1.0, "factor on blade 1's lag spring (1 = identical blades)"},
           {"mistune_c", 1.0, "factor on blade 1's lag damper (0 = inoperative damper)"}},
          BuildRotor,
          {}};
}

}  // namespace ltp
