#pragma once
// Mode tracking along a 1-D sweep: which mode at one point is which mode at the next, so that
// Campbell lines connect and two modes whose frequencies cross keep their labels.
//
// Modes are matched by the modal assurance criterion MAC(x, y) = |xᴴy|² / (|x|²|y|²) of their
// shapes ξ(0) where shapes are available (monodromy route), and by the distance of the
// exponents to their linear extrapolation from the two previous points otherwise (Hill route).
#include <string>
#include <vector>

#include "ltp/studies/sweep.h"

namespace ltp {

struct ModeTracking {
  /// labels[p][k] = index into points[p].modes of the mode that carries label k (-1 for a
  /// failed point). Labels follow the display order of the first successful point.
  std::vector<std::vector<int>> labels;
  /// frequency_hz[p][k]: label k's frequency at point p (Hz, NaN at a failed point). A Floquet
  /// frequency is defined modulo Ωp/2π. A mode whose shape centres its energy on one harmonic
  /// (branch_margin >= 0.25) keeps the branch that shape names; one that cannot name it (no
  /// shape, or energy between two harmonics near a tie) is shifted by the multiple of Ωp/2π
  /// that keeps it nearest to the previous point's. The first point keeps its chosen branch. Points
  /// with period 0 (eigenvalues of a time-invariant system, e.g. MBC3's) have definite frequencies
  /// and are not shifted.
  std::vector<std::vector<double>> frequency_hz;
  /// Smallest MAC of an accepted match (1 when shapes were not used).
  double min_mac = 1;
  /// Points where a match was ambiguous (MAC < 0.5 or a runner-up within 10 %), by sweep order.
  std::vector<size_t> ambiguous;
};

/// The modal assurance criterion |xᴴy|² / (|x|²|y|²): 1 for parallel shapes, 0 for
/// orthogonal ones (and when either is zero).
double Mac(const Eigen::VectorXcd& x, const Eigen::VectorXcd& y);

/// `points` must be in sweep order (ascending grid index of a 1-D sweep).
ModeTracking TrackModes(const std::vector<SweepPoint>& points);

}  // namespace ltp
