#pragma once
// OpenFAST linearisation files (`.lin`, OpenFAST v2/v3 text format) and the sampled periodic
// system they describe.
//
// OpenFAST trims a turbine, linearises it at K rotor azimuths and writes one file per
// azimuth: a header (rotor speed, azimuth, numbers of states, inputs and outputs), one table
// per kind of channel (operating point, "Rotating Frame?" flag, derivative order,
// description) and the matrices A, B, C, D of  x' = A x + B u,  y = C x + D u  at that
// azimuth. A set of files at one operating point is one periodic system with period
// T = 2π/Ω, sampled at the K azimuths ψ_k (t_k = ψ_k/Ω).
//
// The reader tolerates what real files do: extra or missing header lines, tables without the
// "Derivative Order" column (OpenFAST v2), operating points written as three comma-separated
// values (orientations), missing matrices, single- or double-precision numbers and Fortran
// exponents (1.0D+00, 1.0-100). A malformed file throws SceneError "file:line: what was
// expected".
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"

namespace ltp {

/// One row of a channel table (states, state derivatives, inputs or outputs).
struct LinChannel {
  double operating_point = 0;  ///< first value (orientation channels list three; see values)
  std::vector<double> operating_point_values;  ///< all values written in the row
  bool rotating_frame = false;                 ///< "Rotating Frame?" = T
  /// "Derivative Order" column: 2 for a second-order DOF or its rate, 1 for a first-order
  /// state, 0 for inputs/outputs; files without the column (OpenFAST v2) get 2 for states.
  int derivative_order = 0;
  std::string description;
};

/// The OpenFAST module that writes `c`: the first word of its description ("ED", "BD_1", "AD").
std::string ModuleOf(const LinChannel& c);

/// One `.lin` file.
struct LinFile {
  std::string path;                       ///< as given (names the file in messages)
  std::string title;                      ///< first non-empty line ("Linearized model: ...")
  std::optional<double> simulation_time;  ///< s
  std::optional<double> rotor_speed;      ///< Ω (rad/s) from the header
  std::optional<double> azimuth;          ///< rotor azimuth (rad) from the header
  std::optional<double> wind_speed;       ///< m/s
  int continuous_states = 0, discrete_states = 0, constraint_states = 0;
  int inputs = 0, outputs = 0;
  bool jacobians_included = false;
  std::vector<LinChannel> states;             ///< continuous_states rows
  std::vector<LinChannel> state_derivatives;  ///< empty when the table is absent
  std::vector<LinChannel> input_channels;     ///< inputs rows (when written)
  std::vector<LinChannel> output_channels;    ///< outputs rows (when written)
  /// The matrices; a matrix the file does not hold is empty (0×0).
  Eigen::MatrixXd A, B, C, D;
};

/// Parses the text of a `.lin` file; `source` names it in messages.
/// @throws SceneError "source:line: ..." naming what was expected.
LinFile ParseLinFile(const std::string& text, const std::string& source);
/// Reads and parses a file. @throws SceneError (unreadable or malformed).
LinFile ReadLinFile(const std::string& path);

/// Writes `file` in the OpenFAST v3 layout (double precision, 13 significant digits), e.g. to
/// hand a model built elsewhere to the tools that read `.lin` files. rotor_speed and azimuth
/// must be set; tables must match the matrix sizes. @throws InputError.
std::string FormatLinFile(const LinFile& file);
void WriteLinFile(const std::string& path, const LinFile& file);

/// True when `argument` names OpenFAST linearisation input rather than a scene: a `.lin` file,
/// a directory, or a glob pattern (* ? [).
bool LooksLikeLinInput(const std::string& argument);

/// Files named by the arguments: `.lin` files as given, every `*.lin` in a directory, and the
/// matches of glob patterns; sorted, duplicates removed.
/// @throws InputError when an argument matches nothing or a file is not a `.lin` file.
std::vector<std::string> ExpandLinPaths(const std::vector<std::string>& arguments);

/// A set of files at one operating point, sorted by azimuth, with every file's channels
/// matched to the first file's by description.
struct LinOperatingPoint {
  std::vector<std::string> files;    ///< sorted by azimuth
  std::vector<double> azimuths;      ///< ψ_k in [0, 2π) (rad), strictly increasing
  std::vector<double> rotor_speeds;  ///< Ω_k (rad/s) from each header
  /// Rotor speed and acceleration at each azimuth from the operating point, as OpenFAST's
  /// MBC3 takes them: the derivative of the generator azimuth (ED DOF_GeAz, plus the
  /// drivetrain twist DOF_DrTr when present) and of its rate. When the files have no
  /// generator azimuth state: the header's rotor speed and zero.
  std::vector<double> operating_speeds, operating_accelerations;
  double rotor_speed = 0;            ///< mean of rotor_speeds: the period is 2π/rotor_speed
  std::optional<double> wind_speed;  ///< m/s, from the first file's header when it has one
  /// Collective blade pitch (rad): the operating point of ElastoDyn's input "ED Extended
  /// input: collective blade-pitch command", which OpenFAST writes when the files have inputs
  /// (LinInputs); the first file's, as every azimuth of a trimmed point shares it.
  std::optional<double> collective_pitch;
  std::vector<LinChannel> states, inputs, outputs;  ///< in the first file's order
  std::vector<LtiSystem> samples;  ///< A, B, C, D at each azimuth, channels in that order
  /// Index of the generator-azimuth state (the rigid rotation of the rotor), if any.
  std::optional<int> azimuth_state;
  std::vector<Diagnostic> diagnostics;  ///< e.g. unevenly spaced azimuths

