#include "floquet_modes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <unsupported/Eigen/FFT>

#include "ltp/core/whirl.h"
#include "ltp/floquet/periodic_eigen.h"
#include "ltp/integrate/detail/condition_number.h"
#include "ltp/integrate/detail/matrix_product.h"
#include "ltp/integrate/detail/modal_basis.h"

namespace ltp::internal {

namespace {

using cd = std::complex<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The mean's eigenvalues and ξ_k(0) in its eigenbasis (coefficients column k). A real mean
// (every real system) through LAPACK's real eigensolver and its real basis (Eigen's complex
// eigensolver took 0.2 s at 250 states); a complex one through Eigen.
struct MeanModes {
  Eigen::VectorXcd eigenvalues;
  Eigen::MatrixXcd coefficients;
};
std::optional<MeanModes> ModesOfTheMean(const Eigen::MatrixXcd& mean, const Eigen::MatrixXcd& xi0) {
  MeanModes out;
  if (mean.imag().isZero(0)) {
    const std::optional<RealEigenbasis> basis = RealEigenDecomposition(mean.real());
    if (!basis) return std::nullopt;
    out.eigenvalues = basis->eigenvalues;
    out.coefficients = EigenbasisCoefficients(*basis, xi0);
    return out;
  }
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> eig(mean);
  if (eig.info() != Eigen::Success) return std::nullopt;
  out.eigenvalues = eig.eigenvalues();
  out.coefficients = eig.eigenvectors().colPivHouseholderQr().solve(xi0);
  return out;
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
  std::optional<MeanModes> modes = ModesOfTheMean(mean, xi0);
  if (!modes) return prior;
  for (size_t k = 0; k < log_rho.size(); ++k) {
    const cd principal = log_rho[k] / T;
    if (!std::isfinite(principal.imag())) continue;
    Eigen::Index i = 0;
    if (!modes->coefficients.col(k).allFinite()) continue;
    modes->coefficients.col(k).cwiseAbs().maxCoeff(&i);
    const double m = std::round((modes->eigenvalues(i).imag() - principal.imag()) / omega);
    if (std::abs(m) < 1e6) prior[k] = static_cast<int>(m);
  }
  return prior;
}

// A constant A whose grid points lie on the sample grid: the transition from a grid point to
// the m-th sample after it is E^m, E = Φ(T/S, 0) (time-invariant), so one transition and a
// product per sample replace one transition per sample (a 400-state A: 64 exponentials in
// Eigen's products took 20 s). False (nothing done) otherwise.
bool ConstantSamples(const PeriodicSystem& system, const SegmentGrid& grid,
                     const std::vector<PeriodicEigenvector>& vecs, const std::vector<cd>& log_rho,
                     int samples, const IntegratorOptions& integrator, ModeShapes& out,
                     std::vector<Eigen::MatrixXcd>& xi) {
  const int n = system.states();
  const double T = system.period(), h = T / samples;
  std::vector<int> segment(samples), steps(samples);
  for (int s = 0; s < samples; ++s) {
    const double ts = T * s / samples;
    auto it = std::upper_bound(grid.times.begin(), grid.times.end(), ts + 1e-12 * T);
    segment[s] = static_cast<int>(it - grid.times.begin()) - 1;
    const double m = (ts - grid.times[segment[s]]) / h;
    steps[s] = static_cast<int>(std::lround(m));
    if (std::abs(m - steps[s]) > 1e-9 || steps[s] < 0) return false;
  }
  const TransitionResult e = StateTransition(system, 0.0, h, integrator);
  if (!e.ok) return false;
  out.rhs_evals += e.rhs_evals;
  Eigen::MatrixXd power = Eigen::MatrixXd::Identity(n, n), next(n, n), re(n, n), im(n, n);
  int at = 0;
  for (int s = 0; s < samples; ++s) {
    if (steps[s] < at) {
      power.setIdentity();
      at = 0;
    }
    for (; at < steps[s]; ++at) {
      MultiplyInto(e.phi, power, next);
      power.swap(next);
    }
    const int i = segment[s];
    out.sample_times[s] = T * s / samples;
    Eigen::MatrixXcd at_grid(n, n);
    for (int k = 0; k < n; ++k)
      at_grid.col(k) = vecs[k].v[i] * std::exp(-log_rho[k] / T * (steps[s] * h));
    MultiplyInto(power, at_grid.real(), re);
    MultiplyInto(power, at_grid.imag(), im);
    xi[s].real() = re;
    xi[s].imag() = im;
  }
  return true;
}

// ξ_k(t_s) at the uniform sample times. The grid refines the uniform one when the segments
// were chosen automatically, so the samples are grid points; otherwise (a user-chosen K, or
// fewer segments for a large system) they are propagated from the last grid point before each
// sample, ξ(t_s) = Φ(t_s, t_i) ξ(t_i) e^{−λ(t_s − t_i)}.
std::vector<Eigen::MatrixXcd> SampleShapes(const PeriodicSystem& system, const SegmentGrid& grid,
                                           const std::vector<PeriodicEigenvector>& vecs,
                                           const std::vector<cd>& log_rho, int samples,
                                           const IntegratorOptions& integrator, int threads,
                                           bool constant, ModeShapes& out) {
  const int n = system.states();
  const double T = system.period();
  out.sample_times.resize(samples);
  std::vector<int> at(samples);
  bool uniform_hit = true;
  for (int s = 0; s < samples; ++s) {
    const double ts = T * s / samples;
    auto it = std::lower_bound(grid.times.begin(), grid.times.end(), ts - 1e-12 * T);
    at[s] = static_cast<int>(it - grid.times.begin());
    uniform_hit = uniform_hit && at[s] < static_cast<int>(grid.times.size()) - 1 &&
                  std::abs(grid.times[at[s]] - ts) <= 1e-9 * T;
  }
  std::vector<Eigen::MatrixXcd> xi(samples);  // each written whole below, not copied first
  for (Eigen::MatrixXcd& x : xi) x.resize(n, n);
  if (uniform_hit) {
    for (int s = 0; s < samples; ++s) {
      out.sample_times[s] = grid.times[at[s]];
      for (int k = 0; k < n; ++k) xi[s].col(k) = vecs[k].v[at[s]];
    }
    return xi;
  }
  out.diagnostics.push_back(
      {DiagnosticCode::kModeSamplesPropagated, Severity::kNote,
       "mode samples propagated within segments (K = " + std::to_string(grid.factors.size()) +
           " segments for " + std::to_string(samples) + " samples)"});
  if (constant && ConstantSamples(system, grid, vecs, log_rho, samples, integrator, out, xi))
    return xi;
  long rhs_evals = 0;
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1)) reduction(+ : rhs_evals)
  for (int s = 0; s < samples; ++s) {
    const double ts = T * s / samples;
    auto it = std::upper_bound(grid.times.begin(), grid.times.end(), ts + 1e-12 * T);
    const int i = static_cast<int>(it - grid.times.begin()) - 1;
    out.sample_times[s] = ts;
    // ts can sit a rounding error below grid.times[i]: never integrate backwards.
    TransitionResult tr =
        StateTransition(system, grid.times[i], std::max(ts, grid.times[i]), integrator);
    rhs_evals += tr.rhs_evals;
    Eigen::MatrixXcd at_grid(n, n);
    for (int k = 0; k < n; ++k)
      at_grid.col(k) = vecs[k].v[i] * std::exp(-log_rho[k] / T * (ts - grid.times[i]));
    // Φ real: the real and imaginary parts as two real products (BLAS for large n).
    Eigen::MatrixXd re(n, n), im(n, n);
    MultiplyInto(tr.phi, at_grid.real(), re);
    MultiplyInto(tr.phi, at_grid.imag(), im);
    xi[s].real() = re;
    xi[s].imag() = im;
  }
  out.rhs_evals += rhs_evals;
  return xi;
}

