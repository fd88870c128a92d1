// Step-sine identification of partial FRFs from simulated time data (paper eq. 47) against the
// model's own routes (ComputePartialFrf, modal checked by htf to ~1e-12), and the honesty of
// its 95 % bounds under noise (coverage over many seeds).
#include "ltp/htf/identify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "ltp/core/error.h"
#include "ltp/core/periodic_system.h"
#include "ltp/htf/pfrf.h"
#include "ltp/htf/rotor_angle.h"
#include "ltp/htf/simulate.h"
#include "ltp/models/scene.h"

namespace ltp {
namespace {

// a = 2, q = 0.3: between the first two instability tongues (stable), natural frequency ≈ √2 rad/s.
PeriodicSystem Mathieu() {
  return LoadScene("mathieu").Build({{"a", "2"}, {"c", "0.2"}, {"q", "0.3"}});
}

// The model's H_z at the identified frequencies (after ltp simulate moved them to the grid):
// the routes of ComputePartialFrf (modal checked by htf).
std::vector<std::vector<std::complex<double>>> ModelAt(const PeriodicSystem& system,
                                                       const IdentifyResult& id) {
  PfrfOptions o;
  for (const IdentifiedFrequency& f : id.frequencies) o.frequencies_hz.push_back(f.excitation_hz);
  o.min_order = id.min_order;
  o.max_order = id.max_order;
  const PfrfResult r = ComputePartialFrf(system, o);
  EXPECT_TRUE(r.ok);
  return r.values;
}

TEST(IdentifyStepSine, NoiseFreeEstimatesEqualTheModel) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  s.frequencies_hz = {0.05, 0.13, 0.21,
                      0.4};  // around the resonance near 1/(2π) Hz and its sidebands
  s.periods = 16;
  s.samples_per_period = 64;
  const SimulationResult sim = SimulateStepSine(system, s);
  IdentifyOptions o;
  o.min_order = -2;
  o.max_order = 2;
  const IdentifyResult id = IdentifyStepSine(sim.data, o);
  const auto model = ModelAt(system, id);
  ASSERT_EQ(id.frequencies.size(), 4u);
  for (size_t f = 0; f < 4; ++f) {
    double scale = 0;
    for (const auto& h : model[f]) scale = std::max(scale, std::abs(h));
    for (size_t z = 0; z < 5; ++z) {
      EXPECT_LT(std::abs(id.frequencies[f].h[z] - model[f][z]), 1e-6 * scale)
          << "f = " << id.frequencies[f].excitation_hz << ", z = " << int(z) - 2;
      EXPECT_LT(id.frequencies[f].bound[z],
                1e-6 * scale);  // noise-free: the bins off the lines are empty
    }
  }
}

TEST(IdentifyStepSine, StatesOfAnyScaleAreIntegratedToTheRelativeTolerance) {
  // The damped Mathieu oscillator with its input scaled by 1e-9 (units in which the states are
  // nanometres): the simulation's absolute tolerance must follow the states, or the estimates
  // carry an integration error of 1e-4 of |H|. Reference: the model's routes, as above.
  const PeriodicSystem base = Mathieu();
  const PeriodicSystem system = PeriodicSystem::FromFourier(
      base.period(), *base.fourier_A(),
      FourierMatrix::Constant((Eigen::MatrixXd(2, 1) << 0, 1e-9).finished()),
      FourierMatrix::Constant((Eigen::MatrixXd(1, 2) << 1, 0).finished()));
  SimulateOptions s;
  s.frequencies_hz = {0.13, 0.4};
  s.periods = 16;
  const SimulationResult sim = SimulateStepSine(system, s);
  IdentifyOptions o;
  o.min_order = -1;
  o.max_order = 1;
  const IdentifyResult id = IdentifyStepSine(sim.data, o);
  const auto model = ModelAt(system, id);
  for (size_t f = 0; f < id.frequencies.size(); ++f) {
    double scale = 0;
    for (const auto& h : model[f]) scale = std::max(scale, std::abs(h));
    for (size_t z = 0; z < 3; ++z)
      EXPECT_LT(std::abs(id.frequencies[f].h[z] - model[f][z]), 1e-8 * scale)
          << "f = " << id.frequencies[f].excitation_hz << ", z = " << int(z) - 1;
  }
}

TEST(IdentifyStepSine, NinetyFivePercentBoundsCoverTheTruthUnderNoise) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  s.frequencies_hz = {0.13, 0.22};  // on the 8-period grid: 3 and 6 cycles, not multiples of fp/2
  s.periods = 8;
  s.samples_per_period = 32;
  s.noise_snr_db = 20;
  IdentifyOptions o;
  o.min_order = -1;
  o.max_order = 1;
  std::vector<std::vector<std::complex<double>>> truth;
  int inside = 0, total = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    s.seed = 1000 * seed;
    const SimulationResult sim = SimulateStepSine(system, s);
    const IdentifyResult id = IdentifyStepSine(sim.data, o);
    if (truth.empty()) truth = ModelAt(system, id);
    for (size_t f = 0; f < id.frequencies.size(); ++f)
      for (size_t z = 0; z < 3; ++z) {
        ASSERT_TRUE(id.frequencies[f].separable);
        ++total;
        inside += std::abs(id.frequencies[f].h[z] - truth[f][z]) <= id.frequencies[f].bound[z];
      }
  }
  // 360 trials: the binomial standard deviation of the coverage is 1.1 %.
  const double coverage = double(inside) / total;
  EXPECT_GT(coverage, 0.91) << inside << " of " << total;
  EXPECT_LT(coverage, 0.99) << inside << " of " << total;
}

