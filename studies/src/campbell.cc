#include "ltp/studies/campbell.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <tuple>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"

namespace ltp {

std::string_view ToString(CampbellFrequency kind) {
  return kind == CampbellFrequency::kNatural ? "natural" : "damped";
}

std::optional<CampbellFrequency> ParseCampbellFrequency(std::string_view name) {
  if (name == "damped") return CampbellFrequency::kDamped;
  if (name == "natural") return CampbellFrequency::kNatural;
  return std::nullopt;
}

namespace {

using cd = std::complex<double>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoPi = 2 * std::numbers::pi;

// Ωp of a point: exponents are defined modulo jΩp (infinite for a time-invariant point).
double ExponentPeriod(const SweepPoint& point) {
  return point.period > 0 ? kTwoPi / point.period : std::numeric_limits<double>::infinity();
}

// Modes a and b are a conjugate pair mod jΩp, with conjugate shapes where shapes are known.
bool ConjugatePair(const SweepPoint& point, int a, int b) {
  const cd la = point.modes[static_cast<size_t>(a)].exponent,
           lb = point.modes[static_cast<size_t>(b)].exponent;
  const double wp = ExponentPeriod(point);
  const double tol =
      1e-6 * std::max({std::abs(la), std::abs(lb), std::isfinite(wp) ? wp : 0.0, 1e-300});
  if (ExponentDistance(std::conj(la), lb, wp) > tol) return false;
  if (point.shapes.cols() == static_cast<Eigen::Index>(point.modes.size()))
    return Mac(point.shapes.col(a).conjugate(), point.shapes.col(b)) > 0.9;
  return true;
}

// A mode that is its own conjugate: a real multiplier (Im λ ≡ 0 or Ωp/2 mod Ωp).
bool SelfConjugate(const SweepPoint& point, int a) {
  const cd l = point.modes[static_cast<size_t>(a)].exponent;
  const double wp = ExponentPeriod(point);
  const double tol = 1e-9 * std::max({std::abs(l), std::isfinite(wp) ? wp : 0.0, 1e-300});
  return ExponentDistance(std::conj(l), l, wp) <= tol;
}

// Labels kept as lines: one of each conjugate pair at the first successful point.
std::vector<int> PhysicalLabels(const std::vector<SweepPoint>& points,
                                const ModeTracking& tracking) {
  for (size_t p = 0; p < points.size(); ++p) {
    if (!points[p].ok || points[p].modes.empty()) continue;
    const std::vector<int>& at = tracking.labels[p];
    const int n = static_cast<int>(at.size());
    std::vector<char> dropped(static_cast<size_t>(n), 0);
    std::vector<int> kept;
    for (int k = 0; k < n; ++k) {
      if (dropped[static_cast<size_t>(k)]) continue;
      kept.push_back(k);
      if (SelfConjugate(points[p], at[static_cast<size_t>(k)])) continue;
      for (int j = k + 1; j < n; ++j)
        if (!dropped[static_cast<size_t>(j)] &&
            ConjugatePair(points[p], at[static_cast<size_t>(k)], at[static_cast<size_t>(j)])) {
          dropped[static_cast<size_t>(j)] = 1;
          break;
        }
    }
    return kept;
  }
  return {};
}

// Names a point's modes from its shapes (all modes, so their inverse gives the left
// eigenvectors), each point's inverse computed once when first asked.
class ShapeNamer {
 public:
  ShapeNamer(const std::vector<SweepPoint>& points, const SystemLabels& labels,
             const ModeDescriptionOptions& options)
      : points_(points), labels_(labels), options_(options), left_(points.size()) {}

  std::string operator()(size_t p, int mode) {
    const SweepPoint& point = points_[p];
    if (point.shapes.cols() <= mode) return "";
    if (!left_[p]) left_[p] = LeftEigenvectors(point.shapes);
    if (left_[p]->rows() != point.shapes.cols()) return "";
    try {
      return DescribeMode(labels_, point.shapes.col(mode), left_[p]->row(mode).transpose(),
                          options_)
          .text;
    } catch (const InputError&) {
      return "";  // the point's system has other states than the labels name
    }
  }

