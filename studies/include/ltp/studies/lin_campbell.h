#pragma once
// The Campbell diagram most wind-turbine engineers draw: OpenFAST linearisations at several
// operating points (one set of azimuth files each, e.g. one per rotor speed or wind speed),
// MBC3 at each point, modes tracked from point to point by the MAC of their eigenvectors in
// multi-blade coordinates, and the lines named by MBC3's descriptions ("... (cyclic, BW
// whirl) 80%"). The tracking, per-rev lines, crossings and weak-damping regions are those of
// every ltp Campbell diagram (campbell.h): each operating point becomes one point of a sweep
// whose modes are the MBC3 eigenvalues, with rigid-body modes left out.
//
// Frequencies are damped frequencies Im λ/2π of the azimuth-averaged MBC system (absolute,
// not modulo the rotor speed); damping ratios −Re λ/|λ|.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"
#include "ltp/studies/campbell.h"
#include "ltp/studies/mode_tracking.h"
#include "ltp/studies/sweep.h"

namespace ltp {

enum class OperatingPointAxis {
  /// Rotor speed when the points' rotor speeds differ; wind speed when they repeat (a sweep
  /// below rated at minimum speed, or above rated at rated speed) and the wind speeds differ.
  kAuto,
  kRotorSpeed,  ///< order and plot by rotor speed (rpm)
  kWindSpeed,   ///< by wind speed (m/s, from the files' headers)
};
/// "auto", "rotor-speed" or "wind-speed" (the CLI's --by, Python's by=); nullopt otherwise.
std::optional<OperatingPointAxis> ParseOperatingPointAxis(std::string_view name);

struct LinCampbellOptions {
  OperatingPointAxis axis = OperatingPointAxis::kAuto;
  /// Leave out an operating point that cannot be read or analysed (its reason in
  /// LinCampbellResult::skipped) instead of failing the diagram; at least one must remain.
  bool keep_going = false;
  Mbc3Options mbc;
  /// Leave out the modes carried mostly (more than half of their participation) by states of
  /// these OpenFAST modules, e.g. {"AD"} for AeroDyn's inflow states. A state's module is the
  /// first word of its description; a name matches as a prefix ("BD" takes BD_1, BD_2, BD_3).
  std::vector<std::string> exclude_modules;
  /// Natural frequencies |λ|/2π by default: what ACDC and openfast_toolbox draw for .lin sets,
  /// so a design review compares like with like (ltp chart's Floquet lines default to damped).
  CampbellOptions campbell = [] {
    CampbellOptions o;
    o.frequency = CampbellFrequency::kNatural;
    return o;
  }();
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct LinCampbellPoint {
  std::vector<std::string> files;          ///< the azimuth files, sorted by azimuth
  double rotor_speed = 0;                  ///< rad/s
  std::optional<double> wind_speed;        ///< m/s
  std::optional<double> collective_pitch;  ///< rad (LinOperatingPoint::collective_pitch)
  double parameter = 0;                    ///< the diagram's abscissa: rpm or m/s
  Mbc3Result mbc;
  /// Caveats of this point: too few azimuths to resolve the periodic part, rigid-body modes,
  /// the files' and MBC3's own diagnostics.
  std::vector<Diagnostic> diagnostics;
};

struct LinCampbellResult {
  OperatingPointAxis axis = OperatingPointAxis::kRotorSpeed;  ///< as resolved (never kAuto)
  std::string axis_label;  ///< "rotor speed [rpm]" or "wind speed [m/s]"
  /// Operating points left out (keep_going): "files: reason", one each.
  std::vector<std::string> skipped;
  std::vector<LinCampbellPoint> points;  ///< ordered by the abscissa
  std::vector<SweepPoint> sweep;         ///< per point: the MBC3 modes as a sweep point
  ModeTracking tracking;
  CampbellDiagram diagram;  ///< lines named by MBC3's descriptions
};

/// @throws InputError when fewer than one point is given, MBC3 does not apply to a point, two
/// points have different states (their modes cannot be compared), two points share an
/// abscissa, or wind speeds are asked for and a point's files do not give one.
LinCampbellResult MakeLinCampbell(const std::vector<LinOperatingPoint>& points,
                                  const LinCampbellOptions& options = {});

/// The whole job from file arguments, as `ltp campbell` and Python's ltp.campbell run it: the
/// operating points among `arguments` (ReadLinOperatingPoints: OpenFAST output folders, globs,
/// one directory per point), then MakeLinCampbell; with keep_going, points that cannot be read
/// join those MBC3 cannot analyse in `skipped`.
/// @throws InputError as ReadLinOperatingPoints and MakeLinCampbell.
LinCampbellResult ComputeLinCampbell(const std::vector<std::string>& arguments,
                                     const LinCampbellOptions& options = {});

}  // namespace ltp
