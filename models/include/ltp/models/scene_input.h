#pragma once
// What a user names as the system to analyse — a built-in scene, a YAML scene file, or OpenFAST
// .lin files at one operating point — with parameter overrides, loaded and built. The CLI's
// SCENE argument and Python's `ltp.scene` both go through here.
#include <string>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/models/scene.h"

namespace ltp {

struct LoadedScene {
  Scene scene;
  ParameterMap parameters;  ///< every parameter, resolved
  PeriodicSystem system;
  /// Caveats that belong beside any result (for .lin input: what K azimuth samples resolve,
  /// the rigid rotation). The library does not print them.
  std::vector<std::string> notes;
};

/// `names`: one built-in name or YAML file, or one or more .lin files (several files, a
/// directory or a glob). `assignments`: "name=value" (values may be expressions in pi).
/// @throws InputError (unknown scene or parameter, bad value), SceneError (file problems).
LoadedScene LoadSceneInput(const std::vector<std::string>& names,
                           const std::vector<std::string>& assignments = {});

}  // namespace ltp
