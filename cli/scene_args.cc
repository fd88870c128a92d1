#include "scene_args.h"

#include <iostream>
#include <sstream>

#include "format.h"

namespace ltp::cli {

void AddSceneArgs(CLI::App* cmd, SceneArgs& args) {
  cmd->add_option("scene", args.scene,
                  "built-in scene name (see `ltp scenes`), a YAML scene file, or OpenFAST .lin "
                  "files at one operating point (several files, a directory or a glob)")
      ->required();
  cmd->add_option("more-files", args.more_files, "further OpenFAST .lin files (with SCENE.lin)");
  cmd->add_option("--set", args.set, "override a scene parameter: --set name=value (repeatable)")
      ->type_name("NAME=VALUE");
}

LoadedScene LoadSceneArgs(const SceneArgs& args) {
  std::vector<std::string> names{args.scene};
  names.insert(names.end(), args.more_files.begin(), args.more_files.end());
  LoadedScene loaded = LoadSceneInput(names, args.set);
  // Commands print their own results; the caveats go beside them on stderr (stdout may be JSON).
  for (const Diagnostic& d : loaded.diagnostics) std::cerr << "ltp: note: " << d.text << "\n";
  return loaded;
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
