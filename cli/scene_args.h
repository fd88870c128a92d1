#pragma once
// The SCENE argument and --set overrides shared by every command that analyses a scene.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ltp/models/scene.h"
#include "ltp/models/scene_input.h"

namespace ltp::cli {

struct SceneArgs {
  std::string scene;
  std::vector<std::string> more_files;  ///< further OpenFAST .lin files after the first
  std::vector<std::string> set;         ///< "name=value"
};

/// Adds the positional SCENE (a built-in, a YAML file, or OpenFAST .lin files: several files,
/// a directory or a glob) and the repeatable --set NAME=VALUE to `cmd`.
void AddSceneArgs(CLI::App* cmd, SceneArgs& args);

using LoadedScene = ltp::LoadedScene;

/// LoadSceneInput, with the notes printed on stderr. @throws ltp::InputError.
LoadedScene LoadSceneArgs(const SceneArgs& args);

/// "a=1.5, q=2" for headers.
std::string ParameterList(const ParameterMap& p);
nlohmann::json ParametersJson(const ParameterMap& p);

}  // namespace ltp::cli
