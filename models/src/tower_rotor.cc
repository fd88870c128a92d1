// The tower-rotor scene: the flexible rotor system of the reference paper (Fig. 2, §5).
//
// MODEL
// -----
// Inertial axes: x along the cantilever (clamped at x = 0, tip at x = L), y along the rotor
// shaft, z = x × y. Bodies:
//  * Cantilever: Euler–Bernoulli beam, n_c elements. Per node: v (deflection along y), v',
//    w (deflection along z), w', φ (torsion about x). Hermite cubic bending in both planes
//    (EI_z = E h b³/12 for v, EI_y = E b h³/12 for w; b = width along y, h = depth along z),
//    linear torsion elements (GJ with the rectangle's torsion constant, ρI_p = ρA(b²+h²)/12).
//    Axial deformation, shear and rotary inertia are neglected. The tip moves by
//    u_t = (0, v, w) and turns by θ = (φ, −w', v') (small rotation vector).
//  * Hub: rigid solid cylinder (mass m_h, radius r_h, length l_h) whose centre H sits at
//    d·e_y from the cantilever tip, on a driven revolute joint: it turns relative to the tip by
//    the prescribed angle ψ = Ω t about the (tilting) tip y-axis. Its inertia is represented
//    exactly (mass, centre, J_p = m r²/2, J_t = m(3r² + l²)/12) by two rings of 8 point
//    masses at y = ±l_h/√12, radius r_h/√2.
//  * Blades k = 0, 1: Euler–Bernoulli beams clamped to the hub at radius r_h, along a_k in the
//    rotor frame (a_0 = e_z, a_1 = −e_z), length L_b, rectangular section (thickness t along
//    the shaft, width c in the rotor plane). Per node: f (flap, along e_y), f', g (lag, along
//    b_k = e_y × a_k, i.e. b_0 = e_x, b_1 = −e_x: the direction of rotation), g'. Axial and
//    torsional blade deformation are neglected; the centrifugal axial force enters through
//    the foreshortening (geometric stiffness).
//
// REDUCTION (paper eq. 12–20)
// ---------------------------
// Each body is reduced to its own modes below the cutoff f_cut = 2·fmax (at least one mode
// per body), mass-normalised:
//  * cantilever: q_c = Θ_c p_c, modes of the cantilever *loaded by the rigid rotor* (hub and
//    undeformed blades as a rigid body at the tip, its inertia averaged over ψ). This Ritz
//    basis represents the tip-mass-dominated modes with few vectors; the coupled equations
//    below use the exact, ψ-dependent rotor inertia, so the basis choice is only a basis.
//  * blades: q_b = Θ_b p_b, clamped-free, non-rotating modes (flap and lag uncouple).
// Keeping every mode (f_cut = ∞) reproduces the unreduced FE model of the coupled structure
// exactly: TowerRotorModeTable reports both ("MBS" and "FEM" as in the paper's table).
//
// LINEARISED EQUATIONS OF MOTION (paper eq. 32–37, derived here by Lagrange's equations)
// ---------------------------------------------------------------------------------------
// Generalized coordinates p = [p_c; p_b0; p_b1]. A material point of the rotor with rotor-frame
// position ρ (hub point, or blade point s·a_k) is at
//   r = L e_x + u_t + R_t (d e_y + R(ψ)(ρ + u_b)) + (foreshortening),  R(ψ) = R_y(ψ),
// with R_t = I + θ̃ + ½θ̃² + O(θ³) the tip rotation and u_b = f e_y + g b_k. Expanding to second
// order in p:  r = r0(t) + G(t) p + h(p, t),  h quadratic in p, where
//   r0 = L e_x + ρ'(ψ),    ρ' = d e_y + R ρ                      (steady rotation),
//   G p = u_t + θ × ρ' + R u_b                                    (first order),
//   h = ½ θ × (θ × ρ') + θ × (R u_b) − ½ ∫_{r_h}^{s} (f'² + g'²) dσ · R a_k  (second order).
// Kinetic energy T = ½ Σ m |ṙ|² (a sum over quadrature points = exact integral). The terms of T
// linear in p are the steady centrifugal loads; they vanish for the balanced rotor (its centre
// of mass is on the axis and the blade forces are radial, orthogonal to flap and lag), so
// p = 0 is the steady state. The quadratic part is
//   T2 = ½ Σ m |Ġ p + G ṗ|² + Σ m ṙ0 · ḣ,
// and Σ m ṙ0 · ḣ = d/dt(Σ m ṙ0 · h) − Σ m r̈0 · h, so, dropping the total derivative, h acts as
// a potential V_c = Σ m r̈0 · h =: ½ pᵀ S p. Lagrange's equations with V = ½ pᵀ K_e p + V_c:
//   M p̈ + (2 Σ m Gᵀ Ġ) ṗ + (K_e + Σ m Gᵀ G̈ + S) p = Q,   M = M_c + Σ m GᵀG,
// where 2 Σ m GᵀĠ = Ṁ + (Σ m (GᵀĠ − ĠᵀG)) is the time-varying-inertia plus gyroscopic
// (Coriolis) matrix and Σ m GᵀG̈ + S holds the centrifugal terms. With r̈0 = Ω² R'' ρ (the
// centripetal acceleration) the parts of S are
//   * hub tilt θ·θ:  pᵀ S p ∋ Σ m r̈0 · θ̃²ρ'  →  S_θθ = Σ m [sym(r̈0 ρ'ᵀ) − (r̈0·ρ') I]
//     (it cancels the symmetric part of Σ m GᵀG̈ in the tilt block: a rotor spinning about its
//     own tilted axis has no centrifugal tilt stiffness, as it must);
//   * tilt × blade:  Σ m r̈0 · (θ × R u_b) = −θᵀ Σ m r̃̈0 R u_b  →  S_θb = −Σ m r̃̈0 G_b;
//   * blade foreshortening: Σ m r̈0 · h = ½ ∫ N(σ)(f'² + g'²) dσ with the centrifugal axial force
//     N(σ) = ρA Ω² ∫_σ^R s ds = ρA Ω² (R² − σ²)/2, R = r_h + L_b (geometric stiffening).
// The lag softening −Ω² m g² comes out of Σ m GᵀG̈ (G̈ = −Ω² R b_k g for the lag column).
// The second-order terms of the tip's translation and the skew part of the second-order tip
// rotation (which depend on the cantilever's nonlinear kinematics) multiply Σ m r̈0 = 0 and
// Σ m ρ_r × r̈0 = 0 over the balanced rotor, so the cantilever needs no geometric stiffness.
// Neglected: gravity, aerodynamics, blade torsion and extension, shear and rotary inertia of
// the beams, cantilever axial motion, the joint's drive compliance (ψ is prescribed).
// Damping: modal, ζ on every kept body mode, D_s = blockdiag(2ζω_i) (constant, dissipative).
//
// All of G, Ġ, G̈, r̈0, ρ' are trigonometric polynomials of degree 1 in ψ, so M, D, K have
// harmonics |w| <= 2 only. They are sampled at 8 angles and transformed exactly.
#include "ltp/models/tower_rotor.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/core/real_fourier_series.h"
#include "ltp/core/second_order.h"
#include "tower_rotor_fe.h"

