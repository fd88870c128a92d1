#include "ltp/core/periodic_system.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

#include "ltp/core/error.h"
#include "ltp/core/real_fourier_series.h"

namespace ltp {

struct PeriodicSystem::Impl {
  Form form = Form::kFunction;
  double period = 0;
  int n = 0, m = 0, p = 0;
  FourierMatrix fa, fb, fc, fd;  // Fourier form
  // The same in real form: what EvalA…EvalD and the integrators' inner loops read.
  RealFourierSeries a_real, b_real, c_real, d_real;
  Functions fn;               // function form
  std::vector<double> times;  // sampled form
  std::vector<LtiSystem> samples;
  std::vector<double> breakpoints;
  SystemLabels labels;
  std::optional<double> rotor_speed;

  // Index of the sample active at time t (sampled form).
  int SampleIndex(double t) const {
    double tau = std::fmod(t - times.front(), period);
    if (tau < 0) tau += period;
    tau += times.front();
    auto it = std::upper_bound(times.begin(), times.end(), tau);
    int k = static_cast<int>(it - times.begin()) - 1;
    return std::clamp(k, 0, static_cast<int>(times.size()) - 1);
  }
};

namespace {

void CheckPeriod(double period) {
  // A subnormal period (1e-320 s) has Ωp = 2π/T = inf: every exponent's imaginary part and
  // branch would be NaN. Refuse it with the reason.
  if (!std::isfinite(period) || period <= 0 || !std::isnormal(period) ||
      !std::isfinite(2 * std::numbers::pi / period)) {
    std::ostringstream s;
    s << "period = " << period
      << " s: must be a finite, positive, normal number (Ωp = 2π/T must be "
      << "finite too)";
    throw InputError(s.str());
  }
}

void CheckFinite(const FourierMatrix& f, const char* name) {
  for (int w = -f.max_harmonic(); w <= f.max_harmonic(); ++w)
    if (!f[w].allFinite())
      throw InputError(std::string("Fourier coefficient of ") + name + " at harmonic " +
                       std::to_string(w) + " is not finite");
}

}  // namespace

PeriodicSystem PeriodicSystem::FromFourier(double period, FourierMatrix A, FourierMatrix B,
                                           FourierMatrix C, FourierMatrix D) {
  CheckPeriod(period);
  // A default (empty) series has no coefficient to read, not even harmonic 0.
  if (A.rows() == 0 || A.cols() == 0)
    throw InputError("A is missing or empty (" + std::to_string(A.rows()) + "×" +
                     std::to_string(A.cols()) + "): a system needs at least one state");
  auto impl = std::make_shared<Impl>();
  impl->form = Form::kFourier;
  impl->period = period;
  impl->n = A.rows();
  if (A.rows() != A.cols()) throw InputError("A must be square");
  impl->m = B.cols();
  impl->p = C.rows();
  if (B.cols() > 0 && B.rows() != impl->n) throw InputError("B must have as many rows as A");
  if (C.rows() > 0 && C.cols() != impl->n) throw InputError("C must have as many columns as A");
  if (D.rows() == 0 && D.cols() == 0) D = FourierMatrix(impl->p, impl->m, 0);
  if (D.rows() != impl->p || D.cols() != impl->m) throw InputError("D must be outputs × inputs");
  if (B.rows() == 0 && B.cols() == 0) B = FourierMatrix(impl->n, 0, 0);
  if (C.rows() == 0 && C.cols() == 0) C = FourierMatrix(0, impl->n, 0);
  CheckFinite(A, "A");
  CheckFinite(B, "B");
  CheckFinite(C, "C");
  CheckFinite(D, "D");
  impl->a_real = RealFourierSeries(A);
  impl->b_real = RealFourierSeries(B);
  impl->c_real = RealFourierSeries(C);
  impl->d_real = RealFourierSeries(D);
  impl->fa = std::move(A);
  impl->fb = std::move(B);
  impl->fc = std::move(C);
  impl->fd = std::move(D);
  return PeriodicSystem(std::move(impl));
}

PeriodicSystem PeriodicSystem::FromFunctions(double period, int states, int inputs, int outputs,
                                             Functions functions, std::vector<double> breakpoints) {
  CheckPeriod(period);
  if (states < 0 || inputs < 0 || outputs < 0) throw InputError("negative system dimension");
  if (!functions.A) throw InputError("A(t) is missing");
  if (inputs > 0 && !functions.B) throw InputError("B(t) is missing but the system has inputs");
  if (outputs > 0 && !functions.C) throw InputError("C(t) is missing but the system has outputs");
  // Every piece restarts the integrators (tens of evaluations at least): 10^5 jumps per period is
  // beyond any coefficient worth integrating piece by piece (10^6 ran silently for minutes).
  constexpr size_t kMostBreakpoints = 100000;
  if (breakpoints.size() > kMostBreakpoints)
    throw InputError(std::to_string(breakpoints.size()) + " breakpoints: at most " +
                     std::to_string(kMostBreakpoints) +
                     " per period (each piece restarts the integration); a coefficient that "
                     "jumps that often is better given as a smooth or averaged function");
  for (double b : breakpoints)
    if (!std::isfinite(b) || b < 0 || b >= period)
      throw InputError("breakpoint " + std::to_string(b) + " outside [0, T)");
  std::sort(breakpoints.begin(), breakpoints.end());
  breakpoints.erase(std::unique(breakpoints.begin(), breakpoints.end()), breakpoints.end());
  auto impl = std::make_shared<Impl>();
  impl->form = Form::kFunction;
  impl->period = period;
  impl->n = states;
  impl->m = inputs;
  impl->p = outputs;
  impl->fn = std::move(functions);
  impl->breakpoints = std::move(breakpoints);
  return PeriodicSystem(std::move(impl));
}

PeriodicSystem PeriodicSystem::FromSamples(double period, std::vector<double> times,
                                           std::vector<LtiSystem> samples) {
  CheckPeriod(period);
  if (times.empty() || times.size() != samples.size())
    throw InputError("sampled system needs one time per sample and at least one sample");
  for (size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]) || times[k] < 0 || times[k] >= period)
      throw InputError("sample time " + std::to_string(times[k]) + " outside [0, T)");
    if (k > 0 && times[k] <= times[k - 1])
      throw InputError("sample times must be strictly increasing");
  }
  const LtiSystem& s0 = samples.front();
  const auto n = s0.A.rows();
  if (s0.A.cols() != n) throw InputError("sample A must be square");
  const auto m = s0.B.cols(), p = s0.C.rows();
  for (size_t k = 0; k < samples.size(); ++k) {
    LtiSystem& s = samples[k];
    if (s.B.size() == 0) s.B.setZero(n, m);
    if (s.C.size() == 0) s.C.setZero(p, n);
    if (s.D.size() == 0) s.D.setZero(p, m);
    if (s.A.rows() != n || s.A.cols() != n || s.B.rows() != n || s.B.cols() != m ||
        s.C.rows() != p || s.C.cols() != n || s.D.rows() != p || s.D.cols() != m)
      throw InputError("sample " + std::to_string(k) + " has sizes different from sample 0");
    if (!s.A.allFinite() || !s.B.allFinite() || !s.C.allFinite() || !s.D.allFinite())
      throw InputError("sample " + std::to_string(k) + " has a non-finite entry");
  }
  auto impl = std::make_shared<Impl>();
  impl->form = Form::kPiecewiseConstant;
  impl->period = period;
  impl->n = static_cast<int>(n);
  impl->m = static_cast<int>(m);
  impl->p = static_cast<int>(p);
  impl->breakpoints = times;
  impl->times = std::move(times);
  impl->samples = std::move(samples);
  return PeriodicSystem(std::move(impl));
}

