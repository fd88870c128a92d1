#include "ltp/htf/rotor_angle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "angle_interpolation.h"
#include "ltp/core/error.h"

namespace ltp {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// The polynomial through (x[k], y(k)), k = first … last, at t (Lagrange's form).
template <class Values>
double Polynomial(const std::vector<double>& x, const Values& y, long first, long last, double t) {
  double value = 0;
  for (long i = first; i <= last; ++i) {
    double basis = 1;
    for (long j = first; j <= last; ++j)
      if (j != i) basis *= (t - x[j]) / (x[i] - x[j]);
    value += basis * y(i);
  }
  return value;
}

// The time in [t_{i−1}, t_i] where the cubic through the samples i−2 … i+1 (fewer at the
// ends) crosses `level`, by bisection: a smooth edge sampled a few times is timed to O(h⁴)
// where the chord through two samples is O(h²) off; the two samples bracket it either way.
double CrossingTime(const std::vector<double>& time, const Eigen::VectorXd& signal, long i,
                    double level) {
  const long n = static_cast<long>(time.size());
  const long first = std::max(0L, i - 2), last = std::min(n - 1, i + 1);
  const auto value = [&](double t) {
    return Polynomial(
               time, [&](long k) { return signal(k); }, first, last, t) -
           level;
  };
  double lo = time[i - 1], hi = time[i];
  if (value(lo) >= 0 || value(hi) < 0) {  // the cubic overshoots a sharp edge: the chord
    const double f = (level - signal(i - 1)) / (signal(i) - signal(i - 1));
    return lo + f * (hi - lo);
  }
  for (int it = 0; it < 60 && hi - lo > 1e-15 * std::abs(hi); ++it) {
    const double m = 0.5 * (lo + hi);
    (value(m) < 0 ? lo : hi) = m;
  }
  return 0.5 * (lo + hi);
}

void SetSpeeds(const std::vector<double>& time, RotorAngle& r) {
  r.mean_speed = (r.angle.back() - r.angle.front()) / (time.back() - time.front());
  r.min_speed = r.max_speed = r.mean_speed;
}

}  // namespace

namespace internal {

double InterpolateAngle(const std::vector<double>& tau, const std::vector<double>& theta,
                        double t) {
  const long n = static_cast<long>(tau.size());
  const long right = std::upper_bound(tau.begin(), tau.end(), t) - tau.begin();
  const long points = std::min<long>(4, n);
  const long first = std::clamp<long>(right - 2, 0, n - points);
  return Polynomial(
      tau, [&](long k) { return theta[k]; }, first, first + points - 1, t);
}

DelayedClock Delayed(const std::vector<double>& time, const std::vector<double>& theta,
                     bool measured, double T, double delay) {
  if (delay == 0) return {time, theta};
  DelayedClock c;
  for (double t : time) {
    c.time.push_back(t - delay);
    c.theta.push_back(measured ? InterpolateAngle(time, theta, t - delay)
                               : kTwoPi * (t - delay) / T);
  }
  return c;
}

}  // namespace internal

void TachoOptions::Validate() const {
  const OptionCheck check("TachoOptions");
  if (pulses_per_period < 1 || pulses_per_period > 10000)
    check.Fail("pulses_per_period", pulses_per_period, "in 1..10000");
  if (!std::isfinite(pulse_angle)) check.Fail("pulse_angle", pulse_angle, "finite");
}

