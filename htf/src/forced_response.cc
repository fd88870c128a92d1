// Routes 3 and 4: the forced response by integration, with no Fourier truncation of A.
// With x(t) = e^{jωt} y(t) the forced equation x' = A x + B U e^{jωt} becomes
//   y' = (A(t) − jωI) y + B(t) U,
// whose coefficients are T-periodic. Its transition over one period is Φ e^{−jωT}, so
//   shooting: y(0) = (I − Φ e^{−jωT})⁻¹ y_p(T), y_p from y_p(0) = 0 (exact periodic steady
//             state), and y(t_s) = Φ(t_s, 0) e^{−jωt_s} y(0) + y_p(t_s);
//   time:     y from rest, period after period, until the transient has decayed; the last
//             whole periods are averaged (projection of x on e^{j(ω+zΩp)t}, paper eq. 47).
// Then w = C y + D U is T-periodic and its Fourier coefficients are Y_z = H_z(ω) U.
// The complex ODE is integrated as the real system [Re Y, Im Y] by Runge–Kutta–Fehlberg 7(8)
// (Boost.Odeint), restarting at breakpoints and landing exactly on the samples.
#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <limits>
#include <sstream>

#include "fft_util.h"
#include "ltp/core/error.h"
#include "ltp/htf/pfrf.h"
#include "ltp/integrate/integrator_choice.h"

namespace ltp {

namespace {

namespace odeint = boost::numeric::odeint;
using cd = std::complex<double>;
using State = std::vector<double>;

// y' = (A − jωI) y + B on the real n×2m matrix [Re Y, Im Y] (column-major).
class ForcedRhs {
 public:
  ForcedRhs(const PeriodicSystem& system, double omega, long* evals)
      : system_(system),
        n_(system.states()),
        m_(system.inputs()),
        omega_(omega),
        a_(n_, n_),
        b_(n_, m_),
        evals_(evals) {}
  ForcedRhs(const ForcedRhs&) = delete;
  ForcedRhs& operator=(const ForcedRhs&) = delete;

  // Coefficients are evaluated inside [lo, hi] so a jump at a piece end is seen from inside.
  void SetPiece(double a, double b) {
    const double pad = 1e-13 * std::max(1.0, std::abs(b - a));
    lo_ = a + std::min(pad, 0.25 * (b - a));
    hi_ = b - std::min(pad, 0.25 * (b - a));
  }

  void operator()(const State& x, State& dxdt, double t) {
    const double tc = std::clamp(t, lo_, hi_);
    system_.EvalA(tc, a_);
    system_.EvalB(tc, b_);
    ++*evals_;
    Eigen::Map<const Eigen::MatrixXd> re(x.data(), n_, m_), im(x.data() + n_ * m_, n_, m_);
    Eigen::Map<Eigen::MatrixXd> dre(dxdt.data(), n_, m_), dim(dxdt.data() + n_ * m_, n_, m_);
    dre.noalias() = a_ * re;
    dre += omega_ * im + b_;
    dim.noalias() = a_ * im;
    dim -= omega_ * re;
  }

  double Scale() const { return a_.lpNorm<Eigen::Infinity>() + std::abs(omega_); }

