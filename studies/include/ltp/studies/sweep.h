#pragma once
// Parameter sweeps: one independent Floquet analysis per point of a 1-D or 2-D grid of scene
// parameters (rotor speed, stiffness, ...), spread over all cores. The building block of
// Campbell diagrams, damping diagrams and stability maps (Ince–Strutt charts).
//
// Points are delivered to a callback as they complete (in completion order, not grid order),
// so a caller can stream them to disk and resume an interrupted sweep by computing only the
// indices it is missing.
#include <Eigen/Dense>
#include <atomic>
#include <complex>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ltp/floquet/floquet.h"
#include "ltp/hill/hill.h"
#include "ltp/models/scene.h"

namespace ltp {

/// One swept parameter: start, start + step, ..., up to stop (included when it lies on the
/// grid within a rounding error).
struct SweepAxis {
  std::string name;
  double start = 0, stop = 0, step = 0;

  std::vector<double> Values() const;
  /// Parses "NAME=START:STOP:STEP" (numbers may be expressions in pi).
  /// @throws InputError naming the text and what was expected.
  static SweepAxis Parse(const std::string& spec);
};

enum class SweepMethod { kMonodromy, kHill };
std::string_view ToString(SweepMethod method);
/// "monodromy" or "hill"; nullopt otherwise.
std::optional<SweepMethod> ParseSweepMethod(std::string_view name);

struct SweepOptions {
  SweepMethod method = SweepMethod::kMonodromy;
  /// Per-point monodromy options. `threads` is ignored (points run in parallel instead).
  FloquetOptions floquet;
  /// Per-point Hill options; the truncation is chosen automatically to `hill_tol`.
  HillOptions hill;
  double hill_tol = 1e-9;
  int hill_max_harmonics = 128;
  /// Mode shapes, branches and per-mode frequencies (Campbell diagrams). Off for maps: then
  /// each point costs one integration over a period and an n×n eigenvalue problem.
  bool modes = true;
  /// Also the eigenvalues of the frozen system A(0) and of the averaged system A_0 (what
  /// users compute without Floquet theory), for comparison in Campbell diagrams.
  bool snapshot = false;
  /// Run the error estimate (a second, tighter run) on every `check_every`-th point (1 = all;
  /// 0 = none). Unchecked points leave SweepPoint::error_estimate empty.
  int check_every = 1;
  /// |max log|ρ|| below this (per period) is "marginal" rather than stable/unstable: it must
  /// exceed the multipliers' error, which the study in docs/benchmarks.md puts below 1e-8 at
  /// the default tolerances.
  double marginal_log_multiplier = 1e-7;
  /// OpenMP threads over points; 0 = all cores.
  int threads = 0;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct SweepPoint {
  size_t index = 0;            ///< grid index: i0 + n0 · i1 (first axis fastest)
  std::vector<double> values;  ///< parameter value per axis
  bool ok = false;
  std::string failure;  ///< why the point failed (empty when ok)
  StabilityVerdict verdict = StabilityVerdict::kFailed;
  double period = 0;
  /// Rotor speed of the point's system (rad/s; NaN when the system is not a rotor): the
  /// per-rev excitation lines of a Campbell diagram.
  double rotor_speed = std::numeric_limits<double>::quiet_NaN();
  double max_real_exponent = std::numeric_limits<double>::quiet_NaN();   ///< 1/s
  double max_log_multiplier = std::numeric_limits<double>::quiet_NaN();  ///< T · max Re λ
  std::optional<double> error_estimate;  ///< exponents (1/s); empty when not checked
  /// Exponents on the chosen branch, in ModeDisplayOrder (principal branch without modes).
  std::vector<FloquetMode> modes;
  /// Column k: mode k's shape ξ_k(0), unit norm (monodromy route with modes; else empty).
  Eigen::MatrixXcd shapes;
  /// With SweepOptions::snapshot: eigenvalues of A(0) and of the averaged A_0 (1/s).
  std::vector<std::complex<double>> snapshot_eigenvalues, averaged_eigenvalues;
  std::vector<Diagnostic> diagnostics;  ///< the point's analysis's, as it reported them
  double elapsed_s = 0;
};

/// The grid of a sweep: axis values and the parameter map of every point.
struct SweepGrid {
  std::vector<SweepAxis> axes;              ///< 1 or 2
  std::vector<std::vector<double>> values;  ///< per axis
  size_t size() const;
  std::vector<double> PointValues(size_t index) const;
};
/// @throws InputError for 0 or more than 2 axes, an axis that is not a scene parameter, or
/// an empty axis.
SweepGrid MakeSweepGrid(const Scene& scene, std::vector<SweepAxis> axes);

/// One point: builds the system for `base` with the swept values set, and analyses it.
/// Never throws: a failing build (e.g. a singular mass matrix) or analysis is a failed point.
SweepPoint AnalyzeSweepPoint(const Scene& scene, const ParameterMap& base, const SweepGrid& grid,
                             size_t index, const SweepOptions& options, bool check_error);

/// Analyses the points `indices` of the grid in parallel and hands each to `on_point` as it
/// completes. The callback runs on the worker threads, concurrently: it must synchronise what
/// it shares (so that formatting a point costs no lock); an exception it throws stops the
/// sweep and is rethrown. Stops early, leaving the
/// remaining points undone, when `cancel` becomes true. Returns the number of points done.
size_t RunSweep(const Scene& scene, const ParameterMap& base, const SweepGrid& grid,
                const std::vector<size_t>& indices, const SweepOptions& options,
                const std::function<void(SweepPoint&&)>& on_point,
                const std::atomic<bool>* cancel = nullptr);

/// What a sweep's points say together.
struct SweepTally {
  std::map<StabilityVerdict, size_t> counts;  ///< points per verdict (every verdict present)
  size_t checked = 0;                         ///< ok points with an error estimate
  std::optional<double> max_error;            ///< largest of those (1/s); empty when none
};
SweepTally TallySweep(const std::vector<SweepPoint>& points);

}  // namespace ltp
