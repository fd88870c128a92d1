#pragma once
// The one type every analysis takes: a linear T-periodic system
//   x' = A(t) x + B(t) u,   y = C(t) x + D(t) u,   A(t + T) = A(t), ...
// built from Fourier coefficients, from time functions, or from piecewise-constant samples
// (matrices given at K azimuths). Second-order systems M p'' + D p' + K p = F u are converted
// to this form by second_order.h. The object is immutable and cheap to copy (shared state);
// every evaluation is const and thread-safe, so sweeps and segment integrations may call it in
// parallel.
#include <Eigen/Dense>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/fourier_matrix.h"

namespace ltp {

/// A frozen (time-invariant) system: the snapshot of a periodic system at one instant.
struct LtiSystem {
  Eigen::MatrixXd A, B, C, D;
};

/// Names of states, inputs and outputs, for output and for selecting channels by name.
struct SystemLabels {
  std::vector<std::string> states{}, inputs{}, outputs{};
  /// States that are a free rotation angle (e.g. OpenFAST's generator azimuth): each gives a
  /// Floquet exponent that is exactly 0 in theory; the analyses flag that mode as rigid-body
  /// and leave it out of the stability verdict.
  std::vector<int> rigid_body_states{};
  /// Number of rotor blades (0 when the system has none or does not say) and the states that
  /// are blade coordinates, each numbered 1..blades in its label ("zeta2", "blade2_flap1",
  /// "... of blade 2, m"). Mode descriptions group them into multiblade families
  /// (collective, cyclic); other states are named singly, whatever digits their labels hold.
  int blades = 0;
  std::vector<int> blade_states{};
  /// (x, y) state pairs of a rotor's lateral motion (displacements, not rates), the rotor
  /// turning from x towards y when its speed is positive: the modes' forward and backward
  /// whirl is measured in these planes (ltp/core/whirl.h). Empty: no whirl is reported.
  std::vector<std::array<int, 2>> whirl_pairs{};
};

class PeriodicSystem {
 public:
  /// Writes a matrix-valued function of time into `out` (pre-sized). Must be thread-safe.
  using MatrixFunction = std::function<void(double t, Eigen::Ref<Eigen::MatrixXd> out)>;

  enum class Form {
    kFourier,            ///< finite Fourier series: exact coefficients known
    kFunction,           ///< time functions A(t), ...; may jump at breakpoints()
    kPiecewiseConstant,  ///< samples held constant on [t_k, t_{k+1})
  };

  struct Functions {
    MatrixFunction A, B, C, D;  ///< B, C, D may be empty when there are no inputs/outputs
  };

  /// From Fourier coefficients. A is n×n; B n×m, C p×n, D p×m (an empty FourierMatrix means
  /// no inputs / no outputs / zero feedthrough).
  /// @throws InputError on period <= 0 or not finite, inconsistent sizes, non-finite coefficients.
  static PeriodicSystem FromFourier(double period, FourierMatrix A, FourierMatrix B = {},
                                    FourierMatrix C = {}, FourierMatrix D = {});

  /// From time functions with period T. `breakpoints` are the times in [0, T) where a
  /// coefficient jumps (integrators restart there; Fourier fits expect algebraic decay).
  static PeriodicSystem FromFunctions(double period, int states, int inputs, int outputs,
                                      Functions functions, std::vector<double> breakpoints = {});

  /// Piecewise constant: samples[k] holds on [times[k], times[k+1]), times[K] = times[0] + T.
  /// `times` must be strictly increasing in [0, T). The state transition is then an exact
  /// product of matrix exponentials.
  static PeriodicSystem FromSamples(double period, std::vector<double> times,
                                    std::vector<LtiSystem> samples);

  int states() const;
  int inputs() const;
  int outputs() const;
  double period() const;
  /// Ωp = 2π/T.
  double omega() const;
  Form form() const;

  void EvalA(double t, Eigen::Ref<Eigen::MatrixXd> out) const;
  void EvalB(double t, Eigen::Ref<Eigen::MatrixXd> out) const;
  void EvalC(double t, Eigen::Ref<Eigen::MatrixXd> out) const;
  void EvalD(double t, Eigen::Ref<Eigen::MatrixXd> out) const;
  Eigen::MatrixXd A(double t) const;
  Eigen::MatrixXd B(double t) const;
  Eigen::MatrixXd C(double t) const;
  Eigen::MatrixXd D(double t) const;

  /// The frozen LTI system at time t.
  LtiSystem Snapshot(double t) const;
  /// The frozen LTI system at rotor angle `angle_rad` (t = angle/rotor_speed).
  /// @throws InputError if the system has no rotor speed.
  LtiSystem SnapshotAtAngle(double angle_rad) const;

  /// Times in [0, T) where coefficients jump (sorted). For sampled systems: the sample times.
  const std::vector<double>& breakpoints() const;

  /// Exact Fourier coefficients, when the system was built from them; nullptr otherwise.
  const FourierMatrix* fourier_A() const;
  /// Fourier form: A(t) = A_0 + Σ_{w=1..H} (C_w cos wΩt + S_w sin wΩt) as flat column-major
  /// n×n blocks [A_0 | C_1 | S_1 | ... | C_H | S_H] (trailing zero harmonics dropped), for inner
  /// loops that evaluate A(t) themselves; nullptr for the other forms. `harmonics` gets H.
  const double* RealSeriesA(int* harmonics) const;
  const FourierMatrix* fourier_B() const;
  const FourierMatrix* fourier_C() const;
  const FourierMatrix* fourier_D() const;

  /// Sample times and matrices of a piecewise-constant system; empty otherwise.
  const std::vector<double>& sample_times() const;
  const std::vector<LtiSystem>& samples() const;

  const SystemLabels& labels() const;
  /// Returns a copy with these labels (sizes must match states/inputs/outputs or be empty).
  PeriodicSystem WithLabels(SystemLabels labels) const&;
  /// The same for a temporary (a scene builder's `FromFourier(…).WithLabels(…)`): when it is
  /// the only owner of its representation, that is relabelled instead of copied — a sweep
  /// builds one system per point.
  PeriodicSystem WithLabels(SystemLabels labels) &&;
  /// The same system in the scaled states z = S⁻¹ x, S = diag(scale): A_z = S⁻¹ A S,
  /// B_z = S⁻¹ B, C_z = C S, D unchanged; the same form, breakpoints, labels and rotor speed.
  /// Exponents are unchanged; a mode shape of z is S⁻¹ times that of x. Powers of two keep the
  /// scaling exact. @throws InputError for a wrong size or a scale that is not finite and > 0.
  PeriodicSystem WithStateScaling(const Eigen::VectorXd& scale) const;
  /// Rotor speed in rad/s, when the system describes a rotor (rotor angle = speed · t).
  std::optional<double> rotor_speed() const;
  PeriodicSystem WithRotorSpeed(double rad_per_s) const;

  struct Impl;

 private:
  explicit PeriodicSystem(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  void CheckLabels(const SystemLabels& labels) const;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace ltp
