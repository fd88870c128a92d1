#pragma once
// The built-in scene `tower-rotor`: the flexible rotor system of the reference paper
// (reference/partial-frf-paper.md, Fig. 2 and §5). A steel cantilever ("tower") clamped at its
// base carries at its free end a rigid cylindrical hub on a driven revolute joint; two elastic
// aluminium blades are clamped to the hub. Each flexible body is an Euler–Bernoulli beam
// finite-element model reduced to its modes below 2·fmax; the bodies are coupled at the hub and
// the equations are linearised about steady rotation ψ = Ω t (model and derivation in
// tower_rotor.cc).
//
// Axes (inertial): x along the cantilever (base at x = 0, tip at x = L_c), y along the rotor
// shaft (the paper's "YY", the axis of rotation), z perpendicular to both (the paper's "ZZ").
// The blades turn in the x-z plane; at ψ = 0 they point along ±z.
//
// Period: the coordinates include each blade's own modal coordinates, so the coefficients
// repeat once per revolution: T = 2π/Ω, Ωp = Ω (the paper's Ωp = 100 1/s is the rotor speed).
// The cantilever-only blocks (mass geometry of the two-bladed rotor seen from the cantilever)
// repeat twice per revolution (harmonics 0, ±2 only); the cantilever–blade coupling carries
// the odd harmonics. Because swapping the blades and turning by π is a symmetry, transfer
// functions between cantilever channels have only even partial FRFs H_{0, ±2, ...}.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "ltp/core/fourier_matrix.h"
#include "ltp/core/periodic_system.h"
#include "ltp/models/scene.h"
#include "ltp/models/structure_geometry.h"

namespace ltp {

/// Every parameter of the scene, in SI units (Hz for fmax). Defaults are the scene defaults.
///
/// The geometric defaults were fitted offline to the paper's non-rotating table (§5.1, FEM
/// column, modes 1–7) by a bounded Levenberg–Marquardt iteration on the log-frequency
/// misfit, finite-difference Jacobian, with modes matched by character (bending z, bending y,
/// torsion/anti-phase flap pair, in-phase flap) rather than by order. Free: L_c, b_c, h_c,
/// d_hub (>= 30 mm so the hub clears the cantilever), m_hub, r_hub, l_hub, L_b, t_b, w_b;
/// materials fixed (steel, aluminium); results rounded to 3 digits. Achieved (reduced
/// model): 23.6, 35.1, 100.2, 114.6, 188.2, 200.8, 314.3 Hz vs 24.2, 33.4, 100.8, 113.4,
/// 181.3, 200.7, 332.4 Hz (largest deviation −5.4%, mode 7). The hub comes out as a steel
/// disc (r 71 mm, 13.4 mm thick, 1.47 kg); the blade lag modes (~1.4 kHz) lie above 2·fmax.
struct TowerRotorParams {
  double omega = 100;  ///< rotor speed Ω (rad/s), >= 0; 0 = non-rotating (time-invariant)
  double fmax = 400;   ///< frequency range of interest (Hz); body modes kept up to 2·fmax
  double zeta = 0.01;  ///< modal damping ratio of every body mode (structural damping)
  // Cantilever (steel): length, cross-section width along y and depth along z.
  double cantilever_length = 0.470;
  double cantilever_width_y = 0.0227;
  double cantilever_depth_z = 0.0154;
  double cantilever_E = 210e9, cantilever_G = 80.77e9, cantilever_rho = 7850;
  // Hub: rigid solid cylinder on the shaft; its centre (the rotor plane) sits `hub_offset`
  // from the cantilever axis along y.
  double hub_offset = 0.030;
  double hub_radius = 0.071;  ///< also the blade root radius
  double hub_length = 0.0134;
  double hub_mass = 1.47;
  // Blades (aluminium): length from root to tip, width (in the rotor plane), thickness
  // (along the shaft: the flap direction).
  double blade_length = 0.136;
  double blade_width = 0.031;
  double blade_thickness = 0.00255;
  double blade_E = 70e9, blade_rho = 2700;
  int cantilever_elements = 20;  ///< n_c, 1..100
  int blade_elements = 10;       ///< n_b, 1..100

