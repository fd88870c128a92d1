#pragma once
// Names a mode shape in the system's own words: the share of its displacement energy carried
// by each labelled state, with blade coordinates grouped into multiblade families
// (collective, cyclic, differential), e.g. "x 61%, zeta cyclic 37%". This is how a rotor
// engineer tells the regressive lag mode from the support mode in a Campbell diagram.
//
// Displacement states: a state labelled "s_dot" beside a state "s", or OpenFAST's "... First
// time derivative of ...", is a rate and left out (its energy would only double-count the
// displacement's); without rates every state counts. Blade families need SystemLabels::blades
// = B >= 2 and its blade_states: blade states whose labels differ only in the blade number
// 1..B (found as OpenFAST finds it, BladeDigit: "blade 2", "blade2", else the first digit)
// form one family when all B blades are present, and its energy is split by the discrete Fourier
// transform over the blade index: harmonic 0 is the collective, 1 and B−1 the cyclic pair,
// B/2 (even B) the differential, others "cyclic k".
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "ltp/core/periodic_system.h"

namespace ltp {

struct ModeDescriptionOptions {
  /// Families below this share of the displacement energy are left out of the text (the
  /// largest is always named).
  double min_share = 0.10;
  int max_families = 3;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct ModeDescription {
  struct Family {
    std::string name;  ///< "x", "zeta cyclic", "blade_flap1 collective"
    double share = 0;  ///< fraction of the displacement energy, 0..1
  };
  std::vector<Family> families;  ///< all families, largest share first
  std::string text;              ///< "x 61%, zeta cyclic 37%" (empty for a zero shape)
};

/// `shape` has one entry per state of the system `labels` describe (unlabelled states are
/// called x1, x2, ...). @throws InputError when the sizes disagree.
ModeDescription DescribeModeShape(const SystemLabels& labels, const Eigen::VectorXcd& shape,
                                  const ModeDescriptionOptions& options = {});

/// The text of each column of `shapes` (one mode per column); empty texts when the shapes
/// are empty or do not fit the labels.
std::vector<std::string> DescribeModeShapes(const SystemLabels& labels,
                                            const Eigen::MatrixXcd& shapes,
                                            const ModeDescriptionOptions& options = {});

}  // namespace ltp
