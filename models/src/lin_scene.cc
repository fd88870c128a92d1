// An OpenFAST operating point as a scene (ltp/models/lin_scene.h).
#include "ltp/models/lin_scene.h"

#include <filesystem>
#include <string>

#include "ltp/core/error.h"
#include "ltp/openfast/mbc3.h"

namespace ltp {

Scene MakeLinScene(const LinOperatingPoint& op) {
  Scene scene;
  std::string names, paths;
  for (const std::string& f : op.files) {
    names += (names.empty() ? "" : ", ") + std::filesystem::path(f).filename().string();
    paths += (paths.empty() ? "" : ", ") + f;
  }
  scene.name = "openfast: " + names;
  scene.source = paths;
  scene.description = "OpenFAST linearisation: " + std::to_string(op.states.size()) + " states, " +
                      std::to_string(op.inputs.size()) + " inputs, " +
                      std::to_string(op.outputs.size()) + " outputs at " +
                      std::to_string(op.size()) + " azimuths, rotor speed " +
                      MessageNumber(op.rotor_speed) + " rad/s";
  scene.parameters = {
      {"trig", 0,
       "0: each sample held over the azimuths nearest to it (exact product of exponentials); "
       "1: trigonometric interpolation through the samples"},
      {"mbc", 0, "0: the files' coordinates; 1: multi-blade coordinates (MBC3, N >= 3 blades)"}};
  scene.build = [op](const ParameterMap& p) {
    auto flag = [&](const char* name) {
      const double v = p.at(name);
      if (v != 0 && v != 1)
        throw InputError(std::string("parameter '") + name + "' must be 0 or 1, got " +
                         MessageNumber(v));
      return v == 1;
    };
    const SampleInterpolation interpolation =
        flag("trig") ? SampleInterpolation::kTrigonometric : SampleInterpolation::kNearestConstant;
    if (!flag("mbc")) return BuildLinSystem(op, interpolation);
    const Mbc3Result mbc = Mbc3(op);
    return BuildLinSystem(InMultiBladeCoordinates(op, mbc), interpolation);
  };
  return scene;
}

}  // namespace ltp