  int size() const { return static_cast<int>(azimuths.size()); }
  double period() const;
  /// Largest deviation of the azimuth spacing from 2π/K (rad): 0 for evenly spaced samples.
  double SpacingDeviation() const;
};

/// Matches the files' channels and sorts them by azimuth.
/// @throws InputError naming the file when the files are not one operating point: different
/// numbers of states, inputs or outputs, a description missing in one file, rotor speeds or
/// wind speeds that differ by more than 1e-3 relative, two files at the same azimuth, no rotor
/// speed or azimuth in a header, or no state matrix.
LinOperatingPoint MakeLinOperatingPoint(std::vector<LinFile> files);
/// ExpandLinPaths + ReadLinFile + MakeLinOperatingPoint. When the files are not one operating
/// point and GroupLinFiles finds several among them, the error lists those.
LinOperatingPoint ReadLinOperatingPoint(const std::vector<std::string>& arguments);

/// The files of `arguments` (ExpandLinPaths) grouped as OpenFAST names its output: by
/// directory and root name, `<root>.<k>.lin` being linearisation k of the simulation `root`.
/// A flat output folder of several simulations gives one group per simulation; the files of
/// one simulation given one by one (an unquoted glob) give one group; files without a numbered
/// name form one group per directory. Groups in the order of their first file, each sorted.
/// @throws InputError as ExpandLinPaths.
std::vector<std::vector<std::string>> GroupLinFiles(const std::vector<std::string>& arguments);

/// Every operating point among `arguments`: GroupLinFiles, each group split where its headers
/// give other rotor or wind speeds (OpenFAST can linearise one simulation at several times),
/// read and matched (MakeLinOperatingPoint). Without `failures` the first group that cannot be
/// read or is not one operating point throws; with it, that group is left out and described
/// there ("file …: reason") — what a Campbell diagram with --keep-going needs.
/// @throws InputError (bad arguments, or a group's error without `failures`, or no point at all).
std::vector<LinOperatingPoint> ReadLinOperatingPoints(const std::vector<std::string>& arguments,
                                                      std::vector<std::string>* failures = nullptr);

/// How matrices given at K azimuths are extended to the whole revolution.
enum class SampleInterpolation {
  /// Each sample holds over the azimuths nearer to it than to any other sample (breakpoints
  /// midway between neighbours). The state transition is then an exact product of matrix
  /// exponentials; the error is that of the hold, O(Δψ²) for smooth A(ψ).
  kNearestConstant,
  /// The trigonometric polynomial of degree H through the K samples (H = (K−1)/2 for odd K;
  /// for even K, H = K/2 and the minimum-norm interpolant, which for evenly spaced samples
  /// splits the Nyquist term between ±K/2). Exact when A(ψ) has no harmonic above H (odd K);
  /// the samples need not be evenly spaced.
  kTrigonometric,
};

/// How much the trigonometric polynomial through samples at these azimuths (in [0, 2π),
/// strictly increasing) can amplify an error in the samples, or content they leave out: its
/// Lebesgue constant max_ψ Σ_k |ℓ_k(ψ)| (ℓ_k: the interpolant of the k-th unit sample).
/// Evenly spaced: 5/3 for K = 3, 2.8 for K = 36; one file missing from an even set of K: about
/// K − 1; 0.5°, 10°, 20°: 276 (docs/sampled-models.md).
double AzimuthLebesgueConstant(const std::vector<double>& azimuths);

/// Azimuths whose Lebesgue constant exceeds this leave part of the revolution unresolved: a
/// periodic model through them is refused (docs/sampled-models.md).
inline constexpr double kMaxAzimuthLebesgueConstant = 100;

/// Why no periodic model is built from samples at these azimuths (their Lebesgue constant
/// exceeds kMaxAzimuthLebesgueConstant: clustered azimuths, e.g. files picked from the wrong
/// set), as one sentence naming the azimuths; nullopt when they are usable.
std::optional<std::string> AzimuthSamplingProblem(const std::vector<double>& azimuths);

/// The periodic system x' = A(t) x + B(t) u, y = C(t) x + D(t) u with T = 2π/rotor_speed and
/// samples[k] at t_k = azimuths[k]/rotor_speed (azimuths in [0, 2π), strictly increasing).
/// @throws InputError (sizes, rotor_speed <= 0, azimuths out of range or not increasing, or
/// clustered: AzimuthSamplingProblem).
PeriodicSystem BuildAzimuthSampledSystem(double rotor_speed, const std::vector<double>& azimuths,
                                         const std::vector<LtiSystem>& samples,
                                         SampleInterpolation interpolation);

/// The operating point's system in the files' coordinates, labelled with the descriptions and
/// with rotor speed Ω. @throws InputError when the rotor speed is 0 (a parked rotor is
/// time-invariant: no period).
PeriodicSystem BuildLinSystem(const LinOperatingPoint& op, SampleInterpolation interpolation);

/// What K samples can and cannot resolve, the files' own diagnostics, how the rigid rotation
/// shows and the ±1P ambiguity of rotating-frame states: one diagnostic each, to report
/// beside any analysis of these files.
std::vector<Diagnostic> LinCaveats(const LinOperatingPoint& op);

}  // namespace ltp
