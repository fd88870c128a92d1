#include "ltp/core/fourier_fit.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <sstream>
#include <unsupported/Eigen/FFT>
#include <utility>
#include <vector>

#include "ltp/core/error.h"

// Definitions used throughout (norms are Frobenius norms of the coefficient matrices):
//   scale = max_w ||M_w||,
//   tail  = sqrt(Σ_{|w|>H} ||M_w||²) / scale  (both signs of w; by Parseval the RMS over one
//           period of the truncation error M(t) − Σ_{|w|<=H} M_w e^{jwΩp t}, relative to scale).
// Harmonics beyond the FFT's reach are extrapolated from the fitted decay; an algebraic decay
// with p <= 1/2 gives an infinite (unbounded) tail estimate.

namespace ltp {

std::string_view ToString(FourierDecay decay) {
  switch (decay) {
    case FourierDecay::kFinite:
      return "finite";
    case FourierDecay::kExponential:
      return "exponential";
    case FourierDecay::kAlgebraic:
      return "algebraic";
  }
  return "?";
}
namespace {

constexpr int kMinSamples = 16;
// Coefficients below kRoundOffFactor · eps · max_t ||M(t)|| are indistinguishable from the
// round-off of sampling and FFT.
constexpr double kRoundOffFactor = 64;
// A series counts as "finite" when the decay trend predicts the next coefficient at least this
// far above round-off, yet it has vanished.
constexpr double kFiniteGap = 1e3;

// One FFT pass with S samples: one-sided coefficients c_w, w = 0 .. S/2-1 (Nyquist dropped).
struct Spectrum {
  int samples = 0;
  std::vector<Eigen::MatrixXcd> coeffs;
  std::vector<double> norms;  // ||c_w||_F
  double scale = 0;           // max_w ||c_w||
  double floor = 0;           // round-off level of a coefficient (absolute)
};

// Least-squares line y = alpha + beta x.
struct Line {
  double alpha = 0, beta = 0, rss = std::numeric_limits<double>::infinity();
  double operator()(double x) const { return alpha + beta * x; }
};

Line FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double sx = 0, sy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
  }
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  Line l;
  l.beta = sxy / sxx;
  l.alpha = my - l.beta * mx;
  l.rss = 0;
  for (size_t i = 0; i < x.size(); ++i) l.rss += std::pow(y[i] - l(x[i]), 2);
  return l;
}

// Samples f on the half-step grid t_s = (s + 1/2) T/S and returns its coefficients
//   c_w = (1/S) Σ_s M(t_s) e^{-j w Ωp t_s}.
// The half-step offset keeps samples off the jumps that real systems usually have at "round"
// times (0, T/4, the sample times of a piecewise-constant system): such a jump then lies midway
// between two samples, which keeps the aliasing error of the coefficients O(1/S²).
Spectrum Sample(const PeriodicSystem::MatrixFunction& f, int rows, int cols, double period,
                int samples) {
  const int entries = rows * cols;
  // Column s: the matrix at t_s, written whole; entry k's time series is row k, read below as
  // `samples` streams that advance together (a row per sample scattered a 250 × 250 matrix over
  // a cache line per entry: 2 ms a sample).
  Eigen::MatrixXd values(entries, samples);
  Eigen::MatrixXd m(rows, cols);
  double max_value_norm = 0;
  for (int s = 0; s < samples; ++s) {
    const double t = (s + 0.5) * period / samples;
    m.setZero();
    f(t, m);
    if (!m.allFinite()) {
      std::ostringstream msg;
      msg.precision(17);
      msg << "function value is not finite at t = " << t;
      throw InputError(msg.str());
    }
    max_value_norm = std::max(max_value_norm, m.norm());
    values.col(s) = m.reshaped();
  }

  // Real-input FFT, one half of the spectrum: c_{-w} = conj(c_w) then holds exactly.
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  std::vector<std::complex<double>> out(samples / 2 + 1);
  const int half = samples / 2;
  Spectrum sp;
  sp.samples = samples;
  sp.coeffs.assign(half, Eigen::MatrixXcd(rows, cols));
  // Undoes the half-step offset (e^{-j w Ωp t_s} = e^{-2πj w s/S} e^{-jπ w/S}) and scales by 1/S.
  std::vector<std::complex<double>> shift(half);
  for (int w = 0; w < half; ++w)
    shift[w] = std::polar(1.0 / samples, -std::numbers::pi * w / samples);
  std::vector<double> series(samples);
  for (int k = 0; k < entries; ++k) {
    for (int s = 0; s < samples; ++s) series[s] = values(k, s);
    fft.fwd(out.data(), series.data(), samples);
    for (int w = 0; w < half; ++w) sp.coeffs[w](k % rows, k / rows) = out[w] * shift[w];
  }
  sp.coeffs[0] = sp.coeffs[0].real().cast<std::complex<double>>();  // M_0 of a real function
  sp.norms.resize(half);
  for (int w = 0; w < half; ++w) {
    sp.norms[w] = sp.coeffs[w].norm();
    sp.scale = std::max(sp.scale, sp.norms[w]);
  }
  sp.floor = kRoundOffFactor * std::numeric_limits<double>::epsilon() * max_value_norm;
  return sp;
}

