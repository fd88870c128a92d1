#pragma once
// The orbit of a rotor's response to a sinusoidal input, harmonic by harmonic: an input
// u(t) = Re(U e^{jωt}) (an unbalance: U = (1, −j) on forces (fx, fy), i.e. fx = cos ωt,
// fy = sin ωt) makes every output answer at ω + zΩp with Y_z = H_z(jω) U; a pair of outputs
// (x, y) traces one ellipse per order z (ltp/core/whirl.h: forward and backward circles, axes,
// tilt). One HTF serves every order and input at once.
#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "ltp/core/whirl.h"
#include "ltp/htf/harmonic_transfer_function.h"

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

}  // namespace ltp
