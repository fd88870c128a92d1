#include "ltp/htf/simulate.h"

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/floquet/floquet.h"

namespace ltp {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;

// x' = A(t) x + B(t) e_input a cos(ωt).
struct ForcedRealRhs {
  const PeriodicSystem& system;
  int input;
  double amplitude, omega;
  mutable Eigen::MatrixXd a, b;
  void operator()(const State& x, State& dxdt, double t) const {
    system.EvalA(t, a);
    system.EvalB(t, b);
    Eigen::Map<const Eigen::VectorXd> xv(x.data(), static_cast<Eigen::Index>(x.size()));
    Eigen::Map<Eigen::VectorXd> dv(dxdt.data(), static_cast<Eigen::Index>(x.size()));
    dv.noalias() = a * xv;
    dv += b.col(input) * (amplitude * std::cos(omega * t));
  }
};

}  // namespace

void SimulateOptions::Validate() const {
  auto fail = [](const std::string& field, const std::string& value,
                 const std::string& constraint) {
    throw InputError("SimulateOptions::" + field + " = " + value +
                     ". Violated constraint: " + constraint);
  };
  if (input < 0) fail("input", std::to_string(input), ">= 0");
  if (frequencies_hz.empty()) fail("frequencies_hz", "{}", "at least one frequency");
  for (double f : frequencies_hz)
    if (!(f > 0) || !std::isfinite(f))
      fail("frequencies_hz", MessageNumber(f, 10), "finite and > 0");
  if (!(amplitude > 0) || !std::isfinite(amplitude))
    fail("amplitude", MessageNumber(amplitude, 10), "finite and > 0");
  if (periods < 1 || periods > 100000) fail("periods", std::to_string(periods), "in 1..100000");
  if (samples_per_period < 4 || samples_per_period > 100000)
    fail("samples_per_period", std::to_string(samples_per_period), "in 4..100000");
  if (!(settle_tol > 0 && settle_tol < 1))
    fail("settle_tol", MessageNumber(settle_tol, 10), "in (0, 1)");
  if (std::isnan(noise_snr_db)) fail("noise_snr_db", "nan", "a number (+inf = no noise)");
  if (!(rel_tol > 0 && rel_tol < 1e-2)) fail("rel_tol", MessageNumber(rel_tol, 10), "in (0, 0.01)");
}

