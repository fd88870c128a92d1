#pragma once
// The SCENE argument and --set overrides shared by every command that analyses a scene.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ltp/core/scene.h"

namespace ltp::cli {

struct SceneArgs {
  std::string scene;
  std::vector<std::string> set;  ///< "name=value"
};

/// Adds the positional SCENE and the repeatable --set NAME=VALUE to `cmd`.
void AddSceneArgs(CLI::App* cmd, SceneArgs& args);

struct LoadedScene {
  Scene scene;
  ParameterMap parameters;
  PeriodicSystem system;
};

/// Loads the scene, applies the overrides and builds the system. @throws ltp::InputError.
LoadedScene LoadSceneArgs(const SceneArgs& args);

/// "a=1.5, q=2" for headers.
std::string ParameterList(const ParameterMap& p);
nlohmann::json ParametersJson(const ParameterMap& p);

}  // namespace ltp::cli