 private:
  const PeriodicSystem& system_;
  int n_, m_;
  double omega_;
  Eigen::MatrixXd a_, b_;
  long* evals_;
  double lo_ = 0, hi_ = 0;
};

bool IsPowerOfTwo(int x) { return x > 0 && (x & (x - 1)) == 0; }

}  // namespace

void ShootingOptions::Validate() const {
  const OptionCheck check("ShootingOptions");
  if (!(rel_tol > 0)) check.Fail("rel_tol", rel_tol, "> 0");
  if (!(abs_tol > 0)) check.Fail("abs_tol", abs_tol, "> 0");
  if (samples != 0 && (!IsPowerOfTwo(samples) || samples < 8))
    check.Fail("samples", samples, "0 or a power of two >= 8");
  if (!IsPowerOfTwo(max_samples) || max_samples < 8)
    check.Fail("max_samples", max_samples, "a power of two >= 8");
  if (!(sample_tol > 0)) check.Fail("sample_tol", sample_tol, "> 0");
  if (max_steps < 1) check.Fail("max_steps", max_steps, ">= 1");
  if (!(settle_tol > 0 && settle_tol < 1)) check.Fail("settle_tol", settle_tol, "in (0, 1)");
  if (record_periods < 1) check.Fail("record_periods", record_periods, ">= 1");
  if (!(max_settle_periods > 0)) check.Fail("max_settle_periods", max_settle_periods, "> 0");
  integrator.Validate();
}

ForcedResponseSolver::ForcedResponseSolver(const PeriodicSystem& system,
                                           const ShootingOptions& options)
    : system_(system),
      options_(options),
      n_(system.states()),
      m_(system.inputs()),
      p_(system.outputs()) {
  options.Validate();
  options_.integrator =
      ResolveIntegrator(system, options.integrator);  // kAuto: once, not per sample
  if (m_ < 1 || p_ < 1)
    throw InputError("partial FRFs need at least one input and one output; the system has " +
                     std::to_string(m_) + " inputs and " + std::to_string(p_) + " outputs");
  if (options.samples > 0) {
    samples_ = options.samples;
  } else {
    int h = 16;
    if (const FourierMatrix* fa = system.fourier_A()) h = fa->max_harmonic();
    samples_ = std::clamp(internal::NextPowerOfTwo(16 * (h + 1)), 32, options.max_samples);
  }
}

double ForcedResponseSolver::SettlingTime(const FloquetResult& floquet, double settle_tol) {
  const double re = floquet.max_real_exponent;
  if (!(re < 0)) return std::numeric_limits<double>::infinity();
  // cond Ξ scales how far a transient can rise before it decays; unknown or infinite: 1.
  const double c = floquet.mode_condition.value_or(1.0);
  const double cond = std::isfinite(c) ? std::max(1.0, c) : 1.0;
  return std::log(cond / settle_tol) / -re;
}

void ForcedResponseSolver::PrepareTransitions() {
  const double T = system_.period();
  const int S = samples_;
  pieces_.clear();
  for (int s = 0; s <= S; ++s) pieces_.push_back(T * s / S);
  for (double b : system_.breakpoints())
    if (b > 0 && b < T) pieces_.push_back(b);
  std::sort(pieces_.begin(), pieces_.end());
  std::vector<double> unique;
  for (double t : pieces_)
    if (unique.empty() || t - unique.back() > 1e-13 * T) unique.push_back(t);
  unique.back() = T;
  pieces_ = std::move(unique);
  jump_pieces_ = {0.0};
  for (double t : pieces_)
    if (t > 0 && t < T &&
        std::any_of(system_.breakpoints().begin(), system_.breakpoints().end(),
                    [&](double b) { return std::abs(b - t) <= 1e-13 * T; }))
      jump_pieces_.push_back(t);
  jump_pieces_.push_back(T);
  phi_.clear();
}

bool ForcedResponseSolver::Integrate(double omega, const Eigen::MatrixXcd& y0, double /*t0*/,
                                     int periods, std::vector<Eigen::MatrixXcd>* last_period,
                                     Eigen::MatrixXcd* end_state,
                                     std::vector<Eigen::MatrixXcd>* average) {
  if (pieces_.empty()) PrepareTransitions();
  const double T = system_.period();
  const int S = samples_;
  const int n = n_, m = m_;
  State x(2 * static_cast<size_t>(n) * m);
  Eigen::Map<Eigen::MatrixXd> re(x.data(), n, m), im(x.data() + n * m, n, m);
  re = y0.real();
  im = y0.imag();
  ForcedRhs rhs(system_, omega, &rhs_evals_);
  auto stepper = odeint::make_controlled(options_.abs_tol, options_.rel_tol,
                                         odeint::runge_kutta_fehlberg78<State>());
  long attempts = 0;
  double dt = 0;
  if (average) average->assign(S, Eigen::MatrixXcd::Zero(n, m));
  if (last_period) last_period->assign(S + 1, Eigen::MatrixXcd::Zero(n, m));
  const int record_from = periods - (average ? options_.record_periods : 1);
  for (int period = 0; period < periods; ++period) {
    const bool record = period >= record_from;
    const std::vector<double>& grid = record ? pieces_ : jump_pieces_;
    int sample = 0;
    for (size_t piece = 0; piece + 1 < grid.size(); ++piece) {
      const double a = grid[piece], b = grid[piece + 1];
      // Samples sit on piece starts (the grid includes every sample time).
      if (record && sample < S && std::abs(a - T * sample / S) <= 1e-12 * T) {
        Eigen::MatrixXcd y(n, m);
        y.real() = re;
        y.imag() = im;
        if (average) (*average)[sample] += y / double(options_.record_periods);
        if (last_period && period == periods - 1) (*last_period)[sample] = y;
        ++sample;
      }
      rhs.SetPiece(a, b);
      double t = a;
      if (dt <= 0) {
        State scratch(x.size());
        rhs(x, scratch, a);  // evaluates A(a) to size the first step
        dt = std::min(b - a, 0.05 / std::max(1e-300, rhs.Scale()));
      }
      dt = std::min(dt, b - a);
      while (t < b) {
        if (++attempts > options_.max_steps) {
          diagnostics_.push_back({DiagnosticCode::kForcedResponseFailed, Severity::kFailure,
                                  "forced response: max_steps reached"});
          return false;
        }
        const bool last = dt >= b - t;
        double h = last ? b - t : dt;
        if (stepper.try_step(std::ref(rhs), x, t, h) == odeint::success) {
          if (last) t = b;
        }
        dt = h;
        if (t < b && t + dt == t) {
          diagnostics_.push_back({DiagnosticCode::kForcedResponseFailed, Severity::kFailure,
                                  "forced response: step size underflow"});
          return false;
        }
      }
    }
    for (double v : x)
      if (!std::isfinite(v)) {
        diagnostics_.push_back({DiagnosticCode::kForcedResponseFailed, Severity::kFailure,
                                "forced response: solution not finite (overflow?)"});
        return false;
      }
  }
  Eigen::MatrixXcd y(n, m);
  y.real() = re;
  y.imag() = im;
  if (last_period) (*last_period)[S] = y;
  if (end_state) *end_state = y;
  return true;
}

PartialFrfs ForcedResponseSolver::Project(const std::vector<Eigen::MatrixXcd>& y, double /*omega*/,
                                          int min_order, int max_order, double* tail) const {
  const double T = system_.period();
  const int S = samples_;
  Eigen::MatrixXd c(p_, n_), d(p_, m_);
  std::vector<Eigen::MatrixXcd> w(S);
  for (int s = 0; s < S; ++s) {
    const double t = T * s / S;
    system_.EvalC(t, c);
    system_.EvalD(t, d);
    w[s] = c.cast<cd>() * y[s] + d.cast<cd>();
  }
  const std::vector<Eigen::MatrixXcd> coef = internal::SampledFourier(w);
  const int H = static_cast<int>(coef.size()) / 2;
  if (tail) *tail = internal::UpperHalfRatio(coef);
  PartialFrfs h(max_order - min_order + 1, Eigen::MatrixXcd::Zero(p_, m_));
  for (int z = min_order; z <= max_order; ++z)
    if (std::abs(z) <= H) h[z - min_order] = coef[z + H];
  return h;
}

PartialFrfs ForcedResponseSolver::Shooting(double omega, int min_order, int max_order, bool* ok) {
  const double T = system_.period();
  const PartialFrfs failed(
      max_order - min_order + 1,
      Eigen::MatrixXcd::Constant(p_, m_, cd(std::numeric_limits<double>::quiet_NaN(), 0)));
  if (ok) *ok = false;
  for (;;) {
    if (pieces_.empty()) PrepareTransitions();
    const int S = samples_;
    if (phi_.empty()) {
      // Φ(t_s, 0) on the samples, independent of ω (the y-frame transition is Φ e^{−jωt}).
      phi_.assign(S + 1, Eigen::MatrixXd::Identity(n_, n_));
      for (int s = 0; s < S; ++s) {
        TransitionResult tr =
            StateTransition(system_, T * s / S, T * (s + 1) / S, options_.integrator);
        rhs_evals_ += tr.rhs_evals;
        if (!tr.ok) {
          diagnostics_.push_back({DiagnosticCode::kForcedResponseFailed, Severity::kFailure,
                                  "shooting: state transition failed: " + tr.message});
          phi_.clear();
          return failed;
        }
        phi_[s + 1] = tr.phi * phi_[s];
      }
    }
    std::vector<Eigen::MatrixXcd> yp;
    if (!Integrate(omega, Eigen::MatrixXcd::Zero(n_, m_), 0, 1, &yp, nullptr, nullptr))
      return failed;
    const Eigen::MatrixXcd M =
        Eigen::MatrixXcd::Identity(n_, n_) - phi_[S].cast<cd>() * std::polar(1.0, -omega * T);
    Eigen::PartialPivLU<Eigen::MatrixXcd> lu(M);
    if (!(lu.rcond() > 1e-14)) {
      diagnostics_.push_back(
          {DiagnosticCode::kShootingSingular, Severity::kWarning,
           "shooting: I − Φ e^{−jωT} is singular (excitation on a Floquet line)"});
      return failed;
    }
    const Eigen::MatrixXcd y0 = lu.solve(yp[S]);
    std::vector<Eigen::MatrixXcd> y(S);
    for (int s = 0; s < S; ++s)
      y[s] = phi_[s].cast<cd>() * y0 * std::polar(1.0, -omega * T * s / S) + yp[s];
    double tail = 0;
    PartialFrfs h = Project(y, omega, min_order, max_order, &tail);
    if (tail <= options_.sample_tol || 2 * samples_ > options_.max_samples ||
        options_.samples > 0) {
      sample_tail_ = std::max(sample_tail_, tail);
      if (ok) *ok = true;
      return h;
    }
    samples_ *= 2;
    pieces_.clear();
    phi_.clear();
  }
}

PartialFrfs ForcedResponseSolver::TimeSimulation(double omega, int min_order, int max_order,
                                                 double settle_time, bool* ok) {
  const double T = system_.period();
  const PartialFrfs failed(
      max_order - min_order + 1,
      Eigen::MatrixXcd::Constant(p_, m_, cd(std::numeric_limits<double>::quiet_NaN(), 0)));
  if (ok) *ok = false;
  if (!(settle_time >= 0) || settle_time / T > options_.max_settle_periods) {
    std::ostringstream s;
    s << "time: the transient does not decay within " << options_.max_settle_periods
      << " periods (settling time " << settle_time << " s): no steady state to project";
    diagnostics_.push_back({DiagnosticCode::kNoSteadyState, Severity::kFailure, s.str()});
    return failed;
  }
  const int settle_periods = static_cast<int>(std::ceil(settle_time / T));
  std::vector<Eigen::MatrixXcd> avg;
  if (!Integrate(omega, Eigen::MatrixXcd::Zero(n_, m_), 0, settle_periods + options_.record_periods,
                 nullptr, nullptr, &avg))
    return failed;
  double tail = 0;
  PartialFrfs h = Project(avg, omega, min_order, max_order, &tail);
  sample_tail_ = std::max(sample_tail_, tail);
  if (ok) *ok = true;
  return h;
}

}  // namespace ltp