// What one spectrum says about the decay of the coefficients and the harmonics to keep.
struct Analysis {
  FourierDecay decay = FourierDecay::kFinite;
  double rate = 0;
  // Extrapolated Σ_{w >= S/2} ||M_w||² (one side); infinite when the fit does not converge.
  double beyond = 0;
  int last_significant = -1;    // largest w with ||c_w|| above round-off
  std::vector<double> dropped;  // dropped[H] = norm of all harmonics |w| > H (both sides)
};

Analysis Analyse(const Spectrum& sp) {
  const int half = sp.samples / 2;
  Analysis a;
  for (int w = half - 1; w >= 0; --w)
    if (sp.norms[w] > sp.floor) {
      a.last_significant = w;
      break;
    }
  const int last = a.last_significant;

  // Monotone envelope max_{v >= w} ||c_v||: robust to coefficients that vanish by symmetry
  // (the even harmonics of a square wave) and can be fitted on a log scale.
  std::vector<double> envelope(half);
  double run = 0;
  for (int w = half - 1; w >= 0; --w) envelope[w] = run = std::max(run, sp.norms[w]);

  // Fit over the upper half of the significant range. When that range reaches S/4, the
  // coefficients near Nyquist are distorted by aliasing (for 1/w decay inflated by up to π/2):
  // fit below S/8 instead.
  const int hi = last < half / 2 ? last : half / 4;
  const int lo = std::max(1, hi / 2);
  const bool have_fit = hi - lo + 1 >= 2;
  Line exp_fit, alg_fit;
  if (have_fit) {
    std::vector<double> w, logw, y;
    for (int v = lo; v <= hi; ++v) {
      w.push_back(v);
      logw.push_back(std::log(v));
      y.push_back(std::log(envelope[v]));
    }
    exp_fit = FitLine(w, y);
    alg_fit = FitLine(logw, y);
  }
  const bool exponential = exp_fit.rss <= alg_fit.rss;
  auto predicted_log = [&](double w) { return exponential ? exp_fit(w) : alg_fit(std::log(w)); };

  // Finite: the whole upper half of the spectrum vanished (not just single harmonics that are
  // zero by symmetry) although the trend says it should still be clearly visible (or there are
  // too few harmonics to see a trend).
  const bool vanished = last < half / 2;
  if (vanished &&
      (!have_fit || last <= 2 || predicted_log(last + 1) > std::log(kFiniteGap * sp.floor))) {
    a.decay = FourierDecay::kFinite;
    a.rate = 0;
    a.beyond = 0;
  } else if (!have_fit) {
    // Defensive (half >= 8 leaves a fit range whenever `last` reaches S/4): tail unknown.
    a.decay = FourierDecay::kExponential;
    a.rate = 0;
    a.beyond = std::numeric_limits<double>::infinity();
  } else if (exponential) {
    // Σ_{w >= S/2} (e^{alpha} e^{-b w})².
    const double b = -exp_fit.beta;
    a.decay = FourierDecay::kExponential;
    a.rate = b;
    a.beyond = b > 0 ? std::exp(2 * exp_fit(half)) / (1 - std::exp(-2 * b))
                     : std::numeric_limits<double>::infinity();
  } else {
    // Σ_{w >= S/2} e^{2 alpha} w^{-2p} ≈ e^{2 alpha} ∫_{S/2-1/2}^∞ w^{-2p} dw (midpoint rule),
    // finite only for p > 1/2.
    const double p = -alg_fit.beta;
    a.decay = FourierDecay::kAlgebraic;
    a.rate = p;
    a.beyond = p > 0.5 ? std::exp(2 * alg_fit.alpha) * std::pow(half - 0.5, 1 - 2 * p) / (2 * p - 1)
                       : std::numeric_limits<double>::infinity();
  }

  // dropped[H]² = 2 (Σ_{H<w<S/2} ||c_w||² + beyond): both signs of w. For algebraic decay,
  // aliasing can also shrink the coefficients above S/8 (alternating alias sums), so there the
  // trend is used when larger.
  const bool use_trend = a.decay == FourierDecay::kAlgebraic;
  a.dropped.assign(half, 0);
  double sum = a.beyond;
  for (int h = half - 1; h >= 0; --h) {
    a.dropped[h] = std::sqrt(2 * sum);
    double n2 = sp.norms[h] * sp.norms[h];
    if (use_trend && h >= half / 4) n2 = std::max(n2, std::exp(2 * predicted_log(h)));
    sum += n2;
  }
  return a;
}

bool IsPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

FourierFit ExactFit(const FourierMatrix& m) {
  FourierFit fit;
  fit.series = m;
  fit.converged = true;
  fit.decay = FourierDecay::kFinite;
  return fit;
}

}  // namespace