int PeriodicSystem::states() const { return impl_->n; }
int PeriodicSystem::inputs() const { return impl_->m; }
int PeriodicSystem::outputs() const { return impl_->p; }
double PeriodicSystem::period() const { return impl_->period; }
double PeriodicSystem::omega() const { return 2 * std::numbers::pi / impl_->period; }
PeriodicSystem::Form PeriodicSystem::form() const { return impl_->form; }

void PeriodicSystem::EvalA(double t, Eigen::Ref<Eigen::MatrixXd> out) const {
  switch (impl_->form) {
    case Form::kFourier:
      impl_->a_real.Evaluate(t, omega(), out);
      break;
    case Form::kFunction:
      impl_->fn.A(t, out);
      break;
    case Form::kPiecewiseConstant:
      out = impl_->samples[impl_->SampleIndex(t)].A;
      break;
  }
}

void PeriodicSystem::EvalB(double t, Eigen::Ref<Eigen::MatrixXd> out) const {
  if (impl_->m == 0) return;
  switch (impl_->form) {
    case Form::kFourier:
      impl_->b_real.Evaluate(t, omega(), out);
      break;
    case Form::kFunction:
      impl_->fn.B(t, out);
      break;
    case Form::kPiecewiseConstant:
      out = impl_->samples[impl_->SampleIndex(t)].B;
      break;
  }
}

