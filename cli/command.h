#pragma once
// Each `ltp` subcommand lives in its own file and registers itself with the CLI11 app: it adds
// its options (bound to state it owns) and returns what to run when it was chosen. Commands
// parse and write; the numbers come from the library.
#include <CLI/CLI.hpp>
#include <functional>

namespace ltp::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;  ///< exit code: 0 ok, 1 result unusable; throws ltp::Error → 2
};

Command AddScenesCommand(CLI::App& app);
Command AddInfoCommand(CLI::App& app);
Command AddFloquetCommand(CLI::App& app);
Command AddHillCommand(CLI::App& app);
Command AddPfrfCommand(CLI::App& app), AddSnapshotCommand(CLI::App& app);
Command AddChartCommand(CLI::App& app);
Command AddMbcCommand(CLI::App& app);

}  // namespace ltp::cli
