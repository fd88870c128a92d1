// An OpenFAST operating point as a scene (ltp/models/lin_scene.h).
#include "ltp/models/lin_scene.h"

#include <filesystem>
#include <string>

#include "ltp/core/error.h"
#include "ltp/openfast/mbc3.h"

namespace ltp {

std::shared_ptr<const Mbc3Result> Mbc3OrNull(const LinOperatingPoint& op) {
  try {
    return std::make_shared<const Mbc3Result>(Mbc3(op));
  } catch (const InputError&) {
    return nullptr;  // blade channels not recognised: the files' coordinates
  }
}

Scene MakeLinScene(const LinOperatingPoint& op, std::shared_ptr<const Mbc3Result> mbc) {
  if (!mbc) mbc = Mbc3OrNull(op);
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
  // Default: the most accurate route the samples allow (docs/sampled-models.md) — the
  // trigonometric interpolation, which is exact for A(ψ) within the resolved harmonics where
  // the hold is O(Δψ²), in multi-blade coordinates when MBC applies: an isotropic rotor is
  // time-invariant there, so its samples are equal and any interpolation of them exact.
  const bool mbc_applies = mbc && mbc->applicable;
  scene.parameters = {
      {"trig", 1,
       "1: trigonometric interpolation through the samples (default); 0: each sample held over "
       "the azimuths nearest to it (exact product of exponentials)"},
      {"mbc", mbc_applies ? 1.0 : 0.0,
       "1: multi-blade coordinates (MBC3, N >= 3 blades; the default when they apply); 0: the "
       "files' coordinates"}};
  scene.build = [op, mbc](const ParameterMap& p) {
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
    if (!mbc)
      return BuildLinSystem(InMultiBladeCoordinates(op, Mbc3(op)), interpolation);  // throws
    return BuildLinSystem(InMultiBladeCoordinates(op, *mbc), interpolation);
  };
  return scene;
}

}  // namespace ltp
