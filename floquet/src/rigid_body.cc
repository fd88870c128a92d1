// The rigid-body mode of a free rotation angle (rigid_body.h).
#include "ltp/floquet/detail/rigid_body.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace ltp::internal {

std::vector<std::string> FlagRigidBodyModes(const SystemLabels& labels,
                                            const Eigen::MatrixXcd& shapes_at_zero,
                                            std::vector<FloquetMode>& modes) {
  const int n = static_cast<int>(modes.size());
  const bool have_shapes = shapes_at_zero.cols() == n && n > 0;
  std::vector<std::string> lines;
  for (int state : labels.rigid_body_states) {
    if (state < 0 || state >= n) continue;
    int best = -1;
    for (int pass = have_shapes ? 0 : 1; pass < 2 && best < 0; ++pass) {
      for (int k = 0; k < n; ++k) {
        if (modes[k].rigid_body) continue;
        if (pass == 0) {
          const double norm = shapes_at_zero.col(k).norm();
          if (!(norm > 0) || std::abs(shapes_at_zero(state, k)) < 0.5 * norm) continue;
        }
        if (best < 0 || std::abs(modes[k].exponent) < std::abs(modes[best].exponent)) best = k;
      }
    }
    if (best < 0) continue;
    modes[best].rigid_body = true;
    std::ostringstream s;
    s << "mode " << best + 1 << " is the rigid rotation of state " << state + 1
      << (state < static_cast<int>(labels.states.size()) ? " (" + labels.states[state] + ")" : "")
      << ": exponent " << modes[best].exponent.real()
      << " 1/s, exactly 0 for the exact periodic system; its distance from 0 is the model's "
         "error (e.g. azimuth sampling); left out of max Re λ and the stability verdict";
    lines.push_back(s.str());
  }
  return lines;
}

double MaxRealExponent(const std::vector<FloquetMode>& modes) {
  double m = -std::numeric_limits<double>::infinity();
  for (const FloquetMode& mode : modes)
    if (!mode.rigid_body) m = std::max(m, mode.exponent.real());
  return std::isfinite(m) ? m : 0;  // n = 0, or all rigid
}

}  // namespace ltp::internal