RotorAngle AngleFromTacho(const std::vector<double>& time, const Eigen::VectorXd& signal,
                          const TachoOptions& options) {
  options.Validate();
  const long n = static_cast<long>(time.size());
  if (signal.size() != n) throw InputError("tacho: the channel and the times differ in length");
  const double low = signal.minCoeff(), high = signal.maxCoeff();
  const double mid = 0.5 * (low + high), arm = low + 0.25 * (high - low);
  RotorAngle r;
  bool armed = n > 0 && signal(0) < mid;  // a record that starts inside a pulse skips it
  for (long i = 1; i < n && high > low; ++i) {
    if (signal(i) < arm) armed = true;
    if (armed && signal(i - 1) < mid && signal(i) >= mid) {
      r.pulse_times.push_back(CrossingTime(time, signal, i, mid));
      armed = false;
    }
  }
  const size_t pulses = r.pulse_times.size();
  if (pulses < 2)
    throw InputError("tacho: " + std::to_string(pulses) +
                     " pulse(s) in the record; the angle needs at least 2 (a record longer than "
                     "a period, a channel that pulses)");
  const std::vector<double>& tau = r.pulse_times;
  for (size_t k = 1; k + 1 < pulses; ++k) {
    const double here = tau[k] - tau[k - 1], next = tau[k + 1] - tau[k];
    const double before = k > 1 ? tau[k - 1] - tau[k - 2] : next;
    if (std::abs(here / before - 1) > 0.25 && std::abs(here / next - 1) > 0.25)
      throw InputError("tacho: the pulse interval ending at t = " + MessageNumber(tau[k], 10) +
                       " s is " + MessageNumber(here, 6) + " s against " +
                       MessageNumber(before, 6) + " and " + MessageNumber(next, 6) +
                       " s around it: a missed or a double pulse");
  }
  const double step = kTwoPi / options.pulses_per_period;
  std::vector<double> theta(pulses);
  for (size_t k = 0; k < pulses; ++k)
    theta[k] = options.pulse_angle + step * static_cast<double>(k);
  for (double t : time) r.angle.push_back(internal::InterpolateAngle(tau, theta, t));
  SetSpeeds(time, r);
  for (size_t k = 1; k < pulses; ++k) {
    const double speed = step / (tau[k] - tau[k - 1]);
    r.min_speed = std::min(r.min_speed, speed);
    r.max_speed = std::max(r.max_speed, speed);
  }
  return r;
}

RotorAngle AngleFromEncoder(const std::vector<double>& time, const Eigen::VectorXd& signal) {
  if (signal.size() != static_cast<long>(time.size()) || time.size() < 2)
    throw InputError("encoder: the channel and the times differ in length");
  RotorAngle r;
  double offset = 0;
  for (long i = 0; i < signal.size(); ++i) {
    if (i > 0) {
      const double jump = signal(i) - signal(i - 1);
      if (jump < -std::numbers::pi) offset += kTwoPi;
      if (jump > std::numbers::pi) offset -= kTwoPi;
    }
    r.angle.push_back(signal(i) + offset);
  }
  SetSpeeds(time, r);
  if (!(std::abs(r.mean_speed) > 0))
    throw InputError("encoder: the angle does not advance over the record");
  for (size_t i = 1; i < time.size(); ++i) {
    const double speed = (r.angle[i] - r.angle[i - 1]) / (time[i] - time[i - 1]);
    r.min_speed = std::min(r.min_speed, speed);
    r.max_speed = std::max(r.max_speed, speed);
  }
  return r;
}

MeasuredSpeeds SetMeasuredAngles(TimeData& data, const AngleChannel& source) {
  MeasuredSpeeds m;
  m.min_speed = std::numeric_limits<double>::infinity();
  m.max_speed = -m.min_speed;
  double turned = 0, duration = 0;
  for (size_t r = 0; r < data.records.size(); ++r) {
    TimeRecord& rec = data.records[r];
    if (source.channel < 0 || source.channel >= rec.auxiliary.cols())
      throw InputError("the angle channel " + std::to_string(source.channel) +
                       " is not in the data (" + std::to_string(rec.auxiliary.cols()) +
                       " auxiliary channels)");
    RotorAngle a;
    try {
      a = source.kind == AngleChannel::Kind::kTacho
              ? AngleFromTacho(rec.time, rec.auxiliary.col(source.channel), source.tacho)
              : AngleFromEncoder(rec.time, rec.auxiliary.col(source.channel));
    } catch (const InputError& e) {
      throw InputError("record " + std::to_string(r + 1) + ": " + e.what());
    }
    rec.angle = std::move(a.angle);
    m.min_speed = std::min(m.min_speed, a.min_speed);
    m.max_speed = std::max(m.max_speed, a.max_speed);
    turned += rec.angle.back() - rec.angle.front();
    duration += rec.time.back() - rec.time.front();
  }
  m.mean_speed = duration > 0 ? turned / duration : 0;
  if (data.period == 0 && m.mean_speed > 0) data.period = kTwoPi / m.mean_speed;
  return m;
}

}  // namespace ltp