namespace ltp {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using std::numbers::pi;

constexpr int kCantileverNodeDofs = 5;  // v, v', w, w', φ
constexpr int kBladeNodeDofs = 4;       // f, f', g, g'
constexpr int kAngleSamples = 8;       // ≥ 2·2 + 1 for harmonics up to 2; 8 avoids aliasing to 3
constexpr double kCutoffFactor = 2.0;  // keep body modes up to kCutoffFactor · fmax
// Mesh limit: the unreduced reference model of the mode table stays below ~1300 DOFs.
constexpr int kMaxElements = 100;

Matrix3d Skew(const Vector3d& a) {
  Matrix3d s;
  s << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return s;
}

// R_y(ψ): rotation about y by ψ (z → z cos ψ + x sin ψ) and its ψ-derivatives.
Matrix3d RotY(double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  return (Matrix3d() << c, 0, s, 0, 1, 0, -s, 0, c).finished();
}
Matrix3d RotYPrime(double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  return (Matrix3d() << -s, 0, c, 0, 0, 0, -c, 0, -s).finished();
}
Matrix3d RotYSecond(double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  return (Matrix3d() << -c, 0, -s, 0, 0, 0, s, 0, -c).finished();
}

// Torsion constant of a solid rectangle a × c, a >= c (Roark: J = a c³ [1/3 − 0.21 (c/a)(1 −
// c⁴/(12 a⁴))], within 0.5% of the exact series).
double RectangleTorsionConstant(double side1, double side2) {
  const double a = std::max(side1, side2), c = std::min(side1, side2);
  const double r = c / a;
  return a * c * c * c * (1.0 / 3 - 0.21 * r * (1 - r * r * r * r / 12));
}

// Solves K x = ω² M x; keeps modes with f <= cutoff_hz (at least one). Columns M-normalised.
struct ModeSet {
  MatrixXd shapes;
  VectorXd omega;  // rad/s
};
ModeSet Modes(const MatrixXd& k, const MatrixXd& m, double cutoff_hz) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> solver(k, m);
  if (solver.info() != Eigen::Success) throw InputError("tower-rotor: body eigenproblem failed");
  const VectorXd lambda = solver.eigenvalues();
  int keep = 0;
  while (keep < lambda.size() && std::sqrt(std::max(lambda(keep), 0.0)) / (2 * pi) <= cutoff_hz) {
    ++keep;
  }
  keep = std::max(keep, 1);
  ModeSet set;
  set.shapes = solver.eigenvectors().leftCols(keep);
  set.omega = lambda.head(keep).cwiseMax(0).cwiseSqrt();
  return set;
}

// A point mass of the rotor. `blade` = −1 for hub points; for blade points the modal shape
// rows give f (flap) and g (lag) at the point.
struct RotorPoint {
  double mass = 0;
  Vector3d rho;  // rotor-frame position relative to the hub centre
  int blade = -1;
  RowVectorXd flap, lag;
};

// The two reduced bodies and everything needed to assemble the coupled matrices.
struct Structure {
  TowerRotorParams params;
  // Cantilever: full FE stiffness (for energies), loaded modes, tip maps.
  MatrixXd cantilever_k;
  ModeSet cantilever;
  MatrixXd cantilever_mass_modal;  // Θ_cᵀ M_c Θ_c (cantilever's own mass)
  MatrixXd tip_u, tip_theta;       // 3 × n_c: u_t and θ per modal coordinate
  // Blade (one; both are identical): modes, kinds, modal geometric stiffness per Ω².
  ModeSet blade;
  std::vector<std::string> blade_kinds;
  std::vector<bool> blade_is_flap;
  MatrixXd blade_geometric;  // Θ_bᵀ K_g Θ_b / Ω²
  std::vector<RotorPoint> points;
  int nc = 0, nb = 0, n = 0;
};

// Rotor points (hub rings + blade Gauss points) with blade shapes in FE (unreduced) DOFs.
std::vector<RotorPoint> MakeRotorPoints(const TowerRotorParams& p, const MatrixXd* blade_modes) {
  std::vector<RotorPoint> points;
  const double ring_radius = p.hub_radius / std::sqrt(2.0);
  const double ring_y = p.hub_length / std::sqrt(12.0);
  for (int ring = 0; ring < 2; ++ring) {
    for (int i = 0; i < 8; ++i) {
      const double alpha = 2 * pi * i / 8;
      RotorPoint point;
      point.mass = p.hub_mass / 16;
      point.rho = Vector3d(ring_radius * std::sin(alpha), ring == 0 ? ring_y : -ring_y,
                           ring_radius * std::cos(alpha));
      points.push_back(point);
    }
  }
  const int ne = p.blade_elements;
  const int nb_full = kBladeNodeDofs * ne;
  const double le = p.blade_length / ne;
  const double rho_a = p.blade_rho * p.blade_width * p.blade_thickness;
  const internal::GaussRule& gauss = internal::Gauss4();
  for (int k = 0; k < 2; ++k) {
    const double sign = k == 0 ? 1.0 : -1.0;
    for (int e = 0; e < ne; ++e) {
      for (int g = 0; g < 4; ++g) {
        const double s = p.hub_radius + (e + gauss.points[g]) * le;
        const internal::HermiteShape h = internal::Hermite(gauss.points[g], le);
        RowVectorXd flap = RowVectorXd::Zero(nb_full), lag = RowVectorXd::Zero(nb_full);
        for (int a = 0; a < 4; ++a) {
          const int node = e + a / 2;  // local DOFs 0, 1 at node e; 2, 3 at node e + 1
          if (node == 0) continue;     // clamped root
          const int base = kBladeNodeDofs * (node - 1) + a % 2;
          flap(base) = h.value(a);
          lag(base + 2) = h.value(a);
        }
        RotorPoint point;
        point.mass = rho_a * le * gauss.weights[g];
        point.rho = Vector3d(0, 0, sign * s);
        point.blade = k;
        point.flap = blade_modes ? RowVectorXd(flap * *blade_modes) : flap;
        point.lag = blade_modes ? RowVectorXd(lag * *blade_modes) : lag;
        points.push_back(std::move(point));
      }
    }
  }
  return points;
}

