// The rotor's phase from a tacho or an encoder, against the phase the rig was driven with
// (tests/support/rig.h: θ(t) known in closed form, speed offset and ramp).
#include "ltp/htf/rotor_angle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ltp/core/error.h"
#include "support/rig.h"

namespace ltp {
namespace {

TEST(RotorAngle, TachoPulsesGiveThePhaseOfARampingRotor) {
  testing::Rig rig;
  rig.ramp = 0.01;  // the speed rises by 1 % over the record
  const TimeRecord rec = rig.Record(0.2, 0.2);
  TachoOptions o;
  o.pulse_angle = rig.PulseAngle();
  const RotorAngle a = AngleFromTacho(rec.time, rec.auxiliary.col(0), o);
  ASSERT_EQ(a.angle.size(), rec.time.size());
  // θ is quadratic in t: the cubic through the pulses is exact, the edges' timing (a pulse
  // 0.6 rad wide at 64 samples per period) is what is left. The first pulse is θ = pulse_angle:
  // compare modulo its whole turns.
  const double offset = 2 * std::numbers::pi *
                        std::round((a.angle[0] - rig.Theta(rec.time[0])) / (2 * std::numbers::pi));
  double worst = 0;
  for (size_t i = 0; i < rec.time.size(); ++i)
    worst = std::max(worst, std::abs(a.angle[i] - offset - rig.Theta(rec.time[i])));
  EXPECT_LT(worst, 2e-5) << "rad";
  EXPECT_NEAR(a.min_speed / rig.Speed(), 1.0, 2e-3);
  EXPECT_NEAR(a.max_speed / rig.Speed(), 1.01, 2e-3);
  EXPECT_NEAR(a.mean_speed / rig.Speed(), 1.005, 1e-5);
}

TEST(RotorAngle, AMissedPulseIsRefusedWithItsTime) {
  testing::Rig rig;
  TimeRecord rec = rig.Record(0.2, 0.2);
  TachoOptions o;
  o.pulse_angle = rig.PulseAngle();
  // Erase the fifth pulse.
  const RotorAngle clean = AngleFromTacho(rec.time, rec.auxiliary.col(0), o);
  for (size_t i = 0; i < rec.time.size(); ++i)
    if (std::abs(rec.time[i] - clean.pulse_times[4] - 0.3) < 0.5) rec.auxiliary(i, 0) = 0;
  try {
    AngleFromTacho(rec.time, rec.auxiliary.col(0), o);
    ADD_FAILURE() << "a missed pulse was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missed or a double pulse"), std::string::npos)
        << e.what();
  }
  Eigen::VectorXd flat = Eigen::VectorXd::Zero(static_cast<long>(rec.time.size()));
  EXPECT_THROW(AngleFromTacho(rec.time, flat, o), InputError);
}

TEST(RotorAngle, AWrappedEncoderAngleIsUnwrapped) {
  testing::Rig rig;
  const TimeRecord rec = rig.Record(0.2, 0.2);
  Eigen::VectorXd wrapped(static_cast<long>(rec.time.size()));
  for (size_t i = 0; i < rec.time.size(); ++i)
    wrapped(static_cast<long>(i)) = std::remainder(rig.Theta(rec.time[i]), 2 * std::numbers::pi);
  const RotorAngle a = AngleFromEncoder(rec.time, wrapped);
  for (size_t i = 0; i < rec.time.size(); ++i)
    EXPECT_NEAR(a.angle[i] - a.angle[0], rig.Theta(rec.time[i]) - rig.Theta(rec.time[0]), 1e-12);
  EXPECT_NEAR(a.mean_speed / rig.Speed(), 1.0, 1e-12);
}

}  // namespace
}  // namespace ltp
