#pragma once
// The multi-blade-coordinate cross-check of the `rotor` scene: with N >= 3 identical blades the
// rotor is time-invariant in multi-blade coordinates, and the eigenvalues of that constant
// system equal its Floquet exponents modulo jΩ (ltp/models/rotor_mbc.h) — an independent route
// that `ltp floquet rotor` and Python's `ltp.mbc_check` report beside the monodromy result.
#include <optional>
#include <string>

#include "ltp/floquet/floquet.h"
#include "ltp/models/scene.h"

namespace ltp {

struct RotorMbcCheck {
  bool applicable = false;
  std::string reason;  ///< why not, when not applicable (two blades, dissimilar blades)
  int blades = 0;
  /// Largest distance between the Floquet exponents and the MBC eigenvalues, matched one to
  /// one modulo jΩ (1/s); infinite when they cannot be matched.
  double max_difference = 0;
};

/// nullopt unless `scene` is the built-in rotor and `result` is ok; `parameters` are those the
/// analysed system was built with.
std::optional<RotorMbcCheck> CheckRotorByMbc(const Scene& scene, const ParameterMap& parameters,
                                             const FloquetResult& result);

}  // namespace ltp
