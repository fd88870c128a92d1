#pragma once
// Measured or simulated time data of a periodic system: records of sampled inputs and
// outputs, each at one excitation (a step of a step-sine test), on absolute time t (the
// system's phase: A(t) as the model has it, the rotor at angle Ω·t), with the period T that
// the identification needs. On a rig the rotor's angle is measured instead (a tacho or an
// encoder, rotor_angle.h): then each record carries the system's phase θ(t) itself, and the
// speed may differ from 2π/T and drift.
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

namespace ltp {

struct TimeRecord {
  double excitation_hz = 0;  ///< the sine's frequency (Hz) of a step-sine record; 0: broadband
  std::vector<double> time;  ///< increasing (s); uniform for broadband identification
  Eigen::MatrixXd inputs;    ///< samples × inputs
  Eigen::MatrixXd outputs;   ///< samples × outputs
  /// Other channels (a tacho, an encoder), samples × auxiliaries; may have no columns.
  Eigen::MatrixXd auxiliary;
  /// The system's phase θ at each sample (rad; A(t) of the model is the rig's at θ/Ωp), as
  /// measured (AngleFromTacho); empty: θ = 2πt/T, the rotor exactly at the model's speed.
  std::vector<double> angle;
  /// Bound on the error of the written sample times against the clock the model's phase runs
  /// on (s; 0: exact) — a format's digits (UFF keeps 7 of a start and a step). Without a
  /// measured angle it moves θ = 2πt/T, and the bounds of H_z (z ≠ 0) carry it.
  double time_error = 0;
};

struct TimeData {
  double period = 0;                  ///< T (s) of the system
  std::optional<double> rotor_speed;  ///< rad/s, when the system is a rotor
  std::vector<std::string> input_names, output_names, auxiliary_names;
  std::vector<TimeRecord> records;
  /// @throws InputError naming the record and sample: T not positive, sizes that disagree,
  /// non-finite values or values above 1e150 (their squares overflow), times that do not
  /// increase, fewer than 2 samples.
  void Validate() const;
};

/// The sampling step of a record: the median of its steps (a gap or a few slips do not move it).
double SamplingStep(const TimeRecord& record);

/// @throws InputError naming the first sample whose step differs from SamplingStep by more
/// than `tolerance` of it (a gap, dropped samples, jitter) — for methods that need a uniform
/// grid (the DFT of broadband identification).
void RequireUniformSampling(const TimeRecord& record, const std::string& where,
                            double tolerance = 1e-6);

}  // namespace ltp
