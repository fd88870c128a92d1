#include "ltp/studies/sweep.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <numbers>
#include <sstream>

#include "ltp/core/diagnostic.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/core/text.h"
#include "ltp/floquet/formed_monodromy.h"
#include "ltp/integrate/threads.h"

namespace ltp {

namespace {

using cd = std::complex<double>;

// Stability only (maps): the formed product's multipliers. AnalyzeFloquet's segment grid,
// periodic Schur and bookkeeping would cost a quarter of the point. Returns false (caller
// falls back to the full analysis) when FormedLogMultipliers fails.
bool LargestMultiplierOnly(const PeriodicSystem& system, const SweepOptions& options,
                           SweepPoint& point) {
  const std::optional<std::vector<cd>> logs =
      FormedLogMultipliers(system, options.floquet.integrator);
  if (!logs) return false;
  const double T = system.period();
  point.modes.clear();
  for (const cd& log_rho : *logs) point.modes.push_back(MakeFloquetMode(log_rho, 0, T));
  const std::vector<int> order = ModeDisplayOrder(point.modes);
  std::vector<FloquetMode> sorted;
  for (int k : order) sorted.push_back(point.modes[static_cast<size_t>(k)]);
  point.modes = std::move(sorted);
  point.period = T;
  point.max_real_exponent = -std::numeric_limits<double>::infinity();
  for (const auto& m : point.modes)
    point.max_real_exponent = std::max(point.max_real_exponent, m.exponent.real());
  point.max_log_multiplier = point.max_real_exponent * T;
  point.ok = true;
  return true;
}

// Unchecked stability-only points try the formed product first (rigid-body states need the
// full analysis, which flags their mode).
bool TriesFormedRoute(const PeriodicSystem& system, const SweepOptions& options) {
  return !options.modes && options.floquet.segments == 0 &&
         system.labels().rigid_body_states.empty();
}

// A checked map point's estimate covers the route its unchecked neighbours take: the formed
// product at the user's tolerance against the refined run that gives the point's numbers.
// 0 when the formed product fails: a neighbour then takes the full analysis as this point did.
double FormedRouteError(const PeriodicSystem& system, const FloquetOptions& options,
                        const FloquetResult& refined) {
  const std::optional<std::vector<cd>> logs = FormedLogMultipliers(system, options.integrator);
  if (!logs) return 0;
  std::vector<cd> reference;
  for (const FloquetMode& m : refined.modes) reference.push_back(m.exponent * refined.period);
  return MaxExponentMismatch(*logs, reference, 2 * std::numbers::pi) / refined.period;
}

// Monodromy route for one point.
void AnalyzeByMonodromy(const PeriodicSystem& system, const SweepOptions& options, bool check_error,
                        SweepPoint& point) {
  if (!check_error && TriesFormedRoute(system, options) &&
      LargestMultiplierOnly(system, options, point))
    return;
  FloquetOptions o = options.floquet;
  o.threads = 1;
  o.compute_modes = options.modes;
  o.estimate_error = check_error;
  if (!options.modes && o.segments == 0) o.segments = 1;  // as above, with the error estimate
  FloquetResult r = AnalyzeFloquet(system, o);
  if (!r.ok && o.segments == 1 && options.floquet.segments == 0) {
    o.segments = 0;
    r = AnalyzeFloquet(system, o);
  }
  point.period = r.period;
  point.diagnostics = r.diagnostics;
  if (!r.ok) {
    point.failure = r.diagnostics.empty() ? "Floquet analysis failed" : r.diagnostics.back().text;
    return;
  }
  point.ok = true;
  point.max_real_exponent = r.max_real_exponent;
  point.max_log_multiplier = r.max_log_abs_multiplier;
  point.error_estimate = r.error_estimate;
  if (check_error && TriesFormedRoute(system, options) && r.error_estimate)
    point.error_estimate = std::max(*r.error_estimate, FormedRouteError(system, o, r));
  point.modes = std::move(r.modes);
  if (options.modes && !r.mode_samples.empty()) {
    point.shapes = r.mode_samples.front();
    for (Eigen::Index k = 0; k < point.shapes.cols(); ++k) {
      const double norm = point.shapes.col(k).norm();
      if (norm > 0) point.shapes.col(k) /= norm;
    }
  }
}

void AnalyzeByHill(const PeriodicSystem& system, const SweepOptions& options, bool check_error,
                   SweepPoint& point) {
  HillOptions o = options.hill;
  o.koopman_check = false;  // a cross-check per point would dominate the sweep
  HillResult r = AnalyzeHillAuto(system, o, options.hill_tol, options.hill_max_harmonics);
  point.period = system.period();
  point.diagnostics = r.diagnostics;
  if (!r.ok) {
    point.failure = r.diagnostics.empty() ? "Hill analysis failed" : r.diagnostics.back().text;
    return;
  }
  point.ok = true;
  point.max_real_exponent = r.max_real_exponent;
  point.max_log_multiplier = r.max_real_exponent * system.period();
  if (check_error) point.error_estimate = r.error_estimate;
  point.modes = std::move(r.modes);
}

}  // namespace

std::string_view ToString(SweepMethod method) {
  return method == SweepMethod::kMonodromy ? "monodromy" : "hill";
}

std::optional<SweepMethod> ParseSweepMethod(std::string_view name) {
  if (name == "monodromy") return SweepMethod::kMonodromy;
  if (name == "hill") return SweepMethod::kHill;
  return std::nullopt;
}

std::vector<double> SweepAxis::Values() const {
  std::vector<double> v;
  if (step == 0) return {start};
  const double count = (stop - start) / step;
  const long n = static_cast<long>(std::floor(count + 1e-9)) + 1;
  v.reserve(static_cast<size_t>(std::max(n, 1L)));
  // start + i·step rather than repeated addition: no drift over thousands of points.
  for (long i = 0; i < n; ++i) v.push_back(start + static_cast<double>(i) * step);
  return v;
}

SweepAxis SweepAxis::Parse(const std::string& spec) {
  const auto fail = [&](const std::string& why) {
    throw InputError("sweep '" + spec + "': " + why +
                     " (expected NAME=START:STOP:STEP, e.g. a=-2:10:0.03)");
  };
  const auto equals = spec.find('=');
  if (equals == std::string::npos) fail("no '='");
  SweepAxis axis;
  axis.name = Trim(spec.substr(0, equals));
  if (axis.name.empty()) fail("missing parameter name");
  std::vector<std::string> parts;
  std::string rest = spec.substr(equals + 1);
  size_t from = 0;
  while (true) {
    const auto colon = rest.find(':', from);
    parts.push_back(
        Trim(rest.substr(from, colon == std::string::npos ? std::string::npos : colon - from)));
    if (colon == std::string::npos) break;
    from = colon + 1;
  }
  if (parts.size() != 3) fail("need three numbers separated by ':'");
  // Evaluate each number as a scene-parameter expression (numbers and pi).
  Scene scratch;
  scratch.name = "sweep";
  scratch.parameters = {{axis.name, 0.0, ""}};
  double* fields[3] = {&axis.start, &axis.stop, &axis.step};
  const char* names[3] = {"START", "STOP", "STEP"};
  for (int i = 0; i < 3; ++i) {
    if (parts[i].empty()) fail(std::string("missing ") + names[i]);
    try {
      *fields[i] = scratch.Resolve({{axis.name, parts[i]}}).at(axis.name);
    } catch (const InputError& e) {
      fail(std::string(names[i]) + " '" + parts[i] + "' is not a number");
    }
  }
  if (!(axis.step > 0)) fail("STEP must be > 0");
  if (!(axis.stop >= axis.start)) fail("STOP must be >= START");
  if ((axis.stop - axis.start) / axis.step > 1e7) fail("more than 10^7 points on one axis");
  return axis;
}

void SweepOptions::Validate() const {
  const OptionCheck check("SweepOptions");
  floquet.Validate();
  hill.Validate();
  if (!(hill_tol > 0)) check.Fail("hill_tol", hill_tol, "> 0");
  if (hill_max_harmonics < 1) check.Fail("hill_max_harmonics", hill_max_harmonics, ">= 1");
  if (check_every < 0) check.Fail("check_every", check_every, ">= 0");
  if (!(marginal_log_multiplier >= 0))
    check.Fail("marginal_log_multiplier", marginal_log_multiplier, ">= 0");
  if (threads < 0) check.Fail("threads", threads, ">= 0 (0 = all cores)");
}

size_t SweepGrid::size() const {
  size_t n = 1;
  for (const auto& v : values) n *= v.size();
  return n;
}

std::vector<double> SweepGrid::PointValues(size_t index) const {
  std::vector<double> out(values.size());
  for (size_t a = 0; a < values.size(); ++a) {
    out[a] = values[a][index % values[a].size()];
    index /= values[a].size();
  }
  return out;
}

SweepGrid MakeSweepGrid(const Scene& scene, std::vector<SweepAxis> axes) {
  if (axes.empty() || axes.size() > 2)
    throw InputError("a sweep needs one or two parameters, got " + std::to_string(axes.size()));
  if (axes.size() == 2 && axes[0].name == axes[1].name)
    throw InputError("both sweeps vary '" + axes[0].name + "'");
  SweepGrid grid;
  for (const auto& axis : axes) {
    scene.Resolve({{axis.name, "0"}});  // throws for a name the scene does not have
    grid.values.push_back(axis.Values());
    if (grid.values.back().empty()) throw InputError("sweep of '" + axis.name + "' has no points");
  }
  // Both axes within their own limit can still multiply to 10^8 points (several GB of results
  // and hours of work): refuse up front, naming the limit.
  constexpr double kMaxPoints = 1e7;
  if (grid.values.size() == 2 &&
      double(grid.values[0].size()) * double(grid.values[1].size()) > kMaxPoints) {
    std::ostringstream s;
    s << "the sweep has " << grid.values[0].size() << " × " << grid.values[1].size()
      << " points, more than the limit of 10^7 per chart: use coarser steps or split the map";
    throw InputError(s.str());
  }
  grid.axes = std::move(axes);
  return grid;
}

SweepPoint AnalyzeSweepPoint(const Scene& scene, const ParameterMap& base, const SweepGrid& grid,
                             size_t index, const SweepOptions& options, bool check_error) {
  const auto start = std::chrono::steady_clock::now();
  SweepPoint point;
  point.index = index;
  point.values = grid.PointValues(index);
  ParameterMap params = base;
  for (size_t a = 0; a < grid.axes.size(); ++a) params[grid.axes[a].name] = point.values[a];
  try {
    const PeriodicSystem system = scene.build(params);
    if (const auto speed = system.rotor_speed()) point.rotor_speed = *speed;
    if (options.snapshot) {
      const Eigen::VectorXcd frozen = system.A(0).eigenvalues();
      point.snapshot_eigenvalues.assign(frozen.data(), frozen.data() + frozen.size());
      Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(system.states(), system.states());
      if (const FourierMatrix* fa = system.fourier_A()) {
        mean = (*fa)[0].real();
      } else {
        const int samples = 256;  // midpoint rule: spectrally accurate for smooth A
        for (int s = 0; s < samples; ++s) mean += system.A((s + 0.5) * system.period() / samples);
        mean /= samples;
      }
      const Eigen::VectorXcd averaged = mean.eigenvalues();
      point.averaged_eigenvalues.assign(averaged.data(), averaged.data() + averaged.size());
    }
    if (options.method == SweepMethod::kMonodromy)
      AnalyzeByMonodromy(system, options, check_error, point);
    else
      AnalyzeByHill(system, options, check_error, point);
  } catch (const std::exception& e) {
    point.ok = false;
    point.failure = e.what();
  }
  if (point.ok && !std::isfinite(point.max_log_multiplier)) {
    point.ok = false;
    point.failure = "max log|multiplier| is not finite";
  }
  // In log|ρ| units: the marginal band is the error estimate over a period, at least
  // marginal_log_multiplier (points without their own check).
  const double band =
      std::max(options.marginal_log_multiplier, point.error_estimate.value_or(0.0) * point.period);
  point.verdict = ClassifyStability(point.ok, point.max_log_multiplier, band);
  if (!point.ok) point.modes.clear();
  point.elapsed_s = SecondsSince(start);
  return point;
}

size_t RunSweep(const Scene& scene, const ParameterMap& base, const SweepGrid& grid,
                const std::vector<size_t>& indices, const SweepOptions& options,
                const std::function<void(SweepPoint&&)>& on_point,
                const std::atomic<bool>* cancel) {
  options.Validate();
  const int threads = ThreadsFor(options.threads);
  size_t done = 0;
  const long count = static_cast<long>(indices.size());
  std::exception_ptr callback_error;  // rethrown after the loop: no exception leaves OpenMP
  std::atomic<bool> stop{false};
  // Dynamic schedule in small chunks: point costs vary by orders of magnitude across a map
  // (deep in an instability tongue the integrator takes many more steps).
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
  for (long i = 0; i < count; ++i) {
    if ((cancel && cancel->load(std::memory_order_relaxed)) || stop.load()) continue;
    const size_t index = indices[static_cast<size_t>(i)];
    const bool check =
        options.check_every > 0 && index % static_cast<size_t>(options.check_every) == 0;
    SweepPoint point = AnalyzeSweepPoint(scene, base, grid, index, options, check);
    if (!stop.load()) {
      try {
        on_point(std::move(point));
#pragma omp atomic
        ++done;
      } catch (...) {
#pragma omp critical(ltp_sweep_error)
        if (!callback_error) callback_error = std::current_exception();
        stop = true;
      }
    }
  }
  if (callback_error) std::rethrow_exception(callback_error);
  return done;
}

SweepTally TallySweep(const std::vector<SweepPoint>& points) {
  SweepTally t;
  for (StabilityVerdict v : {StabilityVerdict::kStable, StabilityVerdict::kMarginal,
                             StabilityVerdict::kUnstable, StabilityVerdict::kFailed})
    t.counts[v] = 0;
  for (const SweepPoint& p : points) {
    ++t.counts[p.verdict];
    if (p.ok && p.error_estimate) {
      ++t.checked;
      t.max_error = std::max(t.max_error.value_or(0.0), *p.error_estimate);
    }
  }
  return t;
}

}  // namespace ltp
