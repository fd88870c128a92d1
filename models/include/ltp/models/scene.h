#pragma once
// Scenes: named, parametrised recipes that build a PeriodicSystem. Built-in scenes (mathieu,
// meissner, jeffcott, ...) and YAML scene files (numbers or muParser expressions in t and
// named parameters) give the same type, so every command takes either.
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/models/structure_geometry.h"

namespace ltp {

using ParameterMap = std::map<std::string, double>;

struct SceneParameter {
  std::string name;
  double value = 0;         ///< default
  std::string description;  ///< one line, with units
};

struct Scene {
  std::string name;
  std::string description;
  std::string source;  ///< "built-in" or the file path
  std::vector<SceneParameter> parameters;
  /// Builds the system for fully resolved parameters. @throws InputError, SceneError.
  std::function<PeriodicSystem(const ParameterMap&)> build;
  /// The structure to draw for resolved parameters, for scenes that have one (tower-rotor);
  /// empty otherwise. Its coordinates are the system's first states (a second-order system).
  /// @throws InputError, as `build`.
  std::function<GeometryAt(const ParameterMap&)> geometry;

  /// Defaults overridden by `overrides` ("name=value" pairs; values may be expressions in
  /// numbers and pi). @throws InputError on an unknown name, a bad expression or NaN/inf.
  ParameterMap Resolve(const std::vector<std::pair<std::string, std::string>>& overrides) const;
  /// Resolve + build.
  PeriodicSystem Build(
      const std::vector<std::pair<std::string, std::string>>& overrides = {}) const;
};

/// The built-in scenes, in display order.
const std::vector<Scene>& BuiltinScenes();

/// A built-in scene by name, or else a YAML scene file by path.
/// @throws InputError (unknown scene, listing the built-ins), SceneError (file problems).
Scene LoadScene(const std::string& name_or_path);

/// Parses a YAML scene file. @throws SceneError naming file, line and entry.
Scene LoadSceneFile(const std::string& path);
/// Parses YAML text; `source` names it in error messages.
Scene ParseSceneYaml(const std::string& text, const std::string& source);

/// Splits "name=value" into its two parts. @throws InputError if there is no '='.
std::pair<std::string, std::string> SplitAssignment(const std::string& text);

}  // namespace ltp
