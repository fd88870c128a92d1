#include "ltp/floquet/floquet.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <unsupported/Eigen/FFT>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/core/mode_description.h"
#include "ltp/floquet/method_choice.h"
#include "ltp/floquet/periodic_eigen.h"
#include "ltp/floquet/threads.h"
#include "segment_grid.h"

namespace ltp {

namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

int NextPowerOfTwo(int x) {
  int p = 1;
  while (p < x) p *= 2;
  return p;
}

// Mode samples per period: enough to resolve the mode shapes around the branch the averaged
// system predicts (the samples are demodulated by that branch before the FFT, see
// PriorBranches), i.e. somewhat wider than A's own harmonic content; bounded so a
// discontinuous A(t) does not ask for thousands. Before demodulation the count also had to
// cover the largest frozen frequency: 256 samples (and segments) for tower-rotor instead of 64.
int AutoModeSamples(const PeriodicSystem& system) {
  int harmonics = 8;
  if (const FourierMatrix* fa = system.fourier_A())
    harmonics = fa->max_harmonic();
  else if (!system.breakpoints().empty())
    harmonics = 16;
  const double wanted = 4.0 * (harmonics + 2);
  return std::clamp(NextPowerOfTwo(static_cast<int>(std::ceil(wanted))), 32, 1024);
}

// Uniform segments to start from when the mode shapes are wanted. One per mode sample gives the
// samples directly from the periodic eigenvectors, which cost one sparse LU of the (K·n)²
// block-cyclic matrix per mode, O(K n³) in all: fine for tens of states, 18 s for a 60-state
// OpenFAST set at K = 256. Larger systems start from fewer segments (still refined wherever a
// factor's condition demands) and get the remaining samples by propagation within a segment,
// which stays accurate because every factor is well conditioned.
int ModeSegments(int samples, int states) {
  const int shrink = NextPowerOfTwo(std::max(1, (states + 23) / 24));
  return std::max(std::min(samples, 8), samples / shrink);
}

// A first guess of each mode's branch m in λ = Log ρ / T + j m Ωp, from the time-averaged
// system: the averaged A's eigenvector that dominates the mode shape ξ_k(0) (its coefficient
// in the eigenbasis) names the frequency the mode has, and m brings the principal exponent to
// it. The mode samples are demodulated by that branch, so their spectra sit near harmonic 0
// and a few dozen samples resolve them whatever the mode's frequency; the Fourier centroid
// then corrects the guess.
std::vector<int> PriorBranches(const PeriodicSystem& system, const std::vector<cd>& log_rho,
                               const Eigen::MatrixXcd& xi0) {
  const int n = system.states();
  const double T = system.period(), omega = system.omega();
  Eigen::MatrixXcd mean = Eigen::MatrixXcd::Zero(n, n);
  if (const FourierMatrix* fa = system.fourier_A()) {
    mean = (*fa)[0];
  } else {
    constexpr int kSamples = 16;
    Eigen::MatrixXd a(n, n);
    for (int s = 0; s < kSamples; ++s) {
      system.EvalA((s + 0.5) * T / kSamples, a);
      mean += a.cast<cd>() / double(kSamples);
    }
  }
  std::vector<int> prior(log_rho.size(), 0);
  if (!mean.allFinite() || !xi0.allFinite()) return prior;
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(mean);
  if (eig.info() != Eigen::Success) return prior;
  const Eigen::MatrixXcd coefficients =
      eig.eigenvectors().colPivHouseholderQr().solve(xi0);  // ξ_k(0) in the eigenbasis
  for (size_t k = 0; k < log_rho.size(); ++k) {
    const cd principal = log_rho[k] / T;
    if (!std::isfinite(principal.imag())) continue;
    Eigen::Index i = 0;
    if (!coefficients.col(k).allFinite()) continue;
    coefficients.col(k).cwiseAbs().maxCoeff(&i);
    const double m = std::round((eig.eigenvalues()(i).imag() - principal.imag()) / omega);
    if (std::abs(m) < 1e6) prior[k] = static_cast<int>(m);
  }
  return prior;
}

double Condition(const Eigen::MatrixXcd& m) {
  if (m.size() == 0) return 1;
  Eigen::JacobiSVD<Eigen::MatrixXcd> svd(m);
  const auto& s = svd.singularValues();
  if (s(s.size() - 1) == 0) return std::numeric_limits<double>::infinity();
  return s(0) / s(s.size() - 1);
}

}  // namespace