TEST(IdentifyStepSine, BadDataIsRefusedWithTheReason) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  s.frequencies_hz = {0.13};
  s.periods = 4;
  s.samples_per_period = 16;
  SimulationResult sim = SimulateStepSine(system, s);
  IdentifyOptions o;
  TimeData nan = sim.data;
  nan.records[0].outputs(3, 0) = std::nan("");
  EXPECT_THROW(IdentifyStepSine(nan, o), InputError);
  TimeData backwards = sim.data;
  backwards.records[0].time[5] = backwards.records[0].time[4];
  EXPECT_THROW(IdentifyStepSine(backwards, o), InputError);
  TimeData short_record = sim.data;  // less than one period: the orders are not separable
  short_record.records[0].time.resize(10);
  short_record.records[0].inputs.conservativeResize(10, Eigen::NoChange);
  short_record.records[0].outputs.conservativeResize(10, Eigen::NoChange);
  EXPECT_THROW(IdentifyStepSine(short_record, o), InputError);
  TimeData epoch = sim.data;  // times as epoch-like seconds: ωt keeps no digit of its phase
  for (double& t : epoch.records[0].time) t += 1e13;
  try {
    IdentifyStepSine(epoch, o);
    ADD_FAILURE() << "times of 1e13 s were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no correct digit"), std::string::npos) << e.what();
  }
  TimeData gap = sim.data;  // broadband needs the uniform grid; it names the right sample
  gap.records[0].excitation_hz = 0;
  gap.records[0].time[40] += 0.01;
  try {
    IdentifyBroadband(gap, o);
    ADD_FAILURE() << "a jittered sample was accepted by the broadband method";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unequal sampling at sample 41"), std::string::npos)
        << e.what();
  }
  o.max_order = 40;  // above Nyquist at 16 samples per period
  EXPECT_THROW(IdentifyStepSine(sim.data, o), InputError);
  SimulateOptions unstable = s;
  EXPECT_THROW(SimulateStepSine(LoadScene("mathieu").Build({{"c", "0"}, {"q", "0.3"}, {"a", "1"}}),
                                unstable),
               InputError);  // undamped: no steady state
}

