// Step-sine identification on rig data: records made by tests/support/rig.h (not ltp's
// simulator; closed-form partial FRFs), degraded as a rig degrades them — the rotor off the
// model's speed and ramping, shakers off any grid, records of partial periods, noise on input
// and output, synchronous response, clipping, lost samples. Each is absorbed (error below
// the bound, against the closed form at the measured speed) or named in a diagnostic.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "ltp/core/error.h"
#include "ltp/htf/identify.h"
#include "ltp/htf/rotor_angle.h"
#include "support/rig.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

// Off-grid excitations, and the values a rig's log would write for them (rounded).
const std::vector<std::pair<double, double>> kFrequencies = {
    {0.1373, 0.14}, {0.2917, 0.29}, {0.6121, 0.61}};

TimeData RigData(const testing::Rig& rig, bool tacho, double input_noise = 0,
                 double output_noise = 0, unsigned seed = 1) {
  TimeData d;
  d.period = rig.model_period;
  for (const auto& [f, written] : kFrequencies) {
    TimeRecord r = rig.Record(f, written, input_noise, output_noise, seed++);
    if (tacho) {
      TachoOptions o;
      o.pulse_angle = rig.PulseAngle();
      r.angle = AngleFromTacho(r.time, r.auxiliary.col(0), o).angle;
    }
    d.records.push_back(std::move(r));
  }
  return d;
}

// Whether the result reports an event of kind `code` (the sentence it says is in the comment).
bool Says(const IdentifyResult& id, DiagnosticCode code) { return HasCode(id.diagnostics, code); }

// Largest |H_z − closed form at the record's mean speed| relative to max |H_z|, |z| ≤ 2.
double WorstError(const testing::Rig& rig, const IdentifyResult& id, double speed) {
  double worst = 0;
  for (size_t f = 0; f < id.frequencies.size(); ++f) {
    const auto truth = rig.PartialFrf(kFrequencies[f].first, speed);
    double scale = 0;
    for (const cd& h : truth) scale = std::max(scale, std::abs(h));
    for (size_t z = 0; z < 5; ++z)
      worst = std::max(worst, std::abs(id.frequencies[f].h[z] - truth[z]) / scale);
  }
  return worst;
}

IdentifyOptions Orders() {
  IdentifyOptions o;
  o.min_order = -2;
  o.max_order = 2;
  return o;
}

TEST(IdentifyRig, ASpeedOffsetReadFromATachoLeavesNoBias) {
  const testing::Rig rig;  // +1 % speed, 20.3 periods, shakers off the grid, rounded logs
  const IdentifyResult id = IdentifyStepSine(RigData(rig, true), Orders());
  ASSERT_EQ(id.frequencies.size(), 3u);
  EXPECT_LT(WorstError(rig, id, rig.Speed()), 1e-6);
  for (size_t f = 0; f < 3; ++f) {
    EXPECT_NEAR(id.frequencies[f].excitation_hz, kFrequencies[f].first, 1e-10);
    EXPECT_NEAR(id.frequencies[f].speed / rig.Speed(), 1, 1e-6);
  }
  EXPECT_TRUE(
      Says(id, DiagnosticCode::kExcitationFrequencyMoved));  // 3 of 3 records excite at another
                                                             // frequency than the file says
  EXPECT_TRUE(Says(id, DiagnosticCode::kSpeedOffModel));  // measured speed differs from the model's
                                                          // 2π/T by up to 1 %
  // Without the tacho the same records are read at the model's speed: the bias the issue
  // measured (≈ 30° on H_±1) — named, since the lines themselves show the speed.
  const IdentifyResult blind = IdentifyStepSine(RigData(rig, false), Orders());
  EXPECT_GT(WorstError(rig, blind, rig.Speed()), 0.1);
  EXPECT_TRUE(Says(blind, DiagnosticCode::kSpeedOffModel));  // in 3 of 3 records the response's
                                                             // lines sit at a speed up to 1 % off
}