// Harmonics −H … H of every entry of ξ (FFT), H = S/2 − 1: the Nyquist bin is dropped (its
// sign is ambiguous). The n² transforms run on `threads` threads.
std::vector<Eigen::MatrixXcd> FourierCoefficients(const std::vector<Eigen::MatrixXcd>& xi,
                                                  int threads) {
  const int samples = static_cast<int>(xi.size());
  const int n = static_cast<int>(xi[0].rows());
  const int H = samples / 2 - 1;
  // Every entry is written below, on the threads: no zero pass (31 MB at 250 states, page by page
  // on one thread before the loop).
  std::vector<Eigen::MatrixXcd> coef(2 * H + 1);
  for (Eigen::MatrixXcd& c : coef) c.resize(n, n);
#pragma omp parallel for schedule(static) num_threads(std::max(threads, 1))
  for (int k = 0; k < n; ++k) {
    Eigen::FFT<double> fft;
    std::vector<cd> in(samples), out(samples);
    for (int i = 0; i < n; ++i) {
      for (int s = 0; s < samples; ++s) in[s] = xi[s](i, k);
      fft.fwd(out, in);  // out[j] = Σ_s in[s] e^{-2πj js/S}
      for (int v = -H; v <= H; ++v)
        coef[v + H](i, k) = out[(v + samples) % samples] / double(samples);
    }
  }
  return coef;
}