// A record cut off mid-period (rig records need not be whole periods): the least-squares lines
// still give the model's values, noise-free.
TEST(IdentifyStepSine, ARecordOfPartialPeriodsStillGivesTheModel) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  s.frequencies_hz = {0.13};
  s.periods = 16;
  SimulationResult sim = SimulateStepSine(system, s);
  TimeRecord& rec = sim.data.records[0];
  const Eigen::Index keep = rec.inputs.rows() - 23;
  rec.time.resize(static_cast<size_t>(keep));
  rec.inputs.conservativeResize(keep, Eigen::NoChange);
  rec.outputs.conservativeResize(keep, Eigen::NoChange);
  IdentifyOptions o;
  const IdentifyResult id = IdentifyStepSine(sim.data, o);
  const auto model = ModelAt(system, id);
  double scale = 0;
  for (const auto& h : model[0]) scale = std::max(scale, std::abs(h));
  for (size_t z = 0; z < 5; ++z)
    EXPECT_LT(std::abs(id.frequencies[0].h[z] - model[0][z]), 1e-6 * scale) << int(z) - 2;
}

TEST(IdentifyStepSine, AMultipleOfHalfTheParametricFrequencyIsNotSeparable) {
  // Data at f = fp = 1/π Hz (Mathieu: T = π): H_0 and the mirror of H_{−2} share a line.
  TimeData data;
  data.period = std::numbers::pi;
  TimeRecord rec;
  rec.excitation_hz = 1 / std::numbers::pi;
  const int samples = 4 * 64;
  rec.inputs.resize(samples, 1);
  rec.outputs.resize(samples, 1);
  for (int s = 0; s < samples; ++s) {
    const double t = 4 * std::numbers::pi * s / samples;
    rec.time.push_back(t);
    rec.inputs(s, 0) = std::cos(2 * t);
    rec.outputs(s, 0) = 0.5 * std::cos(2 * t + 0.3);
  }
  data.records.push_back(rec);
  const IdentifyResult id = IdentifyStepSine(data, IdentifyOptions{});
  ASSERT_EQ(id.frequencies.size(), 1u);
  EXPECT_FALSE(id.frequencies[0].separable);
  EXPECT_TRUE(std::isnan(id.frequencies[0].h[0].real()));
  EXPECT_TRUE(HasCode(id.diagnostics, DiagnosticCode::kLinesNotSeparable));
  // ltp's own simulation steps aside from such frequencies, and says so.
  SimulateOptions s;
  s.frequencies_hz = {1 / std::numbers::pi};
  s.periods = 4;
  const SimulationResult sim = SimulateStepSine(Mathieu(), s);
  const double cycles_per_half_fp = sim.data.records[0].excitation_hz * 2 * std::numbers::pi;
  EXPECT_GT(std::abs(cycles_per_half_fp - std::round(cycles_per_half_fp)), 0.1);
  ASSERT_FALSE(sim.diagnostics.empty());
  EXPECT_EQ(sim.diagnostics[0].code, DiagnosticCode::kFrequencyMovedToGrid);
}

// ltp simulate as a rig: the rotor 1 % fast with a tacho. The data are those of the same
// coefficients run faster, A'(t) = A(1.01 t) with period T/1.01 — a system of its own, whose
// partial FRFs the model's routes give; identified on the tacho's phase they must equal those.
TEST(SimulateRig, ASpeedOffsetWithATachoIdentifiesTheFasterSystem) {
  const PeriodicSystem system = Mathieu();
  const double factor = 1.01;
  PeriodicSystem::Functions warped;
  warped.A = [&](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalA(factor * t, out); };
  warped.B = [&](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalB(factor * t, out); };
  warped.C = [&](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalC(factor * t, out); };
  warped.D = [&](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalD(factor * t, out); };
  const PeriodicSystem faster = PeriodicSystem::FromFunctions(
      system.period() / factor, system.states(), system.inputs(), system.outputs(), warped);
  SimulateOptions s;
  s.frequencies_hz = {0.13, 0.4};
  s.periods = 16;
  s.speed_offset = factor - 1;
  s.tacho = true;
  SimulationResult sim = SimulateStepSine(system, s);
  ASSERT_EQ(sim.data.auxiliary_names.size(), 1u);
  TimeData blind = sim.data;
  const MeasuredSpeeds speeds = SetMeasuredAngles(sim.data, AngleChannel{});
  EXPECT_NEAR(speeds.mean_speed * system.period() / (2 * std::numbers::pi), factor, 1e-7);
  IdentifyOptions o;
  const IdentifyResult id = IdentifyStepSine(sim.data, o);
  const auto model = ModelAt(faster, id);
  for (size_t f = 0; f < 2; ++f) {
    double scale = 0;
    for (const auto& h : model[f]) scale = std::max(scale, std::abs(h));
    for (size_t z = 0; z < 5; ++z)
      EXPECT_LT(std::abs(id.frequencies[f].h[z] - model[f][z]), 1e-6 * scale)
          << id.frequencies[f].excitation_hz << " z=" << int(z) - 2;
  }
  // Read at the model's speed, the same data are biased, and the lines say why.
  const IdentifyResult wrong = IdentifyStepSine(blind, o);
  EXPECT_TRUE(HasCode(wrong.diagnostics, DiagnosticCode::kSpeedOffModel));
}