TEST(IdentifyRig, ASpeedRampReadFromATachoIsTheModelAtTheMeanSpeed) {
  testing::Rig rig;
  rig.ramp = 0.01;  // +1 % over each record, on top of the +1 % offset
  const IdentifyResult id = IdentifyStepSine(RigData(rig, true), Orders());
  const double mean = rig.Speed() * 1.005;
  for (const IdentifiedFrequency& f : id.frequencies) EXPECT_NEAR(f.speed / mean, 1, 1e-5);
  // H_z itself moves with the speed within the record (the closed form at the record's first
  // and last speed differs by 4 % of max |H_z| at 0.61 Hz, on H_{−1}, whose line ω − Ω passes
  // near the pole): the estimate is the mean speed's to a tenth of that spread, and says so.
  double spread = 0;
  for (const auto& [f, written] : kFrequencies) {
    const auto first = rig.PartialFrf(f, rig.Speed()), last = rig.PartialFrf(f, rig.Speed() * 1.01);
    double scale = 0;
    for (const cd& h : first) scale = std::max(scale, std::abs(h));
    for (size_t z = 0; z < 5; ++z) spread = std::max(spread, std::abs(first[z] - last[z]) / scale);
  }
  EXPECT_GT(spread, 0.03);
  EXPECT_LT(WorstError(rig, id, mean), 0.1 * spread);
  EXPECT_TRUE(Says(
      id, DiagnosticCode::kSpeedChanges));  // the speed changes by up to 0.99 % within a record
}

// The share of estimates, over seeds, whose 95 % bound holds the closed form at the rig's
// speed: `identify(seed)` gives one estimate at the frequencies f_hz.
template <class Identify>
double Coverage(const testing::Rig& rig, const std::vector<double>& f_hz, unsigned seeds,
                const Identify& identify) {
  long inside = 0, total = 0;
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const IdentifyResult id = identify(seed);
    for (size_t f = 0; f < f_hz.size(); ++f) {
      const auto truth = rig.PartialFrf(f_hz[f], rig.Speed());
      for (size_t z = 0; z < 5; ++z) {
        ++total;
        inside += std::abs(id.frequencies[f].h[z] - truth[z]) <= id.frequencies[f].bound[z];
      }
    }
  }
  return static_cast<double>(inside) / static_cast<double>(total);
}

TEST(IdentifyRig, BoundsCoverTheTruthWithNoiseOnInputAndOutput) {
  const testing::Rig rig;
  const double snr = std::pow(10.0, -30.0 / 20);  // 30 dB on both channels
  std::vector<double> f_hz;
  for (const auto& [f, written] : kFrequencies) f_hz.push_back(f);
  const double coverage = Coverage(rig, f_hz, 40, [&](unsigned seed) {
    return IdentifyStepSine(RigData(rig, true, snr, snr, 100 * seed), Orders());
  });
  // 600 estimates: the binomial standard deviation of a 95 % coverage is 0.9 %.
  EXPECT_GT(coverage, 0.92);
  EXPECT_LT(coverage, 0.98);
}

