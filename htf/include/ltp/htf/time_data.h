#pragma once
// Measured or simulated time data of a periodic system: records of sampled inputs and
// outputs, each at one excitation (a step of a step-sine test), on absolute time t (the
// system's phase: A(t) as the model has it, the rotor at angle Ω·t), with the period T that
// the identification needs.
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

namespace ltp {

struct TimeRecord {
  double excitation_hz = 0;  ///< the sine's frequency (Hz) of a step-sine record; 0: broadband
  std::vector<double> time;  ///< uniform, increasing (s)
  Eigen::MatrixXd inputs;    ///< samples × inputs
  Eigen::MatrixXd outputs;   ///< samples × outputs
};

struct TimeData {
  double period = 0;                  ///< T (s) of the system
  std::optional<double> rotor_speed;  ///< rad/s, when the system is a rotor
  std::vector<std::string> input_names, output_names;
  std::vector<TimeRecord> records;
  /// @throws InputError naming the record and sample: T not positive, sizes that disagree,
  /// non-finite values, times that are not uniform and increasing (gaps), fewer than 2
  /// samples.
  void Validate() const;
};

}  // namespace ltp
