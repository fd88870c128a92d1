#include "ltp/studies/mode_tracking.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <tuple>

namespace ltp {

namespace {

// branch_margin (0.5 − distance of the energy centroid from its harmonic) from which a mode's
// own branch is trusted over the line's continuity.
constexpr double kNamedBranchMargin = 0.25;

using cd = std::complex<double>;

}  // namespace

double Mac(const Eigen::VectorXcd& x, const Eigen::VectorXcd& y) {
  const double xx = x.squaredNorm(), yy = y.squaredNorm();
  if (!(xx > 0) || !(yy > 0)) return 0;
  return std::norm(x.dot(y)) / (xx * yy);
}

namespace {

// Where label k's exponent should be at point p: where it was at the previous successful point,
// extrapolated linearly in the swept value (1-D) when there is one before that.
cd ExpectedExponent(const std::vector<SweepPoint>& points, const ModeTracking& t, size_t p, int k,
                    int previous, int before_previous) {
  const SweepPoint& prev = points[previous];
  cd expected = prev.modes[t.labels[previous][k]].exponent;
  if (before_previous >= 0) {
    const SweepPoint& pp = points[before_previous];
    const double x0 = pp.values[0], x1 = prev.values[0], x2 = points[p].values[0];
    if (x1 != x0) {
      const cd older = pp.modes[t.labels[before_previous][k]].exponent;
      expected += (expected - older) * ((x2 - x1) / (x1 - x0));
    }
  }
  return expected;
}

// score[k][j]: how well mode j of point p continues label k, higher is better. The MAC of the
// shapes when both points have them, else minus the distance to the extrapolated exponent.
std::vector<std::vector<double>> MatchScores(const std::vector<SweepPoint>& points,
                                             const ModeTracking& t, size_t p, int previous,
                                             int before_previous, bool shapes) {
  const SweepPoint& point = points[p];
  const SweepPoint& prev = points[previous];
  const int n = static_cast<int>(point.modes.size());
  std::vector<std::vector<double>> score(n, std::vector<double>(n));
  for (int k = 0; k < n; ++k) {
    const int pk = t.labels[previous][k];
    const cd expected = ExpectedExponent(points, t, p, k, previous, before_previous);
    for (int j = 0; j < n; ++j) {
      double s;
      if (shapes) {
        s = Mac(prev.shapes.col(pk), point.shapes.col(j));
        // A mode and its complex conjugate have conjugate shapes: MAC alone cannot tell a
        // nearly real shape from its conjugate, the sign of the frequency can.
        const double f0 = prev.modes[pk].exponent.imag(), f1 = point.modes[j].exponent.imag();
        if (f0 * f1 < 0) s *= 0.5;
      } else {
        s = -std::abs(point.modes[j].exponent - expected);
      }
      score[k][j] = s;
    }
  }
  return score;
}

// Gives every label of point p a mode, greedily, best pairs first. A match by shapes updates
// the smallest accepted MAC and flags the point when the match is weak or has a close rival.
void AssignLabels(const std::vector<std::vector<double>>& score, bool shapes, size_t p,
                  ModeTracking& t) {
  const int n = static_cast<int>(score.size());
  std::vector<std::tuple<double, int, int>> pairs;
  pairs.reserve(static_cast<size_t>(n) * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j) pairs.emplace_back(score[k][j], k, j);
  std::sort(pairs.begin(), pairs.end(),
            [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::vector<int> taken(n, 0);
  t.labels[p].assign(n, -1);
  int assigned = 0;
  for (const auto& [s, k, j] : pairs) {
    if (assigned == n) break;
    if (t.labels[p][k] >= 0 || taken[j]) continue;
    t.labels[p][k] = j;
    taken[j] = 1;
    ++assigned;
    if (shapes) {
      t.min_mac = std::min(t.min_mac, s);
      double runner_up = 0;
      for (int jj = 0; jj < n; ++jj)
        if (jj != j) runner_up = std::max(runner_up, score[k][jj]);
      if (s < 0.5 || runner_up > 0.9 * s) {
        if (t.ambiguous.empty() || t.ambiguous.back() != p) t.ambiguous.push_back(p);
      }
    }
  }
}

// Branch unwrapping along each tracked line: fills t.frequency_hz from the labels.
void UnwrapBranches(const std::vector<SweepPoint>& points, ModeTracking& t) {
  t.frequency_hz.assign(points.size(), {});
  std::vector<double> last;
  for (size_t p = 0; p < points.size(); ++p) {
    const auto& labels = t.labels[p];
    t.frequency_hz[p].assign(labels.size(), std::numeric_limits<double>::quiet_NaN());
    if (!points[p].ok || labels.empty()) continue;
    if (last.size() != labels.size())
      last.assign(labels.size(), std::numeric_limits<double>::quiet_NaN());
    const double fp = points[p].period > 0 ? 1.0 / points[p].period : 0;  // 0: time-invariant
    for (size_t k = 0; k < labels.size(); ++k) {
      if (labels[k] < 0) continue;
      const FloquetMode& m = points[p].modes[labels[k]];
      double f = m.frequency_hz;
      // A shape whose energy is centred on one harmonic names its branch: keep it. Only a
      // branch the point cannot name (no shape, or energy between two harmonics near a tie)
      // follows the line; following it everywhere let a line leave its mode for an alias
      // (laval4 with an anisotropic stator: 2Ω/2π − 31.3 Hz at 800 rad/s, where the point's own
      // shape put 99.9 % of the energy on harmonic 0 at 31.3 Hz).
      const bool named = m.branch_margin >= kNamedBranchMargin;
      if (std::isfinite(last[k]) && fp > 0 && !named) f += fp * std::round((last[k] - f) / fp);
      t.frequency_hz[p][k] = f;
      last[k] = f;
    }
  }
}

}  // namespace

ModeTracking TrackModes(const std::vector<SweepPoint>& points) {
  ModeTracking t;
  t.labels.assign(points.size(), {});
  int previous = -1, before_previous = -1;  // last two successful points
  for (size_t p = 0; p < points.size(); ++p) {
    const SweepPoint& point = points[p];
    const int n = static_cast<int>(point.modes.size());
    if (!point.ok || n == 0) {
      t.labels[p].assign(n, -1);
      continue;
    }
    // The first successful point, or one whose mode count changed, starts the labels afresh.
    if (previous < 0 || static_cast<int>(points[previous].modes.size()) != n) {
      t.labels[p].resize(n);
      for (int k = 0; k < n; ++k) t.labels[p][k] = k;
      before_previous = -1;
      previous = static_cast<int>(p);
      continue;
    }
    const bool shapes = point.shapes.cols() == n && points[previous].shapes.cols() == n;
    AssignLabels(MatchScores(points, t, p, previous, before_previous, shapes), shapes, p, t);
    before_previous = previous;
    previous = static_cast<int>(p);
  }
  UnwrapBranches(points, t);
  return t;
}

}  // namespace ltp