// Tip DOF maps (v, v', w, w', φ) → u_t and θ.
Eigen::Matrix<double, 3, 5> TipTranslationMap() {
  Eigen::Matrix<double, 3, 5> t = Eigen::Matrix<double, 3, 5>::Zero();
  t(1, 0) = 1;  // u_y = v
  t(2, 2) = 1;  // u_z = w
  return t;
}
Eigen::Matrix<double, 3, 5> TipRotationMap() {
  Eigen::Matrix<double, 3, 5> t = Eigen::Matrix<double, 3, 5>::Zero();
  t(0, 4) = 1;   // θ_x = φ
  t(1, 3) = -1;  // θ_y = −w'
  t(2, 1) = 1;   // θ_z = v'
  return t;
}

// Global DOF of `offset` at `node` of a beam clamped at node 0 (−1: clamped, not a DOF).
int BeamDof(int node_dofs, int node, int offset) {
  return node == 0 ? -1 : node_dofs * (node - 1) + offset;
}

// Full FE stiffness and mass of a body; kg: the blade's geometric stiffness per Ω².
struct BeamFe {
  MatrixXd k, m, kg;
};

// Cantilever FE: bending in both planes (v, w) and torsion (φ), clamped at x = 0.
BeamFe CantileverFe(const TowerRotorParams& p) {
  const int nce = p.cantilever_elements;
  const int nc_full = kCantileverNodeDofs * nce;
  const double lc = p.cantilever_length / nce;
  const double b = p.cantilever_width_y, h = p.cantilever_depth_z;
  const double area = b * h;
  const double ei_v = p.cantilever_E * h * b * b * b / 12;  // deflection along y
  const double ei_w = p.cantilever_E * b * h * h * h / 12;  // deflection along z
  const double gj = p.cantilever_G * RectangleTorsionConstant(b, h);
  const double rho_a = p.cantilever_rho * area;
  const double rho_ip = p.cantilever_rho * area * (b * b + h * h) / 12;
  BeamFe fe{MatrixXd::Zero(nc_full, nc_full), MatrixXd::Zero(nc_full, nc_full), MatrixXd()};
  auto node_dof = [](int node, int offset) { return BeamDof(kCantileverNodeDofs, node, offset); };
  for (int e = 0; e < nce; ++e) {
    for (int plane = 0; plane < 2; ++plane) {  // 0: v (offsets 0, 1); 1: w (offsets 2, 3)
      const int o = 2 * plane;
      const std::array<int, 4> dofs = {node_dof(e, o), node_dof(e, o + 1), node_dof(e + 1, o),
                                       node_dof(e + 1, o + 1)};
      internal::Scatter<4>(internal::BendingStiffness(plane == 0 ? ei_v : ei_w, lc), dofs, fe.k);
      internal::Scatter<4>(internal::BendingMass(rho_a, lc), dofs, fe.m);
    }
    const std::array<int, 2> tdofs = {node_dof(e, 4), node_dof(e + 1, 4)};
    internal::Scatter<2>(internal::TorsionStiffness(gj, lc), tdofs, fe.k);
    internal::Scatter<2>(internal::TorsionMass(rho_ip, lc), tdofs, fe.m);
  }
  return fe;
}

// The rigid rotor (hub and undeformed blades) as a mass on the tip DOFs (v, v', w, w', φ), its
// inertia averaged over ψ: Σ m AᵀA with A = T_u − ρ̃' T_θ.
Eigen::Matrix<double, 5, 5> RigidRotorTipMass(const TowerRotorParams& p) {
  const Eigen::Matrix<double, 3, 5> tu = TipTranslationMap(), tt = TipRotationMap();
  const std::vector<RotorPoint> rigid_points = MakeRotorPoints(p, nullptr);
  Eigen::Matrix<double, 5, 5> rigid = Eigen::Matrix<double, 5, 5>::Zero();
  for (int a = 0; a < kAngleSamples; ++a) {
    const Matrix3d r = RotY(2 * pi * a / kAngleSamples);
    for (const RotorPoint& point : rigid_points) {
      const Vector3d rho_p = Vector3d(0, p.hub_offset, 0) + r * point.rho;
      const Eigen::Matrix<double, 3, 5> map = tu - Skew(rho_p) * tt;
      rigid += point.mass / kAngleSamples * map.transpose() * map;
    }
  }
  return rigid;
}

// Blade FE (clamped at the hub radius): flap and lag bending, and the geometric stiffness of
// the centrifugal axial force.
BeamFe BladeFe(const TowerRotorParams& p) {
  const int nbe = p.blade_elements;
  const int nb_full = kBladeNodeDofs * nbe;
  const double lb = p.blade_length / nbe;
  const double tb = p.blade_thickness, cb = p.blade_width;
  const double ei_flap = p.blade_E * cb * tb * tb * tb / 12;
  const double ei_lag = p.blade_E * tb * cb * cb * cb / 12;
  const double rho_ab = p.blade_rho * tb * cb;
  const double tip_radius = p.hub_radius + p.blade_length;
  BeamFe fe;
  fe.k = MatrixXd::Zero(nb_full, nb_full);
  fe.m = fe.k;
  fe.kg = fe.k;
  auto node_dof = [](int node, int offset) { return BeamDof(kBladeNodeDofs, node, offset); };
  for (int e = 0; e < nbe; ++e) {
    const double s0 = p.hub_radius + e * lb;
    // N(s)/Ω² = ρA (R² − s²)/2.
    const Eigen::Matrix4d geometric = internal::BendingGeometricStiffness(
        rho_ab * tip_radius * tip_radius / 2, rho_ab / 2, s0, lb);
    for (int plane = 0; plane < 2; ++plane) {  // 0: flap f; 1: lag g
      const int o = 2 * plane;
      const std::array<int, 4> dofs = {node_dof(e, o), node_dof(e, o + 1), node_dof(e + 1, o),
                                       node_dof(e + 1, o + 1)};
      internal::Scatter<4>(internal::BendingStiffness(plane == 0 ? ei_flap : ei_lag, lb), dofs,
                           fe.k);
      internal::Scatter<4>(internal::BendingMass(rho_ab, lb), dofs, fe.m);
      internal::Scatter<4>(geometric, dofs, fe.kg);
    }
  }
  return fe;
}