TEST(IdentifyRig, SynchronousResponseAndGapsAreAbsorbedAndNamed) {
  const testing::Rig rig;
  TimeData d = RigData(rig, true);
  for (TimeRecord& r : d.records)
    for (size_t i = 0; i < r.time.size(); ++i)  // an unbalance at 1× and 2×
      r.outputs(static_cast<long>(i), 0) +=
          0.5 * std::cos(r.angle[i] + 0.2) + 0.2 * std::cos(2 * r.angle[i] - 1);
  // Record 2 loses samples 601–603 with their times (a gap in t).
  TimeRecord& r = d.records[1];
  const long n = static_cast<long>(r.time.size());
  const auto drop = [&](Eigen::MatrixXd& m) {
    Eigen::MatrixXd kept(n - 3, m.cols());
    kept << m.topRows(600), m.bottomRows(n - 603);
    m = kept;
  };
  drop(r.inputs);
  drop(r.outputs);
  drop(r.auxiliary);
  r.time.erase(r.time.begin() + 600, r.time.begin() + 603);
  r.angle.erase(r.angle.begin() + 600, r.angle.begin() + 603);
  const IdentifyResult id = IdentifyStepSine(d, Orders());
  EXPECT_LT(WorstError(rig, id, rig.Speed()), 1e-6);
  EXPECT_TRUE(Says(id, DiagnosticCode::kSynchronousResponse));  // synchronous response at 1×, 2×
  EXPECT_TRUE(
      Says(id, DiagnosticCode::kRecordGaps));  // record 2: 1 gap(s) in t, the first at sample 601
}

TEST(IdentifyRig, ClippingAndSlippedSamplesAreNamed) {
  const testing::Rig rig;
  TimeData clipped = RigData(rig, true);
  for (TimeRecord& r : clipped.records) {
    const double limit = 0.9 * r.outputs.cwiseAbs().maxCoeff();
    r.outputs = r.outputs.cwiseMin(limit).cwiseMax(-limit);
  }
  EXPECT_TRUE(Says(IdentifyStepSine(clipped, Orders()),
                   DiagnosticCode::kRecordClipped));  // output sits at its extreme value
  // Three samples lost while the DAQ's clock went on: the later samples are written 3 steps
  // early.
  TimeData slipped = RigData(rig, true);
  for (TimeRecord& r : slipped.records) {
    const long n = static_cast<long>(r.time.size());
    r.inputs.middleRows(600, n - 603) = r.inputs.bottomRows(n - 603).eval();
    r.outputs.middleRows(600, n - 603) = r.outputs.bottomRows(n - 603).eval();
    r.inputs.conservativeResize(n - 3, Eigen::NoChange);
    r.outputs.conservativeResize(n - 3, Eigen::NoChange);
    r.auxiliary.conservativeResize(n - 3, Eigen::NoChange);
    r.time.resize(static_cast<size_t>(n - 3));
    r.angle.resize(static_cast<size_t>(n - 3));
  }
  EXPECT_TRUE(Says(IdentifyStepSine(slipped, Orders()),
                   DiagnosticCode::kInputPhaseMoves));  // the input's phase moves by
}

// An output sampled late (here 2.6 samples: an anti-alias filter's group delay) turns the
// phase of every H_z by its lines' frequencies; given the delay, the fit takes the output's
// lines at t − delay and the estimate is the undelayed system's — with a tacho (θ interpolated
// at t − delay) and at the model's speed (θ = 2πt/T exact). Truth: the closed form.
TEST(IdentifyRig, AChannelDelayIsUndone) {
  for (const bool tacho : {true, false}) {
    testing::Rig rig;
    rig.speed_factor = tacho ? 1.01 : 1.0;  // without a tacho: the model's speed and phase
    rig.theta0 = tacho ? rig.theta0 : 0;
    rig.output_delay_steps = 104;  // 2.6 samples
    const TimeData d = RigData(rig, tacho);
    const IdentifyResult blind = IdentifyStepSine(d, Orders());
    EXPECT_GT(WorstError(rig, blind, rig.Speed()), 0.05) << "tacho " << tacho;
    IdentifyOptions o = Orders();
    o.output_delay = rig.OutputDelay();
    const IdentifyResult id = IdentifyStepSine(d, o);
    EXPECT_LT(WorstError(rig, id, rig.Speed()), 1e-6) << "tacho " << tacho;
  }
}