// Seeds K and K + 1 give independent noise (each record's stream hashes seed and record; with
// seed + record, K + 1's records were K's shifted by one).
// A hardening cubic spring on the excited DOF (force u − k3·y³): at an amplitude where k3·y³ is
// a tenth of the linear restoring force the response holds 3ω, which identify names; the
// linear system's records do not trigger the note.
TEST(SimulateRig, ACubicSpringIsNamedAsNonlinearity) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  s.frequencies_hz = {0.13, 0.22};
  s.periods = 16;
  IdentifyOptions o;
  o.min_order = -1;
  o.max_order = 1;
  const auto harmonic = [](const IdentifyResult& id) {
    return HasCode(id.diagnostics, DiagnosticCode::kNonlinearResponse);
  };
  EXPECT_FALSE(harmonic(IdentifyStepSine(SimulateStepSine(system, s).data, o)));
  s.cubic_stiffness = 0.2;  // y ≈ 0.5–1: k3·y³ up to 10 % of a·y
  EXPECT_TRUE(harmonic(IdentifyStepSine(SimulateStepSine(system, s).data, o)));
  s.cubic_stiffness = -1;
  EXPECT_THROW(SimulateStepSine(system, s), InputError);
}

TEST(SimulateRig, NeighbouringSeedsShareNoNoise) {
  SimulateOptions s;
  s.frequencies_hz = {0.05, 0.1, 0.15};
  s.periods = 16;
  s.noise_snr_db = 20;
  const SimulationResult clean = [&] {
    SimulateOptions c = s;
    c.noise_snr_db = std::numeric_limits<double>::infinity();
    return SimulateStepSine(Mathieu(), c);
  }();
  s.seed = 7;
  const SimulationResult a = SimulateStepSine(Mathieu(), s);
  s.seed = 8;
  const SimulationResult b = SimulateStepSine(Mathieu(), s);
  ASSERT_EQ(a.data.records.size(), 3u);
  ASSERT_EQ(b.data.records.size(), 3u);
  ASSERT_EQ(clean.data.records.size(), 3u);
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 3; ++k) {
      const Eigen::VectorXd na =
          a.data.records[i].outputs.col(0) - clean.data.records[i].outputs.col(0);
      const Eigen::VectorXd nb =
          b.data.records[k].outputs.col(0) - clean.data.records[k].outputs.col(0);
      const double correlation = std::abs(na.dot(nb)) / (na.norm() * nb.norm());
      EXPECT_LT(correlation, 0.3) << "seed 7 record " << i << ", seed 8 record " << k;
    }
}

// Broadband (multisine) records, least squares across records per response line (§4.2).

