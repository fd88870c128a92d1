#pragma once
// The segment factors Φ_i = Φ(t_{i+1}, t_i) over one period, on a grid that starts uniform and
// is refined where a factor's condition number says it grows or decays too fast for its small
// singular directions to survive. Segments are integrated in parallel (OpenMP).
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"

namespace ltp::internal {

struct SegmentGridOptions {
  IntegratorOptions integrator;
  int uniform_segments = 1;         ///< starting grid: t_i = i T / uniform_segments
  std::vector<double> fixed_times;  ///< if non-empty: use exactly this grid (no refinement)
  bool refine = true;
  double max_factor_condition = 1e3;
  int max_segments = 20000;
  int threads = 1;
  /// When set (RealModalBasis of the mean Ā), a factor Φ is also measured as W⁻¹ Φ W and
  /// accepted when either measure is within the limit. For integrators whose error is a
  /// backward error of each step's generator (Magnus, Magnus–Filon, exponentials) that error
  /// sits on each mode's own scale in this basis, so what limits a segment is how far the modes'
  /// rates spread over it, not how non-normal the states make Ā (docs/model-sizes.md,
  /// "Segments in the mean's modes").
  std::optional<Eigen::MatrixXd> modal_basis;
};

struct SegmentGrid {
  bool ok = false;
  std::vector<double> times;             ///< K + 1 points, 0 … T
  std::vector<Eigen::MatrixXd> factors;  ///< K factors
  /// TransitionResult::local_error_effect of every factor, when the integrator carried them
  /// (all K, else empty).
  std::vector<Eigen::MatrixXd> local_error_effects;
  long rhs_evals = 0;
  int initial_segments = 0;    ///< the uniform grid it started from
  double worst_condition = 1;  ///< max over the factors of σmax/σmin (1 unless refining)
  /// Matrix products inside the factors of fixed-step methods (Magnus, expm): their steps,
  /// each with its own rounding that no error control sees. 0 for adaptive methods.
  long fixed_steps = 0;
  std::vector<Diagnostic> diagnostics;
};

SegmentGrid ComputeSegmentGrid(const PeriodicSystem& system, const SegmentGridOptions& options);

}  // namespace ltp::internal