// Broadband records of the rig on its tacho: a multisine of 5 lines (whole cycles of the
// record, random phases per record), the rotor 1 % fast, 20.3 periods per record. The lines
// ω_k + zθ' leave the DFT's bins; the one fit over all records on the measured angle gives the
// closed form at the rig's speed, and with 30 dB on input and output its bounds cover it.
struct MultisineRig {
  testing::Rig rig;
  std::vector<double> f_hz;
  std::vector<TimeRecord> records;  // noise-free
  MultisineRig() {
    for (const int k : {3, 7, 12, 18, 25}) f_hz.push_back(k / rig.RecordLength());
    std::mt19937_64 gen(11);
    std::uniform_real_distribution<double> phase(0, 2 * std::numbers::pi);
    for (int r = 0; r < 8; ++r) {
      std::vector<double> phases;
      for (size_t k = 0; k < f_hz.size(); ++k) phases.push_back(phase(gen));
      records.push_back(rig.MultisineRecord(f_hz, phases));
    }
  }
  // The records with white noise of a fraction of each channel's rms, their angle from the
  // tacho.
  TimeData Data(double input_noise, double output_noise, unsigned seed) const {
    TimeData d;
    d.period = rig.model_period;
    std::mt19937_64 gen(seed);
    std::normal_distribution<double> normal;
    for (TimeRecord r : records) {
      for (const auto& [m, fraction] :
           {std::pair{&r.inputs, input_noise}, {&r.outputs, output_noise}}) {
        const double rms = std::sqrt(m->squaredNorm() / static_cast<double>(m->rows()));
        for (Eigen::Index i = 0; i < m->rows(); ++i) (*m)(i, 0) += fraction * rms * normal(gen);
      }
      TachoOptions o;
      o.pulse_angle = rig.PulseAngle();
      r.angle = AngleFromTacho(r.time, r.auxiliary.col(0), o).angle;
      d.records.push_back(std::move(r));
    }
    return d;
  }
};

TEST(IdentifyRig, BroadbandOnATachoGivesTheClosedForm) {
  const MultisineRig m;
  const IdentifyResult id = IdentifyBroadband(m.Data(0, 0, 1), Orders());
  ASSERT_EQ(id.frequencies.size(), m.f_hz.size());
  double worst = 0;
  for (size_t f = 0; f < m.f_hz.size(); ++f) {
    EXPECT_NEAR(id.frequencies[f].excitation_hz, m.f_hz[f], 1e-12);
    EXPECT_NEAR(id.frequencies[f].speed / m.rig.Speed(), 1, 1e-6);
    const auto truth = m.rig.PartialFrf(m.f_hz[f], m.rig.Speed());
    double scale = 0;
    for (const cd& h : truth) scale = std::max(scale, std::abs(h));
    for (size_t z = 0; z < 5; ++z)
      worst = std::max(worst, std::abs(id.frequencies[f].h[z] - truth[z]) / scale);
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_TRUE(Says(id, DiagnosticCode::kBroadbandFit));  // broadband on the measured angle
  EXPECT_TRUE(Says(
      id, DiagnosticCode::kSpeedOffModel));  // measured speed differs from the model's 2π/T by 1 %
  // The constant-speed route on the same records, without the angle: refused (not whole
  // periods) — it could only have been biased.
  TimeData blind = m.Data(0, 0, 1);
  for (TimeRecord& r : blind.records) r.angle.clear();
  EXPECT_THROW(IdentifyBroadband(blind, Orders()), InputError);
}

TEST(IdentifyRig, BroadbandOnATachoBoundsCoverTheTruthWithNoisyInputAndOutput) {
  const MultisineRig m;
  const double snr = std::pow(10.0, -30.0 / 20);
  const double coverage = Coverage(m.rig, m.f_hz, 30, [&](unsigned seed) {
    return IdentifyBroadband(m.Data(snr, snr, 7 * seed), Orders());
  });
  // 750 estimates: the binomial standard deviation of a 95 % coverage is 0.8 %.
  EXPECT_GT(coverage, 0.92);
  EXPECT_LT(coverage, 0.98);
}

}  // namespace
}  // namespace ltp