TEST(IdentifyBroadband, NoiseFreeEstimatesEqualTheModel) {
  // 11 lines from 0.05 to 0.45 Hz excited at once, 12 records of random phases, orders −4..4:
  // up to 9 unknowns per response line. Orders beyond ±4 are left out of the regression; for
  // this Mathieu they are below 1e-7 of the response.
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  for (double f = 0.05; f < 0.46; f += 0.04) s.frequencies_hz.push_back(f);
  s.periods = 16;
  s.samples_per_period = 64;
  s.records = 12;
  const SimulationResult sim = SimulateMultisine(system, s);
  ASSERT_EQ(sim.data.records.size(), 12u);
  IdentifyOptions o;
  o.min_order = -4;
  o.max_order = 4;
  const IdentifyResult id = IdentifyBroadband(sim.data, o);
  ASSERT_EQ(id.frequencies.size(), s.frequencies_hz.size());
  // Every line determined (the bias note may come).
  EXPECT_FALSE(HasCode(id.diagnostics, DiagnosticCode::kLinesUnderDetermined));
  const auto model = ModelAt(system, id);
  for (size_t f = 0; f < id.frequencies.size(); ++f) {
    double scale = 0;
    for (const auto& h : model[f]) scale = std::max(scale, std::abs(h));
    for (size_t z = 0; z < 9; ++z) {
      EXPECT_LT(std::abs(id.frequencies[f].h[z] - model[f][z]), 1e-6 * scale)
          << "f = " << id.frequencies[f].excitation_hz << ", z = " << int(z) - 4;
      EXPECT_LT(id.frequencies[f].condition[z], 1e3);
    }
  }
}

// A late output (3 samples: an anti-alias filter) turns each H_z by its line's frequency; the
// records repeat over their length in the steady state, so a circular shift is the exact
// delayed record. Given the delay, the estimate is the model's again (routes of
// ComputePartialFrf).
TEST(IdentifyBroadband, AnOutputDelayIsUndone) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  for (double f = 0.05; f < 0.46; f += 0.08) s.frequencies_hz.push_back(f);
  s.periods = 16;
  s.samples_per_period = 64;
  s.records = 12;
  SimulationResult sim = SimulateMultisine(system, s);
  const long m = 3;
  for (TimeRecord& r : sim.data.records) {
    const long n = r.outputs.rows();
    Eigen::MatrixXd late(n, r.outputs.cols());
    for (long k = 0; k < n; ++k) late.row(k) = r.outputs.row(((k - m) % n + n) % n);
    r.outputs = late;
  }
  IdentifyOptions o;  // orders beyond ±4 are below 1e-7 of the response (test above)
  o.min_order = -4;
  o.max_order = 4;
  const auto worst = [&](const IdentifyResult& id) {
    const auto model = ModelAt(system, id);
    double error = 0;
    for (size_t f = 0; f < id.frequencies.size(); ++f) {
      double scale = 0;
      for (const auto& h : model[f]) scale = std::max(scale, std::abs(h));
      for (size_t z = 0; z < model[f].size(); ++z)
        error = std::max(error, std::abs(id.frequencies[f].h[z] - model[f][z]) / scale);
    }
    return error;
  };
  EXPECT_GT(worst(IdentifyBroadband(sim.data, o)), 0.05);
  o.output_delay = m * sim.data.period / s.samples_per_period;
  EXPECT_LT(worst(IdentifyBroadband(sim.data, o)), 1e-6);
}

// Sample times written with few digits (UFF keeps 7 of a start and a step): every time off by
// e0 + e1·(t − t0). Without a measured angle θ = 2πt/T moves with them; with the records'
// time_error set, the bounds of H_z (z ≠ 0) hold the model's values (ComputePartialFrf).
TEST(IdentifyStepSine, TheWrittenTimesErrorIsInTheBounds) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  s.frequencies_hz = {0.05, 0.13, 0.4};
  s.periods = 16;
  s.samples_per_period = 64;
  SimulationResult sim = SimulateStepSine(system, s);
  for (TimeRecord& r : sim.data.records) {
    const double t0 = r.time.front(), L = r.time.back() - t0, e0 = 4e-5, e1 = 3e-8;
    for (double& t : r.time) t += e0 + e1 * (t - t0);
    r.time_error = e0 + e1 * L;
  }
  IdentifyOptions o;
  o.min_order = -2;
  o.max_order = 2;
  const IdentifyResult id = IdentifyStepSine(sim.data, o);
  const auto model = ModelAt(system, id);
  double largest = 0;
  for (size_t f = 0; f < id.frequencies.size(); ++f)
    for (size_t z : {0u, 1u, 3u, 4u}) {
      const double error = std::abs(id.frequencies[f].h[z] - model[f][z]);
      largest = std::max(largest, error / std::abs(model[f][z]));
      EXPECT_LE(error, id.frequencies[f].bound[z]) << "f " << f << " z " << int(z) - 2;
    }
  EXPECT_GT(largest, 1e-5);  // the shift is seen (noise-free bounds are 1e-10 without it)
}

