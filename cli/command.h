#pragma once
// Each `ltp` subcommand lives in its own file and registers itself with the CLI11 app: it adds
// its options (bound to state it owns) and returns what to run when it was chosen. Commands
// parse and write; the numbers come from the library.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace ltp::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;  ///< exit code: 0 ok, 1 result unusable; throws ltp::Error → 2
};

/// Why a command's result is unusable (exit 1): `main` prints it as one line `ltp: failed: …`
/// on stderr, so scripts and sweeps can log the cause (the full report is on stdout).
inline std::string& FailureReason() {
  static std::string reason;
  return reason;
}
/// The exit reason of a failed analysis: its typed `failure` (FloquetResult, HillResult,
/// PfrfResult), prefixed by `what`.
inline void SetFailureFrom(const std::string& what, const std::string& failure) {
  FailureReason() = what + ": " + (failure.empty() ? "it failed its own checks" : failure);
}

/// A flag's finite number > 0 (or >= 0 with `or_zero`). CLI11's PositiveNumber and
/// NonNegativeNumber (the same checks) say "not in range 0.000000 to" the 309 digits of DBL_MAX;
/// this says "--tol: must be a finite number > 0, got -1".
inline CLI::Validator NumberAboveZero(bool or_zero = false) {
  return CLI::Validator(
      [or_zero](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return "'" + text + "' is not a number";
        if (std::isfinite(x) && (or_zero ? x >= 0 : x > 0)) return {};
        return std::string("must be a finite number ") + (or_zero ? ">= 0" : "> 0") + ", got " +
               text;
      },
      or_zero ? "NONNEGATIVE" : "POSITIVE");
}

Command AddScenesCommand(CLI::App& app);
Command AddInfoCommand(CLI::App& app);
Command AddFloquetCommand(CLI::App& app);
Command AddHillCommand(CLI::App& app);
Command AddPfrfCommand(CLI::App&app), AddSnapshotCommand(CLI::App&app);
Command AddOrbitCommand(CLI::App& app);
Command AddChartCommand(CLI::App& app);
Command AddMbcCommand(CLI::App& app);
Command AddCampbellCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App&app), AddIdentifyCommand(CLI::App&app);

}  // namespace ltp::cli