// Names the kept blade modes flap1, flap2, … or lag1, … by where their kinetic energy is.
void ClassifyBladeModes(const MatrixXd& mb, Structure& st) {
  int flaps = 0, lags = 0;
  for (int j = 0; j < st.blade.shapes.cols(); ++j) {
    double flap_energy = 0, total = 0;
    for (int i = 0; i < mb.rows(); ++i) {
      const double w = st.blade.shapes(i, j) * mb.row(i).dot(st.blade.shapes.col(j));
      total += w;
      if (i % kBladeNodeDofs < 2) flap_energy += w;
    }
    const bool is_flap = flap_energy > 0.5 * total;
    st.blade_is_flap.push_back(is_flap);
    st.blade_kinds.push_back(is_flap ? "flap" + std::to_string(++flaps)
                                     : "lag" + std::to_string(++lags));
  }
}

// `cutoff_hz` = ∞ keeps every mode (the unreduced FE model).
Structure MakeStructure(const TowerRotorParams& p, double cutoff_hz) {
  Structure st;
  st.params = p;
  // Cantilever: modes of the cantilever loaded by the rigid rotor at its tip (a Ritz basis
  // for the tip-mass-dominated modes; the coupled equations use the exact rotor inertia).
  const BeamFe cantilever = CantileverFe(p);
  const int tip0 = static_cast<int>(cantilever.k.rows()) - kCantileverNodeDofs;
  MatrixXd loaded = cantilever.m;
  loaded.block(tip0, tip0, 5, 5) += RigidRotorTipMass(p);
  st.cantilever_k = cantilever.k;
  st.cantilever = Modes(cantilever.k, loaded, cutoff_hz);
  st.cantilever_mass_modal = st.cantilever.shapes.transpose() * cantilever.m * st.cantilever.shapes;
  const MatrixXd tip_rows = st.cantilever.shapes.middleRows(tip0, 5);
  st.tip_u = TipTranslationMap() * tip_rows;
  st.tip_theta = TipRotationMap() * tip_rows;

  // Blades: clamped-free, non-rotating modes.
  const BeamFe blade = BladeFe(p);
  st.blade = Modes(blade.k, blade.m, cutoff_hz);
  st.blade_geometric = st.blade.shapes.transpose() * blade.kg * st.blade.shapes;
  ClassifyBladeModes(blade.m, st);
  st.points = MakeRotorPoints(p, &st.blade.shapes);
  st.nc = static_cast<int>(st.cantilever.shapes.cols());
  st.nb = static_cast<int>(st.blade.shapes.cols());
  st.n = st.nc + 2 * st.nb;
  return st;
}

// M, D, K at rotor angle ψ for rotor speed Ω (see the derivation at the top of the file).
TowerRotorMatrices Assemble(const Structure& st, double psi, double omega, double zeta) {
  const int n = st.n, nc = st.nc, nb = st.nb;
  TowerRotorMatrices out{MatrixXd::Zero(n, n), MatrixXd::Zero(n, n), MatrixXd::Zero(n, n)};
  const Matrix3d r = RotY(psi), r1 = RotYPrime(psi), r2 = RotYSecond(psi);
  const Vector3d offset(0, st.params.hub_offset, 0);
  MatrixXd g(3, n), gd(3, n), gdd(3, n);
  for (const RotorPoint& point : st.points) {
    const Vector3d rho_p = offset + r * point.rho;
    const Vector3d vel = omega * (r1 * point.rho);
    const Vector3d acc = omega * omega * (r2 * point.rho);  // r̈0
    g.setZero();
    gd.setZero();
    gdd.setZero();
    g.leftCols(nc) = st.tip_u - Skew(rho_p) * st.tip_theta;
    gd.leftCols(nc) = -Skew(vel) * st.tip_theta;
    gdd.leftCols(nc) = -Skew(acc) * st.tip_theta;
    const double m = point.mass;
    if (point.blade >= 0) {
      const int col = nc + point.blade * nb;
      const Vector3d lag_dir(point.blade == 0 ? 1.0 : -1.0, 0, 0);         // b_k
      const Vector3d flap_dir(0, 1, 0);                                    // e_y
      const MatrixXd local = flap_dir * point.flap + lag_dir * point.lag;  // 3 × nb
      g.middleCols(col, nb) = r * local;
      gd.middleCols(col, nb) = omega * (r1 * local);
      gdd.middleCols(col, nb) = omega * omega * (r2 * local);
      // S_θb = −Σ m r̃̈0 G_b (tilt × blade deflection), both symmetric blocks.
      const MatrixXd s_tb = st.tip_theta.transpose() * (-m * Skew(acc) * (r * local));
      out.K.block(0, col, nc, nb) += s_tb;
      out.K.block(col, 0, nb, nc) += s_tb.transpose();
    }
    out.M.noalias() += m * g.transpose() * g;
    out.D.noalias() += 2 * m * g.transpose() * gd;
    out.K.noalias() += m * g.transpose() * gdd;
    // S_θθ = Σ m [sym(r̈0 ρ'ᵀ) − (r̈0·ρ') I] (second-order tilt kinematics).
    const Matrix3d outer = acc * rho_p.transpose();
    const Matrix3d w =
        m * (0.5 * (outer + outer.transpose()) - acc.dot(rho_p) * Matrix3d::Identity());
    out.K.topLeftCorner(nc, nc) += st.tip_theta.transpose() * w * st.tip_theta;
  }
  // The cantilever's own mass and the bodies' elastic stiffness, damping, geometric stiffness.
  out.M.topLeftCorner(nc, nc) += st.cantilever_mass_modal;
  out.K.topLeftCorner(nc, nc) += st.cantilever.omega.cwiseAbs2().asDiagonal();
  out.D.topLeftCorner(nc, nc) += (2 * zeta * st.cantilever.omega).asDiagonal();
  for (int k = 0; k < 2; ++k) {
    const int col = nc + k * nb;
    out.K.block(col, col, nb, nb) += st.blade.omega.cwiseAbs2().asDiagonal();
    out.K.block(col, col, nb, nb) += omega * omega * st.blade_geometric;
    out.D.block(col, col, nb, nb) += (2 * zeta * st.blade.omega).asDiagonal();
  }
  return out;
}

