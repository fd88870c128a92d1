#include "scene_args.h"

#include <iostream>
#include <optional>
#include <sstream>

#include "format.h"
#include "ltp/core/error.h"
#include "ltp/core/mbc3.h"
#include "ltp/core/openfast_lin.h"

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
  std::optional<LinOperatingPoint> op;
  Scene scene;
  if (!args.more_files.empty() && !LooksLikeLinInput(args.scene))
    throw InputError("unexpected argument '" + args.more_files.front() + "' after scene '" +
                     args.scene + "': only OpenFAST .lin input takes several files");
  if (!args.more_files.empty() || LooksLikeLinInput(args.scene)) {
    std::vector<std::string> files{args.scene};
    files.insert(files.end(), args.more_files.begin(), args.more_files.end());
    op = ReadLinOperatingPoint(files);
    scene = MakeLinScene(*op);
  } else {
    scene = LoadScene(args.scene);
  }
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const std::string& s : args.set) overrides.push_back(SplitAssignment(s));
  ParameterMap parameters = scene.Resolve(overrides);
  PeriodicSystem system = scene.build(parameters);
  std::vector<std::string> notes;
  if (op)  // the caveats of the coordinates actually analysed
    notes = LinCaveats(parameters.at("mbc") == 1 ? InMultiBladeCoordinates(*op, Mbc3(*op)) : *op);
  // Commands print their own results; the caveats go beside them on stderr (stdout may be JSON).
  for (const std::string& note : notes) std::cerr << "ltp: note: " << note << "\n";
  return {std::move(scene), std::move(parameters), std::move(system), std::move(notes)};
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