// Branch of mode k from the centroid of its (demodulated) spectrum, the shape shifted onto it:
// ξ^(m)(t) = ξ(t) e^{−j m Ωp t}, coefficients c_{v+m}. Returns the upper-half energy share
// (the resolution check), or −1 when the shape is unusable.
double ChooseBranch(int k, int prior, cd log_rho, double T, double omega, double residual,
                    ModeShapes& out) {
  const int H = out.harmonics;
  std::vector<Eigen::MatrixXcd>& coef = out.fourier;
  std::vector<double> energy(2 * H + 1);
  double total = 0, first_moment = 0, tail = 0;
  for (int v = -H; v <= H; ++v) {
    energy[v + H] = coef[v + H].col(k).squaredNorm();
    total += energy[v + H];
    first_moment += v * energy[v + H];
    if (std::abs(v) > H / 2) tail += energy[v + H];
  }
  if (!(total > 0) || !std::isfinite(total) || !std::isfinite(residual)) return -1;
  const double centroid = first_moment / total;
  int m = static_cast<int>(std::lround(centroid));
  if (std::abs(std::abs(centroid - m) - 0.5) < 0.01) {
    // A tie (negative real multiplier: the exponent sits on the strip edge ±Ωp/2). Both
    // neighbours are valid; take the one with the smallest non-negative frequency so that
    // repeated runs agree (AnalyzeFloquet says so in its diagnostics).
    const int lo = static_cast<int>(std::floor(centroid)), hi = lo + 1;
    const double im_lo = (log_rho / T).imag() + (prior + lo) * omega;
    const double im_hi = (log_rho / T).imag() + (prior + hi) * omega;
    m = (im_lo >= -1e-12 * omega && (im_hi < -1e-12 * omega || im_lo <= im_hi)) ? lo : hi;
  }
  FloquetMode& mode = out.modes[k];
  mode = MakeFloquetMode(log_rho, prior + m, T);
  mode.central_weight = (std::abs(m) <= H ? energy[m + H] : 0) / total;
  mode.branch_margin = std::max(0.0, 0.5 - std::abs(centroid - m));
  mode.eigvec_residual = residual;
  for (size_t s = 0; s < out.samples.size(); ++s)
    out.samples[s].col(k) *= std::polar(1.0, -m * omega * out.sample_times[s]);
  std::vector<Eigen::VectorXcd> shifted(2 * H + 1, Eigen::VectorXcd::Zero(coef[0].rows()));
  for (int v = -H; v <= H; ++v)
    if (std::abs(v + m) <= H) shifted[v + H] = coef[v + m + H].col(k);
  for (int v = -H; v <= H; ++v) coef[v + H].col(k) = shifted[v + H];
  return tail / total;
}

// Condition of the mode matrix: the best over (up to 16 of) the sample times (a mode shape
// may be tiny at t = 0 and large elsewhere; defectiveness makes Ξ(t) ill-conditioned at
// every t). An SVD per sample was a fifth of a 60-state analysis. Then the eigenvalue
// condition numbers κ_k = ||x_k|| ||y_k|| with x_k = ξ_k(t)/||ξ_k(t)|| and y_k the k-th row of
// Ξ(t)⁻¹ (left eigenvector scaled so that y_k x_k = 1), at that best t. Modes whose shape
// could not be computed are left out (κ = ∞). The sample times' conditions are measured on
// `threads` threads.
void ModeMatrixCondition(const std::vector<int>& good, int threads, ModeShapes& out) {
  const int n = static_cast<int>(out.modes.size());
  const int samples = static_cast<int>(out.samples.size());
  out.condition = kInf;
  out.kappa.assign(n, kInf);
  if (good.empty()) return;  // every cyclic solve failed: no mode matrix (and no condition)
  auto normalised = [&](int s) {
    Eigen::MatrixXcd x(n, good.size());
    for (size_t j = 0; j < good.size(); ++j) {
      x.col(j) = out.samples[s].col(good[j]);
      const double norm = x.col(j).norm();
      if (norm > 0) x.col(j) /= norm;
    }
    return x;
  };
  const int stride = std::max(1, samples / 16), measured = (samples + stride - 1) / stride;
  std::vector<double> conditions(measured);
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1))
  for (int m = 0; m < measured; ++m) conditions[m] = ConditionNumber(normalised(m * stride));
  int best = 0;  // the first of the smallest, as a serial scan finds it
  for (int m = 1; m < measured; ++m)
    if (conditions[m] < conditions[best]) best = m;
  out.condition = conditions[best];
  const Eigen::MatrixXcd best_xi = normalised(best * stride);
  const Eigen::MatrixXcd left = best_xi.completeOrthogonalDecomposition().pseudoInverse();
  for (size_t j = 0; j < good.size(); ++j)
    out.kappa[good[j]] = std::isfinite(out.condition) ? left.row(j).norm() : kInf;
}

}  // namespace