FourierFit FitFourier(const PeriodicSystem::MatrixFunction& f, int rows, int cols, double period,
                      const FourierFitOptions& options) {
  if (rows < 0 || cols < 0) throw InputError("FitFourier: negative matrix size");
  if (!std::isfinite(period) || period <= 0)
    throw InputError("FitFourier: period must be finite and > 0");
  if (!std::isfinite(options.tol) || options.tol <= 0)
    throw InputError("FitFourier: tol must be finite and > 0");
  if (!IsPowerOfTwo(options.max_samples) || options.max_samples < kMinSamples)
    throw InputError("FitFourier: max_samples must be a power of two >= 16");
  if (options.max_harmonics < 0) throw InputError("FitFourier: max_harmonics must be >= 0");
  if (rows == 0 || cols == 0) return ExactFit(FourierMatrix(rows, cols, 0));
  if (!f) throw InputError("FitFourier: no function given");

  const double tol = options.tol;
  Spectrum prev, cur;
  Analysis an;
  int keep = 0;
  double alias_change = 0;  // max change of the kept coefficients from S/2 to S, relative
  bool checked = false;     // alias_change was measured
  for (int s = kMinSamples;; s *= 2) {
    cur = Sample(f, rows, cols, period, s);
    an = Analyse(cur);
    const int half = s / 2;
    const double limit = tol * cur.scale;

    // Smallest H whose dropped norm is within tolerance (-1: none at this S). Harmonics
    // beyond the last significant one are round-off: needing them means tol is below what
    // the samples can resolve.
    int needed = -1;
    for (int h = 0; h <= std::max(an.last_significant, 0); ++h)
      if (an.dropped[h] <= limit) {
        needed = h;
        break;
      }

    if (needed >= 0) {
      keep = needed;
    } else {
      // Not resolved: keep the significant harmonics, but none from the upper 3/4 of the
      // spectrum, where aliasing makes slowly decaying coefficients unreliable.
      keep = std::clamp(an.last_significant, 0, half / 4);
    }
    if (options.max_harmonics > 0) keep = std::min(keep, options.max_harmonics);

    // Aliasing check: the kept coefficients must not move when S doubles.
    checked = false;
    alias_change = 0;
    if (prev.samples > 0 && keep < prev.samples / 2) {
      for (int w = 0; w <= keep; ++w)
        alias_change = std::max(alias_change, (cur.coeffs[w] - prev.coeffs[w]).norm());
      alias_change = cur.scale > 0 ? alias_change / cur.scale : 0;
      checked = true;
    }
    if ((needed >= 0 && checked && alias_change <= tol) || s >= options.max_samples) break;
    prev = std::move(cur);
  }

  FourierFit fit;
  fit.samples = cur.samples;
  fit.decay = an.decay;
  fit.decay_rate = an.rate;
  fit.tail = cur.scale > 0 ? an.dropped[keep] / cur.scale : 0;
  // A failed aliasing check means the kept coefficients are off by about that much; fold it
  // into the reported tail so that `converged` and `tail` agree.
  if (checked && alias_change > tol) fit.tail = std::max(fit.tail, alias_change);
  fit.converged = fit.tail <= tol;
  fit.series = FourierMatrix(rows, cols, keep);
  for (int w = 0; w <= keep; ++w) fit.series.SetHarmonic(w, cur.coeffs[w]);
  return fit;
}

SystemFourier ToFourier(const PeriodicSystem& system, const FourierFitOptions& options) {
  const int n = system.states(), m = system.inputs(), p = system.outputs();
  if (system.form() == PeriodicSystem::Form::kFourier) {
    return {ExactFit(*system.fourier_A()), ExactFit(*system.fourier_B()),
            ExactFit(*system.fourier_C()), ExactFit(*system.fourier_D())};
  }
  // Function and piecewise-constant forms: fit what the system evaluates (a held,
  // piecewise-constant function jumps, so its fit shows algebraic decay).
  const double period = system.period();
  auto a = [&system](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalA(t, out); };
  auto b = [&system](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalB(t, out); };
  auto c = [&system](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalC(t, out); };
  auto d = [&system](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalD(t, out); };
  return {FitFourier(a, n, n, period, options), FitFourier(b, n, m, period, options),
          FitFourier(c, p, n, period, options), FitFourier(d, p, m, period, options)};
}

PeriodicSystem ToFourierSystem(const PeriodicSystem& system, const FourierFitOptions& options) {
  SystemFourier fits = ToFourier(system, options);
  PeriodicSystem out = PeriodicSystem::FromFourier(
                           system.period(), std::move(fits.A.series), std::move(fits.B.series),
                           std::move(fits.C.series), std::move(fits.D.series))
                           .WithLabels(system.labels());
  if (auto speed = system.rotor_speed()) out = out.WithRotorSpeed(*speed);
  return out;
}

}  // namespace ltp
