#pragma once
// Multi-blade coordinate transformation of linearised wind-turbine models with azimuth
// averaging (MBC3), after G. Bir, "Multi-Blade Coordinate Transformation and its Application
// to Wind Turbine Analysis", NREL/CP-500-42553 (2008), and its user's guide NREL/TP-500-44327
// (2010) — the formulation of OpenFAST's MBC3 (matlab-toolbox MBC/Source/fx_mbc3.m) and of
// openfast_toolbox's linearization/mbc.py, generalised from 3 to N >= 3 blades with the
// Coleman transform of ltp/core/multiblade.h.
//
// Blade b of N sits at ψ_b = ψ + 2π(b−1)/N. A rotating-frame quantity q_b of every blade is
// written in MBC coordinates z = (q_0, q_1c, q_1s, …[, q_d]) as q_b = Σ_c t̃_bc(ψ) z_c with
// t̃ = MbcTransform(N, ψ) (for N = 3: rows [1, cos ψ_b, sin ψ_b], Bir eq. 9). For a
// second-order DOF with displacement q and rate q̇ in the state, q̇ = t̃ ż + Ω t̃' z, so
// x_R = T(ψ) x_NR with, per blade triplet,
//
//   T = [[t̃, 0], [Ω t̃', t̃]],  Ṫ = [[Ω t̃', 0], [Ω² t̃'' + Ω̇ t̃', Ω t̃']]
//
// (t̃' = dt̃/dψ, t̃'' = d²t̃/dψ²; first-order states: T = t̃, Ṫ = Ω t̃'; fixed-frame states:
// identity) and the state equation becomes
//
//   A_NR = T⁻¹ (A_R T − Ṫ),  B_NR = T⁻¹ B_R T_u,  C_NR = T_y⁻¹ C_R T,  D_NR = T_y⁻¹ D_R T_u
//
// (T_u, T_y: t̃ on rotating input/output triplets). This is Bir's eq. 29–32; where the
// displacement rows of A_R are [0 I] (always, for OpenFAST's second-order states), his
// block-diagonal T⁻¹ and the exact one give identical matrices. MBC3 then averages the
// transformed matrices over the K azimuths (a plain mean, as OpenFAST does, whatever the
// spacing) and takes the eigenvalues λ of the mean: natural frequency |λ|/2π, damped
// frequency Im λ/2π, damping ratio −Re λ/|λ|.
//
// T(ψ) is a Lyapunov transformation (periodic, invertible): the transformed periodic system
// has the same Floquet exponents modulo jΩ. Averaging drops the periodic part of A_NR(ψ);
// for N >= 3 identical blades on an isotropic rotor it is constant and nothing is lost.
//
// Blade triplets (N-tuples) are found as OpenFAST finds them: rotating-frame channels whose
// descriptions, with "(internal DOF index = ...)" removed, differ only in the blade number
// (the first match of "blade N", "blade root N", "BD_N", "bN", "bladeN", "PitchBearingN",
// else the first digit). A second-order module lists its displacements, then their rates in
// the same order (OpenFAST's layout).
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/openfast/linearization.h"