std::string_view ToString(MultiplierMethod method) {
  return method == MultiplierMethod::kPeriodicSchur ? "periodic-schur" : "single-shot";
}

std::string_view ToString(StabilityVerdict verdict) {
  switch (verdict) {
    case StabilityVerdict::kStable:
      return "stable";
    case StabilityVerdict::kMarginal:
      return "marginal";
    case StabilityVerdict::kUnstable:
      return "unstable";
    case StabilityVerdict::kFailed:
      return "failed";
  }
  return "failed";
}

StabilityVerdict ClassifyStability(bool ok, double max_real_exponent, double band) {
  if (!ok || std::isnan(max_real_exponent) || std::isnan(band)) return StabilityVerdict::kFailed;
  band = std::max(band, 0.0);
  if (max_real_exponent > band) return StabilityVerdict::kUnstable;
  if (max_real_exponent < -band) return StabilityVerdict::kStable;
  return StabilityVerdict::kMarginal;
}

void FloquetOptions::Validate() const {
  integrator.Validate();
  auto fail = [](const std::string& field, double value, const std::string& constraint) {
    std::ostringstream s;
    s << "FloquetOptions::" << field << " = " << value << ". Violated constraint: " << constraint;
    throw InputError(s.str());
  };
  if (segments < 0) fail("segments", segments, "segments >= 0 (0 = automatic)");
  if (!(max_factor_condition > 10)) fail("max_factor_condition", max_factor_condition, "> 10");
  if (max_segments < 1) fail("max_segments", max_segments, "max_segments >= 1");
  if (!(max_period_scale > 0)) fail("max_period_scale", max_period_scale, "max_period_scale > 0");
  if (segments > max_segments)
    fail("segments", segments, "segments <= max_segments (" + std::to_string(max_segments) + ")");
  if (mode_samples != 0 && (mode_samples < 4 || (mode_samples & (mode_samples - 1)) != 0))
    fail("mode_samples", mode_samples, "0 or a power of two >= 4");
  if (threads < 0) fail("threads", threads, "threads >= 0 (0 = all cores)");
}

FloquetMode MakeFloquetMode(std::complex<double> log_multiplier, int branch, double period) {
  FloquetMode m;
  m.log_multiplier = log_multiplier;
  m.branch = branch;
  m.exponent = log_multiplier / period + cd(0, branch * 2 * kPi / period);
  m.frequency_hz = m.exponent.imag() / (2 * kPi);
  const double mag = std::abs(m.exponent);
  m.damping_ratio = mag > 0 ? -m.exponent.real() / mag : 0;
  return m;
}

std::vector<int> ModeDisplayOrder(const std::vector<FloquetMode>& modes) {
  std::vector<int> order(modes.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const double fa = std::abs(modes[a].exponent.imag()), fb = std::abs(modes[b].exponent.imag());
    if (std::abs(fa - fb) > 1e-9 * (1 + fa)) return fa < fb;
    if (modes[a].exponent.imag() != modes[b].exponent.imag())
      return modes[a].exponent.imag() > modes[b].exponent.imag();
    return modes[a].exponent.real() > modes[b].exponent.real();
  });
  return order;
}

double IntegralOfTrace(const PeriodicSystem& system) {
  const double T = system.period();
  if (const FourierMatrix* fa = system.fourier_A()) return T * (*fa)[0].real().trace();
  if (system.form() == PeriodicSystem::Form::kPiecewiseConstant) {
    const auto& times = system.sample_times();
    double sum = 0;
    for (size_t k = 0; k < times.size(); ++k) {
      const double end = k + 1 < times.size() ? times[k + 1] : times.front() + T;
      sum += (end - times[k]) * system.samples()[k].A.trace();
    }
    return sum;
  }
  // 10-point Gauss–Legendre on each of 16 panels of every smooth piece.
  static const double x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244,
                              0.8650633666889845, 0.9739065285171717};
  static const double w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820,
                              0.1494513491505806, 0.0666713443086881};
  std::vector<double> cuts = {0.0};
  for (double b : system.breakpoints())
    if (b > 0) cuts.push_back(b);
  cuts.push_back(T);
  Eigen::MatrixXd a(system.states(), system.states());
  double sum = 0;
  for (size_t p = 0; p + 1 < cuts.size(); ++p) {
    const int panels = 16;
    const double h = (cuts[p + 1] - cuts[p]) / panels;
    for (int q = 0; q < panels; ++q) {
      const double mid = cuts[p] + (q + 0.5) * h;
      for (int i = 0; i < 5; ++i)
        for (double sgn : {-1.0, 1.0}) {
          system.EvalA(mid + sgn * x[i] * h / 2, a);
          sum += w[i] * h / 2 * a.trace();
        }
    }
  }
  return sum;
}

