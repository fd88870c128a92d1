#pragma once
// A rig that is not ltp's simulator, for the identification tests: the scalar periodic system
//   x' = −a x + (1 + β cos θ) u,   y = (1 + γ cos θ) x,
// driven by u = A cos(ωt + φ), with the rotor's phase θ(t) = θ0 + Ω t + ½ α t² (a speed off
// the model's and a ramp), a once-per-period tacho pulse exp(−(θ mod 2π)²/w²), optional white
// noise on the measured input and output. x is integrated by classical RK4 at 1/40 of the
// sampling step from rest 60 time constants before the record (RK4's global error at
// h·max|ν| ≈ 6e-3 is ~1e-9 of the response). At constant speed its partial FRFs are known in
// closed form: with G(ν) = 1/(a + jν), and the lines e^{j(ωt + zθ)},
//   H_0 = G(ω) + βγ/4 (G(ω+Ω) + G(ω−Ω)),  H_{±1} = β/2 G(ω±Ω) + γ/2 G(ω),  H_{±2} = βγ/4 G(ω±Ω).
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "ltp/htf/time_data.h"

namespace ltp::testing {

struct Rig {
  double a = 0.5, beta = 0.6, gamma = 0.4;
  double model_period = 2;  ///< T of the model (s); the rotor turns at speed_factor · 2π/T
  double speed_factor = 1.01;
  double ramp = 0;      ///< relative speed change over the record
  double theta0 = 0.4;  ///< θ at t = 0 (rad)
  double edge = 0.5;    ///< width of the tacho pulse's edges (rad); it is high for 2 rad
  int samples_per_period = 64;
  double periods = 20.3;  ///< record length in model periods (need not be whole)
  /// The output is sampled this many integration steps (dt/40) late: an anti-alias filter's
  /// group delay, a DAQ's skew.
  int output_delay_steps = 0;
  double OutputDelay() const { return output_delay_steps * model_period / samples_per_period / 40; }

  double Speed() const { return speed_factor * 2 * std::numbers::pi / model_period; }
  double Length() const { return periods * model_period; }
  double Theta(double t) const {
    const double alpha = ramp * Speed() / Length();
    return theta0 + Speed() * t + 0.5 * alpha * t * t;
  }
  /// θ where the tacho's rising edge crosses half its height.
  double PulseAngle() const { return edge / 2; }
  /// The tacho's signal at phase θ: rises from 0 at θ = 0 (mod 2π) to 1 at θ = edge, falls
  /// from θ = 2 rad on.
  double Tacho(double theta) const {
    const auto step = [](double x) {
      x = std::clamp(x, 0.0, 1.0);
      return x * x * (3 - 2 * x);
    };
    const double wrapped =
        theta - 2 * std::numbers::pi * std::floor(theta / (2 * std::numbers::pi));
    return step(wrapped / edge) * (1 - step((wrapped - 2) / edge));
  }

  /// One record at excitation f_hz (written to the record as `written_hz`); noise rms as a
  /// fraction of each channel's rms (0: none), from `seed`.
  TimeRecord Record(double f_hz, double written_hz, double input_noise = 0, double output_noise = 0,
                    unsigned seed = 1) const {
    const double w = 2 * std::numbers::pi * f_hz, phi = 0.3;
    return Response([&](double t) { return std::cos(w * t + phi); }, written_hz, input_noise,
                    output_noise, seed);
  }

  /// The record's length as sampled (s): a multisine of frequencies k / RecordLength() repeats
  /// over it.
  double RecordLength() const {
    const double dt = model_period / samples_per_period;
    return static_cast<double>(std::lround(Length() / dt)) * dt;
  }

  /// One broadband record: u = Σ_k cos(2π f_k t + φ_k) (excitation_hz 0), noise as Record's.
  TimeRecord MultisineRecord(const std::vector<double>& f_hz, const std::vector<double>& phases,
                             double input_noise = 0, double output_noise = 0,
                             unsigned seed = 1) const {
    return Response(
        [&](double t) {
          double u = 0;
          for (size_t k = 0; k < f_hz.size(); ++k)
            u += std::cos(2 * std::numbers::pi * f_hz[k] * t + phases[k]);
          return u;
        },
        0, input_noise, output_noise, seed);
  }

  /// The response to u(t) (a linear combination of sines: the closed form holds per line).
  template <class Input>
  TimeRecord Response(const Input& u, double written_hz, double input_noise, double output_noise,
                      unsigned seed) const {
    const double dt = model_period / samples_per_period;
    const long n = std::lround(Length() / dt);
    const auto rhs = [&](double t, double x) {
      return -a * x + (1 + beta * std::cos(Theta(t))) * u(t);
    };
    const int sub = 40;
    const double h = dt / sub;
    double t = -60 / a, x = 0;
    t = std::floor(t / dt) * dt;
    TimeRecord r;
    r.excitation_hz = written_hz;
    r.inputs.resize(n, 1);
    r.outputs.resize(n, 1);
    r.auxiliary.resize(n, 1);
    long k = std::lround(t / dt);
    std::vector<double> history;  // x at every integration step from the start
    const auto output = [&](long s) {
      const long back = output_delay_steps;
      const double td = static_cast<double>(s) * dt - back * h;
      return (1 + gamma * std::cos(Theta(td))) * history[history.size() - 1 - back];
    };
    for (long s = k; s < n; ++s) {
      history.push_back(x);
      if (s >= 0) {
        const double ts = static_cast<double>(s) * dt;
        r.time.push_back(ts);
        r.inputs(s, 0) = u(ts);
        r.outputs(s, 0) = output(s);
        r.auxiliary(s, 0) = Tacho(Theta(ts));
      }
      for (int i = 0; i < sub; ++i) {
        if (i > 0) history.push_back(x);
        const double ti = static_cast<double>(s) * dt + i * h;
        const double k1 = rhs(ti, x), k2 = rhs(ti + h / 2, x + h / 2 * k1);
        const double k3 = rhs(ti + h / 2, x + h / 2 * k2), k4 = rhs(ti + h, x + h * k3);
        x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      }
    }
    std::mt19937_64 gen(seed);
    std::normal_distribution<double> normal;
    const double ui = std::sqrt(r.inputs.squaredNorm() / n),
                 yo = std::sqrt(r.outputs.squaredNorm() / n);
    for (long s = 0; s < n; ++s) {
      r.inputs(s, 0) += input_noise * ui * normal(gen);
      r.outputs(s, 0) += output_noise * yo * normal(gen);
    }
    return r;
  }

  /// The closed-form H_z, z = −2 … 2, at excitation f_hz and rotor speed `speed` (rad/s).
  std::vector<std::complex<double>> PartialFrf(double f_hz, double speed) const {
    const double w = 2 * std::numbers::pi * f_hz;
    const auto G = [&](double nu) { return 1.0 / std::complex<double>(a, nu); };
    const double bg = beta * gamma / 4;
    return {bg * G(w - speed), beta / 2 * G(w - speed) + gamma / 2 * G(w),
            G(w) + bg * (G(w + speed) + G(w - speed)), beta / 2 * G(w + speed) + gamma / 2 * G(w),
            bg * G(w + speed)};
  }
};

}  // namespace ltp::testing
