#include "scene_args.h"

#include <sstream>

#include "format.h"

namespace ltp::cli {

void AddSceneArgs(CLI::App* cmd, SceneArgs& args) {
  cmd->add_option("scene", args.scene, "built-in scene name (see `ltp scenes`) or a YAML scene file")
      ->required();
  cmd->add_option("--set", args.set, "override a scene parameter: --set name=value (repeatable)")
      ->type_name("NAME=VALUE");
}

LoadedScene LoadSceneArgs(const SceneArgs& args) {
  Scene scene = LoadScene(args.scene);
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const std::string& s : args.set) overrides.push_back(SplitAssignment(s));
  ParameterMap parameters = scene.Resolve(overrides);
  PeriodicSystem system = scene.build(parameters);
  return {std::move(scene), std::move(parameters), std::move(system)};
}

std::string ParameterList(const ParameterMap& p) {
  std::ostringstream s;
  bool first = true;
  for (const auto& [name, value] : p) {
    s << (first ? "" : ", ") << name << "=" << Num(value, 8);
    first = false;
  }
  return s.str();
}

nlohmann::json ParametersJson(const ParameterMap& p) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, value] : p) j[name] = JsonNumber(value);
  return j;
}

}  // namespace ltp::cli