Eigen::MatrixXcd FloquetResult::ModeMatrix(double t) const {
  Eigen::MatrixXcd xi = Eigen::MatrixXcd::Zero(states, states);
  const double omega = 2 * kPi / period;
  for (int v = -mode_harmonics; v <= mode_harmonics; ++v)
    xi += mode_fourier[v + mode_harmonics] * std::polar(1.0, v * omega * t);
  return xi;
}

Eigen::MatrixXcd FloquetResult::LeftModes(double t) const {
  const Eigen::MatrixXcd xi = ModeMatrix(t);
  return xi.completeOrthogonalDecomposition().pseudoInverse();
}

std::string FloquetResult::BriefReport() const {
  std::ostringstream s;
  s << (ok ? "" : "FAILED: ") << "K = " << segments << ", max Re λ = " << max_real_exponent
    << " 1/s (" << (stable ? "stable" : "unstable") << "), error ≈ " << error_estimate << ", "
    << elapsed_s << " s";
  return s.str();
}

// T · max ‖A(t)‖ over 16 samples: the number of e-folds or radians a solution can move through
// in one period, i.e. the work any integrator has to do. @throws InputError beyond the limit.
void CheckPeriodScale(const PeriodicSystem& system, double limit) {
  const int n = system.states();
  if (n == 0) return;
  Eigen::MatrixXd a(n, n);
  double largest = 0;
  for (int s = 0; s < 16; ++s) {
    system.EvalA((s + 0.5) / 16 * system.period(), a);
    largest = std::max(largest, a.stableNorm());  // no overflow for entries of 1e200
  }
  const double scale = system.period() * largest;
  if (!(scale <= limit)) {
    std::ostringstream s;
    s << "T · max ‖A(t)‖ = " << scale << " (T = " << system.period()
      << " s): following the solutions "
      << "over one period would take at least that many steps, beyond the limit "
      << "FloquetOptions::max_period_scale = " << limit
      << " (coefficients or period out of scale?)";
    throw InputError(s.str());
  }
}

