#pragma once
// The built-in `rotor` scene (ltp/models/rotor.h) written as OpenFAST `.lin` files at chosen
// azimuths, the way OpenFAST would write a linearisation: one file per azimuth, blade lag
// angles in the rotating frame ("... of blade b"), hub displacements in the fixed frame,
// displacements first and then their rates (second-order states), inputs f_x, f_y and
// outputs x, y in the fixed frame.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "ltp/models/rotor.h"
#include "ltp/openfast/linearization.h"

namespace ltp::test {

/// The source tree (LTP_SOURCE_DIR when set, else two levels above tests/support/).
inline std::string SourceDir() {
  if (const char* dir = std::getenv("LTP_SOURCE_DIR")) return dir;
  return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path().string();
}
/// The shipped NREL 5 MW linearisation files (tests/data/openfast/README.md).
inline std::string FiveMwDir() { return SourceDir() + "/tests/data/openfast/nrel5mw-rotating"; }

inline std::vector<LinFile> RotorLinFiles(const RotorParameters& rotor,
                                          const std::vector<double>& azimuths) {
  const PeriodicSystem system = BuildRotorSystem(rotor);
  const int N = rotor.blades, q = N + 2;
  std::vector<LinChannel> states;
  for (int order = 0; order < 2; ++order)
    for (int i = 0; i < q; ++i) {
      std::string what = i < N ? "lag angle of blade " + std::to_string(i + 1)
                               : std::string("hub displacement ") + (i == N ? "x" : "y");
      std::string unit = i < N ? "rad" : "m";
      LinChannel c;
      c.rotating_frame = i < N;
      c.derivative_order = 2;
      c.description = order == 0 ? "RT " + what + ", " + unit
                                 : "RT First time derivative of " + what + ", " + unit + "/s";
      states.push_back(c);
    }
  auto fixed = [](const std::string& d) {
    LinChannel c;
    c.description = d;
    return c;
  };
  std::vector<LinFile> files;
  for (size_t k = 0; k < azimuths.size(); ++k) {
    const double t = azimuths[k] / rotor.omega;
    LinFile f;
    f.path = "rotor." + std::to_string(k + 1) + ".lin";
    f.title = "Linearized model: the ltp rotor scene at one azimuth";
    f.rotor_speed = rotor.omega;
    f.azimuth = azimuths[k];
    f.continuous_states = 2 * q;
    f.inputs = 2;
    f.outputs = 2;
    f.states = states;
    f.input_channels = {fixed("RT hub force fx, N"), fixed("RT hub force fy, N")};
    f.output_channels = {fixed("RT hub displacement x, m"), fixed("RT hub displacement y, m")};
    f.A = system.A(t);
    f.B = system.B(t);
    f.C = system.C(t);
    f.D = system.D(t);
    files.push_back(std::move(f));
  }
  return files;
}

}  // namespace ltp::test