  /// From resolved scene parameters. @throws InputError naming a bad parameter.
  static TowerRotorParams FromMap(const ParameterMap& values);
};

/// What the modal reduction kept.
struct TowerRotorReduction {
  double cutoff_hz = 0;                  ///< 2·fmax
  std::vector<double> cantilever_hz;     ///< kept cantilever modes (with the rigid rotor)
  std::vector<double> blade_hz;          ///< kept modes of one blade (clamped, non-rotating)
  std::vector<std::string> blade_kinds;  ///< "flap1", "lag1", ... for each kept blade mode
  int dofs = 0;                          ///< cantilever modes + 2 · blade modes
  std::string Summary() const;           ///< one line: counts and frequencies
};

/// The linearised second-order equations M(ψ) p'' + D(ψ) p' + K(ψ) p = F u, y = Cd p,
/// ψ = Ω t, p = [cantilever modal coords; blade 1 modal coords; blade 2 modal coords].
/// The coefficients are exact Fourier series in ψ (harmonics −2..2), i.e. in t with Ωp = Ω.
struct TowerRotorModel {
  double omega = 0;  ///< rotor speed Ω (rad/s)
  int dofs = 0;
  FourierMatrix M, D, K;  ///< in harmonics of ψ (constant when Ω = 0)
  Eigen::MatrixXd F;      ///< dofs × 2: columns Fz_tip, Fy_tip
  Eigen::MatrixXd Cd;     ///< 2 × dofs: rows z_tip, y_tip
  std::vector<std::string> dof_labels;
  TowerRotorReduction reduction;
};

/// Builds the reduced, linearised model. @throws InputError on invalid parameters.
TowerRotorModel BuildTowerRotorModel(const TowerRotorParams& params);

/// The structure as drawn, at time t (ψ = Ω t): the cantilever's FE nodes from base to tip,
/// the shaft from the tip to the hub centre, and each blade from the hub centre through its
/// root to its FE nodes. Motion per generalized coordinate p of BuildTowerRotorModel, to first
/// order: tip translation and tilt carried to the rotor, blade flap along the shaft and lag in
/// the direction of rotation, turned by ψ. @throws InputError on invalid parameters.
GeometryAt TowerRotorGeometry(const TowerRotorParams& params);

/// M, D, K evaluated directly (not from the Fourier series) at rotor angle ψ, for checks.
struct TowerRotorMatrices {
  Eigen::MatrixXd M, D, K;
};
TowerRotorMatrices TowerRotorMatricesAt(const TowerRotorParams& params, double psi);

/// One row of the non-rotating mode table (Ω = 0, blades along ±z, i.e. ψ = 0, undamped).
struct TowerRotorMode {
  int index = 0;                  ///< 1-based
  double frequency_hz = 0;        ///< reduced model (the paper's "MBS" column)
  double fe_frequency_hz = 0;     ///< unreduced FE model of the coupled structure ("FEM")
  double paper_fem_hz = 0;        ///< paper §5.1 table, FEM column; 0 when the paper has no row
  double paper_mbs_hz = 0;        ///< paper §5.1 table, MBS column; 0 when absent
  std::string paper_description;  ///< "cantilever | blades" as in the paper's table
  /// This model's mode from its strain-energy shares, e.g.
  /// "cantilever bending z 80%, blade flap anti-phase 15%".
  std::string description;
};

/// Modes of the non-rotating system below 2·fmax (at least the paper's 8 rows when present).
std::vector<TowerRotorMode> TowerRotorModeTable(const TowerRotorParams& params);
/// Same from resolved scene parameters (what `ltp info tower-rotor --set ...` has).
std::vector<TowerRotorMode> TowerRotorModeTable(const ParameterMap& values);

/// The scene: parameters with descriptions and the builder (registered in BuiltinScenes()).
Scene TowerRotorScene();

/// Natural frequencies (Hz) of a uniform clamped-free beam from the FE elements used here:
/// Hermite cubic bending elements (`torsion` = false) or linear torsion elements (true).
/// stiffness = EI or GJ, inertia = ρA or ρI_p (per length). Exposed for tests.
std::vector<double> TowerRotorBeamFrequencies(double stiffness, double inertia, double length,
                                              int elements, int count, bool torsion);
/// Flap (out-of-plane) frequencies (Hz, in the rotating frame) of a uniform blade clamped at
/// `root_radius` from the axis and spinning at `omega` (rad/s): Hermite elements plus the
/// geometric stiffness of the centrifugal axial force N(s) = ρA Ω² (R² − s²)/2 — the blade
/// part of the scene's stiffness. Exposed for tests (Southwell coefficients).
std::vector<double> TowerRotorRotatingBladeFlapFrequencies(double ei, double rho_a,
                                                           double root_radius, double length,
                                                           double omega, int elements, int count);

}  // namespace ltp
