#pragma once
// A Campbell diagram from a tracked 1-D sweep: one line per physical mode, named by the
// states that carry it, the per-rev excitation lines n·Ω/2π, where each mode crosses them, and
// where the rotor is weakly damped. Built from the sweep's points and mode tracking alone, so
// a resumed or journalled sweep gives the same diagram.
//
// One line per physical mode: a real system's exponents come in conjugate pairs λ, λ̄ (mod
// jΩp) with conjugate shapes, and both members describe the same motion; the member listed
// first at the first point (the positive frequency, ModeDisplayOrder) is kept.
//
// Crossings: where f_k(x) − n·Ω(x)/2π changes sign between two neighbouring points, the root of
// the quadratic through three neighbouring points; its error estimate is its distance to the
// root of the straight line through the two bracketing points (the size of the curvature term
// the quadratic corrects), and the half step when no third point exists.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/mode_description.h"
#include "ltp/core/periodic_system.h"
#include "ltp/studies/mode_tracking.h"
#include "ltp/studies/sweep.h"

namespace ltp {

/// Which frequency a Campbell line shows.
enum class CampbellFrequency {
  kDamped,   ///< Im λ/2π on the tracked branch
  kNatural,  ///< |λ|/2π (what ACDC and openfast_toolbox draw; above the damped one by ζ²/2)
};

/// "damped" or "natural" (the CLI's --frequency, Python's frequency=); nullopt otherwise.
std::optional<CampbellFrequency> ParseCampbellFrequency(std::string_view name);
/// The name ParseCampbellFrequency reads: "damped" or "natural".
std::string_view ToString(CampbellFrequency kind);

struct CampbellOptions {
  CampbellFrequency frequency = CampbellFrequency::kDamped;
  /// Lines whose damping ratio is above this wherever they are tracked are left out (1 = keep
  /// all): overdamped states such as AeroDyn's DBEMT inflow, which crowd a design review's
  /// chart; a diagnostic counts them.
  double max_damping_ratio = 1;
  /// The band of interest (Hz): lines above it wherever they are tracked are left out (0 = keep
  /// all), and a diagnostic counts them.
  double max_frequency_hz = 0;
  /// Per-rev lines n = 1..max_per_rev; 0 = those below the highest mode frequency at the
  /// median rotor speed, at least up to the blade count B and at most to 3B (6 without blades).
  int max_per_rev = 0;
  /// A stable point where some mode's damping ratio is below this is weakly damped (shaded);
  /// 0 = none. Rigid-body modes (λ = 0) are left out. 0.5 %: below the 1 % structural damping
  /// usually assumed for steel and composite structures.
  double weak_damping_ratio = 0.005;
  ModeDescriptionOptions description;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct CampbellLine {
  int label = 0;  ///< the ModeTracking label this line follows
  /// The mode's states at the first and the last point where it is tracked (they differ when
  /// the mode changes character along the sweep, e.g. near a veering); "mode k" without shapes.
  std::string description, description_end;
  /// Per point (NaN where the mode is not tracked): |frequency| on the tracked branch (Hz,
  /// damped or natural as CampbellOptions::frequency says; a branch below zero is shown by its
  /// conjugate), Re λ (1/s) and damping ratio −Re λ/|λ|.
  std::vector<double> frequency_hz, real_part, damping_ratio;
  /// Index of the last point before the line is first lost (a failed point); nullopt when
  /// the line runs through the whole sweep.
  std::optional<size_t> lost_after;
};

struct CampbellCrossing {
  size_t line = 0;                            ///< index into CampbellDiagram::lines
  int per_rev = 0;                            ///< n of the line n·Ω/2π
  double parameter = 0, parameter_error = 0;  ///< swept value at the crossing, its error estimate
  double rotor_speed = 0;                     ///< rad/s
  double frequency_hz = 0;                    ///< n·Ω/2π there
  double real_part = 0;                       ///< Re λ of the mode there (1/s), interpolated
  double damping_ratio = 0;
};

struct CampbellDiagram {
  CampbellFrequency frequency = CampbellFrequency::kDamped;  ///< what frequency_hz holds
  std::vector<double> parameter;                             ///< swept value per point
  std::vector<double> rotor_speed;                           ///< rad/s per point (NaN: not a rotor)
  int blades = 0;            ///< SystemLabels::blades (per-rev multiples to emphasise)
  std::vector<int> per_rev;  ///< n of the drawn per-rev lines; empty without a rotor speed
  std::vector<CampbellLine> lines;
  std::vector<CampbellCrossing> crossings;  ///< by line, then per-rev, then parameter
  /// Intervals of the swept parameter where the system is stable but weakly damped.
  std::vector<std::pair<double, double>> weakly_damped;
  std::vector<Diagnostic> diagnostics;
};

/// Names mode `mode` of point `point` (indices into the sweep points and their modes).
using CampbellModeNamer = std::function<std::string(size_t point, int mode)>;

/// `points` in sweep order (a 1-D sweep), `tracking` = TrackModes(points), `labels` those of
/// the swept scene's system (they name the states in the descriptions). `namer` names a line
/// by its mode at its first and last point; without one, by the states carrying the mode's
/// participation (DescribeMode with `labels`).
CampbellDiagram MakeCampbellDiagram(const std::vector<SweepPoint>& points,
                                    const ModeTracking& tracking, const SystemLabels& labels,
                                    const CampbellOptions& options = {},
                                    const CampbellModeNamer& namer = {});

}  // namespace ltp
