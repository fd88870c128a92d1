#include "ltp/studies/rotor_mbc_check.h"

#include <complex>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/models/rotor.h"
#include "ltp/models/rotor_mbc.h"

namespace ltp {

std::optional<RotorMbcCheck> CheckRotorByMbc(const Scene& scene, const ParameterMap& parameters,
                                             const FloquetResult& result) {
  if (scene.name != "rotor" || !result.ok) return std::nullopt;
  RotorMbcCheck check;
  const RotorParameters rotor = RotorParametersFrom(parameters);
  if (auto reason = MbcNotApplicable(rotor)) {
    check.reason = *reason;
    return check;
  }
  const MbcRotorSystem mbc = RotorInMultiBladeCoordinates(rotor);
  const std::vector<std::complex<double>> exponents = Exponents(result.modes);
  check.applicable = true;
  check.blades = mbc.blades;
  check.max_difference = MaxExponentMismatch(exponents, mbc.eigenvalues, mbc.rotor_speed);
  return check;
}

}  // namespace ltp
