#pragma once
// Snapshot FRFs: the frequency response H(ω) = C (jωI − A)⁻¹ B + D of the system frozen at
// one time or rotor angle (what a time-invariant analysis at that instant would predict), and
// for comparison the response of the periodic system to an impulse, i.e. the sum of the
// partial FRFs at the response frequency (paper Fig. 6):
//   G(ω) = Σ_z H_z(ω − zΩp)   (every excitation line ω − zΩp contributes to the response at ω).
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/htf/pfrf.h"

namespace ltp {

/// C (jωI − A)⁻¹ B + D of a frozen system (LU solve per frequency). NaN entries when
/// jωI − A is singular.
Eigen::MatrixXcd FrozenFrf(const LtiSystem& system, double omega);

struct SnapshotOptions {
  std::vector<double> frequencies_hz;
  /// Freeze at this time (s) ...
  std::optional<double> time;
  /// ... or at this rotor angle (degrees; the system must have a rotor speed). Exactly one.
  std::optional<double> angle_deg;
  int input = 0, output = 0;
  /// Also the summed partials G(ω) of the periodic system (modal route, checked by htf).
  bool compare = false;
  int min_order = -4, max_order = 4;
  /// The modal model behind G is checked against the htf route at this many excitation
  /// frequencies, spread evenly over the band the orders need ([f0 − zmax·fp, f1 − zmin·fp]);
  /// one banded solve gives every order there.
  int check_points = 12;
  FloquetOptions floquet;
  ModalOptions modal;
  HtfOptions htf;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct SnapshotResult {
  double time = 0;                  ///< the instant frozen (s)
  std::optional<double> angle_deg;  ///< when frozen at a rotor angle
  LtiSystem frozen;
  std::vector<std::complex<double>> eigenvalues;  ///< of the frozen A ("snapshot modes")
  std::vector<double> frequencies_hz;
  std::vector<std::complex<double>> snapshot;  ///< H(2πf) of the channel
  std::vector<std::complex<double>> summed;    ///< G(2πf) (compare only)
  /// Error estimate of G: the check's relative disagreement times Σ_z |H_z(ω − zΩp)|.
  std::vector<double> summed_error;
  /// max over check points of max_z |H_z,modal − H_z,htf| / max_z |H_z,htf|
  double max_summed_disagreement = 0;
  bool modal_reliable = true;
  std::vector<std::complex<double>> floquet_exponents;  ///< compare only
  double elapsed_s = 0;
  std::vector<Diagnostic> diagnostics;
};

/// @throws InputError (bad options, channel out of range, angle without a rotor speed).
SnapshotResult ComputeSnapshotFrf(const PeriodicSystem& system, const SnapshotOptions& options);

}  // namespace ltp
