#include "ltp/htf/simulate.h"

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <set>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/floquet/floquet.h"
#include "ltp/htf/pfrf.h"

namespace ltp {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;

// u(t) = Σ_k a_k cos(c_k ω0 t + φ_k) with whole multiples c_k of the record's base frequency
// ω0 = 2π/L (every excitation lies on the record's grid) = Re Σ_k P_k z^{c_k}, z = e^{jω0 t}.
// A dense band of lines is one polynomial z^{c_min} Σ_c P_c z^{c − c_min} by Horner's rule
// (backward stable on |z| = 1; ~10× cheaper than a cosine per line for hundreds of lines); a
// few lines spread far apart (a step-sine) keep one phasor each.
class Excitation {
 public:
  explicit Excitation(double omega0) : omega0_(omega0) {}
  void Add(long cycles, double amplitude, double phase) {
    lines_.emplace_back(cycles, std::polar(amplitude, phase));
  }
  /// After the last Add: chooses the evaluation.
  void Finish() {
    if (lines_.empty()) return;
    long lo = lines_.front().first, hi = lo;
    for (const auto& [c, p] : lines_) {
      lo = std::min(lo, c);
      hi = std::max(hi, c);
    }
    if (hi - lo + 1 > 8 * static_cast<long>(lines_.size()) + 8) return;  // sparse: per line
    lowest_ = lo;
    dense_.assign(static_cast<size_t>(hi - lo + 1), 0.0);
    for (const auto& [c, p] : lines_) dense_[static_cast<size_t>(c - lo)] += p;
  }
  double operator()(double t) const {
    if (dense_.empty()) {
      double u = 0;
      for (const auto& [c, p] : lines_)
        u += (p * std::polar(1.0, omega0_ * static_cast<double>(c) * t)).real();
      return u;
    }
    const std::complex<double> z = std::polar(1.0, omega0_ * t);
    std::complex<double> sum = 0;
    for (auto c = dense_.rbegin(); c != dense_.rend(); ++c) sum = sum * z + *c;
    return (sum * std::polar(1.0, omega0_ * static_cast<double>(lowest_) * t)).real();
  }

 private:
  double omega0_;
  std::vector<std::pair<long, std::complex<double>>> lines_;
  std::vector<std::complex<double>> dense_;  // P_c for c = lowest_ … (empty: sparse)
  long lowest_ = 0;
};

// The system's phase in its own time (θ/Ωp) as a rig's rotor turns it: (1 + offset)·t, and from
// `start` (the record) on a further ½·rate·(t − start)² — the speed rising linearly.
struct RigPhase {
  double factor = 1, rate = 0, start = 0;
  double operator()(double t) const {
    const double s = std::max(0.0, t - start);
    return factor * t + 0.5 * rate * s * s;
  }
};

// A once-per-period tacho at phase τ (model time): high for a quarter of the period, its
// smoothstep edges `edge` wide (a fraction of the period) centred on τ = 0 mod T.
double TachoSignal(double tau, double T, double edge) {
  const auto step = [](double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3 - 2 * x);
  };
  const double x = tau / T - std::floor(tau / T + 0.5);  // in [−½, ½)
  return step(x / edge + 0.5) * (1 - step((x - 0.25) / edge + 0.5));
}

struct ForcedRealRhs {
  const PeriodicSystem& system;
  int input;
  const Excitation& u;
  RigPhase phase;
  double cubic_stiffness;
  mutable Eigen::MatrixXd a, b, c;
  void operator()(const State& x, State& dxdt, double t) const {
    system.EvalA(phase(t), a);
    system.EvalB(phase(t), b);
    Eigen::Map<const Eigen::VectorXd> xv(x.data(), static_cast<Eigen::Index>(x.size()));
    Eigen::Map<Eigen::VectorXd> dv(dxdt.data(), static_cast<Eigen::Index>(x.size()));
    dv.noalias() = a * xv;
    double force = u(t);
    if (cubic_stiffness != 0) {
      system.EvalC(phase(t), c);
      const double y0 = c.row(0).dot(xv);
      force -= cubic_stiffness * y0 * y0 * y0;
    }
    dv += b.col(input) * force;
  }
};

// What every record shares: the settling time, the grid of the record's frequencies.
struct RecordPlan {
  double settle_time = 0, length = 0;
  int samples = 0;
};

