#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.h"
#include "format.h"
#include "ltp/models/scene.h"

namespace ltp::cli {

namespace {

using nlohmann::json;

int RunScenes(bool as_json) {
  json list = json::array();
  for (const Scene& s : BuiltinScenes()) {
    if (as_json) {
      json params = json::array();
      for (const auto& p : s.parameters)
        params.push_back({{"name", p.name}, {"default", p.value}, {"description", p.description}});
      list.push_back({{"name", s.name}, {"description", s.description}, {"parameters", params}});
      continue;
    }
    std::cout << s.name << "\n    " << s.description << "\n";
    for (const auto& p : s.parameters)
      std::cout << "    " << std::left << std::setw(8) << p.name << std::right << std::setw(10)
                << Num(p.value, 6) << "   " << p.description << "\n";
    std::cout << "\n";
  }
  if (as_json) {
    std::cout << list.dump(2) << "\n";
  } else {
    std::cout << "Scene files (YAML) work wherever a scene name does; examples in scenes/.\n";
  }
  return 0;
}

}  // namespace

Command AddScenesCommand(CLI::App& app) {
  static bool json_flag = false;
  json_flag = false;  // fresh state for each RunLtp call
  auto* cmd = app.add_subcommand("scenes", "list the built-in scenes with their parameters");
  cmd->add_flag("--json", json_flag, "machine-readable output on stdout");
  return {cmd, [] { return RunScenes(json_flag); }};
}

}  // namespace ltp::cli