// The share of broadband estimates (orders −1…1, three lines, 6 records of 8 periods) whose 95 %
// bound holds the model's value (routes of ComputePartialFrf), over 40 seeds: 360 trials, the
// binomial standard deviation of a 95 % coverage 1.1 %.
double BroadbandCoverage(double output_snr_db, double input_snr_db, std::uint64_t seed_step) {
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  s.frequencies_hz = {0.13, 0.22, 0.35};
  s.periods = 8;
  s.samples_per_period = 32;
  s.noise_snr_db = output_snr_db;
  s.input_noise_snr_db = input_snr_db;
  s.records = 6;
  IdentifyOptions o;
  o.min_order = -1;
  o.max_order = 1;
  std::vector<std::vector<std::complex<double>>> truth;
  int inside = 0, total = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    s.seed = seed_step * seed;
    const IdentifyResult id = IdentifyBroadband(SimulateMultisine(system, s).data, o);
    EXPECT_EQ(id.frequencies.size(), 3u) << "seed " << s.seed;
    if (truth.empty()) truth = ModelAt(system, id);
    for (size_t f = 0; f < id.frequencies.size(); ++f)
      for (size_t z = 0; z < 3; ++z) {
        ++total;
        inside += std::abs(id.frequencies[f].h[z] - truth[f][z]) <= id.frequencies[f].bound[z];
      }
  }
  return static_cast<double>(inside) / total;
}

TEST(IdentifyBroadband, NinetyFivePercentBoundsCoverTheTruthUnderNoise) {
  const double coverage = BroadbandCoverage(20, std::numeric_limits<double>::infinity(), 1000);
  EXPECT_GT(coverage, 0.91);
  EXPECT_LT(coverage, 0.99);
}

// A measured input carries noise in every bin: the excited lines are told from its floor (the
// largest drop of the input's power), not refused as "other frequencies", and the noise on
// both channels reaches the bounds through the residuals. 30 dB on input and output.
TEST(IdentifyBroadband, NoisyInputsAreIdentifiedWithBoundsThatCover) {
  const double coverage = BroadbandCoverage(30, 30, 977);
  EXPECT_GT(coverage, 0.91);
  EXPECT_LT(coverage, 0.99);
}

TEST(IdentifyBroadband, TooFewRecordsAreReportedNotGuessed) {
  // 2 records for up to 3 unknowns per line: under-determined lines give NaN and an infinite
  // bound, and the note says how many records are missing. (Lines with one unknown are
  // determined, and their residuals estimate the noise.)
  const PeriodicSystem system = Mathieu();
  SimulateOptions s;
  for (double f = 0.05; f < 0.46; f += 0.04) s.frequencies_hz.push_back(f);
  s.periods = 16;
  s.records = 2;
  const SimulationResult sim = SimulateMultisine(system, s);
  IdentifyOptions o;
  const IdentifyResult id = IdentifyBroadband(sim.data, o);
  int nan = 0;
  for (const auto& f : id.frequencies)
    for (size_t z = 0; z < f.h.size(); ++z)
      if (std::isnan(f.h[z].real())) {
        ++nan;
        EXPECT_TRUE(std::isinf(f.bound[z]));
        EXPECT_TRUE(std::isinf(f.condition[z]));
      }
  EXPECT_GT(nan, 0);
  ASSERT_EQ(id.diagnostics.size(), 1u);
  EXPECT_EQ(id.diagnostics[0].code, DiagnosticCode::kLinesUnderDetermined)
      << id.diagnostics[0].text;
  // A step-sine record is not broadband data.
  SimulateOptions step = s;
  step.frequencies_hz = {0.13};
  EXPECT_THROW(IdentifyBroadband(SimulateStepSine(system, step).data, o), InputError);
}

}  // namespace
}  // namespace ltp
