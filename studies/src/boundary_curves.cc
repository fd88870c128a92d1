#include "ltp/studies/boundary_curves.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/floquet/half_period_blocks.h"

namespace ltp {

namespace {

using cd = std::complex<double>;
using Vec = std::array<double, 2>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Is `v` certainly nonzero, beyond `log_noise`?
bool Certain(const CharacteristicValue& v, double log_noise) {
  return v.sign != 0 && v.log_abs > log_noise;
}

}  // namespace

namespace {

// A point on a line of the map: the line holds every coordinate but `axis` fixed at `at`.
struct Line {
  int axis = 0;
  Vec at{};
  Vec Point(double x) const {
    Vec u = at;
    u[static_cast<size_t>(axis)] = x;
    return u;
  }
};

// A root of D_σ on a line: value x, the boundary within ±bracket of it along the line.
struct Crossing {
  bool ok = false;
  double x = 0, bracket = 0;
  bool merged = false;
  bool off_map = false;  // the search reached the map's edge without a sign change
  std::string note;
};

// What a curve is a root of: D_σ (symmetry kNone), or the determinant of the half-period
// block of σ and the symmetry (half_period_blocks.h).
struct Target {
  int sigma = 1;
  BoundarySymmetry symmetry = BoundarySymmetry::kNone;
  bool operator==(const Target&) const = default;
};

class Tracer {
 public:
  Tracer(const Scene& scene, const ParameterMap& base, const SweepGrid& grid,
         const SweepOptions& sweep, const BoundaryOptions& options,
         const BoundaryCurveOptions& curve)
      : scene_(scene),
        base_(base),
        grid_(grid),
        sweep_(sweep),
        options_(options),
        curve_(curve),
        integrator_(BoundaryIntegrator(sweep, options)) {
    for (size_t a = 0; a < 2; ++a) {
      lo_[a] = grid.values[a].front();
      span_[a] = grid.values[a].back() - grid.values[a].front();
    }
    factored = sweep.method == SweepMethod::kMonodromy && FactoredOverMap();
  }
  int evaluations = 0;
  Target target;
  /// The map's system is time-reversible without damping (at its corners and centre): its
  /// curves are roots of half-period blocks' determinants.
  bool factored = false;
  double log_noise = -kInf;  // log of the traced function's error at the last checked point, ×2

  std::optional<CharacteristicValue> D(const Vec& u, bool checked = false) {
    if (!checked) {
      const auto hit = cache_.find(u);
      if (hit != cache_.end()) return hit->second;
    }
    const std::optional<CharacteristicValue> v = target.symmetry == BoundarySymmetry::kNone
                                                     ? FromMultipliers(u, checked)
                                                     : FromBlocks(u, checked);
    if (!v) return std::nullopt;
    if (checked) log_noise = v->log_abs_error + std::log(2.0);
    if (!checked) cache_[u] = v;
    return v;
  }
  void SetTarget(const Target& next) {
    if (!(next == target)) cache_.clear();
    target = next;
  }
  // The tolerance of the 1-D root along `axis` at unit coordinate x.
  double Tolerance(int axis, double x) const {
    const size_t a = static_cast<size_t>(axis);
    const double p = lo_[a] + x * span_[a];
    return curve_.rel_tol * std::max(std::abs(p), 1e-3 * span_[a]) / span_[a];
  }
  double Value(int axis, double x) const {
    return lo_[static_cast<size_t>(axis)] + x * span_[static_cast<size_t>(axis)];
  }
  double Span(int axis) const { return span_[static_cast<size_t>(axis)]; }

  Crossing Solve(const Line& line, double guess, double reach, double window, int pos_dir);
  Crossing Bracketed(const Line& line, double a, double b, double reach, bool valley_ok);

 private:
  ParameterMap Params(const Vec& u) const {
    ParameterMap params = base_;
    for (size_t a = 0; a < 2; ++a) params[grid_.axes[a].name] = lo_[a] + u[a] * span_[a];
    return params;
  }
  bool FactoredOverMap() const;
  std::optional<CharacteristicValue> FromMultipliers(const Vec& u, bool checked);
  std::optional<CharacteristicValue> FromBlocks(const Vec& u, bool checked);
  Crossing Valley(const Line& line, double center, double window, int outside, int pos_dir);
  double Vertex(const Line& line, double center, double spread);
  std::optional<double> Edge(const Line& line, double m, double end, int outside);