 private:
  const std::vector<SweepPoint>& points_;
  const SystemLabels& labels_;
  const ModeDescriptionOptions& options_;
  std::vector<std::optional<Eigen::MatrixXcd>> left_;
};

CampbellLine TraceLine(const std::vector<SweepPoint>& points, const ModeTracking& tracking,
                       int label, const CampbellModeNamer& describe, CampbellFrequency kind) {
  CampbellLine line;
  line.label = label;
  const size_t P = points.size();
  line.frequency_hz.assign(P, kNaN);
  line.real_part.assign(P, kNaN);
  line.damping_ratio.assign(P, kNaN);
  long first = -1, last = -1;
  for (size_t p = 0; p < P; ++p) {
    const auto& at = tracking.labels[p];
    if (!points[p].ok || label >= static_cast<int>(at.size()) || at[static_cast<size_t>(label)] < 0)
      continue;
    const FloquetMode& m = points[p].modes[static_cast<size_t>(at[static_cast<size_t>(label)])];
    // |f|: where a tracked branch passes below zero, its conjugate (same motion, same damping)
    // is the one at +|f|, and the line stays on the chart.
    const double f = std::abs(tracking.frequency_hz[p][static_cast<size_t>(label)]);
    const double re = m.exponent.real();
    const double magnitude = std::hypot(re, kTwoPi * f);
    line.frequency_hz[p] = kind == CampbellFrequency::kNatural ? magnitude / kTwoPi : f;
    line.real_part[p] = re;
    line.damping_ratio[p] = magnitude > 0 ? -re / magnitude : 0;
    if (first < 0)
      first = static_cast<long>(p);
    else if (last != static_cast<long>(p) - 1 && !line.lost_after)
      line.lost_after = static_cast<size_t>(last);
    last = static_cast<long>(p);
  }
  if (last >= 0 && last < static_cast<long>(P) - 1 && !line.lost_after)
    line.lost_after = static_cast<size_t>(last);
  if (first >= 0) {
    const auto mode_at = [&](long p) {
      return tracking.labels[static_cast<size_t>(p)][static_cast<size_t>(label)];
    };
    line.description = describe(static_cast<size_t>(first), mode_at(first));
    line.description_end = describe(static_cast<size_t>(last), mode_at(last));
  }
  return line;
}

// Root in [x0, x1] of the quadratic through (x_i, g_i), i = 0..2; NaN when none is there.
double QuadraticRoot(const double x[3], const double g[3], double lo, double hi) {
  // Newton form: g(x) = g0 + d1 (x − x0) + d2 (x − x0)(x − x1).
  const double d1 = (g[1] - g[0]) / (x[1] - x[0]);
  const double d2 = ((g[2] - g[1]) / (x[2] - x[1]) - d1) / (x[2] - x[0]);
  // In u = x − x0: d2 u² + (d1 − d2 (x1 − x0)) u + g0 = 0.
  const double a = d2, b = d1 - d2 * (x[1] - x[0]), c = g[0];
  std::vector<double> roots;
  if (std::abs(a) <= 1e-14 * std::abs(b)) {
    if (b != 0) roots.push_back(-c / b);
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      if (q != 0) roots.push_back(q / a);
      roots.push_back(q != 0 ? c / q : -b / (2 * a));
    }
  }
  for (double u : roots)
    if (x[0] + u >= std::min(lo, hi) && x[0] + u <= std::max(lo, hi)) return x[0] + u;
  return kNaN;
}

// The crossing of line `line_index` with nΩ/2π at the fraction s of the way from point p to
// p + 1 (values interpolated linearly there).
CampbellCrossing MakeCrossing(const CampbellDiagram& d, size_t line_index, int n, size_t p,
                              double s, double parameter_error) {
  const CampbellLine& line = d.lines[line_index];
  const auto at = [&](const std::vector<double>& v) {
    return s == 0 ? v[p] : v[p] + s * (v[p + 1] - v[p]);
  };
  CampbellCrossing c;
  c.line = line_index;
  c.per_rev = n;
  c.parameter = at(d.parameter);
  c.parameter_error = parameter_error;
  c.rotor_speed = at(d.rotor_speed);
  c.frequency_hz = n * c.rotor_speed / kTwoPi;
  c.real_part = at(line.real_part);
  c.damping_ratio = at(line.damping_ratio);
  return c;
}

// Crossings of one line with every per-rev line. Where the mode's frequency sits on nΩ/2π to
// round-off over a stretch of points (locked: inside an instability tongue whose frequency is
// Ωp/2 = nΩ/2π), the sign of the difference is noise: no crossing is counted there, and the
// stretch is reported in `notes`.
void FindCrossings(const CampbellDiagram& d, size_t line_index, std::vector<CampbellCrossing>& out,
                   std::vector<Diagnostic>& notes) {
  const CampbellLine& line = d.lines[line_index];
  const size_t P = d.parameter.size();
  const auto& x = d.parameter;
  for (int n : d.per_rev) {
    const auto g = [&](size_t p) { return line.frequency_hz[p] - n * d.rotor_speed[p] / kTwoPi; };
    const auto locked = [&](size_t p) {
      return std::abs(g(p)) <=
             1e-8 * (std::abs(line.frequency_hz[p]) + std::abs(n * d.rotor_speed[p] / kTwoPi));
    };
    const auto tracked = [&](size_t p) {
      return p < P && std::isfinite(line.frequency_hz[p]) && std::isfinite(d.rotor_speed[p]);
    };
    const auto valid = [&](size_t p) { return tracked(p) && !locked(p); };
    for (size_t p = 0; p < P;) {  // locked stretches
      if (!tracked(p) || !locked(p)) {
        ++p;
        continue;
      }
      size_t q = p;
      while (tracked(q + 1) && locked(q + 1)) ++q;
      if (q > p) {
        notes.push_back(
            {DiagnosticCode::kLineLockedToHarmonic, Severity::kNote,
             "mode " + std::to_string(line_index + 1) + " is locked to " + std::to_string(n) +
                 "P for " + MessageNumber(x[p]) + " … " + MessageNumber(x[q]) +
                 " (its frequency is nΩ/2π to round-off: no crossing is counted there)"});
      } else if (p > 0 && p + 1 < P && valid(p - 1) && valid(p + 1) &&
                 (g(p - 1) < 0) != (g(p + 1) < 0)) {
        // A crossing on a grid point: its error is the residual over the slope.
        const double slope = (g(p + 1) - g(p - 1)) / (x[p + 1] - x[p - 1]);
        out.push_back(MakeCrossing(d, line_index, n, p, 0, std::abs(g(p) / slope)));
      }
      p = q + 1;
    }
    for (size_t p = 0; p + 1 < P; ++p) {
      if (!valid(p) || !valid(p + 1)) continue;
      const double g0 = g(p), g1 = g(p + 1);
      if ((g0 < 0) == (g1 < 0)) continue;
      const double t = g0 / (g0 - g1);
      const double linear = x[p] + t * (x[p + 1] - x[p]);
      double root = linear, error = 0.5 * std::abs(x[p + 1] - x[p]);
      const size_t third = p > 0 && valid(p - 1) ? p - 1 : (valid(p + 2) ? p + 2 : P);
      if (third < P) {
        const double xs[3] = {x[p], x[p + 1], x[third]}, gs[3] = {g0, g1, g(third)};
        const double quadratic = QuadraticRoot(xs, gs, x[p], x[p + 1]);
        if (std::isfinite(quadratic)) {
          root = quadratic;
          error = std::abs(quadratic - linear);
        }
      }
      out.push_back(MakeCrossing(d, line_index, n, p, (root - x[p]) / (x[p + 1] - x[p]), error));
    }
  }
}

// The per-rev lines worth drawing: those below the highest mode frequency at the median
// rotor speed, at least up to the blade count (its multiples excite the fixed frame) and at
// most to 3 blade passings (6P without blades): higher orders carry little excitation and
// would bury the chart (more with CampbellOptions::max_per_rev).
std::vector<int> PerRevLines(const CampbellDiagram& d, int max_per_rev) {
  std::vector<double> speeds;
  double top_frequency = 0;
  for (double w : d.rotor_speed) {
    if (!std::isfinite(w)) return {};
    speeds.push_back(std::abs(w));
  }
  for (const CampbellLine& line : d.lines)
    for (double f : line.frequency_hz)
      if (std::isfinite(f)) top_frequency = std::max(top_frequency, f);
  if (speeds.empty()) return {};
  std::nth_element(speeds.begin(), speeds.begin() + static_cast<long>(speeds.size() / 2),
                   speeds.end());
  const double median = speeds[speeds.size() / 2];
  if (!(median > 0)) return {};
  int count = max_per_rev;
  if (count == 0)
    count = std::clamp(static_cast<int>(std::ceil(top_frequency / (median / kTwoPi))),
                       std::max(d.blades, 1), std::max(3 * d.blades, 6));
  std::vector<int> n(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) n[static_cast<size_t>(k)] = k + 1;
  return n;
}

// Stable points where some (non-rigid) mode's damping ratio is below the threshold, as
// intervals reaching halfway to the neighbouring points.
std::vector<std::pair<double, double>> WeaklyDamped(const std::vector<SweepPoint>& points,
                                                    const CampbellDiagram& d, double threshold) {
  std::vector<std::pair<double, double>> out;
  if (!(threshold > 0)) return out;
  const size_t P = points.size();
  std::vector<char> weak(P, 0);
  for (size_t p = 0; p < P; ++p) {
    if (points[p].verdict != StabilityVerdict::kStable) continue;
    const double scale = points[p].period > 0 ? kTwoPi / points[p].period : 0;
    for (const CampbellLine& line : d.lines) {
      const bool rigid =
          std::hypot(line.real_part[p], kTwoPi * line.frequency_hz[p]) <= 1e-9 * scale;
      if (std::isfinite(line.damping_ratio[p]) && !rigid && line.damping_ratio[p] < threshold)
        weak[p] = 1;
    }
  }
  const auto& x = d.parameter;
  for (size_t p = 0; p < P;) {
    if (!weak[p]) {
      ++p;
      continue;
    }
    size_t q = p;
    while (q + 1 < P && weak[q + 1]) ++q;
    const double lo = p > 0 ? 0.5 * (x[p - 1] + x[p]) : x[p];
    const double hi = q + 1 < P ? 0.5 * (x[q] + x[q + 1]) : x[q];
    out.emplace_back(lo, hi);
    p = q + 1;
  }
  return out;
}

}  // namespace

