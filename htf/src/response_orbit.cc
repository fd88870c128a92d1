#include "ltp/htf/response_orbit.h"

#include <cmath>
#include <numbers>
#include <string>

#include "ltp/core/error.h"

namespace ltp {

std::vector<ResponseOrbit> ResponseOrbits(const HarmonicTransferFunction& htf, double omega,
                                          const Eigen::VectorXcd& input, int x_output, int y_output,
                                          int min_order, int max_order, OperatorRoute route) {
  const PeriodicSystem& system = htf.system();
  if (input.size() != system.inputs())
    throw InputError("ResponseOrbits: the input has " + std::to_string(input.size()) +
                     " weights, the system " + std::to_string(system.inputs()) + " inputs");
  for (int o : {x_output, y_output})
    if (o < 0 || o >= system.outputs())
      throw InputError("ResponseOrbits: output index " + std::to_string(o) + " is out of range");
  if (!std::isfinite(omega)) throw InputError("ResponseOrbits: the frequency must be finite");
  const int spin = RotorSpin(system);
  const double omega_p = 2 * std::numbers::pi / system.period();
  const PartialFrfs H = htf.Partial(std::complex<double>(0, omega), min_order, max_order, route);
  std::vector<ResponseOrbit> out;
  for (int z = min_order; z <= max_order; ++z) {
    const Eigen::VectorXcd y = H[static_cast<size_t>(z - min_order)] * input;
    ResponseOrbit r;
    r.order = z;
    r.frequency = omega + z * omega_p;
    r.x = y(x_output);
    r.y = y(y_output);
    r.orbit = OrbitOf(r.x, r.y, r.frequency, spin);
    out.push_back(r);
  }
  return out;
}

}  // namespace ltp