// Checks the system and the cost, and sets the settling time from the slowest Floquet
// exponent and the conditioning of the modes.
RecordPlan PlanRecords(const PeriodicSystem& system, const SimulateOptions& options, double records,
                       SimulationResult& r) {
  const int m = system.inputs(), p = system.outputs();
  if (options.input >= m)
    throw InputError("input " + std::to_string(options.input) + " does not exist (the system has " +
                     std::to_string(m) + " inputs)");
  if (p < 1) throw InputError("the system has no outputs to record");
  const double T = system.period();
  r.data.period = T;
  r.data.rotor_speed = system.rotor_speed();
  r.data.input_names = system.labels().inputs;
  r.data.output_names = system.labels().outputs;
  if (options.tacho) r.data.auxiliary_names = {"tacho"};
  FloquetOptions fo;
  fo.estimate_error = false;
  const FloquetResult floquet = AnalyzeFloquet(system, fo);
  if (!floquet.ok) throw InputError("the Floquet analysis that sets the settling time failed");
  r.max_real_exponent = floquet.max_real_exponent;
  if (!(floquet.max_real_exponent < 0))
    throw InputError("the system is not asymptotically stable (max Re λ = " +
                     MessageNumber(floquet.max_real_exponent, 10) +
                     " 1/s): a sine never reaches a steady state to record");
  const double settle_periods =
      std::ceil(ForcedResponseSolver::SettlingTime(floquet, options.settle_tol) / T);
  const double total = records * options.periods * options.samples_per_period;
  if (total > 1e8)
    throw InputError(MessageNumber(total, 10) +
                     " samples in all: more than 10^8 (split the test or sample slower)");
  if (settle_periods > options.max_settle_periods)
    throw InputError("the transient needs " + MessageNumber(settle_periods, 10) +
                     " periods to decay, more than SimulateOptions::max_settle_periods = " +
                     MessageNumber(options.max_settle_periods, 10) +
                     " (ltp: --max-transient PERIODS): too lightly damped to simulate");
  r.settle_time = settle_periods * T;
  return {r.settle_time, options.periods * T, options.periods * options.samples_per_period};
}

