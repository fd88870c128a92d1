#pragma once
// Pictures of `ltp chart`: Campbell + damping diagrams (1-D sweeps) and stability maps
// (2-D sweeps, the Ince–Strutt chart for Mathieu), through gnuplot.
#include <string>
#include <vector>

#include "ltp/studies/boundary_curves.h"
#include "ltp/studies/campbell.h"
#include "ltp/studies/stability_boundary.h"
#include "ltp/studies/sweep.h"

namespace ltp::cli {

struct ChartPlotInput {
  std::string title;
  /// What the Campbell diagram's frequencies and real parts are (panel titles).
  std::string eigenvalues = "Floquet frequencies",
              real_parts = "real parts of the Floquet exponents";
  std::vector<std::string> axis_labels;             ///< "Omega [rad/s]"
  const SweepGrid* grid = nullptr;                  ///< null: a Campbell diagram without a grid
  const std::vector<SweepPoint>* points = nullptr;  ///< whole grid, index order
  const CampbellDiagram* campbell = nullptr;        ///< 1-D
  const std::vector<UnstableInterval>* intervals = nullptr;  ///< 1-D
  const std::vector<BoundaryPoint>* boundary = nullptr;      ///< 2-D
  const BoundaryCurves* curves = nullptr;  ///< 2-D: drawn as lines; untraced points as dots
  /// 2-D: the grid axis drawn horizontally (0: the first sweep; 1: the second).
  int x_axis = 0;
  /// A line under the title: every parameter of the scene, defaults included.
  std::string caption;
  int sidebands = 2;  ///< faint families f ± kΩp/2π, k = 1..sidebands (1-D)
  /// The lower Campbell panel shows the damping ratio ζ in % (eigenvalues of one averaged
  /// system, MBC3) instead of Re λ (Floquet exponents, whose ζ depends on the branch).
  bool damping_ratio_panel = false;
  bool compare = false;  ///< draw snapshot and averaged-system frequencies (1-D)
};

/// The gnuplot script (data inline) for the chart.
std::string ChartPlotScript(const ChartPlotInput& in, const std::string& file);

/// Draws the chart. Without gnuplot, writes the script to `file + ".gp"` and returns a message
/// telling how to render it; returns "" when the picture was drawn.
std::string DrawChart(const ChartPlotInput& in, const std::string& file);

}  // namespace ltp::cli