FloquetResult AnalyzeFloquet(const PeriodicSystem& system, const FloquetOptions& requested) {
  requested.Validate();
  CheckPeriodScale(system, requested.max_period_scale);
  const auto start = std::chrono::steady_clock::now();
  FloquetResult r;
  std::string choice;
  FloquetOptions options = requested;
  options.integrator = ResolveIntegrator(system, requested.integrator, &choice);
  if (!choice.empty())
    r.diagnostics.push_back("integrator auto → " + std::string(ToString(options.integrator.type)) +
                            ": " + choice);
  const int n = system.states();
  const double T = system.period();
  const double omega = system.omega();
  r.states = n;
  r.period = T;
  r.integrator = std::string(ToString(options.integrator.type));
  r.multiplier_method = std::string(ToString(options.multipliers));
  const int threads = ThreadsFor(options.threads);

  // 1. Segment factors on a grid refined where factors grow or decay too fast.
  const int samples = options.compute_modes ? (options.mode_samples > 0 ? options.mode_samples
                                                                        : AutoModeSamples(system))
                                            : 1;
  internal::SegmentGridOptions grid_options;
  grid_options.integrator = options.integrator;
  grid_options.uniform_segments =
      options.segments > 0 ? options.segments : ModeSegments(samples, n);
  grid_options.refine = options.segments == 0;
  grid_options.max_factor_condition = options.max_factor_condition;
  grid_options.max_segments = options.max_segments;
  grid_options.threads = threads;
  internal::SegmentGrid grid = internal::ComputeSegmentGrid(system, grid_options);
  r.rhs_evals += grid.rhs_evals;
  for (auto& d : grid.diagnostics) r.diagnostics.push_back(d);
  if (options.segments == 0 && grid.ok) {
    // Fewest segments whose factors stay well conditioned: the study's K panel found more
    // segments only cost time once every factor is below the limit, and fewer lose the small
    // multipliers (stiff.yaml: K = 1 overflows, K = 4 is off by 327 1/s).
    std::ostringstream s;
    s << "segments auto → K = " << grid.times.size() - 1
      << (options.estimate_error ? " (halved again in the refined run that gives the numbers)" : "")
      << ": ";
    if (static_cast<int>(grid.times.size()) - 1 == grid.initial_segments)
      s << "the " << grid.initial_segments
        << (grid.initial_segments == 1 ? " segment" : " uniform segments")
        << " already keep every factor's condition below " << options.max_factor_condition
        << " (worst " << std::setprecision(3) << grid.worst_condition << ")";
    else
      s << "refined from " << grid.initial_segments
        << " where factors grew or decayed beyond condition " << options.max_factor_condition
        << " (worst now " << std::setprecision(3) << grid.worst_condition << ")";
    r.diagnostics.push_back(s.str());
  }
  if (!grid.ok) {
    r.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  }
  // 2. Multipliers as logarithms.
  auto log_eigenvalues = [&](const internal::SegmentGrid& g) {
    if (options.multipliers == MultiplierMethod::kSingleShot) {
      Eigen::MatrixXd product = Eigen::MatrixXd::Identity(n, n);
      for (const auto& f : g.factors) product = f * product;
      return SingleShotLogEigenvalues(product);
    }
    return PeriodicSchurLogEigenvalues(g.factors);
  };
  LogEigenvalues eig = log_eigenvalues(grid);
  if (!eig.ok) {
    r.diagnostics.push_back("eigenvalues of the monodromy failed: " + eig.message);
    r.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  }

  // 3. Error estimate: a second run with every segment halved and a 100× tighter tolerance
  // (twice the fixed steps). Halving the segments matters: on short segments an adaptive
  // method may take the same single step at both tolerances, and a same-grid comparison would
  // then see no difference at all. The reported numbers come from this better run, so the
  // difference bounds their error with a wide margin.
  double integration_error = 0;
  if (options.estimate_error && n > 0) {
    internal::SegmentGridOptions fine = grid_options;
    fine.refine = false;
    fine.fixed_times.clear();
    for (size_t i = 0; i + 1 < grid.times.size(); ++i) {
      fine.fixed_times.push_back(grid.times[i]);
      fine.fixed_times.push_back(0.5 * (grid.times[i] + grid.times[i + 1]));
    }
    fine.fixed_times.push_back(grid.times.back());
    fine.integrator.rel_tol = std::max(options.integrator.rel_tol * 1e-2, 1e-15);
    fine.integrator.abs_tol = options.integrator.abs_tol * 1e-2;
    if (fine.integrator.steps_per_period > 0) fine.integrator.steps_per_period *= 2;
    internal::SegmentGrid reference = internal::ComputeSegmentGrid(system, fine);
    r.rhs_evals += reference.rhs_evals;
    LogEigenvalues ref_eig = reference.ok ? log_eigenvalues(reference) : LogEigenvalues{};
    if (ref_eig.ok) {
      integration_error = MaxExponentMismatch(eig.log_values, ref_eig.log_values, 2 * kPi) / T;
      grid = std::move(reference);
      eig = std::move(ref_eig);
    } else {
      r.diagnostics.push_back(
          "error estimate: the refined reference run failed; results are "
          "from the first run and their error is unknown");
      integration_error = std::numeric_limits<double>::infinity();
    }
  }
  r.segments = static_cast<int>(grid.factors.size());
  r.segment_times = grid.times;
  r.monodromy = Eigen::MatrixXd::Identity(n, n);
  for (const auto& f : grid.factors) r.monodromy = f * r.monodromy;
  const std::vector<cd>& log_rho = eig.log_values;
  std::vector<double> kappa(n, 1.0);  // eigenvalue condition numbers, from the modes below

  // 4. Modes: periodic eigenvectors at the grid points, samples on the uniform mode grid.
  std::vector<FloquetMode> modes(n);
  for (int k = 0; k < n; ++k) modes[k] = MakeFloquetMode(log_rho[k], 0, T);  // principal branch
  if (options.compute_modes && n > 0) {
    std::vector<double> dt(grid.factors.size());
    for (size_t i = 0; i < dt.size(); ++i) dt[i] = grid.times[i + 1] - grid.times[i];
    std::vector<PeriodicEigenvector> vecs = ComputePeriodicEigenvectors(grid.factors, dt, log_rho);
    // The uniform mode samples are grid points (the grid refines the uniform one); find them.
    r.sample_times.resize(samples);
    std::vector<int> at(samples);
    for (int s = 0; s < samples; ++s) {
      const double ts = T * s / samples;
      auto it = std::lower_bound(grid.times.begin(), grid.times.end(), ts - 1e-12 * T);
      at[s] = static_cast<int>(it - grid.times.begin());
      r.sample_times[s] = grid.times[at[s]];
    }
    bool uniform_hit = true;
    for (int s = 0; s < samples; ++s)
      uniform_hit = uniform_hit && at[s] < static_cast<int>(grid.times.size()) - 1 &&
                    std::abs(grid.times[at[s]] - T * s / samples) <= 1e-9 * T;
    std::vector<Eigen::MatrixXcd> xi(samples, Eigen::MatrixXcd(n, n));
    if (uniform_hit) {
      for (int s = 0; s < samples; ++s)
        for (int k = 0; k < n; ++k) xi[s].col(k) = vecs[k].v[at[s]];
    } else {
      // A grid that does not contain the uniform samples (a user-chosen K, or fewer segments
      // for a large system, see ModeSegments): propagate from the last grid point before each
      // sample, ξ(t_s) = Φ(t_s, t_i) ξ(t_i) e^{-λ(t_s − t_i)}.
      r.diagnostics.push_back(
          "mode samples propagated within segments (K = " + std::to_string(grid.factors.size()) +
          " segments for " + std::to_string(samples) + " samples)");
      for (int s = 0; s < samples; ++s) {
        const double ts = T * s / samples;
        auto it = std::upper_bound(grid.times.begin(), grid.times.end(), ts + 1e-12 * T);
        const int i = static_cast<int>(it - grid.times.begin()) - 1;
        r.sample_times[s] = ts;
        // ts can sit a rounding error below grid.times[i]: never integrate backwards.
        TransitionResult tr =
            StateTransition(system, grid.times[i], std::max(ts, grid.times[i]), options.integrator);
        r.rhs_evals += tr.rhs_evals;
        for (int k = 0; k < n; ++k)
          xi[s].col(k) =
              tr.phi.cast<cd>() * vecs[k].v[i] * std::exp(-log_rho[k] / T * (ts - grid.times[i]));
      }
    }
    // Demodulate by the prior branch, so the FFT sees spectra near harmonic 0.
    const std::vector<int> prior = PriorBranches(system, log_rho, xi[0]);
    for (int s = 0; s < samples; ++s)
      for (int k = 0; k < n; ++k)
        xi[s].col(k) *= std::polar(1.0, -prior[k] * omega * r.sample_times[s]);
    // Fourier coefficients of every entry (FFT), then the branch centred on harmonic 0.
    Eigen::FFT<double> fft;
    const int H = samples / 2 - 1;  // the Nyquist bin is dropped (ambiguous sign)
    std::vector<Eigen::MatrixXcd> coef(2 * H + 1, Eigen::MatrixXcd::Zero(n, n));
    std::vector<cd> in(samples), out(samples);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) {
        for (int s = 0; s < samples; ++s) in[s] = xi[s](i, k);
        fft.fwd(out, in);  // out[j] = Σ_s in[s] e^{-2πj js/S}
        for (int v = -H; v <= H; ++v)
          coef[v + H](i, k) = out[(v + samples) % samples] / double(samples);
      }
    double worst_tail = 0;
    std::vector<int> failed_modes;
    for (int k = 0; k < n; ++k) {
      std::vector<double> energy(2 * H + 1);
      double total = 0, first_moment = 0, tail = 0;
      for (int v = -H; v <= H; ++v) {
        energy[v + H] = coef[v + H].col(k).squaredNorm();
        total += energy[v + H];
        first_moment += v * energy[v + H];
        if (std::abs(v) > H / 2) tail += energy[v + H];
      }
      if (!(total > 0) || !std::isfinite(total) || !std::isfinite(vecs[k].residual)) {
        // The cyclic null-vector solve failed (seen for mode shapes whose magnitude varies
        // over hundreds of decades within a period). The exponent does not depend on it.
        failed_modes.push_back(k);
        for (int s = 0; s < samples; ++s) xi[s].col(k).setZero();
        for (auto& c : coef) c.col(k).setZero();
        modes[k].eigvec_residual = std::numeric_limits<double>::infinity();
        continue;
      }
      worst_tail = std::max(worst_tail, tail / total);
      const double centroid = first_moment / total;
      int m = static_cast<int>(std::lround(centroid));
      if (std::abs(std::abs(centroid - m) - 0.5) < 0.01) {
        // A tie (negative real multiplier: the exponent sits on the strip edge ±Ωp/2). Both
        // neighbours are valid; take the one with the smallest non-negative frequency so that
        // repeated runs agree, and say so in the diagnostics below.
        const int lo = static_cast<int>(std::floor(centroid)), hi = lo + 1;
        const double im_lo = (log_rho[k] / T).imag() + (prior[k] + lo) * omega;
        const double im_hi = (log_rho[k] / T).imag() + (prior[k] + hi) * omega;
        m = (im_lo >= -1e-12 * omega && (im_hi < -1e-12 * omega || im_lo <= im_hi)) ? lo : hi;
      }
      FloquetMode& mode = modes[k];
      mode = MakeFloquetMode(log_rho[k], prior[k] + m, T);
      mode.central_weight = (std::abs(m) <= H ? energy[m + H] : 0) / total;
      mode.branch_margin = std::max(0.0, 0.5 - std::abs(centroid - m));
      mode.eigvec_residual = vecs[k].residual;
      // Shift to the chosen branch: ξ^(m)(t) = ξ(t) e^{-j m Ωp t}, coefficients c_{v+m}.
      for (int s = 0; s < samples; ++s)
        xi[s].col(k) *= std::polar(1.0, -m * omega * r.sample_times[s]);
      std::vector<Eigen::VectorXcd> shifted(2 * H + 1, Eigen::VectorXcd::Zero(n));
      for (int v = -H; v <= H; ++v)
        if (std::abs(v + m) <= H) shifted[v + H] = coef[v + m + H].col(k);
      for (int v = -H; v <= H; ++v) coef[v + H].col(k) = shifted[v + H];
    }
    if (worst_tail > 1e-10) {
      std::ostringstream s;
      s << "mode shapes under-resolved: " << worst_tail
        << " of a mode's Fourier energy lies in the upper half of the " << samples
        << " samples; raise --mode-samples";
      r.diagnostics.push_back(s.str());
    }
    r.mode_samples = std::move(xi);
    r.mode_fourier = std::move(coef);
    r.mode_harmonics = H;
    // Condition of the mode matrix: the best over (up to 16 of) the sample times (a mode shape
    // may be tiny at t = 0 and large elsewhere; defectiveness makes Ξ(t) ill-conditioned at
    // every t). An SVD per sample was a fifth of a 60-state analysis. Modes whose shape could
    // not be computed are left out.
    std::vector<int> good;
    for (int k = 0; k < n; ++k)
      if (std::find(failed_modes.begin(), failed_modes.end(), k) == failed_modes.end())
        good.push_back(k);
    r.mode_condition = std::numeric_limits<double>::infinity();
    Eigen::MatrixXcd best_xi;
    for (int s = 0; s < samples; s += std::max(1, samples / 16)) {
      Eigen::MatrixXcd x(n, good.size());
      for (size_t j = 0; j < good.size(); ++j) {
        x.col(j) = r.mode_samples[s].col(good[j]);
        const double norm = x.col(j).norm();
        if (norm > 0) x.col(j) /= norm;
      }
      const double c = Condition(x);
      if (c < r.mode_condition || best_xi.size() == 0) {
        r.mode_condition = c;
        best_xi = x;
      }
    }
    // Eigenvalue condition numbers κ_k = ||x_k|| ||y_k|| with x_k = ξ_k(t)/||ξ_k(t)|| and y_k
    // the k-th row of Ξ(t)⁻¹ (left eigenvector scaled so that y_k x_k = 1), at that best t.
    if (good.empty()) {  // every cyclic solve failed: no mode matrix (and no condition) at all
      r.mode_condition = std::numeric_limits<double>::infinity();
    } else {
      const Eigen::MatrixXcd left = best_xi.completeOrthogonalDecomposition().pseudoInverse();
      for (size_t j = 0; j < good.size(); ++j)
        kappa[good[j]] = std::isfinite(r.mode_condition) ? left.row(j).norm()
                                                         : std::numeric_limits<double>::infinity();
    }
    for (int k : failed_modes) {
      kappa[k] = std::numeric_limits<double>::infinity();
      std::ostringstream s;
      s << "the periodic mode shape of the exponent " << (log_rho[k] / T).real()
        << (log_rho[k].imag() < 0 ? " - " : " + ") << std::abs((log_rho[k] / T).imag())
        << "j could not be computed (cyclic eigenvector solve failed); its exponent is "
           "unaffected, its branch is the principal one and its shape is reported as zero";
      r.diagnostics.push_back(s.str());
    }
    if (good.empty()) {
      r.diagnostics.push_back(
          "no periodic mode shape could be computed (the solutions grow and "
          "decay over hundreds of decades within a period): exponents and "
          "multipliers are unaffected; mode shapes, left modes and branches "
          "are not available");
    } else if (!(r.mode_condition < 1e8)) {
      std::ostringstream s;
      s << "mode matrix is ill-conditioned (cond = " << r.mode_condition
        << "): the monodromy is (near-)defective, e.g. a double multiplier at ±1 on a stability "
           "boundary; mode shapes, left modes and branch choices are unreliable, and exponents "
           "are accurate only to about the square root of the integration error";
      r.diagnostics.push_back(s.str());
    }
  } else {
    r.diagnostics.push_back("branch: principal logarithm (modes not computed)");
  }

  // 5. Order the modes: by |frequency|, positive first, then by Re λ.
  const std::vector<int> order = ModeDisplayOrder(modes);
  for (int k : order) r.modes.push_back(modes[k]);
  if (options.compute_modes)
    for (int k = 0; k < n; ++k)
      if (r.modes[k].branch_margin < 0.05 && std::isfinite(r.modes[k].eigvec_residual)) {
        std::ostringstream s;
        const bool negative_real =
            std::abs(std::abs(r.modes[k].log_multiplier.imag()) - kPi) < 1e-6;
        if (negative_real) {
          s << "mode " << k + 1
            << ": negative real multiplier, so the exponent sits on the strip "
               "edge: Im λ = +Ωp/2 and −Ωp/2 (mod Ωp) describe the same solution; the "
               "non-negative one is reported";
        } else {
          s << "mode " << k + 1 << ": branch ambiguous (margin " << r.modes[k].branch_margin
            << "): its mode shape's Fourier energy is split between two neighbouring harmonics; "
               "the smaller non-negative frequency was taken";
        }
        r.diagnostics.push_back(s.str());
      }
  if (!r.mode_samples.empty()) {
    auto permute = [&](Eigen::MatrixXcd& m) {
      Eigen::MatrixXcd p(m.rows(), m.cols());
      for (int j = 0; j < n; ++j) p.col(j) = m.col(order[j]);
      m = p;
    };
    for (auto& m : r.mode_samples) permute(m);
    for (auto& m : r.mode_fourier) permute(m);
    r.mode_descriptions = DescribeModeShapes(system.labels(), r.mode_samples.front());
  }

  // 6. Summary numbers and checks. A state labelled rigid-body (a free rotation angle) owns
  // one exponent that is 0 in theory: among the modes whose shape lies mostly in that state
  // (without shapes: all modes), the exponent nearest 0 is flagged and left out of the verdict.
  // Nearest 0, not largest share: a slow real mode of the rotor speed also lies mostly in the
  // angle (its angle amplitude is the speed amplitude divided by λ).
  for (int state : system.labels().rigid_body_states) {
    if (state < 0 || state >= n) continue;
    int best = -1;
    for (int pass = 0; pass < 2 && best < 0; ++pass) {
      for (int k = 0; k < n; ++k) {
        if (r.modes[k].rigid_body) continue;
        if (pass == 0) {
          if (r.mode_samples.empty()) continue;
          const double norm = r.mode_samples.front().col(k).norm();
          if (!(norm > 0) || std::abs(r.mode_samples.front()(state, k)) < 0.5 * norm) continue;
        }
        if (best < 0 || std::abs(r.modes[k].exponent) < std::abs(r.modes[best].exponent)) best = k;
      }
    }
    if (best < 0) continue;
    r.modes[best].rigid_body = true;
    std::ostringstream s;
    s << "mode " << best + 1 << " is the rigid rotation of state " << state + 1
      << (state < static_cast<int>(system.labels().states.size())
              ? " (" + system.labels().states[state] + ")"
              : "")
      << ": exponent " << r.modes[best].exponent.real()
      << " 1/s, exactly 0 for the exact periodic system; its distance from 0 is the model's "
         "error (e.g. azimuth sampling); left out of max Re λ and the stability verdict";
    r.diagnostics.push_back(s.str());
  }
  r.max_real_exponent = -std::numeric_limits<double>::infinity();
  for (const auto& mode : r.modes)
    if (!mode.rigid_body) r.max_real_exponent = std::max(r.max_real_exponent, mode.exponent.real());
  if (!std::isfinite(r.max_real_exponent)) r.max_real_exponent = 0;  // n = 0, or all rigid
  r.max_log_abs_multiplier = r.max_real_exponent * T;
  double max_abs_log = 0;
  double sum_log_abs = 0;
  for (const cd& l : log_rho) {
    if (std::isfinite(l.real())) max_abs_log = std::max(max_abs_log, std::abs(l));
    sum_log_abs += l.real();
  }
  const double trace_integral = IntegralOfTrace(system);
  r.liouville_residual =
      std::abs(sum_log_abs - trace_integral) / std::max(1.0, std::abs(trace_integral));
  // Round-off floor: every factor carries a backward error of a few eps, K + n of them
  // accumulate; an eigenvalue moves by κ_k times that, or by its square root when the
  // eigenvalue is defective (κ = ∞).
  const double backward = 16 * std::numeric_limits<double>::epsilon() * (r.segments + n);
  double floor = 0;
  for (int k = 0; k < n; ++k)
    floor = std::max(floor, std::min(kappa[k] * backward, 2 * std::sqrt(backward)) / T);
  floor = std::max(floor, backward * max_abs_log / T);
  r.error_estimate = options.estimate_error ? integration_error + floor : -1;
  // Liouville: Σ log|ρ_k| = ∫ tr A exactly, and every exponent is within the estimate, so the
  // sum is within n·T·estimate of it. Beyond that some exponents are wrong — e.g. forced
  // settings: one segment with single-shot multipliers loses every |ρ| below eps·max|ρ| — and
  // the result is not ok. Without an estimate only a gross failure can be told from the
  // integration's own error: the allowance is then 1e4 × the tolerance (at least 1e-6), relative.
  const double gross =
      std::max(1e-6, 1e4 * options.integrator.rel_tol) * std::max(1.0, std::abs(trace_integral));
  const double liouville_allowance =
      options.estimate_error
          ? std::max(n * T * r.error_estimate, 1e-6 * std::max(1.0, std::abs(trace_integral)))
          : gross;
  r.ok = std::abs(sum_log_abs - trace_integral) <= liouville_allowance;
  if (!r.ok) {
    std::ostringstream s;
    s << "Liouville check failed: Σ log|ρ| = " << sum_log_abs
      << " but ∫ tr A dt = " << trace_integral << ", beyond what the error estimate allows ("
      << liouville_allowance
      << "): some exponents are wrong (too few segments, single-shot multipliers or too loose a "
         "tolerance for this system; the automatic settings avoid this)";
    r.diagnostics.push_back(s.str());
  }
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, r.error_estimate);
  r.stable = r.verdict == StabilityVerdict::kStable;
  if (r.verdict == StabilityVerdict::kMarginal && r.error_estimate >= 0)
    r.diagnostics.push_back(
        "stability undecided (marginal): |max Re λ| is within the error "
        "estimate (a conservative system, or one on a stability boundary)");
  r.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace ltp