// A rotor point at rotor-frame position ρ (from the hub centre): where it is at rotor angle ψ
// and how the cantilever's coordinates move it (u_t + θ × ρ', as G in Assemble).
void AddRotorNode(const Structure& st, double psi, const Vector3d& rho, DrawnBody& body, int node) {
  const Vector3d rho_p = Vector3d(0, st.params.hub_offset, 0) + RotY(psi) * rho;
  body.rest.col(node) = Vector3d(st.params.cantilever_length, 0, 0) + rho_p;
  body.motion.block(3 * node, 0, 3, st.nc) = st.tip_u - Skew(rho_p) * st.tip_theta;
}

// The drawn bodies at rotor angle ψ (TowerRotorGeometry).
StructureGeometry DrawStructure(const Structure& st, double psi) {
  const TowerRotorParams& p = st.params;
  StructureGeometry g;
  g.axes = "x along the cantilever (base at 0), y along the rotor shaft, z = x × y";
  const int nce = p.cantilever_elements, nbe = p.blade_elements;
  DrawnBody cantilever{"cantilever", Eigen::Matrix3Xd::Zero(3, nce + 1),
                       MatrixXd::Zero(3 * (nce + 1), st.n)};
  for (int i = 1; i <= nce; ++i) {  // node 0 is clamped: no motion
    cantilever.rest(0, i) = p.cantilever_length * i / nce;
    const int row = kCantileverNodeDofs * (i - 1);
    cantilever.motion.row(3 * i + 1).head(st.nc) = st.cantilever.shapes.row(row);      // v
    cantilever.motion.row(3 * i + 2).head(st.nc) = st.cantilever.shapes.row(row + 2);  // w
  }
  DrawnBody shaft{"shaft", Eigen::Matrix3Xd::Zero(3, 2), MatrixXd::Zero(6, st.n)};
  shaft.rest.col(0) = cantilever.rest.col(nce);
  shaft.motion.topRows(3) = cantilever.motion.bottomRows(3);
  AddRotorNode(st, psi, Vector3d::Zero(), shaft, 1);
  g.bodies.push_back(std::move(cantilever));
  g.bodies.push_back(shaft);
  const Matrix3d r = RotY(psi);
  for (int k = 0; k < 2; ++k) {
    const double sign = k == 0 ? 1.0 : -1.0;
    const Vector3d axis(0, 0, sign), lag_dir(sign, 0, 0), flap_dir(0, 1, 0);  // a_k, b_k, e_y
    DrawnBody blade{"blade" + std::to_string(k + 1), Eigen::Matrix3Xd::Zero(3, nbe + 2),
                    MatrixXd::Zero(3 * (nbe + 2), st.n)};
    blade.rest.col(0) = shaft.rest.col(1);  // from the hub centre
    blade.motion.topRows(3) = shaft.motion.bottomRows(3);
    for (int j = 0; j <= nbe; ++j) {  // FE node j at radius r_h + j L_b/n_b; node 0 clamped
      const int node = j + 1;
      AddRotorNode(st, psi, (p.hub_radius + p.blade_length * j / nbe) * axis, blade, node);
      if (j == 0) continue;
      const int row = kBladeNodeDofs * (j - 1);
      const MatrixXd local = flap_dir * st.blade.shapes.row(row) +    // f
                             lag_dir * st.blade.shapes.row(row + 2);  // g
      blade.motion.block(3 * node, st.nc + k * st.nb, 3, st.nb) = r * local;
    }
    g.bodies.push_back(std::move(blade));
  }
  return g;
}

// Exact Fourier coefficients (harmonics 0..2 of ψ) from 8 equally spaced samples.
void ToFourier(const std::vector<MatrixXd>& samples, FourierMatrix& series) {
  const int n = static_cast<int>(samples[0].rows());
  series = FourierMatrix(n, n, 2);
  for (int w = 0; w <= 2; ++w) {
    Eigen::MatrixXcd c = Eigen::MatrixXcd::Zero(n, n);
    for (int a = 0; a < kAngleSamples; ++a) {
      const double psi = 2 * pi * a / kAngleSamples;
      c += samples[a].cast<std::complex<double>>() * std::polar(1.0 / kAngleSamples, -w * psi);
    }
    if (w == 0) c = c.real().cast<std::complex<double>>();
    series.SetHarmonic(w, c);
  }
}

// ---------------------------------------------------------------------------------------------
// Parameters.

struct ParamSpec {
  const char* name;
  double TowerRotorParams::*field;  // nullptr for the integer element counts
  const char* description;
};

