// The `ltp` command line as a function (main.cc calls it; so does the argument fuzzer).
// Exit codes: 0 done; 1 the analysis ran and its result is unusable (failed its own checks, no
// steady state, …: the report is on stdout, one line `ltp: failed: …` on stderr); 2 the input was
// refused (one line `ltp: error: …` on stderr).
#include "run_ltp.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "command.h"
#include "ltp/core/error.h"
#include "ltp/integrate/threads.h"

namespace ltp::cli {

int RunLtp(int argc, char** argv) {
  CLI::App app{"ltp — analysis of linear time-periodic systems (Floquet, Hill, partial FRFs)",
               "ltp"};
  FailureReason().clear();
  UseSingleThreadedBlas();  // ltp runs its own threads (see threads.h)
  app.set_version_flag("--version", std::string("ltp ") + LTP_VERSION);
  app.require_subcommand(1);
  app.footer(
      "SCENE is a built-in scene (`ltp scenes`), a YAML scene file (examples in scenes/), or "
      "OpenFAST .lin files (files, a directory or a quoted glob).");

  const std::vector<Command> commands = {
      AddScenesCommand(app),   AddInfoCommand(app),     AddFloquetCommand(app),
      AddHillCommand(app),     AddPfrfCommand(app),     AddOrbitCommand(app),
      AddSnapshotCommand(app), AddChartCommand(app),    AddMbcCommand(app),
      AddCampbellCommand(app), AddSimulateCommand(app), AddIdentifyCommand(app),
  };
  // Subcommands inherit the footer; it explains SCENE, so only those that take one keep it.
  for (const auto& c : commands)
    if (!c.app->get_option_no_throw("scene")) c.app->footer("");

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
      if (c.app->parsed()) {
        const int code = c.run();
        if (code == 1) {
          std::string reason = FailureReason();
          if (reason.empty())
            reason = "the analysis ran but its result is unusable (report on stdout)";
          for (char& ch : reason)
            if (ch == '\n') ch = ' ';
          if (reason.size() > 400) reason = reason.substr(0, 400) + " …";
          std::cerr << "ltp: failed: " << c.app->get_name() << ": " << reason << "\n";
        }
        return code;
      }
  } catch (const std::exception& e) {
    std::string message = e.what();  // one line, whatever the library's message holds
    for (char& ch : message)
      if (ch == '\n') ch = ' ';
    std::cerr << "ltp: error: " << message << "\n";
    return 2;
  }
  return 0;
}

}  // namespace ltp::cli
