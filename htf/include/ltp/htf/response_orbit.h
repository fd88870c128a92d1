#pragma once
// The orbit of a rotor's response to a sinusoidal input, harmonic by harmonic: an input
// u(t) = Re(U e^{jωt}) (an unbalance: U = (1, −j) on forces (fx, fy), i.e. fx = cos ωt,
// fy = sin ωt) makes every output answer at ω + zΩp with Y_z = H_z(jω) U; a pair of outputs
// (x, y) traces one ellipse per order z (ltp/core/whirl.h: forward and backward circles, axes,
// tilt). One HTF serves every order, input and frequency: ResponseOrbitSweep evaluates a list of
// frequencies on one analysis, by one route checked by the other.
#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/whirl.h"
#include "ltp/htf/harmonic_transfer_function.h"
#include "ltp/htf/route_reason.h"

namespace ltp {

struct ResponseOrbit {
  int order = 0;              ///< z
  double frequency = 0;       ///< ω + zΩp (rad/s)
  std::complex<double> x, y;  ///< the outputs' phasors Y_z at that frequency
  Orbit orbit;                ///< the ellipse x(t) = Re(x e^{j(ω+zΩp)t}), y(t) likewise
};

/// Orders min_order…max_order of the response of outputs `x_output`, `y_output` to
/// Re(input e^{jωt}) (one complex weight per input), by `route`. Forward means turning the way
/// the rotor does (the system's rotor speed's sign; + without one).
/// @throws InputError for an output index out of range or an input of the wrong size.
std::vector<ResponseOrbit> ResponseOrbits(const HarmonicTransferFunction& htf, double omega,
                                          const Eigen::VectorXcd& input, int x_output, int y_output,
                                          int min_order, int max_order,
                                          OperatorRoute route = OperatorRoute::kModal);

/// The input of a unit unbalance on the force inputs `fx`, `fy` (indices) of a system with
/// `inputs` inputs: a force of magnitude 1 turning at ω the way the rotor does,
/// (fx, fy) = (cos ωt, spin·sin ωt), i.e. the weights 1 on fx, −j·spin on fy and 0 elsewhere
/// ((1, −j) for a rotor turning from x towards y; `spin` as RotorSpin). An unbalance m·e
/// turning at the rotor speed Ω is this input scaled by m·e·Ω² at ω = Ω.
/// @throws InputError when fx == fy or either is out of range.
Eigen::VectorXcd UnbalanceInput(int inputs, int fx, int fy, int spin);

/// Which way an orbit turns, judged against the uncertainty of its radii.
enum class OrbitSense {
  kForward,   ///< forward − backward exceeds the uncertainty
  kBackward,  ///< backward − forward exceeds it
  kStraight,  ///< the radii are equal within it: a line (or its turning is undecided)
  kStill,     ///< both radii are within it: no motion to speak of
};
/// "FW", "BW", "line", "still".
std::string_view ToString(OrbitSense sense);
/// The sense of `orbit` when each radius may be off by `uncertainty` (>= 0, absolute).
OrbitSense SenseOf(const Orbit& orbit, double uncertainty);
/// Whether the orbit's major axis has a direction (its tilt means something): it is no circle
/// within `uncertainty`, both radii exceed it.
bool HasTilt(const Orbit& orbit, double uncertainty);

struct OrbitSweepOptions {
  int min_order = -2, max_order = 2;  ///< orders z of the response
  /// The route of the reported values; empty = automatic: modal, unless the Floquet
  /// decomposition failed or the modal model reports itself unreliable (then hill).
  std::optional<OperatorRoute> route;
  /// Evaluate the other route at every frequency too: the phasors' disagreement is each
  /// value's error estimate (cheap: both routes reuse the one set-up).
  bool check = true;
  /// The largest disagreement of the routes, relative to the sweep's largest semi-major axis,
  /// for which the sweep is ok. Measured on unbalance orbits (orders −2…2 or −3…3): 3e-14
  /// (jeffcott), 4e-14 (rotor, tower-rotor); a truncation of the Hill route too short for the
  /// orders asked shows up far above this.
  double max_relative_disagreement = 1e-6;
  /// Radii below this fraction of the sweep's largest semi-major axis are round-off: the floor
  /// of every value's uncertainty when its sense is judged (the check's estimate can be
  /// smaller, or absent).
  double negligible = 1e-12;
  /// OpenMP threads over the frequencies; 0 = all cores.
  int threads = 0;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct OrbitSweep {
  /// The reported route gave finite phasors at every frequency and, with the check, the routes
  /// agree within max_relative_disagreement.
  bool ok = false;
  std::string failure;         ///< why ok is false, one sentence; empty when ok
  std::vector<double> omegas;  ///< excitation frequencies ω (rad/s), as given
  int min_order = 0, max_order = 0;
  OperatorRoute route = OperatorRoute::kModal;           ///< whose values are reported
  std::optional<OperatorRoute> check_route;              ///< empty without the check
  RouteReason route_reason = RouteReason::kAsRequested;  ///< why this route
  std::string route_choice;  ///< the same in words ("as requested", ...)
  int spin = 1;              ///< RotorSpin of the system
  /// orbits[i][z − min_order]: order z at omegas[i], by `route`
  std::vector<std::vector<ResponseOrbit>> orbits;
  /// Each value's |ΔX| + |ΔY| between the routes: a bound on how far any of its radii and
  /// semi-axes moves between them (each radius by half of it). Empty without the check.
  std::vector<std::vector<double>> error_estimate;
  /// Each value's uncertainty: max(its estimate, negligible × max_semi_major); its sense is
  /// judged with it (and HasTilt may be asked with it).
  std::vector<std::vector<double>> uncertainty;
  std::vector<std::vector<OrbitSense>> sense;
  double max_semi_major = 0;             ///< over the sweep
  double max_disagreement = 0;           ///< max error_estimate (0 without the check)
  double max_relative_disagreement = 0;  ///< divided by max_semi_major
  std::vector<Diagnostic> diagnostics;
};

/// ResponseOrbits at every frequency of `omegas` (rad/s) on the one set-up of `htf`, by the
/// route `options` ask for and checked by the other. Never throws for numerical trouble (see
/// ok); a route that gives NaN (modal without a decomposition) fails the sweep.
/// @throws InputError as ResponseOrbits, for an empty list or invalid options.
OrbitSweep ResponseOrbitSweep(const HarmonicTransferFunction& htf,
                              const std::vector<double>& omegas, const Eigen::VectorXcd& input,
                              int x_output, int y_output, const OrbitSweepOptions& options = {});

}  // namespace ltp