const std::vector<ParamSpec>& Specs() {
  using P = TowerRotorParams;
  static const std::vector<ParamSpec> specs = {
      {"Omega", &P::omega, "rotor speed (rad/s), >= 0; period 2 pi/Omega (0: non-rotating)"},
      {"fmax", &P::fmax, "frequency range of interest (Hz), > 0; body modes kept up to 2 fmax"},
      {"zeta", &P::zeta, "modal damping ratio of every body mode, 0 <= zeta < 1"},
      {"L_c", &P::cantilever_length, "cantilever length (m)"},
      {"b_c", &P::cantilever_width_y, "cantilever cross-section width along the shaft y (m)"},
      {"h_c", &P::cantilever_depth_z, "cantilever cross-section depth along z (m)"},
      {"E_c", &P::cantilever_E, "cantilever Young's modulus (Pa), steel"},
      {"G_c", &P::cantilever_G, "cantilever shear modulus (Pa), steel"},
      {"rho_c", &P::cantilever_rho, "cantilever density (kg/m^3), steel"},
      {"d_hub", &P::hub_offset, "rotor plane offset from the cantilever axis along y (m)"},
      {"r_hub", &P::hub_radius, "hub radius = blade root radius (m)"},
      {"l_hub", &P::hub_length, "hub length along the shaft (m)"},
      {"m_hub", &P::hub_mass, "hub mass (kg), rigid solid cylinder"},
      {"L_b", &P::blade_length, "blade length, root to tip (m)"},
      {"w_b", &P::blade_width, "blade width in the rotor plane (m): sets the lag stiffness"},
      {"t_b", &P::blade_thickness, "blade thickness along the shaft (m): sets the flap stiffness"},
      {"E_b", &P::blade_E, "blade Young's modulus (Pa), aluminium"},
      {"rho_b", &P::blade_rho, "blade density (kg/m^3), aluminium"},
      {"n_c", nullptr, "cantilever finite elements (integer, 1..100)"},
      {"n_b", nullptr, "finite elements per blade (integer, 1..100)"},
  };
  return specs;
}

[[noreturn]] void BadParameter(const std::string& name, double value, const std::string& rule) {
  std::ostringstream message;
  message << "scene 'tower-rotor': parameter '" << name << "' must be " << rule << ", got "
          << value;
  throw InputError(message.str());
}

int ElementCount(const ParameterMap& values, const std::string& name, int fallback) {
  const auto it = values.find(name);
  if (it == values.end()) return fallback;
  const double v = it->second;
  if (!(v >= 1 && v <= kMaxElements && v == std::floor(v)))
    BadParameter(name, v, "an integer in 1..100");
  return static_cast<int>(v);
}

void Validate(const TowerRotorParams& p) {
  for (const ParamSpec& spec : Specs()) {
    if (!spec.field) continue;
    const double v = p.*spec.field;
    const std::string name = spec.name;
    if (!std::isfinite(v)) BadParameter(name, v, "finite");
    if (name == "Omega") {
      if (v < 0) BadParameter(name, v, ">= 0");
    } else if (name == "zeta") {
      if (!(v >= 0 && v < 1)) BadParameter(name, v, "in [0, 1)");
    } else if (!(v > 0)) {
      BadParameter(name, v, "> 0");
    }
  }
  if (p.cantilever_elements < 1 || p.cantilever_elements > kMaxElements)
    BadParameter("n_c", p.cantilever_elements, "an integer in 1..100");
  if (p.blade_elements < 1 || p.blade_elements > kMaxElements)
    BadParameter("n_b", p.blade_elements, "an integer in 1..100");
}

// ---------------------------------------------------------------------------------------------
// Mode descriptions from strain-energy shares.

// Cantilever strain energy by family: bending y (v), bending z (w), torsion (φ), from the
// cantilever's modal coordinates (K_c does not couple v, w and φ DOFs).
std::array<double, 3> CantileverFamilyEnergy(const Structure& st, const VectorXd& modal) {
  const VectorXd q = st.cantilever.shapes * modal;
  std::array<double, 3> family = {0, 0, 0};
  for (int f = 0; f < 3; ++f) {
    VectorXd part = VectorXd::Zero(q.size());
    for (int i = 0; i < q.size(); ++i) {
      const int o = i % kCantileverNodeDofs;
      const int fam = o < 2 ? 0 : (o < 4 ? 1 : 2);
      if (fam == f) part(i) = q(i);
    }
    family[f] = 0.5 * part.dot(st.cantilever_k * part);
  }
  return family;
}

// The state label of cantilever mode i: its family and its rank in that family, e.g.
// "cantilever_bend_z2" (each cantilever mode lies in one family).
std::string CantileverModeLabel(const Structure& st, int i, std::array<int, 3>& counts) {
  const std::array<double, 3> e = CantileverFamilyEnergy(st, VectorXd::Unit(st.nc, i));
  const int f = static_cast<int>(std::max_element(e.begin(), e.end()) - e.begin());
  static const char* names[3] = {"cantilever_bend_y", "cantilever_bend_z", "cantilever_torsion"};
  return names[f] + std::to_string(++counts[static_cast<size_t>(f)]);
}

std::string Describe(const Structure& st, const VectorXd& x) {
  const int nc = st.nc, nb = st.nb;
  const std::array<double, 3> family = CantileverFamilyEnergy(st, x.head(nc));
  double blades[4] = {0, 0, 0, 0};  // flap in phase, flap anti, lag in phase, lag anti
  for (int j = 0; j < nb; ++j) {
    const double sym = (x(nc + j) + x(nc + nb + j)) / std::sqrt(2.0);
    const double anti = (x(nc + j) - x(nc + nb + j)) / std::sqrt(2.0);
    const double w2 = st.blade.omega(j) * st.blade.omega(j);
    const int base = st.blade_is_flap[j] ? 0 : 2;
    blades[base] += 0.5 * w2 * sym * sym;
    blades[base + 1] += 0.5 * w2 * anti * anti;
  }
  const std::vector<std::pair<double, std::string>> parts = {
      {family[1], "cantilever bending z"},  {family[0], "cantilever bending y"},
      {family[2], "cantilever torsion"},    {blades[0], "blade flap in phase"},
      {blades[1], "blade flap anti-phase"}, {blades[2], "blade lag in phase"},
      {blades[3], "blade lag anti-phase"}};
  double total = 0;
  for (const auto& part : parts) total += part.first;
  std::vector<std::pair<double, std::string>> sorted = parts;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::ostringstream text;
  bool first = true;
  for (const auto& [energy, name] : sorted) {
    const double share = total > 0 ? energy / total : 0;
    if (share < 0.1 && !first) break;
    text << (first ? "" : ", ") << name << " " << static_cast<int>(std::lround(100 * share)) << "%";
    first = false;
  }
  return text.str();
}

// Non-rotating undamped eigen-solution of the structure at ψ = 0: frequencies (Hz), shapes.
std::pair<VectorXd, MatrixXd> NonRotatingModes(const Structure& st) {
  const TowerRotorMatrices m = Assemble(st, 0, 0, 0);
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> solver(m.K, m.M);
  if (solver.info() != Eigen::Success) throw InputError("tower-rotor: eigenproblem failed");
  return {solver.eigenvalues().cwiseMax(0).cwiseSqrt() / (2 * pi), solver.eigenvectors()};
}

