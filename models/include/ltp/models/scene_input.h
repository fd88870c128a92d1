#pragma once
// What a user names as the system to analyse — a built-in scene, a YAML scene file, or OpenFAST
// .lin files at one operating point — with parameter overrides, loaded and built. The CLI's
// SCENE argument and Python's `ltp.scene` both go through here.
#include <optional>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/models/scene.h"

namespace ltp {

struct LoadedScene {
  Scene scene;
  ParameterMap parameters;  ///< every parameter, resolved
  PeriodicSystem system;
  /// Caveats that belong beside any result (for .lin input: what K azimuth samples resolve,
  /// the rigid rotation). The library does not print them.
  std::vector<Diagnostic> diagnostics;
  /// For a model built from samples (.lin input): the same samples through the other
  /// interpolation (trigonometric ↔ nearest-sample hold) and, when MBC applies, the same
  /// interpolation in the other coordinates (multi-blade ↔ the files'). How far their exponents
  /// are from the analysed system's is the sampling part of its error estimate
  /// (IncludeModelError in ltp/floquet/model_error.h; docs/sampled-models.md). Empty otherwise.
  std::vector<PeriodicSystem> model_alternatives;
};

/// `names`: one built-in name or YAML file, or one or more .lin files (several files, a
/// directory or a glob). `assignments`: "name=value" (values may be expressions in pi).
/// @throws InputError (unknown scene or parameter, bad value), SceneError (file problems).
LoadedScene LoadSceneInput(const std::vector<std::string>& names,
                           const std::vector<std::string>& assignments = {});

}  // namespace ltp
