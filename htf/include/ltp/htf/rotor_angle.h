#pragma once
// The system's phase θ(t) from a rig's channels. A rotor on a rig does not turn at exactly
// the model's speed, and drifts: the response lines of a step-sine test sit at ω·t + z·θ(t),
// not at (ω + zΩp)·t, and an estimate that assumes the latter is biased by the phase the
// rotor gains or loses over a record (a 1 % speed offset: ≈ 30° on H_{±1}). A tacho's pulses
// or an encoder's angle give θ(t); identify.h fits the lines on it (docs/rig-data.md).
#include <Eigen/Dense>
#include <vector>

#include "ltp/htf/time_data.h"

namespace ltp {

struct TachoOptions {
  /// Pulses per period of the system (1: a once-per-revolution tacho on a rotor whose model
  /// period is one revolution). With K > 1 identical pulses the first one in each record is
  /// taken as θ = pulse_angle: H_z is then known only for z a multiple of K.
  int pulses_per_period = 1;
  /// θ (rad) when a pulse fires: where the tacho sits relative to the model's t = 0.
  double pulse_angle = 0;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct RotorAngle {
  std::vector<double> angle;        ///< θ at each sample (rad)
  std::vector<double> pulse_times;  ///< s, the rising edges at mid-level (tacho only)
  /// dθ/dt (rad/s): over the record, and the least and largest over one pulse interval.
  double mean_speed = 0, min_speed = 0, max_speed = 0;
};

/// θ from a tacho channel: each rising edge through the middle of the signal's range (with
/// re-arming below ¼ of it, so noise on a pulse does not count twice), timed where the cubic
/// through the four samples around it crosses (O(h⁴) on an edge a few samples wide), advances
/// θ by 2π/K; between and around the pulses θ is the cubic through the four nearest pulses
/// (exact for a speed that changes linearly). An edge sharper than a sample is timed to ±½
/// sample only: sample the tacho faster than its edge.
/// @throws InputError for fewer than 2 pulses, or a pulse interval more than 25 % off both its
/// neighbours (a missed or a double pulse), naming its time.
RotorAngle AngleFromTacho(const std::vector<double>& time, const Eigen::VectorXd& signal,
                          const TachoOptions& options);

/// θ from an encoder channel holding the angle in rad, wrapped or not: steps of more than π
/// are unwrapped (the channel must be sampled faster than half a revolution per sample).
/// @throws InputError when the angle does not advance over the record.
RotorAngle AngleFromEncoder(const std::vector<double>& time, const Eigen::VectorXd& signal);

/// Where the records' phase is measured: a column of TimeRecord::auxiliary.
struct AngleChannel {
  enum class Kind { kTacho, kEncoder };
  Kind kind = Kind::kTacho;
  int channel = 0;
  TachoOptions tacho;
};

/// The speeds the records were measured at (dθ/dt, rad/s): the least and largest over the
/// records' pulse intervals (encoder: samples), and the mean over all records.
struct MeasuredSpeeds {
  double min_speed = 0, max_speed = 0, mean_speed = 0;
};

/// Sets every record's angle from `source`; data without a period (0) get T = 2π / the mean
/// speed. @throws InputError naming the record (see AngleFromTacho), or a channel not in the
/// data.
MeasuredSpeeds SetMeasuredAngles(TimeData& data, const AngleChannel& source);

}  // namespace ltp