struct PaperRow {
  double fem, mbs;
  const char* description;
};
// Reference paper, §5.1 "Modes of Non-Rotating System" (FEM and MBS columns; "cantilever |
// blades").
constexpr PaperRow kPaperTable[] = {
    {24.2, 24.2, "1. bend. z | -"},
    {33.4, 33.5, "1. bend. y | -"},
    {100.8, 101.8, "1. torsion | 1. bend. z in phase"},
    {113.4, 113.4, "- | 1. bending z"},
    {181.3, 185.7, "2. bend. z | 1. bending z"},
    {200.7, 205.6, "1. torsion | 1. bend. z out of phase"},
    {332.4, 338.4, "2. bend. y / 1. torsion | 1. bending z"},
    {437.1, 492.6, "3. bend. z | 1. bend. y"},
};

PeriodicSystem BuildSystem(const ParameterMap& values) {
  const TowerRotorParams p = TowerRotorParams::FromMap(values);
  auto model = std::make_shared<const TowerRotorModel>(BuildTowerRotorModel(p));
  const double omega = model->omega;
  // Ω = 0: time-invariant; any period describes it, 2π/100 s is used.
  const double period = omega > 0 ? 2 * pi / omega : 2 * pi / 100;
  const double omega_p = 2 * pi / period;
  SecondOrderSystem so;
  so.period = period;
  so.dofs = model->dofs;
  so.inputs = 2;
  so.outputs = 2;
  // M, D, K in real form: evaluated at every A(t) of every integration.
  struct RealForm {
    RealFourierSeries M, D, K;
  };
  auto real = std::make_shared<const RealForm>(RealForm{
      RealFourierSeries(model->M), RealFourierSeries(model->D), RealFourierSeries(model->K)});
  so.M = [real, omega_p](double t, Eigen::Ref<MatrixXd> out) { real->M.Evaluate(t, omega_p, out); };
  so.D = [real, omega_p](double t, Eigen::Ref<MatrixXd> out) { real->D.Evaluate(t, omega_p, out); };
  so.K = [real, omega_p](double t, Eigen::Ref<MatrixXd> out) { real->K.Evaluate(t, omega_p, out); };
  so.F = [model](double, Eigen::Ref<MatrixXd> out) { out = model->F; };
  so.Cd = [model](double, Eigen::Ref<MatrixXd> out) { out = model->Cd; };
  SystemLabels labels;
  labels.states = model->dof_labels;
  for (const std::string& name : model->dof_labels) labels.states.push_back(name + "_dot");
  labels.inputs = {"Fz_tip", "Fy_tip"};
  labels.outputs = {"z_tip", "y_tip"};
  labels.blades = 2;
  for (size_t i = 0; i < model->dof_labels.size(); ++i)
    if (model->dof_labels[i].starts_with("blade"))
      labels.blade_states.push_back(static_cast<int>(i));
  PeriodicSystem system = FromSecondOrder(so).WithLabels(std::move(labels));
  return omega > 0 ? system.WithRotorSpeed(omega) : system;
}

}  // namespace

TowerRotorParams TowerRotorParams::FromMap(const ParameterMap& values) {
  TowerRotorParams p;
  for (const ParamSpec& spec : Specs()) {
    const auto it = values.find(spec.name);
    if (spec.field && it != values.end()) p.*spec.field = it->second;
  }
  p.cantilever_elements = ElementCount(values, "n_c", p.cantilever_elements);
  p.blade_elements = ElementCount(values, "n_b", p.blade_elements);
  Validate(p);
  return p;
}

std::string TowerRotorReduction::Summary() const {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(1);
  text << "modes kept up to " << cutoff_hz << " Hz: cantilever " << cantilever_hz.size() << " (";
  for (size_t i = 0; i < cantilever_hz.size(); ++i) text << (i ? ", " : "") << cantilever_hz[i];
  text << " Hz), each blade " << blade_hz.size() << " (";
  for (size_t i = 0; i < blade_hz.size(); ++i)
    text << (i ? ", " : "") << blade_kinds[i] << " " << blade_hz[i];
  text << " Hz); " << dofs << " coordinates, " << 2 * dofs << " states";
  return text.str();
}

TowerRotorModel BuildTowerRotorModel(const TowerRotorParams& params) {
  Validate(params);
  const double cutoff = kCutoffFactor * params.fmax;
  const Structure st = MakeStructure(params, cutoff);
  TowerRotorModel model;
  model.omega = params.omega;
  model.dofs = st.n;
  if (params.omega > 0) {
    std::vector<MatrixXd> m, d, k;
    for (int a = 0; a < kAngleSamples; ++a) {
      TowerRotorMatrices at = Assemble(st, 2 * pi * a / kAngleSamples, params.omega, params.zeta);
      m.push_back(std::move(at.M));
      d.push_back(std::move(at.D));
      k.push_back(std::move(at.K));
    }
    ToFourier(m, model.M);
    ToFourier(d, model.D);
    ToFourier(k, model.K);
  } else {
    const TowerRotorMatrices at = Assemble(st, 0, 0, params.zeta);
    model.M = FourierMatrix::Constant(at.M);
    model.D = FourierMatrix::Constant(at.D);
    model.K = FourierMatrix::Constant(at.K);
  }
  // Inputs Fz, Fy at the tip: generalized forces Θ_tipᵀ T_uᵀ e; outputs the tip deflections.
  model.F = MatrixXd::Zero(st.n, 2);
  model.F.col(0).head(st.nc) = st.tip_u.row(2).transpose();
  model.F.col(1).head(st.nc) = st.tip_u.row(1).transpose();
  model.Cd = model.F.transpose();
  std::array<int, 3> family_counts = {0, 0, 0};
  for (int i = 0; i < st.nc; ++i)
    model.dof_labels.push_back(CantileverModeLabel(st, i, family_counts));
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < st.nb; ++j)
      model.dof_labels.push_back("blade" + std::to_string(k + 1) + "_" + st.blade_kinds[j]);
  }
  TowerRotorReduction& r = model.reduction;
  r.cutoff_hz = cutoff;
  for (int i = 0; i < st.nc; ++i) r.cantilever_hz.push_back(st.cantilever.omega(i) / (2 * pi));
  for (int j = 0; j < st.nb; ++j) r.blade_hz.push_back(st.blade.omega(j) / (2 * pi));
  r.blade_kinds = st.blade_kinds;
  r.dofs = st.n;
  return model;
}

