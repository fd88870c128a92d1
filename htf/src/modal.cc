// Route 1: Floquet modal partial FRFs (paper eq. 42–46, docs/conventions.md, "Independent routes").
// With x = Ξ(t) q the modal coordinates obey q' = Λ q + Ξ⁻¹B u, so for u = U e^{jωt}
//   q_k = Σ_u [B̂_u]_k U e^{j(ω+uΩp)t} / (j(ω+uΩp) − λ_k),   y = CΞ q + D u
// and grouping u + v = z gives H_z(ω) = Σ_{u+v=z} Ĉ_v (j(ω+uΩp)I − Λ)⁻¹ B̂_u + D_z.
// The Fourier coefficients Ĉ_v of C(t)Ξ(t) and B̂_u of Ξ(t)⁻¹B(t) come from an FFT of uniform
// samples; new samples are propagated from the Floquet mode samples until the spectra have
// decayed (tail check). Any branch λ_k + jmΩp with ξ_k e^{−jmΩp t} gives the same H_z.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "fft_util.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/htf/pfrf.h"
#include "ltp/integrate/integrator_choice.h"
#include "ltp/integrate/threads.h"

namespace ltp {

namespace {

using cd = std::complex<double>;

bool IsPowerOfTwo(int x) { return x > 0 && (x & (x - 1)) == 0; }

// Worst per-mode ratio of the upper-half Fourier amplitude to the largest amplitude, for
// column k of Ĉ and row k of B̂ (each mode is scaled arbitrarily, so mode by mode).
double PerModeTail(const std::vector<Eigen::MatrixXcd>& c, const std::vector<Eigen::MatrixXcd>& b,
                   int n) {
  const int H = static_cast<int>(c.size()) / 2;
  double worst = 0;
  for (int k = 0; k < n; ++k) {
    double c_all = 0, c_up = 0, b_all = 0, b_up = 0;
    for (int v = -H; v <= H; ++v) {
      const double cn = c[v + H].col(k).norm(), bn = b[v + H].row(k).norm();
      c_all = std::max(c_all, cn);
      b_all = std::max(b_all, bn);
      if (2 * std::abs(v) > H) {
        c_up = std::max(c_up, cn);
        b_up = std::max(b_up, bn);
      }
    }
    if (c_all > 0) worst = std::max(worst, c_up / c_all);
    if (b_all > 0) worst = std::max(worst, b_up / b_all);
  }
  return worst;
}

// The Floquet result must belong to this system and carry mode samples the FFT can use.
void CheckModalInputs(const PeriodicSystem& system, const FloquetResult& floquet) {
  const int n = system.states(), m = system.inputs(), p = system.outputs();
  const double T = system.period();
  if (m < 1 || p < 1)
    throw InputError("partial FRFs need at least one input and one output; the system has " +
                     std::to_string(m) + " inputs and " + std::to_string(p) + " outputs");
  if (floquet.states != n || std::abs(floquet.period - T) > 1e-12 * T)
    throw InputError("modal model: the Floquet result belongs to another system");
  if (floquet.mode_samples.empty() || static_cast<int>(floquet.modes.size()) != n)
    throw InputError("modal model: the Floquet result has no mode shapes (compute_modes off?)");
  if (!IsPowerOfTwo(static_cast<int>(floquet.mode_samples.size())))
    throw InputError("modal model: mode samples must be a power of two per period");
}

// The Fourier coefficients Ĉ_v of CΞ, B̂_u of Ξ⁻¹B and D_w of D, from one set of samples of Ξ.
struct ModalSpectra {
  std::vector<Eigen::MatrixXcd> c_hat, b_hat, d_hat;
  double sample_condition = 1;  // max over the samples of cond Ξ(t_s), columns normalised
};

ModalSpectra TransformModeSamples(const PeriodicSystem& system,
                                  const std::vector<Eigen::MatrixXcd>& xi) {
  const int n = system.states(), m = system.inputs(), p = system.outputs();
  const double T = system.period();
  const int S = static_cast<int>(xi.size());
  Eigen::MatrixXd a_buf(p, n), b_buf(n, m), d_buf(p, m);
  std::vector<Eigen::MatrixXcd> cxi(S), xib(S), dd(S);
  ModalSpectra spectra;
  for (int s = 0; s < S; ++s) {
    const double t = T * s / S;
    system.EvalC(t, a_buf);
    system.EvalB(t, b_buf);
    system.EvalD(t, d_buf);
    cxi[s] = a_buf.cast<cd>() * xi[s];
    // Column-normalised Ξ for the condition estimate; the scaling is undone on B̂.
    Eigen::VectorXd scale = xi[s].colwise().norm().transpose();
    for (int k = 0; k < n; ++k)
      if (!(scale(k) > 0)) scale(k) = 1;
    const Eigen::MatrixXcd xn = xi[s] * scale.cwiseInverse().asDiagonal();
    Eigen::PartialPivLU<Eigen::MatrixXcd> lu(xn);
    const double rc = lu.rcond();
    spectra.sample_condition = std::max(spectra.sample_condition, rc > 0 ? 1.0 / rc : HUGE_VAL);
    xib[s] = scale.cwiseInverse().asDiagonal() * lu.solve(b_buf.cast<cd>());
    dd[s] = d_buf.cast<cd>();
  }
  spectra.c_hat = internal::SampledFourier(cxi);
  spectra.b_hat = internal::SampledFourier(xib);
  spectra.d_hat = internal::SampledFourier(dd);
  return spectra;
}

// Refine by f: ξ_k(t_s + qh) = Φ(t_s + qh, t_s) ξ_k(t_s) e^{−λ_k qh}, h = T/(fS), q < f.
// False (xi unchanged) when a propagation failed.
bool RefineModeSamples(const PeriodicSystem& system, const ModalOptions& options, int f,
                       ModalModel* r, std::vector<Eigen::MatrixXcd>* xi) {
  const int n = system.states(), S = static_cast<int>(xi->size());
  const double T = system.period();
  const double h = T / (f * S);
  Eigen::VectorXcd decay(n);
  for (int k = 0; k < n; ++k) decay(k) = std::exp(-r->exponents[k] * h);
  // Chains over the fine grid on the cores (the step size carries across the samples).
  std::vector<std::pair<double, double>> fine(f * S);
  for (int q = 0; q < f * S; ++q) fine[q] = {T * q / (f * S), T * (q + 1) / (f * S)};
  const std::vector<TransitionResult> steps =
      IntervalTransitions(system, fine, options.integrator, ThreadsFor(0));
  bool ok = true;
  for (const TransitionResult& tr : steps) {
    r->rhs_evals += tr.rhs_evals;
    ok = ok && tr.ok;
  }
  if (!ok) return false;
  std::vector<Eigen::MatrixXcd> finer(f * S);
  for (int s = 0; s < S; ++s) {
    finer[f * s] = (*xi)[s];
    for (int q = 1; q < f; ++q)
      finer[f * s + q] =
          steps[f * s + q - 1].phi.cast<cd>() * finer[f * s + q - 1] * decay.asDiagonal();
  }
  *xi = std::move(finer);
  return true;
}

// Transforms the mode samples, refining them until the spectra have decayed to tail_tol, reach
// the noise level of the samples, or max_samples is reached. Sets samples, tail, noise_floor
// and rhs_evals of r.
ModalSpectra ResolveSpectra(const PeriodicSystem& system, const FloquetResult& floquet,
                            const ModalOptions& options, ModalModel* r) {
  std::vector<Eigen::MatrixXcd> xi = floquet.mode_samples;
  for (;;) {
    const int S = static_cast<int>(xi.size());
    ModalSpectra spectra = TransformModeSamples(system, xi);
    r->samples = S;
    const double previous_tail = r->tail;
    r->tail = PerModeTail(spectra.c_hat, spectra.b_hat, r->states);
    if (r->tail <= options.tail_tol || 2 * S > options.max_samples) return spectra;
    // Noise level: the mode samples carry the integration error (~ its rel_tol), white
    // across harmonics. A tail within 10× of it is what the samples can resolve (tower-rotor:
    // 2.4e-10 at 512 samples, 1e-10 at 1024 and on); and once a doubling no longer shrinks a
    // small tail fourfold, more samples only resolve noise (2047 harmonics were once kept,
    // each evaluation 30× slower, for nothing).
    const double noise = std::min(10 * options.integrator.rel_tol, 0.1 * options.max_tail);
    const bool at_noise = r->tail <= noise;
    const bool stalled = S > static_cast<int>(floquet.mode_samples.size()) &&
                         r->tail <= 0.1 * options.max_tail && r->tail > 0.25 * previous_tail;
    if (at_noise || stalled) {
      r->noise_floor = true;
      return spectra;
    }
    // One refinement integrates the period once whatever f is, so a tail far above its
    // target is refined fourfold in one pass.
    const int f =
        r->tail > 10 * std::max(options.tail_tol, noise) && 4 * S <= options.max_samples ? 4 : 2;
    if (!RefineModeSamples(system, options, f, r, &xi)) {
      r->diagnostics.push_back(
          {DiagnosticCode::kModalSamplesFailed, Severity::kWarning,
           "modal: propagating mode samples failed; kept " + std::to_string(S) + " samples"});
      return spectra;
    }
  }
}

// Keep only the harmonics that matter (relative per mode, round-off level).
void KeepSignificantHarmonics(const ModalSpectra& spectra, ModalModel* r) {
  const std::vector<Eigen::MatrixXcd>& c_hat = spectra.c_hat;
  const std::vector<Eigen::MatrixXcd>& b_hat = spectra.b_hat;
  const std::vector<Eigen::MatrixXcd>& d_hat = spectra.d_hat;
  const int n = r->states;
  const int H = static_cast<int>(c_hat.size()) / 2;
  std::vector<double> c_max(n, 0), b_max(n, 0);
  double d_max = 0;
  for (int v = -H; v <= H; ++v) {
    for (int k = 0; k < n; ++k) {
      c_max[k] = std::max(c_max[k], c_hat[v + H].col(k).norm());
      b_max[k] = std::max(b_max[k], b_hat[v + H].row(k).norm());
    }
    d_max = std::max(d_max, d_hat[v + H].norm());
  }
  // Harmonics at or below the noise plateau carry nothing but that noise (the tail, part of
  // the route's error estimate, accounts for them).
  const double keep = r->noise_floor ? std::max(1e-17, r->tail) : 1e-17;
  int V = 0;
  for (int v = -H; v <= H; ++v) {
    bool significant = d_hat[v + H].norm() > 1e-17 * d_max;
    for (int k = 0; k < n && !significant; ++k)
      significant = c_hat[v + H].col(k).norm() > keep * c_max[k] ||
                    b_hat[v + H].row(k).norm() > keep * b_max[k];
    if (significant) V = std::max(V, std::abs(v));
  }
  r->harmonics = V;
  for (int v = -V; v <= V; ++v) {
    r->c_hat.push_back(c_hat[v + H]);
    r->b_hat.push_back(b_hat[v + H]);
    r->d_hat.push_back(d_hat[v + H]);
  }
}

// Unresolved spectra and an ill-conditioned mode matrix, in words.
void DiagnoseModalModel(const FloquetResult& floquet, const ModalOptions& options, ModalModel* r) {
  std::ostringstream s;
  if (!floquet.ok)
    r->diagnostics.push_back(
        {DiagnosticCode::kFloquetFailed, Severity::kFailure, "modal: the Floquet analysis failed"});
  if (r->tail > options.tail_tol) {
    s << "modal: Fourier series of CΞ and Ξ⁻¹B not resolved with " << r->samples
      << " samples (upper-half amplitude " << r->tail << " > " << options.tail_tol << ")"
      << (r->noise_floor
              ? ", the noise level of the integrated mode samples (harmonics below it dropped)"
              : "")
      << (r->tail > options.max_tail ? ": UNRELIABLE" : "");
    r->diagnostics.push_back(
        {DiagnosticCode::kModalSpectrumUnresolved, Severity::kWarning, s.str()});
    s.str("");
  }
  if (r->condition > options.max_condition) {
    s << "modal: the mode matrix is ill-conditioned (cond Ξ = " << r->condition << " > "
      << options.max_condition
      << "): either the modes differ widely in scale (harmless) or the monodromy is "
         "(near-)defective, e.g. close to a stability boundary, where the modal terms lose "
         "accuracy; only a cross-check against another route tells which";
    r->diagnostics.push_back(
        {DiagnosticCode::kModeMatrixIllConditioned, Severity::kWarning, s.str()});
  }
}

}  // namespace
std::string_view ToString(PfrfRoute route) {
  switch (route) {
    case PfrfRoute::kModal:
      return "modal";
    case PfrfRoute::kHtf:
      return "htf";
    case PfrfRoute::kShooting:
      return "shooting";
    case PfrfRoute::kTime:
      return "time";
    case PfrfRoute::kAuto:
      return "auto";
  }
  return "?";
}

std::optional<PfrfRoute> ParsePfrfRoute(std::string_view name) {
  for (PfrfRoute r : {PfrfRoute::kModal, PfrfRoute::kHtf, PfrfRoute::kShooting, PfrfRoute::kTime,
                      PfrfRoute::kAuto})
    if (name == ToString(r)) return r;
  return std::nullopt;
}

bool SelectPfrfRoutes(std::string_view name, PfrfOptions* options) {
  if (name == "all") {
    options->primary = PfrfRoute::kModal;
    options->checks = {PfrfRoute::kHtf, PfrfRoute::kShooting, PfrfRoute::kTime};
    return true;
  }
  const auto route = ParsePfrfRoute(name);
  if (!route) return false;
  options->primary = *route;
  options->checks = {PfrfRoute::kAuto};
  return true;
}

void ModalOptions::Validate() const {
  const OptionCheck check("ModalOptions");
  if (!(tail_tol > 0) || !std::isfinite(tail_tol))
    check.Fail("tail_tol", tail_tol, "finite and > 0");
  if (!IsPowerOfTwo(max_samples) || max_samples < 4)
    check.Fail("max_samples", max_samples, "a power of two >= 4");
  if (!(max_condition >= 1)) check.Fail("max_condition", max_condition, ">= 1");
  if (!(max_tail >= tail_tol))
    check.Fail("max_tail", max_tail, "max_tail >= tail_tol (" + MessageNumber(tail_tol) + ")");
  integrator.Validate();
}

ModalModel BuildModalModel(const PeriodicSystem& system, const FloquetResult& floquet,
                           const ModalOptions& requested) {
  requested.Validate();
  // IntegratorType::kAuto resolved once, not on every sample propagation below.
  ModalOptions options = requested;
  options.integrator = ResolveIntegrator(system, requested.integrator);
  const auto start = std::chrono::steady_clock::now();
  CheckModalInputs(system, floquet);

  ModalModel r;
  r.states = system.states();
  r.inputs = system.inputs();
  r.outputs = system.outputs();
  r.period = system.period();
  r.omega_p = system.omega();
  for (const FloquetMode& mode : floquet.modes) r.exponents.push_back(mode.exponent);

  const ModalSpectra spectra = ResolveSpectra(system, floquet, options, &r);
  KeepSignificantHarmonics(spectra, &r);
  r.condition = std::max(floquet.mode_condition.value_or(0.0), spectra.sample_condition);
  // cond Ξ alone does not make the numbers wrong: modes of widely different frequency and
  // amplitude scales give 1e4 from scaling alone (tower-rotor: 2e4, and the HTF agrees to
  // 1e-12). It is reported; the sweep's cross-check against another route decides.
  r.reliable = floquet.ok && r.tail <= options.max_tail;
  DiagnoseModalModel(floquet, options, &r);
  r.elapsed_s = SecondsSince(start);
  return r;
}

PartialFrfs ModalModel::Evaluate(double omega, int min_order, int max_order) const {
  return EvaluateAt(cd(0, omega), min_order, max_order);
}

PartialFrfs ModalModel::EvaluateAt(cd s, int min_order, int max_order) const {
  const int V = harmonics;
  PartialFrfs h(max_order - min_order + 1, Eigen::MatrixXcd::Zero(outputs, inputs));
  Eigen::MatrixXcd scaled(states, inputs);
  for (int u = -V; u <= V; ++u) {
    // R_u = ((s + juΩp) I − Λ)⁻¹ B̂_u, reused for every z.
    const cd su = s + cd(0, u * omega_p);
    for (int k = 0; k < states; ++k) scaled.row(k) = b_hat[u + V].row(k) / (su - exponents[k]);
    for (int z = min_order; z <= max_order; ++z) {
      const int v = z - u;
      if (std::abs(v) <= V) h[z - min_order].noalias() += c_hat[v + V] * scaled;
    }
  }
  for (int z = min_order; z <= max_order; ++z)
    if (std::abs(z) <= V) h[z - min_order] += d_hat[z + V];
  return h;
}

std::complex<double> ModalModel::Term(double omega, int k, int u, int v, int output,
                                      int input) const {
  const int V = harmonics;
  if (std::abs(u) > V || std::abs(v) > V) return 0;
  return c_hat[v + V](output, k) * b_hat[u + V](k, input) /
         (cd(0, omega + u * omega_p) - exponents[k]);
}

ModalChannel::ModalChannel(const ModalModel& model, int output, int input)
    : harmonics_(model.harmonics), omega_p_(model.omega_p) {
  const int V = harmonics_, n = model.states;
  decay_.resize(n);
  frequency_.resize(n);
  for (int k = 0; k < n; ++k) {
    decay_(k) = -model.exponents[k].real();
    frequency_(k) = model.exponents[k].imag();
  }
  b_.resize(2 * V + 1, n);
  c_.resize(2 * V + 1, n);
  for (int w = 0; w <= 2 * V; ++w) {
    b_.row(w) = model.b_hat[w].col(input).transpose();
    c_.row(w) = model.c_hat[w].row(output);
    d_.push_back(model.d_hat[w](output, input));
  }
}

std::vector<std::complex<double>> ModalChannel::Evaluate(double omega, int min_order,
                                                         int max_order) const {
  const int V = harmonics_, n = static_cast<int>(decay_.size());
  Eigen::VectorXcd h = Eigen::VectorXcd::Zero(max_order - min_order + 1);
  Eigen::ArrayXd detuning(n), denominator(n);
  Eigen::ArrayXcd resolvent(n);
  Eigen::VectorXcd scaled(n);
  const Eigen::ArrayXd decay_squared = decay_.square();
  for (int u = -V; u <= V; ++u) {
    // The orders z whose partner v = z − u is kept (|v| <= V).
    const int z0 = std::max(min_order, u - V), z1 = std::min(max_order, u + V);
    if (z0 > z1) continue;
    // 1/(j(ω+uΩp) − λ_k) = (−Re λ_k − j(ω+uΩp − Im λ_k)) / |·|², in real arithmetic (no
    // complex division per term; an exact resonance, |·| = 0, is flagged by the sweep).
    detuning = (omega + u * omega_p_) - frequency_;
    denominator = decay_squared + detuning.square();
    resolvent.real() = decay_ / denominator;
    resolvent.imag() = -detuning / denominator;
    scaled = (b_.row(u + V).transpose().array() * resolvent).matrix();
    h.segment(z0 - min_order, z1 - z0 + 1).noalias() +=
        c_.middleRows(z0 - u + V, z1 - z0 + 1) * scaled;
  }
  for (int z = min_order; z <= max_order; ++z)
    if (std::abs(z) <= V) h(z - min_order) += d_[z + V];
  return {h.data(), h.data() + h.size()};
}

}  // namespace ltp