void PeriodicSystem::EvalC(double t, Eigen::Ref<Eigen::MatrixXd> out) const {
  if (impl_->p == 0) return;
  switch (impl_->form) {
    case Form::kFourier:
      impl_->c_real.Evaluate(t, omega(), out);
      break;
    case Form::kFunction:
      impl_->fn.C(t, out);
      break;
    case Form::kPiecewiseConstant:
      out = impl_->samples[impl_->SampleIndex(t)].C;
      break;
  }
}

void PeriodicSystem::EvalD(double t, Eigen::Ref<Eigen::MatrixXd> out) const {
  if (impl_->p == 0 || impl_->m == 0) return;
  switch (impl_->form) {
    case Form::kFourier:
      impl_->d_real.Evaluate(t, omega(), out);
      break;
    case Form::kFunction:
      if (impl_->fn.D) {
        impl_->fn.D(t, out);
      } else {
        out.setZero();
      }
      break;
    case Form::kPiecewiseConstant:
      out = impl_->samples[impl_->SampleIndex(t)].D;
      break;
  }
}

Eigen::MatrixXd PeriodicSystem::A(double t) const {
  Eigen::MatrixXd out(impl_->n, impl_->n);
  EvalA(t, out);
  return out;
}
Eigen::MatrixXd PeriodicSystem::B(double t) const {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(impl_->n, impl_->m);
  EvalB(t, out);
  return out;
}
Eigen::MatrixXd PeriodicSystem::C(double t) const {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(impl_->p, impl_->n);
  EvalC(t, out);
  return out;
}
Eigen::MatrixXd PeriodicSystem::D(double t) const {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(impl_->p, impl_->m);
  EvalD(t, out);
  return out;
}

LtiSystem PeriodicSystem::Snapshot(double t) const {
  if (!std::isfinite(t)) throw InputError("snapshot time must be a finite number of seconds");
  t = std::fmod(t, period());  // exact: the system is T-periodic, and A(1e308) would be noise
  return {A(t), B(t), C(t), D(t)};
}

LtiSystem PeriodicSystem::SnapshotAtAngle(double angle_rad) const {
  if (!impl_->rotor_speed || *impl_->rotor_speed == 0)
    throw InputError("this system has no rotor speed: give a snapshot time instead of an angle");
  if (!std::isfinite(angle_rad)) throw InputError("snapshot angle must be a finite number");
  // One revolution is 2π whatever the angle's size; reducing first keeps t finite.
  return Snapshot(std::fmod(angle_rad, 2 * std::numbers::pi) / *impl_->rotor_speed);
}

const std::vector<double>& PeriodicSystem::breakpoints() const { return impl_->breakpoints; }
const double* PeriodicSystem::RealSeriesA(int* harmonics) const {
  if (impl_->form != Form::kFourier) return nullptr;
  if (harmonics) *harmonics = impl_->a_real.harmonics();
  return impl_->a_real.data();
}

const FourierMatrix* PeriodicSystem::fourier_A() const {
  return impl_->form == Form::kFourier ? &impl_->fa : nullptr;
}
const FourierMatrix* PeriodicSystem::fourier_B() const {
  return impl_->form == Form::kFourier ? &impl_->fb : nullptr;
}
const FourierMatrix* PeriodicSystem::fourier_C() const {
  return impl_->form == Form::kFourier ? &impl_->fc : nullptr;
}
const FourierMatrix* PeriodicSystem::fourier_D() const {
  return impl_->form == Form::kFourier ? &impl_->fd : nullptr;
}
const std::vector<double>& PeriodicSystem::sample_times() const { return impl_->times; }
const std::vector<LtiSystem>& PeriodicSystem::samples() const { return impl_->samples; }
const SystemLabels& PeriodicSystem::labels() const { return impl_->labels; }

void PeriodicSystem::CheckLabels(const SystemLabels& labels) const {
  auto check = [](const std::vector<std::string>& v, int n, const char* what) {
    if (!v.empty() && static_cast<int>(v.size()) != n)
      throw InputError(std::string("expected ") + std::to_string(n) + " " + what + " names, got " +
                       std::to_string(v.size()));
  };
  check(labels.states, impl_->n, "state");
  check(labels.inputs, impl_->m, "input");
  check(labels.outputs, impl_->p, "output");
  if (labels.blades < 0) throw InputError("blade count " + std::to_string(labels.blades) + " < 0");
  for (int i : labels.blade_states)
    if (i < 0 || i >= impl_->n)
      throw InputError("blade state index " + std::to_string(i) + " out of range");
}