GeometryAt TowerRotorGeometry(const TowerRotorParams& params) {
  Validate(params);
  auto st = std::make_shared<const Structure>(MakeStructure(params, kCutoffFactor * params.fmax));
  return [st](double t) { return DrawStructure(*st, st->params.omega * t); };
}

TowerRotorMatrices TowerRotorMatricesAt(const TowerRotorParams& params, double psi) {
  Validate(params);
  const Structure st = MakeStructure(params, kCutoffFactor * params.fmax);
  return Assemble(st, psi, params.omega, params.zeta);
}

std::vector<TowerRotorMode> TowerRotorModeTable(const TowerRotorParams& params) {
  Validate(params);
  const double cutoff = kCutoffFactor * params.fmax;
  const Structure reduced = MakeStructure(params, cutoff);
  const Structure full = MakeStructure(params, std::numeric_limits<double>::infinity());
  const auto [freq, shapes] = NonRotatingModes(reduced);
  const auto [fe_freq, fe_shapes] = NonRotatingModes(full);
  const int paper_rows = static_cast<int>(std::size(kPaperTable));
  std::vector<TowerRotorMode> table;
  for (int i = 0; i < freq.size(); ++i) {
    if (freq(i) > params.fmax && i >= paper_rows) break;
    TowerRotorMode mode;
    mode.index = i + 1;
    mode.frequency_hz = freq(i);
    mode.fe_frequency_hz = i < fe_freq.size() ? fe_freq(i) : 0;
    if (i < paper_rows) {
      mode.paper_fem_hz = kPaperTable[i].fem;
      mode.paper_mbs_hz = kPaperTable[i].mbs;
      mode.paper_description = kPaperTable[i].description;
    }
    mode.description = Describe(reduced, shapes.col(i));
    table.push_back(std::move(mode));
  }
  return table;
}

std::vector<TowerRotorMode> TowerRotorModeTable(const ParameterMap& values) {
  return TowerRotorModeTable(TowerRotorParams::FromMap(values));
}

std::vector<double> TowerRotorBeamFrequencies(double stiffness, double inertia, double length,
                                              int elements, int count, bool torsion) {
  const int per_node = torsion ? 1 : 2;
  const int n = per_node * elements;
  const double le = length / elements;
  MatrixXd k = MatrixXd::Zero(n, n), m = MatrixXd::Zero(n, n);
  auto dof = [per_node](int node, int offset) {
    return node == 0 ? -1 : per_node * (node - 1) + offset;
  };
  for (int e = 0; e < elements; ++e) {
    if (torsion) {
      const std::array<int, 2> dofs = {dof(e, 0), dof(e + 1, 0)};
      internal::Scatter<2>(internal::TorsionStiffness(stiffness, le), dofs, k);
      internal::Scatter<2>(internal::TorsionMass(inertia, le), dofs, m);
    } else {
      const std::array<int, 4> dofs = {dof(e, 0), dof(e, 1), dof(e + 1, 0), dof(e + 1, 1)};
      internal::Scatter<4>(internal::BendingStiffness(stiffness, le), dofs, k);
      internal::Scatter<4>(internal::BendingMass(inertia, le), dofs, m);
    }
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> solver(k, m);
  std::vector<double> hz;
  for (int i = 0; i < std::min(count, n); ++i)
    hz.push_back(std::sqrt(std::max(solver.eigenvalues()(i), 0.0)) / (2 * pi));
  return hz;
}

std::vector<double> TowerRotorRotatingBladeFlapFrequencies(double ei, double rho_a,
                                                           double root_radius, double length,
                                                           double omega, int elements, int count) {
  const int n = 2 * elements;
  const double le = length / elements, tip = root_radius + length;
  MatrixXd k = MatrixXd::Zero(n, n), m = MatrixXd::Zero(n, n);
  auto dof = [](int node, int offset) { return node == 0 ? -1 : 2 * (node - 1) + offset; };
  for (int e = 0; e < elements; ++e) {
    const std::array<int, 4> dofs = {dof(e, 0), dof(e, 1), dof(e + 1, 0), dof(e + 1, 1)};
    const double w2 = omega * omega;
    internal::Scatter<4>(internal::BendingStiffness(ei, le), dofs, k);
    internal::Scatter<4>(internal::BendingGeometricStiffness(
                             w2 * rho_a * tip * tip / 2, w2 * rho_a / 2, root_radius + e * le, le),
                         dofs, k);
    internal::Scatter<4>(internal::BendingMass(rho_a, le), dofs, m);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> solver(k, m);
  std::vector<double> hz;
  for (int i = 0; i < std::min(count, n); ++i)
    hz.push_back(std::sqrt(std::max(solver.eigenvalues()(i), 0.0)) / (2 * pi));
  return hz;
}

Scene TowerRotorScene() {
  const TowerRotorParams defaults;
  Scene scene;
  scene.name = "tower-rotor";
  scene.description =
      "flexible rotor of the partial-FRF paper (Fig. 2): steel cantilever (bending y, z, "
      "torsion) with a rigid hub and two elastic aluminium blades spinning at Omega about the "
      "shaft axis y; FE beams reduced to body modes below 2 fmax; inputs Fz_tip, Fy_tip, "
      "outputs z_tip, y_tip (the paper's ZZ, YY); period 2 pi/Omega (Omega_p = Omega)";
  scene.source = "built-in";
  for (const ParamSpec& spec : Specs()) {
    double value = 0;
    if (spec.field) {
      value = defaults.*spec.field;
    } else {
      value =
          std::string(spec.name) == "n_c" ? defaults.cantilever_elements : defaults.blade_elements;
    }
    scene.parameters.push_back({spec.name, value, spec.description});
  }
  scene.build = BuildSystem;
  scene.geometry = [](const ParameterMap& values) {
    return TowerRotorGeometry(TowerRotorParams::FromMap(values));
  };
  return scene;
}

}  // namespace ltp