SimulationResult SimulateStepSine(const PeriodicSystem& system, const SimulateOptions& options) {
  options.Validate();
  const int n = system.states(), m = system.inputs(), p = system.outputs();
  if (options.input >= m)
    throw InputError("input " + std::to_string(options.input) + " does not exist (the system has " +
                     std::to_string(m) + " inputs)");
  if (p < 1) throw InputError("the system has no outputs to record");
  const double T = system.period();
  SimulationResult r;
  r.data.period = T;
  r.data.rotor_speed = system.rotor_speed();
  r.data.input_names = system.labels().inputs;
  r.data.output_names = system.labels().outputs;
  // Settling time from the slowest Floquet exponent and the conditioning of the modes.
  FloquetOptions fo;
  fo.estimate_error = false;
  const FloquetResult floquet = AnalyzeFloquet(system, fo);
  if (!floquet.ok) throw InputError("the Floquet analysis that sets the settling time failed");
  r.max_real_exponent = floquet.max_real_exponent;
  if (!(floquet.max_real_exponent < 0))
    throw InputError("the system is not asymptotically stable (max Re λ = " +
                     MessageNumber(floquet.max_real_exponent, 10) +
                     " 1/s): a sine never reaches a steady state to record");
  const double cond =
      std::isfinite(floquet.mode_condition) ? std::max(1.0, floquet.mode_condition) : 1.0;
  const double settle_periods =
      std::ceil(std::log(cond / options.settle_tol) / -floquet.max_real_exponent / T);
  const double total =
      double(options.frequencies_hz.size()) * options.periods * options.samples_per_period;
  if (total > 1e8)
    throw InputError(MessageNumber(total, 10) +
                     " samples in all: more than 10^8 (split the test or sample slower)");
  if (settle_periods > 100000)
    throw InputError("the transient needs " + MessageNumber(settle_periods, 10) +
                     " periods to decay: too lightly damped to simulate");
  r.settle_time = settle_periods * T;
  const double length = options.periods * T;
  const int samples = options.periods * options.samples_per_period;
  double largest_move = 0;
  int moved = 0, merged = 0;
  std::set<long> used;
  for (size_t k = 0; k < options.frequencies_hz.size(); ++k) {
    const double requested = options.frequencies_hz[k];
    if (!(2 * requested * T < options.samples_per_period))  // first: keeps the cycle count small
      throw InputError("excitation " + MessageNumber(requested, 10) +
                       " Hz is above the Nyquist frequency of " +
                       std::to_string(options.samples_per_period) + " samples per period");
    // Whole cycles per record, and not a multiple of fp/2 (2k/P whole), where one record
    // cannot separate H_z from the mirror of another order (identify.h): one grid step aside.
    long cycles = std::max(1L, std::lround(requested * length));
    if ((2 * cycles) % options.periods == 0)
      cycles += (requested * length > static_cast<double>(cycles) || cycles == 1) ? 1 : -1;
    if (!used.insert(cycles).second) {
      ++merged;  // two requested frequencies on one grid frequency: one record
      continue;
    }
    const double f = static_cast<double>(cycles) / length;
    if (std::abs(f - requested) > 1e-12 * requested) {
      ++moved;
      largest_move = std::max(largest_move, std::abs(f - requested));
    }
    if (2 * f * T >= options.samples_per_period)
      throw InputError("excitation " + MessageNumber(f, 10) +
                       " Hz is above the Nyquist frequency of " +
                       std::to_string(options.samples_per_period) + " samples per period");
    ForcedRealRhs rhs{system,     options.input,         options.amplitude,
                      kTwoPi * f, Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, m)};
    State x(static_cast<size_t>(n), 0.0);
    auto stepper =
        odeint::make_controlled(options.rel_tol * options.amplitude * 1e-3, options.rel_tol,
                                odeint::runge_kutta_fehlberg78<State>());
    const double dt0 = T / options.samples_per_period;
    odeint::integrate_adaptive(stepper, std::cref(rhs), x, 0.0, r.settle_time, dt0);
    TimeRecord rec;
    rec.excitation_hz = f;
    rec.time.resize(static_cast<size_t>(samples));
    for (int s = 0; s < samples; ++s)
      rec.time[static_cast<size_t>(s)] = r.settle_time + length * s / samples;
    rec.inputs = Eigen::MatrixXd::Zero(samples, m);
    rec.outputs.resize(samples, p);
    Eigen::MatrixXd c(p, n), d(p, m);
    int s = 0;
    odeint::integrate_times(stepper, std::cref(rhs), x, rec.time.begin(), rec.time.end(), dt0,
                            [&](const State& xs, double t) {
                              system.EvalC(t, c);
                              system.EvalD(t, d);
                              const double u = options.amplitude * std::cos(kTwoPi * f * t);
                              Eigen::Map<const Eigen::VectorXd> xv(xs.data(), n);
                              rec.inputs(s, options.input) = u;
                              rec.outputs.row(s) = (c * xv + d.col(options.input) * u).transpose();
                              ++s;
                            });
    if (!rec.outputs.allFinite())
      throw InputError("the simulation diverged at " + MessageNumber(f, 10) + " Hz");
    if (std::isfinite(options.noise_snr_db)) {
      std::mt19937_64 rng(options.seed + k);
      std::normal_distribution<double> normal;
      for (int j = 0; j < p; ++j) {
        const double rms = std::sqrt(rec.outputs.col(j).squaredNorm() / samples);
        const double sigma = rms * std::pow(10.0, -options.noise_snr_db / 20);
        for (int i = 0; i < samples; ++i) rec.outputs(i, j) += sigma * normal(rng);
      }
    }
    r.data.records.push_back(std::move(rec));
  }
  if (merged)
    r.diagnostics.push_back(
        std::to_string(merged) +
        " requested frequencies fell on the grid frequency of another and were "
        "recorded once: the grid is 1/(periods·T); record more periods for a finer one");
  if (moved)
    r.diagnostics.push_back(
        std::to_string(moved) + " of " + std::to_string(options.frequencies_hz.size()) +
        " excitation frequencies moved to whole cycles of the " + std::to_string(options.periods) +
        "-period record, off the multiples of fp/2 (grid " + MessageNumber(1 / length, 10) +
        " Hz; largest move " + MessageNumber(largest_move, 10) +
        " Hz): each record's own frequency is in the data");
  return r;
}

}  // namespace ltp