namespace ltp {

/// How a set of channels maps to multi-blade coordinates.
struct BladeCoordinates {
  int blades = 0;  ///< N (0: no rotating-frame channel)
  /// groups[g][b]: channel of blade b+1 in group g (a blade N-tuple).
  std::vector<std::vector<int>> groups;
  /// For each channel: the group it belongs to (−1: fixed frame) and its blade (0-based).
  std::vector<int> group_of, blade_of;
  /// Descriptions of the MBC coordinates, in the channel order: a fixed-frame channel keeps
  /// its description; the channel of blade b+1 in a group holds coordinate b (collective,
  /// cosine, sine, cosine 2, sine 2, …, differential), e.g.
  /// "ED 1st flapwise bending-mode DOF of blade (cosine), m".
  std::vector<std::string> descriptions;
};

/// Groups rotating-frame channels into blade N-tuples by description.
/// @throws InputError naming a rotating-frame channel without a blade number or whose group
/// misses a blade, or groups of different sizes.
BladeCoordinates FindBladeCoordinates(const std::vector<LinChannel>& channels);

/// For each state: the index of its displacement when it is the rate of a second-order DOF,
/// else −1 (OpenFAST layout: consecutive states of one module with derivative order 2 are
/// the displacements followed by their rates). @throws InputError on an odd-sized block.
std::vector<int> RateOf(const std::vector<LinChannel>& states);

/// The state transformation x_R = T x_NR at azimuth ψ (see the header comment) and its time
/// derivative Ṫ, for rotor speed Ω and acceleration Ω̇. Channels keep their positions: blade
/// b+1 of a group holds MBC coordinate b.
struct MbcStateTransform {
  Eigen::MatrixXd T, T_dot;
};
MbcStateTransform MbcStateTransformAt(const BladeCoordinates& states,
                                      const std::vector<int>& rate_of, double psi, double omega,
                                      double omega_dot);
/// t̃ on rotating input or output channels (identity on fixed-frame ones).
Eigen::MatrixXd MbcChannelTransformAt(const BladeCoordinates& channels, double psi);

struct Mbc3Options {
  /// Rotor speed in the transform at each azimuth: true (OpenFAST's MBC3) takes Ω and Ω̇ from
  /// the operating point (LinOperatingPoint::operating_speeds / operating_accelerations);
  /// false uses each header's rotor speed and Ω̇ = 0.
  bool speed_from_operating_point = true;
  /// Share of a mode's displacement-state energy (|v_i|² / Σ|v|², rates excluded) above which
  /// a state is listed in the mode's description (at most `max_dominant_states`).
  double dominant_share = 0.10;
  int max_dominant_states = 3;
};

struct MbcMode {
  std::complex<double> eigenvalue;  ///< λ of the averaged MBC state matrix (1/s), Im λ >= 0
  double natural_frequency_hz = 0;  ///< |λ|/2π
  double damped_frequency_hz = 0;   ///< Im λ/2π
  double damping_ratio = 0;         ///< −Re λ/|λ| (0 when λ = 0)
  enum class Kind {
    kOscillatory,  ///< a complex pair, listed once
    kReal,         ///< a real eigenvalue: overdamped or first-order motion
    kRigidBody,    ///< the rigid rotation of the rotor (see rigid_body)
  };
  Kind kind = Kind::kOscillatory;
  /// The rigid rotation of the rotor: exactly 0 for the true periodic system (the orbit's own
  /// tangent is a Floquet solution with multiplier 1); its value here is the error of
  /// sampling and averaging. Recognised as the real eigenvalue nearest 0 among the modes led
  /// by the generator-azimuth state, or any |λ| <= 1e-9 ‖A‖.
  bool rigid_body = false;
  struct Share {
    int state = 0;     ///< index into Mbc3Result::states
    double share = 0;  ///< fraction of the mode's participation (a displacement's with its rate's)
  };
  std::vector<Share> dominant;  ///< single states, largest first
  /// Participation summed per coordinate family (a fixed-frame state, a collective, a cosine/sine
  /// pair), e.g. "ED 1st flapwise bending-mode DOF of blade (cyclic, BW whirl: regressive) 99%".
  std::string description;
  /// "forward" or "backward" when the leading family is a cyclic pair whose cosine and sine
  /// are about ±90° apart (the pattern travels with or against the rotor), else empty.
  std::string whirl;
  /// The mode shape in MBC coordinates (all states, Mbc3Result::states' order), scaled so its
  /// largest entry is 1: the other entries' phases are relative to the leading state.
  Eigen::VectorXcd eigenvector;
  /// Participation factor of each state, p_i = v_i·w_i (right and left eigenvectors of the
  /// averaged matrix, w·v = 1): unit-free, summing to 1; for a second-order DOF the
  /// displacement's and rate's parts add up to its share of the mode's energy
  /// (docs/mode-descriptions.md). Zero when the averaged matrix has no complete eigenvectors.
  Eigen::VectorXcd participation;
};

/// "oscillatory", "real", "rigid-body" (the words of the CLI's output).
std::string_view ToString(MbcMode::Kind kind);

struct Mbc3Result {
  /// False when MBC does not apply (1 or 2 blades): `reason` says why, and the matrices and
  /// modes below are empty. With no rotating-frame state the transform is the identity.
  bool applicable = false;
  std::string reason;
  int blades = 0;
  double rotor_speed = 0;        ///< mean Ω (rad/s)
  std::vector<double> azimuths;  ///< ψ_k (rad)
  BladeCoordinates state_coordinates, input_coordinates, output_coordinates;
  std::vector<LinChannel> states;      ///< MBC state descriptions (derivative order and flags kept)
  std::vector<LtiSystem> transformed;  ///< A_NR, B_NR, C_NR, D_NR at each azimuth
  LtiSystem average;                   ///< their mean over the azimuths
  std::vector<MbcMode> modes;          ///< sorted by natural frequency
  int rigid_body_modes = 0;
  /// max Re λ over the modes that are not rigid-body (1/s).
  double max_real_part = 0;
  /// max_k ‖A_NR(ψ_k) − mean‖ / ‖mean‖ (Frobenius): the periodicity averaging discards.
  double periodic_part = 0;
  std::vector<Diagnostic> diagnostics;
};

/// MBC3 of a set of `.lin` files at one operating point. @throws InputError when channels
/// cannot be grouped into blade tuples (see FindBladeCoordinates).
Mbc3Result Mbc3(const LinOperatingPoint& op, const Mbc3Options& options = {});

/// The operating point in MBC coordinates: its transformed matrices at the same azimuths and
/// labels, as a LinOperatingPoint (the rigid-body state and rotor speeds kept). Floquet
/// analysis of this periodic system gives the exponents of the original one modulo jΩ, with
/// mode shapes in the fixed frame. @throws InputError when MBC does not apply.
LinOperatingPoint InMultiBladeCoordinates(const LinOperatingPoint& op, const Mbc3Result& mbc);

/// A model of `op`'s samples in the files' (blade) coordinates carried into multi-blade
/// coordinates, x_R = T(ψ) x_NR with ψ = Ω t, A_NR = T⁻¹(A_R T − Ṫ) — or, with
/// `to_multiblade` false, a multi-blade model carried back, A_R = (T A_NR + Ṫ) T⁻¹. A periodic
/// Lyapunov transformation: the exponents are unchanged, and the model shares the state space
/// of one built in the other coordinates, so the two can be compared mode by mode (the
/// sampling error of docs/sampled-models.md, on the modes below a cut-off). A and T hold
/// finitely many harmonics of ψ, so the result is a Fourier series, fitted exactly by FFT.
/// B, C, D are carried with the states and take the channels of the other coordinates
/// (u_R = T_u u_NR, y_NR = T_y⁻¹ y_R for the tables MBC transforms), so partial FRFs compare
/// channel by channel too. `mbc` is Mbc3(op). `channels_only`: the states stay as they are and
/// only the inputs and outputs take the other coordinates — for a model constant in its own
/// states (one azimuth), whose transfer functions are then compared channel by channel while
/// its A stays constant (its exponents the eigenvalues of A; carried into the other states it
/// would be periodic and costly to integrate). @throws InputError when MBC does not apply.
PeriodicSystem TransformedMultiBlade(const PeriodicSystem& system, const LinOperatingPoint& op,
                                     const Mbc3Result& mbc, bool to_multiblade,
                                     bool channels_only = false);

}  // namespace ltp
