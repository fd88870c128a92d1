// Multi-blade coordinates: the transform and the blade number of a label (ltp/core/multiblade.h).
#include "ltp/core/multiblade.h"

#include <cmath>
#include <numbers>
#include <regex>

#include "ltp/core/error.h"

namespace ltp {

using Eigen::MatrixXd;
using std::numbers::pi;

MatrixXd MbcTransform(int blades, double psi, int dpsi_order) {
  if (blades < 3)
    throw InputError("multi-blade coordinates need at least 3 blades, got " +
                     std::to_string(blades));
  if (dpsi_order < 0 || dpsi_order > 2) throw InputError("MbcTransform: derivative order 0..2");
  const int n = blades, cyclics = (n - 1) / 2;
  MatrixXd t = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    const double psi_i = psi + 2 * pi * i / n;
    t(i, 0) = dpsi_order == 0 ? 1.0 : 0.0;
    for (int h = 1; h <= cyclics; ++h) {
      const double c = std::cos(h * psi_i), s = std::sin(h * psi_i);
      switch (dpsi_order) {
        case 0:
          t(i, 2 * h - 1) = c;
          t(i, 2 * h) = s;
          break;
        case 1:
          t(i, 2 * h - 1) = -h * s;
          t(i, 2 * h) = h * c;
          break;
        default:
          t(i, 2 * h - 1) = -h * h * c;
          t(i, 2 * h) = -h * h * s;
          break;
      }
    }
    // Differential (−1)^i with blades numbered from 1: blade 1 gets −1.
    if (n % 2 == 0) t(i, n - 1) = dpsi_order == 0 ? (i % 2 == 0 ? -1.0 : 1.0) : 0.0;
  }
  return t;
}

std::vector<std::string> MbcCoordinateNames(int blades) {
  std::vector<std::string> names{"zeta_0"};
  for (int h = 1; h <= (blades - 1) / 2; ++h) {
    names.push_back("zeta_" + std::to_string(h) + "c");
    names.push_back("zeta_" + std::to_string(h) + "s");
  }
  if (blades % 2 == 0) names.push_back("zeta_d");
  return names;
}

std::optional<size_t> BladeDigit(const std::string& description) {
  static const std::vector<std::regex> patterns = [] {
    std::vector<std::regex> p;
    for (const char* s : {"[Bb]lade \\d", "[Bb]lade [Rr]oot \\d", "BD_\\d", "[Bb]\\d",
                          "[Bb]lade\\d", "PitchBearing\\d", "\\d"})
      p.emplace_back(s);
    return p;
  }();
  for (const std::regex& r : patterns) {
    std::smatch m;
    if (std::regex_search(description, m, r))
      return static_cast<size_t>(m.position(0) + m.length(0) - 1);
  }
  return std::nullopt;
}

}  // namespace ltp