void CampbellOptions::Validate() const {
  const OptionCheck check("CampbellOptions");
  if (max_per_rev < 0 || max_per_rev > 100)
    check.Fail("max_per_rev", max_per_rev, "in 0..100 (0 = automatic)");
  if (!(max_damping_ratio > 0 && max_damping_ratio <= 1))
    check.Fail("max_damping_ratio", max_damping_ratio, "in (0, 1]");
  if (!(max_frequency_hz >= 0 && std::isfinite(max_frequency_hz)))
    check.Fail("max_frequency_hz", max_frequency_hz, ">= 0 and finite (0 = every line)");
  if (!(weak_damping_ratio >= 0 && weak_damping_ratio < 1))
    check.Fail("weak_damping_ratio", weak_damping_ratio, "in [0, 1)");
  description.Validate();
}

CampbellDiagram MakeCampbellDiagram(const std::vector<SweepPoint>& points,
                                    const ModeTracking& tracking, const SystemLabels& labels,
                                    const CampbellOptions& options,
                                    const CampbellModeNamer& namer) {
  options.Validate();
  if (tracking.labels.size() != points.size())
    throw InputError("mode tracking covers " + std::to_string(tracking.labels.size()) +
                     " points of " + std::to_string(points.size()));
  CampbellDiagram d;
  d.frequency = options.frequency;
  d.blades = labels.blades;
  for (const SweepPoint& p : points) {
    if (p.values.size() != 1) throw InputError("a Campbell diagram needs a 1-D sweep");
    d.parameter.push_back(p.values[0]);
    d.rotor_speed.push_back(p.rotor_speed);
  }
  ShapeNamer shape_namer(points, labels, options.description);
  const CampbellModeNamer by_shape = [&](size_t p, int mode) { return shape_namer(p, mode); };
  const CampbellModeNamer& describe = namer ? namer : by_shape;
  long overdamped = 0, above_band = 0;
  for (int label : PhysicalLabels(points, tracking)) {
    CampbellLine traced = TraceLine(points, tracking, label, describe, options.frequency);
    if (options.max_damping_ratio < 1 &&
        std::none_of(traced.damping_ratio.begin(), traced.damping_ratio.end(),
                     [&](double z) { return z <= options.max_damping_ratio; })) {
      ++overdamped;  // NaN (not tracked) compares false: a line tracked nowhere goes too
      continue;
    }
    if (options.max_frequency_hz > 0 &&
        std::none_of(traced.frequency_hz.begin(), traced.frequency_hz.end(),
                     [&](double f) { return f <= options.max_frequency_hz; })) {
      ++above_band;
      continue;
    }
    d.lines.push_back(std::move(traced));
    CampbellLine& line = d.lines.back();
    const std::string name = "mode " + std::to_string(d.lines.size());
    if (line.description.empty()) line.description = name;
    if (line.description_end.empty()) line.description_end = line.description;
    if (line.lost_after) {
      const size_t at = *line.lost_after;
      std::string why = "its mode count changed";
      for (size_t p = at + 1; p < points.size(); ++p)
        if (!points[p].ok) {
          why = "the point failed: " + points[p].failure;
          break;
        }
      d.diagnostics.push_back({DiagnosticCode::kLineLost, Severity::kWarning,
                               name + " (" + line.description + ") is lost after " +
                                   MessageNumber(d.parameter[at]) + ": " + why});
    }
  }
  if (overdamped > 0)
    d.diagnostics.push_back(
        {DiagnosticCode::kOverdampedLinesLeftOut, Severity::kNote,
         std::to_string(overdamped) + (overdamped == 1 ? " line" : " lines") +
             " left out: damped above " + MessageNumber(100 * options.max_damping_ratio, 3) +
             " % wherever tracked (overdamped states such as inflow dynamics)"});
  if (above_band > 0)
    d.diagnostics.push_back({DiagnosticCode::kLinesAboveBandLeftOut, Severity::kNote,
                             std::to_string(above_band) + (above_band == 1 ? " line" : " lines") +
                                 " left out: above " + MessageNumber(options.max_frequency_hz) +
                                 " Hz wherever tracked (the band of interest)"});
  d.per_rev = PerRevLines(d, options.max_per_rev);
  for (size_t k = 0; k < d.lines.size(); ++k) FindCrossings(d, k, d.crossings, d.diagnostics);
  std::stable_sort(d.crossings.begin(), d.crossings.end(), [](const auto& a, const auto& b) {
    return std::tie(a.line, a.per_rev, a.parameter) < std::tie(b.line, b.per_rev, b.parameter);
  });
  d.weakly_damped = WeaklyDamped(points, d, options.weak_damping_ratio);
  if (!tracking.ambiguous.empty()) {
    std::string where;
    for (size_t k = 0; k < tracking.ambiguous.size() && k < 5; ++k)
      where += (k ? ", " : "") + MessageNumber(d.parameter[tracking.ambiguous[k]]);
    if (tracking.ambiguous.size() > 5) where += ", …";
    d.diagnostics.push_back(
        {DiagnosticCode::kTrackingAmbiguous, Severity::kWarning,
         "mode tracking is ambiguous at " + std::to_string(tracking.ambiguous.size()) +
             " points (" + where +
             "; MAC below 0.5 or a runner-up within 10 %): lines may swap there"});
  }
  return d;
}

}  // namespace ltp