  const Scene& scene_;
  const ParameterMap& base_;
  const SweepGrid& grid_;
  const SweepOptions& sweep_;
  const BoundaryOptions& options_;
  const BoundaryCurveOptions& curve_;
  const IntegratorOptions integrator_;
  Vec lo_{}, span_{};
  std::map<Vec, std::optional<CharacteristicValue>> cache_;  // unchecked evaluations of target
};

bool Tracer::FactoredOverMap() const {
  for (const Vec& u : {Vec{0, 0}, Vec{0, 1}, Vec{1, 0}, Vec{1, 1}, Vec{0.5, 0.5}}) {
    try {
      if (!HasHalfPeriodBlocks(scene_.build(Params(u)))) return false;
    } catch (const std::exception&) {
      return false;
    }
  }
  return true;
}

// D_σ from the multipliers of the refinement's analysis (AnalyzeBoundaryPoint); checked: with
// the exponents' error estimate × T as each log multiplier's error.
std::optional<CharacteristicValue> Tracer::FromMultipliers(const Vec& u, bool checked) {
  ++evaluations;
  const SweepPoint p = AnalyzeBoundaryPoint(scene_, Params(u), sweep_, options_, checked);
  if (!p.ok || (checked && !(p.error_estimate && std::isfinite(*p.error_estimate))))
    return std::nullopt;
  std::vector<cd> logs;
  for (const FloquetMode& mode : p.modes) logs.push_back(mode.exponent * p.period);
  const double log_error = checked ? std::max(*p.error_estimate * p.period, 1e-16) : 0.0;
  return MultiplierDeterminant(logs, target.sigma, log_error);
}

// The determinant of the target's half-period block; checked: the block again at a hundredth
// of the tolerance (its value is reported), the difference plus the round-off of Φ(T/2)'s
// entries (16 n ε max|Φ(T/2)|) as the entries' error.
std::optional<CharacteristicValue> Tracer::FromBlocks(const Vec& u, bool checked) {
  ++evaluations;
  const bool even = target.symmetry == BoundarySymmetry::kEven;
  try {
    const PeriodicSystem system = scene_.build(Params(u));
    const auto blocks = ComputeHalfPeriodBlocks(system, integrator_);
    if (!blocks) return std::nullopt;
    const Eigen::MatrixXd& coarse = blocks->Factor(target.sigma, even);
    if (!checked) return BlockDeterminant(coarse);
    const auto refined = ComputeHalfPeriodBlocks(system, RefinedIntegratorOptions(integrator_));
    if (!refined) return std::nullopt;
    const double largest =
        std::max({refined->P.cwiseAbs().maxCoeff(), refined->Q.cwiseAbs().maxCoeff(),
                  refined->U.cwiseAbs().maxCoeff(), refined->W.cwiseAbs().maxCoeff()});
    const double round_off =
        16 * system.states() * std::numeric_limits<double>::epsilon() * largest;
    const Eigen::MatrixXd& value = refined->Factor(target.sigma, even);
    const Eigen::MatrixXd error = ((value - coarse).cwiseAbs().array() + round_off).matrix();
    return BlockDeterminant(value, &error);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// TOMS 748's function: D_σ scaled by e^{-norm} (a constant per solve, so it stays smooth),
// clamped into the doubles; NaN when the analysis fails.
double Scaled(const std::optional<CharacteristicValue>& v, double norm) {
  if (!v) return std::numeric_limits<double>::quiet_NaN();
  return v->sign * std::exp(std::clamp(v->log_abs - norm, -700.0, 700.0));
}

// The root of D_σ in [a, b] (opposite signs), then certified: each end is moved outwards until
// D_σ's sign there is certain beyond the checked evaluation's own error. Opposite certain signs:
// one crossing within the certified interval. Equal ones: two edges of a tongue (or none) closer
// than the evaluations resolve — the valley search brackets them together.
Crossing Tracer::Bracketed(const Line& line, double a, double b, double reach, bool valley_ok) {
  Crossing c;
  const auto da = D(line.Point(a)), db = D(line.Point(b));
  if (!da || !db) return c.note = "the analysis failed at a bracket end", c;
  const double norm = std::max(da->log_abs, db->log_abs);
  auto f = [&](double x) { return Scaled(D(line.Point(x)), norm); };
  std::uintmax_t iterations = static_cast<std::uintmax_t>(options_.max_iterations);
  const double tol = Tolerance(line.axis, 0.5 * (a + b));
  double lo = std::min(a, b), hi = std::max(a, b);
  if (da->sign * db->sign < 0) {
    std::tie(lo, hi) = boost::math::tools::toms748_solve(
        f, lo, hi, a < b ? Scaled(da, norm) : Scaled(db, norm),
        a < b ? Scaled(db, norm) : Scaled(da, norm),
        [tol](double x, double y) { return std::abs(y - x) <= tol; }, iterations);
  }
  const double mid = 0.5 * (lo + hi);
  if (!D(line.Point(mid), true)) return c.note = "the checked analysis failed at the root", c;
  // Outwards from each end until the sign is certain.
  int signs[2] = {0, 0};
  double ends[2] = {lo, hi};
  for (int side = 0; side < 2; ++side) {
    double w = std::max(hi - lo, tol), x = ends[side];
    for (;;) {
      const auto v = D(line.Point(x));
      if (!v) return c.note = "the analysis failed while certifying the bracket", c;
      if (Certain(*v, log_noise)) {
        signs[side] = v->sign;
        break;
      }
      x = side == 0 ? x - w : x + w;
      w *= 2;
      if (std::abs(x - mid) > reach || x < -1e-12 || x > 1 + 1e-12)
        return c.note = "the sign of D_σ is not certain within the reach", c;
      x = std::clamp(x, 0.0, 1.0);
    }
    ends[side] = x;
  }
  if (signs[0] != signs[1]) {
    c.ok = true;
    c.x = mid;
    c.bracket = std::max(mid - ends[0], ends[1] - mid) + tol;
    return c;
  }
  if (!valley_ok) return c.note = "no certain sign change", c;
  return Valley(line, mid, std::max(reach, ends[1] - ends[0]), signs[0], 0);
}

// The end of the set {outside · D_σ ≤ noise} between m (inside it) and `end` (outside it).
std::optional<double> Tracer::Edge(const Line& line, double m, double end, int outside) {
  const double noise = log_noise;
  const auto dm = D(line.Point(m)), de = D(line.Point(end));
  if (!dm || !de) return std::nullopt;
  const double norm = noise;  // g = outside · D / noise − 1
  auto g = [&](const std::optional<CharacteristicValue>& v) {
    return outside * Scaled(v, norm) - 1.0;
  };
  const double gm = g(dm), ge = g(de);
  if (!(gm <= 0 && ge > 0)) return std::nullopt;
  std::uintmax_t iterations = static_cast<std::uintmax_t>(options_.max_iterations);
  const double tol = Tolerance(line.axis, m);
  const auto [lo, hi] = boost::math::tools::toms748_solve(
      [&](double x) { return g(D(line.Point(x))); }, std::min(m, end), std::max(m, end),
      m < end ? gm : ge, m < end ? ge : gm,
      [tol](double x, double y) { return std::abs(y - x) <= tol; }, iterations);
  return m < end ? hi : lo;  // the outer end: the set lies within
}

// The vertex of the parabola fitted to D_σ at center + k·spread, k = −3…3, by least squares:
// where the evaluations' noise hides the valley's floor, its flanks (D_σ well above the noise)
// still place its middle. Returns center when the fit fails.
double Tracer::Vertex(const Line& line, double center, double spread) {
  spread = std::min({spread, center, 1 - center});
  if (!(spread > 0)) return center;
  Eigen::Matrix<double, 7, 3> A;
  Eigen::Matrix<double, 7, 1> y;
  const auto d0 = D(line.Point(center + spread));
  if (!d0) return center;
  for (int k = -3; k <= 3; ++k) {
    const double s = k / 3.0;
    const double v = Scaled(D(line.Point(center + s * spread)), d0->log_abs);
    if (!std::isfinite(v)) return center;
    A.row(k + 3) << 1, s, s * s;
    y(k + 3) = v;
  }
  const Eigen::Vector3d c = A.colPivHouseholderQr().solve(y);
  if (!(c(2) != 0) || !std::isfinite(c(1) / c(2))) return center;
  return center - 0.5 * c(1) / c(2) * spread;
}

// Where no sign change shows: the valley of outside · D_σ near `center`. Its minimum below
// −noise: two certain crossings, ours by the orientation (pos_dir; 0: the one nearer center).
// Within ±noise: the edges merge beyond resolution — the point brackets the whole set where
// |D_σ| ≤ noise. Above: no crossing here.
Crossing Tracer::Valley(const Line& line, double center, double window, int outside, int pos_dir) {
  Crossing c;
  const double lo = std::max(0.0, center - window), hi = std::min(1.0, center + window);
  const auto d0 = D(line.Point(center));
  if (!d0) return c.note = "the analysis failed", c;
  const double norm = d0->log_abs;
  boost::uintmax_t iterations = 80;
  const auto [m, fm] = boost::math::tools::brent_find_minima(
      [&](double x) {
        const double v = Scaled(D(line.Point(x)), norm);
        return std::isfinite(v) ? outside * v : kInf;
      },
      lo, hi, 40, iterations);
  const auto dm = D(line.Point(m), true);
  if (!dm) return c.note = "the checked analysis failed at the valley's floor", c;
  if (Certain(*dm, log_noise) && dm->sign == outside)
    return c.note = "no crossing: D_σ keeps its sign beyond its error near the prediction", c;
  if (Certain(*dm, log_noise)) {
    // Two resolved crossings around m: ours is where D_σ turns positive along pos_dir.
    const bool right = pos_dir == 0 ? center >= m : (pos_dir > 0) == (outside > 0);
    Crossing r = Bracketed(line, m, right ? hi : lo, window, false);
    if (!r.ok) r.note = "valley: " + r.note;
    return r;
  }
  const auto left = Edge(line, m, lo, outside), right = Edge(line, m, hi, outside);
  if (!left || !right)
    return c.note = "the edges of the unresolved valley lie beyond the search window", c;
  c.ok = c.merged = true;
  c.x = Vertex(line, 0.5 * (*left + *right), 16 * (*right - *left));
  c.x = std::clamp(c.x, *left, *right);
  c.bracket = std::max(c.x - *left, *right - c.x) + Tolerance(line.axis, c.x);
  return c;
}

// The crossing near `guess` on a line, where D_σ turns positive in direction pos_dir: a search
// outwards from the guess (steps reach/32, doubling) for a sign change, then Bracketed; without
// one, the valley within `window`.
Crossing Tracer::Solve(const Line& line, double guess, double reach, double window, int pos_dir) {
  Crossing c;
  const auto d0 = D(line.Point(guess));
  if (!d0) return c.note = "the analysis failed at the prediction", c;
  if (Certain(*d0, log_noise)) {
    const double dir = d0->sign > 0 ? -pos_dir : pos_dir;
    double previous = guess;
    for (double d = reach / 32; d <= reach * 1.0001; d *= 2) {
      const double x = std::clamp(guess + dir * d, 0.0, 1.0);
      const auto v = D(line.Point(x));
      if (!v) return c.note = "the analysis failed during the search", c;
      if (v->sign != d0->sign) return Bracketed(line, previous, x, reach, true);
      if (x == 0.0 || x == 1.0) {
        c.off_map = true;
        break;
      }
      previous = x;
    }
  }
  Crossing v = Valley(line, guess, std::min(window, reach), d0->sign == 0 ? 1 : d0->sign, pos_dir);
  v.off_map = c.off_map && !v.ok;
  return v;
}

}  // namespace

void BoundaryCurveOptions::Validate() const {
  const OptionCheck check("BoundaryCurveOptions");
  if (!(rel_tol > 0 && rel_tol < 1e-2)) check.Fail("rel_tol", rel_tol, "0 < rel_tol < 0.01");
  if (!(min_step > 0)) check.Fail("min_step", min_step, "> 0");
  if (!(initial_step >= min_step)) check.Fail("initial_step", initial_step, ">= min_step");
  if (!(max_step >= initial_step && max_step <= 0.5))
    check.Fail("max_step", max_step, "initial_step <= max_step <= 0.5");
  if (!(max_displacement > 0 && max_displacement < 1))
    check.Fail("max_displacement", max_displacement, "0 < max_displacement < 1");
  if (!(max_turn > 0 && max_turn < 1.5)) check.Fail("max_turn", max_turn, "0 < max_turn < 1.5");
  if (max_points < 2) check.Fail("max_points", max_points, ">= 2");
}

}  // namespace ltp

namespace ltp {
namespace {

Vec Add(const Vec& a, const Vec& b, double s) { return {a[0] + s * b[0], a[1] + s * b[1]}; }
double Norm(const Vec& a) { return std::hypot(a[0], a[1]); }

// One direction of a curve from its seed: predictor along the secant tangent, corrector across
// (along the axis the tangent leans least towards), step adapted to the corrector's displacement
// and the turning; ends at the map's edge, where the curve closes, or where the step collapses.
struct Walk {
  std::vector<Vec> u;
  std::vector<int> across;
  std::vector<double> bracket;  // unit coordinates along `across`
  std::vector<char> merged;
  std::string end;
};

// The curve's direction at its seed: the gradient of D_σ by central differences (normal, towards
// D_σ > 0) and the tangent perpendicular to it.
struct Frame {
  Vec tangent{}, normal{};
};

std::optional<Frame> SeedFrame(Tracer& t, const Vec& seed) {
  const double d = 1e-5;
  double norm = 0;
  Vec g{};
  for (size_t a = 0; a < 2; ++a) {
    Vec up = seed, down = seed;
    up[a] = std::min(1.0, seed[a] + d);
    down[a] = std::max(0.0, seed[a] - d);
    const auto du = t.D(up), dd = t.D(down);
    if (!du || !dd) return std::nullopt;
    if (a == 0) norm = std::max(du->log_abs, dd->log_abs);
    g[a] = (Scaled(du, norm) - Scaled(dd, norm)) / (up[a] - down[a]);
  }
  const double len = Norm(g);
  if (!(len > 0) || !std::isfinite(len)) return std::nullopt;
  Frame f;
  f.normal = {g[0] / len, g[1] / len};
  f.tangent = {-f.normal[1], f.normal[0]};
  return f;
}

// An exit through the edge of the across axis: the crossing on that edge, between the last
// point and the prediction (along the step axis).
std::optional<std::pair<Vec, Crossing>> EdgeExit(Tracer& t, const Vec& P, const Vec& Q, int step,
                                                 int across, int pos_dir) {
  Line edge;
  edge.axis = step;
  edge.at = Q;
  edge.at[static_cast<size_t>(across)] = Q[static_cast<size_t>(across)] > 0.5 ? 1.0 : 0.0;
  const double a = P[static_cast<size_t>(step)], b = Q[static_cast<size_t>(step)];
  const double reach = std::abs(b - a) + 1e-9;
  Crossing c = t.Solve(edge, 0.5 * (a + b), reach, reach, pos_dir);
  if (!c.ok) return std::nullopt;
  return std::make_pair(edge.Point(c.x), c);
}

void Append(Walk& w, const Vec& u, int across, const Crossing& c) {
  w.u.push_back(u);
  w.across.push_back(across);
  w.bracket.push_back(c.bracket);
  w.merged.push_back(c.merged);
}

Walk WalkCurve(Tracer& t, const Vec& seed, const Frame& frame, int dir,
               const BoundaryCurveOptions& o, int max_points) {
  Walk w;
  Vec P = seed, tangent{dir * frame.tangent[0], dir * frame.tangent[1]}, normal = frame.normal;
  const Vec start = tangent;
  double h = 0.25 * o.initial_step, last_disp = 0, last_bracket = 0;
  bool first = true, refreshed = false;
  while (static_cast<int>(w.u.size()) < max_points) {
    const int step = std::abs(tangent[0]) >= std::abs(tangent[1]) ? 0 : 1, across = 1 - step;
    const size_t s = static_cast<size_t>(step), a = static_cast<size_t>(across);
    Vec Q = Add(P, tangent, h);
    bool at_edge = false;
    if (Q[s] < 0 || Q[s] > 1) {
      const double edge = Q[s] < 0 ? 0.0 : 1.0;
      if (std::abs(P[s] - edge) < 1e-12) return w.end = "reached the map's edge", w;
      Q = Add(P, tangent, (edge - P[s]) / tangent[s]);
      Q[s] = edge;
      at_edge = true;
    }
    if ((Q[a] < 0 && P[a] < 1e-12) || (Q[a] > 1 && P[a] > 1 - 1e-12))
      return w.end = "reached the map's edge", w;  // a seed on the edge, walking outwards
    const int pos_dir = normal[a] >= 0 ? 1 : -1;
    const double guess = std::clamp(Q[a], 0.0, 1.0);
    const double window = std::max({8 * last_disp, 8 * last_bracket, 0.25 * h});
    Line line{across, Q};
    Crossing c = t.Solve(line, guess, h, window, pos_dir);
    if (!c.ok && c.off_map && !first) {
      if (const auto exit = EdgeExit(t, P, Q, step, across, normal[s] >= 0 ? 1 : -1)) {
        Append(w, exit->first, step, exit->second);
        return w.end = "reached the map's edge", w;
      }
    }
    const Vec R = line.Point(c.x);
    const Vec chord = Add(R, P, -1);
    const double disp = std::abs(c.x - guess), len = Norm(chord);
    const double turn = len > 0
                            ? std::acos(std::clamp(
                                  (chord[0] * tangent[0] + chord[1] * tangent[1]) / len, -1.0, 1.0))
                            : 0;
    if (!c.ok || len == 0 ||
        (!first && (disp > o.max_displacement * h || turn > o.max_turn) && !c.merged)) {
      // The secant lags the curve where it turns fast (a damped tongue's nose): once per
      // point, take the tangent from the gradient of D_σ instead, keeping the direction.
      if (!refreshed && !first) {
        refreshed = true;
        if (const auto f = SeedFrame(t, P)) {
          const double s = f->tangent[0] * tangent[0] + f->tangent[1] * tangent[1] < 0 ? -1 : 1;
          tangent = {s * f->tangent[0], s * f->tangent[1]};
          normal = f->normal;
          continue;
        }
      }
      h *= 0.5;
      if (h < o.min_step)
        return w.end = "the step fell below its minimum: " +
                       (c.ok ? std::string("the curve turns too sharply") : c.note),
               w;
      continue;
    }
    Append(w, R, across, c);
    refreshed = false;
    const Vec next{chord[0] / len, chord[1] / len};
    Vec n{-next[1], next[0]};
    if (n[0] * normal[0] + n[1] * normal[1] < 0) n = {-n[0], -n[1]};
    tangent = next;
    normal = n;
    P = R;
    last_disp = disp;
    last_bracket = c.bracket;
    const bool on_edge = std::min({R[0], R[1], 1 - R[0], 1 - R[1]}) < 1e-12;
    if (at_edge || (on_edge && !first)) return w.end = "reached the map's edge", w;
    if (first || (disp < 0.25 * o.max_displacement * h && turn < 0.25 * o.max_turn))
      h = std::min(first ? o.initial_step : 1.6 * h, o.max_step);
    first = false;
    // Closed: back next to the seed, heading the way the walk set out (the other edge of a
    // tongue passes next to a seed near its nose, heading the other way).
    if (w.u.size() > 3 && Norm(Add(R, seed, -1)) < h &&
        tangent[0] * start[0] + tangent[1] * start[1] > 0.5)
      return w.end = "the curve closes", w;
  }
  return w.end = "reached max_points", w;
}

// The seed of a curve at a refined boundary point: the root of the traced function on the
// point's grid line between the grid values around it, for the target (σ, and the symmetry on a
// factored map) whose function changes sign there (the nearer root when several do). Empty when
// none does: a complex pair crosses.
struct Seed {
  Target target;
  Crossing crossing;
};

std::vector<Target> Targets(bool factored) {
  if (!factored) return {{1, BoundarySymmetry::kNone}, {-1, BoundarySymmetry::kNone}};
  std::vector<Target> all;
  for (int sigma : {1, -1})
    for (BoundarySymmetry s : {BoundarySymmetry::kEven, BoundarySymmetry::kOdd})
      all.push_back({sigma, s});
  return all;
}

template <class Skip>
std::optional<Seed> FindSeed(Tracer& t, const Line& line, double a, double b, double value,
                             Skip skip) {
  std::optional<Seed> best;
  for (const Target& target : Targets(t.factored)) {
    t.SetTarget(target);
    const auto da = t.D(line.Point(a)), db = t.D(line.Point(b));
    if (!da || !db || da->sign * db->sign >= 0 || skip(target)) continue;
    Crossing c = t.Bracketed(line, a, b, std::abs(b - a), true);
    if (!c.ok) continue;
    if (!best || std::abs(c.x - value) < std::abs(best->crossing.x - value)) best = Seed{target, c};
  }
  return best;
}

bool Follows(const BoundaryCurve& c, const Target& target) {
  return (c.kind == BoundaryKind::kRealPlusOne) == (target.sigma > 0) &&
         c.symmetry == target.symmetry;
}

// Does a curve (of `target`; none: any) cross the seed's grid line within `near` of it (unit
// coordinates along axis), or end next to it on the line?
bool OnACurve(const std::vector<BoundaryCurve>& curves, const Vec& u, int axis, double near,
              const Tracer& t, const std::optional<Target>& target = std::nullopt) {
  const size_t k = static_cast<size_t>(axis), o = 1 - k;
  const double line = t.Value(1 - axis, u[o]), at = t.Value(axis, u[k]);
  for (const BoundaryCurve& c : curves) {
    if (target && !Follows(c, *target)) continue;
    for (size_t i = 0; i < c.points.size(); ++i) {
      const auto& p = c.points[i];
      if (std::abs(p[o] - line) <= 1e-6 * t.Span(1 - axis) &&
          std::abs(p[k] - at) <= near * t.Span(axis))
        return true;  // a curve's point next to it (ends exactly at the grid line)
      if (i + 1 == c.points.size()) continue;
      const auto& q = c.points[i + 1];
      if ((p[o] - line) * (q[o] - line) > 0 || p[o] == q[o]) continue;
      const double x = p[k] + (q[k] - p[k]) * (line - p[o]) / (q[o] - p[o]);
      if (std::abs(x - at) <= near * t.Span(axis)) return true;
    }
  }
  return false;
}

BoundaryCurve Assemble(const Tracer& t, const Target& target, const Vec& seed, int seed_axis,
                       const Crossing& c, Walk back, const Walk& ahead) {
  BoundaryCurve curve;
  curve.kind = target.sigma > 0 ? BoundaryKind::kRealPlusOne : BoundaryKind::kRealMinusOne;
  curve.symmetry = target.symmetry;
  auto add = [&](const Vec& u, int across, double bracket, bool merged) {
    curve.points.push_back({t.Value(0, u[0]), t.Value(1, u[1])});
    curve.across.push_back(across);
    curve.bracket.push_back(bracket * t.Span(across));
    curve.merged.push_back(merged);
  };
  for (size_t i = back.u.size(); i-- > 0;)
    add(back.u[i], back.across[i], back.bracket[i], back.merged[i]);
  add(seed, seed_axis, c.bracket, c.merged);
  for (size_t i = 0; i < ahead.u.size(); ++i)
    add(ahead.u[i], ahead.across[i], ahead.bracket[i], ahead.merged[i]);
  curve.end_notes = {back.end, ahead.end};
  return curve;
}

}  // namespace

BoundaryCurves TraceBoundaryCurves(const Scene& scene, const ParameterMap& base,
                                   const SweepGrid& grid,
                                   const std::vector<BoundaryPoint>& boundary,
                                   const SweepOptions& sweep, const BoundaryOptions& options,
                                   const BoundaryCurveOptions& curve_options) {
  curve_options.Validate();
  BoundaryCurves out;
  if (grid.axes.size() != 2 || grid.values[0].size() < 2 || grid.values[1].size() < 2) return out;
  Tracer t(scene, base, grid, sweep, options, curve_options);
  for (size_t i = 0; i < boundary.size(); ++i) {
    const BoundaryPoint& bp = boundary[i];
    const size_t k = static_cast<size_t>(bp.axis);
    const auto& v = grid.values[k];
    const double step = (v.back() - v.front()) / double(v.size() - 1);
    Vec u{(bp.values[0] - grid.values[0].front()) / t.Span(0),
          (bp.values[1] - grid.values[1].front()) / t.Span(1)};
    // On a traced curve of the same σ (crossing the grid line within a quarter step, or 5e-4 of
    // the span: the chords' sagitta): no new seed. Two edges of a thin tongue share a σ but do
    // not share a grid interval where the grid shows a boundary point.
    const double near = std::max(0.25 * step / t.Span(bp.axis), 5e-4);
    const bool near_any = OnACurve(out.curves, u, bp.axis, near, t);
    const auto above = std::upper_bound(v.begin(), v.end(), bp.values[k]);
    if (above == v.begin() || above == v.end()) continue;
    const double a = (*(above - 1) - v.front()) / t.Span(bp.axis),
                 b = (*above - v.front()) / t.Span(bp.axis);
    Line line{bp.axis, u};
    const auto seed = FindSeed(t, line, a, b, u[k], [&](const Target& target) {
      return near_any && OnACurve(out.curves, u, bp.axis, near, t, target);
    });
    if (!seed && near_any) continue;
    if (!seed) {
      out.untraced.push_back(i);
      out.untraced_notes.push_back(
          "D_σ changes sign for neither σ = +1 nor −1 across the grid step: a complex pair "
          "crosses the unit circle (or the analysis failed)");
      continue;
    }
    t.SetTarget(seed->target);
    const int before = t.evaluations;
    const Vec start = line.Point(seed->crossing.x);
    const int half = curve_options.max_points / 2;
    const auto frame = SeedFrame(t, start);
    if (!frame) {
      out.untraced.push_back(i);
      out.untraced_notes.push_back("the gradient of D_σ at the seed could not be computed");
      continue;
    }
    Walk back = WalkCurve(t, start, *frame, -1, curve_options, half);
    Walk ahead = WalkCurve(t, start, *frame, 1, curve_options, half);
    out.curves.push_back(
        Assemble(t, seed->target, start, bp.axis, seed->crossing, std::move(back), ahead));
    out.curves.back().evaluations = t.evaluations - before;
  }
  // A point whose seed failed may lie on a curve traced later (a tongue's tip at the map's edge).
  BoundaryCurves kept = out;
  kept.untraced.clear();
  kept.untraced_notes.clear();
  for (size_t j = 0; j < out.untraced.size(); ++j) {
    const BoundaryPoint& bp = boundary[out.untraced[j]];
    const auto& v = grid.values[static_cast<size_t>(bp.axis)];
    const double step = (v.back() - v.front()) / double(v.size() - 1);
    const Vec u{(bp.values[0] - grid.values[0].front()) / t.Span(0),
                (bp.values[1] - grid.values[1].front()) / t.Span(1)};
    if (OnACurve(out.curves, u, bp.axis, 1.25 * step / t.Span(bp.axis), t)) continue;
    kept.untraced.push_back(out.untraced[j]);
    kept.untraced_notes.push_back(out.untraced_notes[j]);
  }
  kept.evaluations = t.evaluations;
  return kept;
}

}  // namespace ltp