// The requested frequencies moved to whole cycles of the record and off the multiples of fp/2
// (2k/P whole), where one record cannot separate H_z from the mirror of another order
// (identify.h): one grid step aside. Two on one grid frequency are merged; both are reported.
std::vector<double> GridFrequencies(const SimulateOptions& options, double T, SimulationResult& r) {
  const double length = options.periods * T;
  double largest_move = 0;
  int moved = 0, merged = 0;
  std::set<long> used;
  std::vector<double> grid;
  for (double requested : options.frequencies_hz) {
    if (!(2 * requested * T < options.samples_per_period))  // first: keeps the cycle count small
      throw InputError("excitation " + MessageNumber(requested, 10) +
                       " Hz is above the Nyquist frequency of " +
                       std::to_string(options.samples_per_period) + " samples per period");
    long cycles = std::max(1L, std::lround(requested * length));
    if ((2 * cycles) % options.periods == 0)
      cycles += (requested * length > static_cast<double>(cycles) || cycles == 1) ? 1 : -1;
    if (!used.insert(cycles).second) {
      ++merged;
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
    grid.push_back(f);
  }
  if (merged)
    r.diagnostics.push_back(
        {DiagnosticCode::kFrequenciesMerged, Severity::kNote,
         std::to_string(merged) +
             " requested frequencies fell on the grid frequency of another and were "
             "recorded once: the grid is 1/(periods·T); record more periods for a finer one"});
  if (moved)
    r.diagnostics.push_back(
        {DiagnosticCode::kFrequencyMovedToGrid, Severity::kNote,
         std::to_string(moved) + " of " + std::to_string(options.frequencies_hz.size()) +
             " excitation frequencies moved to whole cycles of the " +
             std::to_string(options.periods) + "-period record, off the multiples of fp/2 (grid " +
             MessageNumber(1 / length, 10) + " Hz; largest move " +
             MessageNumber(largest_move, 10) + " Hz): each record's own frequency is in the data"});
  return grid;
}

// One record: from rest through the transient, then the samples, then the output noise
// (seeded with `seed`).
TimeRecord SimulateRecord(const PeriodicSystem& system, const SimulateOptions& options,
                          const RecordPlan& plan, const Excitation& u, std::uint64_t seed) {
  const int n = system.states(), m = system.inputs(), p = system.outputs();
  const double T = system.period();
  const RigPhase phase{1 + options.speed_offset,
                       (1 + options.speed_offset) * options.speed_ramp / plan.length,
                       plan.settle_time};
  ForcedRealRhs rhs{system,
                    options.input,
                    u,
                    phase,
                    options.cubic_stiffness,
                    Eigen::MatrixXd(n, n),
                    Eigen::MatrixXd(n, m),
                    Eigen::MatrixXd(p, n)};
  const double dt0 = T / options.samples_per_period;
  // The absolute tolerance follows the size of the states, which depends on the system's
  // units (tower-rotor: displacements of 1e-6 m per newton): a pilot over the first period
  // from rest, at a loose tolerance, measures it.
  State x(static_cast<size_t>(n), 0.0);
  double scale = 0;
  {
    auto pilot = odeint::make_controlled(1e-30, 1e-6, odeint::runge_kutta_fehlberg78<State>());
    odeint::integrate_adaptive(pilot, std::cref(rhs), x, 0.0, std::min(T, plan.settle_time), dt0,
                               [&](const State& xs, double) {
                                 for (double v : xs) scale = std::max(scale, std::abs(v));
                               });
    std::fill(x.begin(), x.end(), 0.0);
  }
  if (!(scale > 0) || !std::isfinite(scale)) scale = options.amplitude;
  auto stepper = odeint::make_controlled(options.rel_tol * scale * 1e-3, options.rel_tol,
                                         odeint::runge_kutta_fehlberg78<State>());
  odeint::integrate_adaptive(stepper, std::cref(rhs), x, 0.0, plan.settle_time, dt0);
  TimeRecord rec;
  rec.time.resize(static_cast<size_t>(plan.samples));
  for (int s = 0; s < plan.samples; ++s)
    rec.time[static_cast<size_t>(s)] = plan.settle_time + plan.length * s / plan.samples;
  rec.inputs = Eigen::MatrixXd::Zero(plan.samples, m);
  rec.outputs.resize(plan.samples, p);
  if (options.tacho) rec.auxiliary.resize(plan.samples, 1);
  // Edges eight samples wide: the four samples around mid-level lie on one cubic piece, which
  // AngleFromTacho's cubic then times exactly.
  const double edge = std::min(0.1, 8.0 / options.samples_per_period);
  Eigen::MatrixXd c(p, n), d(p, m);
  int s = 0;
  odeint::integrate_times(stepper, std::cref(rhs), x, rec.time.begin(), rec.time.end(), dt0,
                          [&](const State& xs, double t) {
                            const double tau = phase(t);
                            system.EvalC(tau, c);
                            system.EvalD(tau, d);
                            const double ut = u(t);
                            Eigen::Map<const Eigen::VectorXd> xv(xs.data(), n);
                            rec.inputs(s, options.input) = ut;
                            rec.outputs.row(s) = (c * xv + d.col(options.input) * ut).transpose();
                            if (options.tacho) rec.auxiliary(s, 0) = TachoSignal(tau, T, edge);
                            ++s;
                          });
  if (!rec.outputs.allFinite()) throw InputError("the simulation diverged");
  // Each record's noise from its own stream (RecordSeed): seeds K and K + 1 share nothing
  // (seed + record did: 26 of 27 records alike).
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  const auto add_noise = [&](Eigen::MatrixXd& channels, int column, double snr_db) {
    if (!std::isfinite(snr_db)) return;
    const double rms = std::sqrt(channels.col(column).squaredNorm() / plan.samples);
    const double sigma = rms * std::pow(10.0, -snr_db / 20);
    for (int i = 0; i < plan.samples; ++i) channels(i, column) += sigma * normal(rng);
  };
  for (int j = 0; j < p; ++j) add_noise(rec.outputs, j, options.noise_snr_db);
  add_noise(rec.inputs, options.input, options.input_noise_snr_db);
  return rec;
}

// The noise stream of record k: (seed, k) hashed, not seed + k.
std::uint64_t RecordSeed(const SimulateOptions& options, size_t k) {
  std::uint64_t z = options.seed + 0x9E3779B97F4A7C15ULL * (static_cast<std::uint64_t>(k) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;  // SplitMix64's finaliser
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace

void SimulateOptions::Validate() const {
  const OptionCheck check("SimulateOptions");
  if (input < 0) check.Fail("input", input, ">= 0");
  if (frequencies_hz.empty()) check.Fail("frequencies_hz", "{}", "at least one frequency");
  for (double f : frequencies_hz)
    if (!(f > 0) || !std::isfinite(f)) check.Fail("frequencies_hz", f, "finite and > 0");
  if (!(amplitude > 0) || !std::isfinite(amplitude))
    check.Fail("amplitude", amplitude, "finite and > 0");
  if (periods < 1 || periods > 100000) check.Fail("periods", periods, "in 1..100000");
  if (samples_per_period < 4 || samples_per_period > 100000)
    check.Fail("samples_per_period", samples_per_period, "in 4..100000");
  if (!(settle_tol > 0 && settle_tol < 1)) check.Fail("settle_tol", settle_tol, "in (0, 1)");
  if (!(max_settle_periods >= 1)) check.Fail("max_settle_periods", max_settle_periods, ">= 1");
  if (std::isnan(noise_snr_db))
    check.Fail("noise_snr_db", noise_snr_db, "a number (+inf = no noise)");
  if (std::isnan(input_noise_snr_db))
    check.Fail("input_noise_snr_db", input_noise_snr_db, "a number (+inf = no noise)");
  if (!(std::abs(speed_offset) <= 0.5))
    check.Fail("speed_offset", speed_offset, "within ±0.5 (relative)");
  if (!(std::abs(speed_ramp) <= 0.5))
    check.Fail("speed_ramp", speed_ramp, "within ±0.5 (relative, over a record)");
  if (!(rel_tol > 0 && rel_tol < 1e-2)) check.Fail("rel_tol", rel_tol, "in (0, 0.01)");
  if (records < 1 || records > 10000) check.Fail("records", records, "in 1..10000");
  if (!(cubic_stiffness >= 0) || !std::isfinite(cubic_stiffness))  // a softening spring escapes
    check.Fail("cubic_stiffness", cubic_stiffness, "finite and >= 0 (hardening)");
}

SimulationResult SimulateStepSine(const PeriodicSystem& system, const SimulateOptions& options) {
  options.Validate();
  SimulationResult r;
  const RecordPlan plan =
      PlanRecords(system, options, static_cast<double>(options.frequencies_hz.size()), r);
  const std::vector<double> grid = GridFrequencies(options, system.period(), r);
  for (size_t k = 0; k < grid.size(); ++k) {
    Excitation u(kTwoPi / plan.length);
    u.Add(std::lround(grid[k] * plan.length), options.amplitude, 0.0);
    u.Finish();
    try {
      r.data.records.push_back(SimulateRecord(system, options, plan, u, RecordSeed(options, k)));
    } catch (const InputError& e) {
      throw InputError(std::string(e.what()) + " at " + MessageNumber(grid[k], 10) + " Hz");
    }
    r.data.records.back().excitation_hz = grid[k];
  }
  return r;
}

SimulationResult SimulateMultisine(const PeriodicSystem& system, const SimulateOptions& options) {
  options.Validate();
  SimulationResult r;
  const RecordPlan plan = PlanRecords(system, options, options.records, r);
  const std::vector<double> grid = GridFrequencies(options, system.period(), r);
  const double amplitude = options.amplitude / std::sqrt(static_cast<double>(grid.size()));
  for (int k = 0; k < options.records; ++k) {
    std::mt19937_64 rng(options.seed + 1000003 * static_cast<std::uint64_t>(k + 1));
    std::uniform_real_distribution<double> phase(-std::numbers::pi, std::numbers::pi);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    Excitation u(kTwoPi / plan.length);
    for (double f : grid) {
      // Rayleigh with E a² = amplitude²: the lines of a periodic Gaussian noise.
      const double a = options.random_amplitudes
                           ? amplitude * std::sqrt(-std::log(1.0 - uniform(rng)))
                           : amplitude;
      u.Add(std::lround(f * plan.length), a, phase(rng));
    }
    u.Finish();
    r.data.records.push_back(
        SimulateRecord(system, options, plan, u, RecordSeed(options, static_cast<size_t>(k))));
    r.data.records.back().excitation_hz = 0;  // broadband
  }
  return r;
}

}  // namespace ltp
