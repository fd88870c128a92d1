// The `ltp` command. Errors: one line on stderr, exit code 2. Unusable numerical results:
// exit code 1.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "command.h"
#include "ltp/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"ltp — analysis of linear time-periodic systems (Floquet, Hill, partial FRFs)",
               "ltp"};
  app.set_version_flag("--version", std::string("ltp ") + LTP_VERSION);
  app.require_subcommand(1);
  app.footer("SCENE is a built-in scene (`ltp scenes`), a YAML scene file (examples in scenes/), or OpenFAST .lin files (files, a directory or a quoted glob).");

  const std::vector<ltp::cli::Command> commands = {
      ltp::cli::AddScenesCommand(app),
      ltp::cli::AddInfoCommand(app),
      ltp::cli::AddFloquetCommand(app),
      ltp::cli::AddHillCommand(app),
      ltp::cli::AddPfrfCommand(app),
      ltp::cli::AddSnapshotCommand(app),
      ltp::cli::AddChartCommand(app),
      ltp::cli::AddMbcCommand(app),
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "ltp: error: " << e.what() << " (see `ltp --help`)\n";
    return 2;
  }
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const std::exception& e) {
    std::string message = e.what();  // one line, whatever the library's message holds
    for (char& ch : message)
      if (ch == '\n') ch = ' ';
    std::cerr << "ltp: error: " << message << "\n";
    return 2;
  }
  return 0;
}