ModeShapes ComputeModeShapes(const PeriodicSystem& system, const SegmentGrid& grid,
                             const std::vector<cd>& log_rho, int samples,
                             const IntegratorOptions& integrator, int threads, bool constant,
                             const PeriodicSchurForm* form) {
  const int n = system.states();
  const double T = system.period();
  const double omega = system.omega();
  ModeShapes out;
  out.modes.resize(n);
  for (int k = 0; k < n; ++k) out.modes[k] = MakeFloquetMode(log_rho[k], 0, T);
  std::vector<double> dt(grid.factors.size());
  for (size_t i = 0; i < dt.size(); ++i) dt[i] = grid.times[i + 1] - grid.times[i];
  const std::vector<PeriodicEigenvector> vecs =
      ComputePeriodicEigenvectors(grid.factors, dt, log_rho, threads, form);
  out.samples =
      SampleShapes(system, grid, vecs, log_rho, samples, integrator, threads, constant, out);
  // Demodulate by the prior branch, so the FFT sees spectra near harmonic 0.
  const std::vector<int> prior = PriorBranches(system, log_rho, out.samples[0]);
  for (int s = 0; s < samples; ++s)
    for (int k = 0; k < n; ++k)
      out.samples[s].col(k) *= std::polar(1.0, -prior[k] * omega * out.sample_times[s]);
  out.fourier = FourierCoefficients(out.samples, threads);
  out.harmonics = samples / 2 - 1;
  double worst_tail = 0;
  std::vector<int> good, failed;
  for (int k = 0; k < n; ++k) {
    const double tail = ChooseBranch(k, prior[k], log_rho[k], T, omega, vecs[k].residual, out);
    if (tail >= 0) {
      worst_tail = std::max(worst_tail, tail);
      good.push_back(k);
    } else {
      // The cyclic null-vector solve failed (seen for mode shapes whose magnitude varies
      // over hundreds of decades within a period). The exponent does not depend on it.
      failed.push_back(k);
      for (auto& x : out.samples) x.col(k).setZero();
      for (auto& c : out.fourier) c.col(k).setZero();
      out.modes[k].eigvec_residual = kInf;
    }
  }
  if (worst_tail > 1e-10) {
    std::ostringstream s;
    s << "mode shapes under-resolved: " << worst_tail
      << " of a mode's Fourier energy lies in the upper half of the " << samples
      << " samples; raise --mode-samples";
    out.diagnostics.push_back({DiagnosticCode::kModesUnderResolved, Severity::kWarning, s.str()});
  }
  ModeMatrixCondition(good, threads, out);
  for (int k : failed) {
    std::ostringstream s;
    s << "the periodic mode shape of the exponent " << (log_rho[k] / T).real()
      << (log_rho[k].imag() < 0 ? " - " : " + ") << std::abs((log_rho[k] / T).imag())
      << "j could not be computed (cyclic eigenvector solve failed); its exponent is "
         "unaffected, its branch is the principal one and its shape is reported as zero";
    out.diagnostics.push_back({DiagnosticCode::kModeShapeFailed, Severity::kWarning, s.str()});
  }
  if (good.empty()) {
    out.diagnostics.push_back(
        {DiagnosticCode::kNoModeShapes, Severity::kWarning,
         "no periodic mode shape could be computed (the solutions grow and decay over hundreds "
         "of decades within a period): exponents and multipliers are unaffected; mode shapes, "
         "left modes and branches are not available"});
  } else if (!(out.condition < 1e8)) {
    std::ostringstream s;
    s << "mode matrix is ill-conditioned (cond = " << out.condition
      << "): the monodromy is (near-)defective, e.g. a double multiplier at ±1 on a stability "
         "boundary; mode shapes, left modes and branch choices are unreliable, and exponents "
         "are accurate only to about the square root of the integration error";
    out.diagnostics.push_back(
        {DiagnosticCode::kModeMatrixIllConditioned, Severity::kWarning, s.str()});
  }
  return out;
}

void AssignWhirl(const PeriodicSystem& system, FloquetResult& r) {
  const auto& pairs = system.labels().whirl_pairs;
  if (pairs.empty() || r.mode_fourier.empty()) return;
  const int spin = RotorSpin(system);
  const double omega_p = 2 * std::numbers::pi / r.period;
  std::vector<Eigen::VectorXcd> harmonics(r.mode_fourier.size());
  for (size_t k = 0; k < r.modes.size(); ++k) {
    for (size_t v = 0; v < harmonics.size(); ++v)
      harmonics[v] = r.mode_fourier[v].col(static_cast<Eigen::Index>(k));
    r.modes[k].forward_whirl =
        ForwardWhirlShare(pairs, harmonics, r.modes[k].exponent.imag(), omega_p, spin);
  }
}

}  // namespace ltp::internal