PeriodicSystem PeriodicSystem::WithLabels(SystemLabels labels) const& {
  CheckLabels(labels);
  auto impl = std::make_shared<Impl>(*impl_);
  impl->labels = std::move(labels);
  return PeriodicSystem(std::move(impl));
}

PeriodicSystem PeriodicSystem::WithLabels(SystemLabels labels) && {
  if (impl_.use_count() != 1) return std::as_const(*this).WithLabels(std::move(labels));
  CheckLabels(labels);
  // Every Impl is made by make_shared<Impl> (never const), so it may be written through.
  auto impl = std::const_pointer_cast<Impl>(std::move(impl_));
  impl->labels = std::move(labels);
  return PeriodicSystem(std::move(impl));
}

PeriodicSystem PeriodicSystem::WithStateScaling(const Eigen::VectorXd& scale) const {
  const int n = impl_->n;
  if (scale.size() != n || !scale.allFinite() || !(scale.array() > 0).all())
    throw InputError("state scaling: " + std::to_string(n) +
                     " finite positive scales needed, one per state");
  const Eigen::VectorXd inverse = scale.cwiseInverse();
  // M ↦ S⁻¹ M S, S⁻¹ M or M S, in place; real or complex.
  auto rows = [&](auto& m) { m = inverse.asDiagonal() * m; };
  auto cols = [&](auto& m) { m = m * scale.asDiagonal(); };
  PeriodicSystem out = *this;
  switch (impl_->form) {
    case Form::kFourier: {
      FourierMatrix a = impl_->fa, b = impl_->fb, c = impl_->fc;
      for (int w = -a.max_harmonic(); w <= a.max_harmonic(); ++w) {
        Eigen::MatrixXcd m = a[w];
        rows(m);
        cols(m);
        a[w] = m;
      }
      for (int w = -b.max_harmonic(); w <= b.max_harmonic(); ++w) {
        Eigen::MatrixXcd m = b[w];
        rows(m);
        b[w] = m;
      }
      for (int w = -c.max_harmonic(); w <= c.max_harmonic(); ++w) {
        Eigen::MatrixXcd m = c[w];
        cols(m);
        c[w] = m;
      }
      out = FromFourier(impl_->period, std::move(a), std::move(b), std::move(c), impl_->fd);
      break;
    }
    case Form::kPiecewiseConstant: {
      std::vector<LtiSystem> samples = impl_->samples;
      for (LtiSystem& s : samples) {
        rows(s.A);
        cols(s.A);
        rows(s.B);
        cols(s.C);
      }
      out = FromSamples(impl_->period, impl_->times, std::move(samples));
      break;
    }
    case Form::kFunction: {
      Functions f = impl_->fn;
      const Functions original = impl_->fn;
      f.A = [original, scale, inverse](double t, Eigen::Ref<Eigen::MatrixXd> m) {
        original.A(t, m);
        m = inverse.asDiagonal() * m * scale.asDiagonal();
      };
      if (original.B)
        f.B = [original, inverse](double t, Eigen::Ref<Eigen::MatrixXd> m) {
          original.B(t, m);
          m = inverse.asDiagonal() * m;
        };
      if (original.C)
        f.C = [original, scale](double t, Eigen::Ref<Eigen::MatrixXd> m) {
          original.C(t, m);
          m = m * scale.asDiagonal();
        };
      out = FromFunctions(impl_->period, n, impl_->m, impl_->p, std::move(f), impl_->breakpoints);
      break;
    }
  }
  auto impl = std::const_pointer_cast<Impl>(std::move(out.impl_));
  impl->labels = impl_->labels;
  impl->rotor_speed = impl_->rotor_speed;
  return PeriodicSystem(std::move(impl));
}

std::optional<double> PeriodicSystem::rotor_speed() const { return impl_->rotor_speed; }

PeriodicSystem PeriodicSystem::WithRotorSpeed(double rad_per_s) const {
  if (!std::isfinite(rad_per_s)) throw InputError("rotor speed must be finite");
  auto impl = std::make_shared<Impl>(*impl_);
  impl->rotor_speed = rad_per_s;
  return PeriodicSystem(std::move(impl));
}

}  // namespace ltp
