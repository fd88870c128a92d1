#pragma once
// Names a mode in the system's own words: the share of each labelled state family in the
// mode's participation factors, with blade coordinates grouped into multiblade families
// (collective, cyclic, differential), e.g. "x 61%, zeta cyclic 37%". This is how a rotor
// engineer tells the regressive lag mode from the support mode in a Campbell diagram.
//
// Participation, not the size of the shape's entries: state i takes part in mode k by
// p_ik = v_ik·w_ki (right eigenvector v, left w, wv = 1). That number has no unit (scaling a
// state scales v_ik and w_ki inversely), the p_ik of a mode sum to 1, and for M q'' + K q = 0
// with M, K symmetric the displacement and rate parts of DOF i add up to its share
// φ_i(Mφ)_i / φᵀMφ of the mode's kinetic (equally, strain) energy (docs/mode-descriptions.md).
// |v_i|² instead counted metres against radians: a shaft mode that is 99.6 % translation by
// kinetic energy was named after its slopes.
//
// A rate state (a state labelled "s_dot" beside a state "s", or OpenFAST's "... First time
// derivative of ..." beside its displacement) belongs to its displacement's family. Blade
// families need SystemLabels::blades = B >= 2 and its blade_states: blade states whose labels
// differ only in the blade number 1..B (found as OpenFAST finds it, BladeDigit: "blade 2",
// "blade2", else the first digit) form one family when all B blades are present, and its
// participation is split by the discrete Fourier transform over the blade index (of v, and
// inversely of w, so the parts add up to the family's): harmonic 0 is the collective, 1 and
// B−1 the cyclic pair, B/2 (even B) the differential, others "cyclic k". A family's share is
// |Σ p| over its states, divided by the sum of all families' |Σ p|.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "ltp/core/periodic_system.h"

namespace ltp {

struct ModeDescriptionOptions {
  /// Families below this share of the participation are left out of the text (the
  /// largest is always named).
  double min_share = 0.10;
  int max_families = 3;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct ModeDescription {
  struct Family {
    std::string name;  ///< "x", "zeta cyclic", "blade_flap1 collective"
    double share = 0;  ///< fraction of the mode's participation, 0..1
  };
  std::vector<Family> families;  ///< all families, largest share first
  std::string text;              ///< "x 61%, zeta cyclic 37%" (empty for a zero shape)
};

/// The mode whose right eigenvector is `right` and left eigenvector `left` (both one entry per
/// state of the system `labels` describe; left·right need not be 1). Unlabelled states are
/// called x1, x2, ... @throws InputError when the sizes disagree.
ModeDescription DescribeMode(const SystemLabels& labels, const Eigen::VectorXcd& right,
                             const Eigen::VectorXcd& left,
                             const ModeDescriptionOptions& options = {});

/// The text of each mode: `right` holds one right eigenvector per column (n × k), `left` the
/// matching left eigenvectors as rows (k × n). Empty texts when the sizes do not fit the labels.
std::vector<std::string> DescribeModes(const SystemLabels& labels, const Eigen::MatrixXcd& right,
                                       const Eigen::MatrixXcd& left,
                                       const ModeDescriptionOptions& options = {});

/// The left eigenvectors (rows) of a complete set of modes: right⁻¹. Empty when `right` is not
/// square or its inverse is not finite.
Eigen::MatrixXcd LeftEigenvectors(const Eigen::MatrixXcd& right);

/// DescribeModes of a complete set of modes (n × n), their left eigenvectors from the inverse;
/// empty texts when there is none.
std::vector<std::string> DescribeModeShapes(const SystemLabels& labels,
                                            const Eigen::MatrixXcd& shapes,
                                            const ModeDescriptionOptions& options = {});

}  // namespace ltp
