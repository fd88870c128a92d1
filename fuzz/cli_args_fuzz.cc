// Fuzz target: the `ltp` command line. The input is an argument vector, one argument per line;
// RunLtp runs it in-process, printing into the void, and must return 0, 1 or 2 (or 130 for a
// chart the harness stopped) — never crash,
// never let an untyped exception out (it catches everything itself), never hang.
//
// The harness bounds the work, not the parsing: the fuzzer should find inputs the CLI handles
// badly, not legitimate long analyses (a 10^6-point chart is allowed and shows progress). So
// charts stop after a few points (--stop-after, as Ctrl-C would), frequency lists and sweeps
// above a few hundred points, truncations above 48 harmonics, parameters above 1e4, more than
// 1e5 fixed steps per period and tolerances below 1e-12 are skipped, and so are
// arguments that would write outside the working directory or start gnuplot.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "frf_args.h"
#include "ltp/htf/frequency_range.h"
#include "ltp/studies/sweep.h"
#include "run_ltp.h"

namespace {

bool StartsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Value of "--opt V" or "--opt=V" at position i, or nullptr.
const std::string* ValueOf(const std::vector<std::string>& args, size_t i, const char* opt,
                           std::string& scratch) {
  const std::string o(opt);
  if (args[i] == o) return i + 1 < args.size() ? &args[i + 1] : nullptr;
  if (StartsWith(args[i], (o + "=").c_str())) {
    scratch = args[i].substr(o.size() + 1);
    return &scratch;
  }
  return nullptr;
}

// True when running these arguments could take long for a legitimate reason.
bool TooMuchWork(const std::vector<std::string>& args) {
  constexpr size_t kMaxPoints = 400;
  constexpr int kMaxHarmonics = 48;
  std::string scratch;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i].find('/') != std::string::npos || StartsWith(args[i], "--plot") ||
        StartsWith(args[i], "--stop-after"))
      return true;
    try {
      // orbit checks every frequency by the second route (tower-rotor: 400 frequencies 2.6 s
      // plain): a quarter of the points.
      if (const std::string* v = ValueOf(args, i, "--freq", scratch))
        if (ltp::ParseFrequencyList(*v, "--freq").size() >
            (args[1] == "orbit" ? kMaxPoints / 4 : kMaxPoints))
          return true;
      for (const char* sweep : {"--sweep", "--sweep2"})
        if (const std::string* v = ValueOf(args, i, sweep, scratch)) {
          const ltp::SweepAxis a = ltp::SweepAxis::Parse(*v);
          if (std::abs((a.stop - a.start) / a.step) > kMaxPoints) return true;
        }
      // Coefficients beyond 1e4 make stiff systems: seconds of honest work each (10× that
      // under the sanitizers); the reproducers of that class are regression tests instead.
      if (const std::string* v = ValueOf(args, i, "--set", scratch)) {
        const size_t eq = v->find('=');
        if (eq != std::string::npos && std::abs(std::atof(v->c_str() + eq + 1)) > 1e4) return true;
      }
      // Simulated time data: records × periods × samples of honest integration.
      if (const std::string* v = ValueOf(args, i, "--periods", scratch))
        if (std::atof(v->c_str()) > 64) return true;
      if (const std::string* v = ValueOf(args, i, "--samples-per-period", scratch))
        if (std::atof(v->c_str()) > 256) return true;
      if (const std::string* v = ValueOf(args, i, "--excitation", scratch)) {
        if (StartsWith(*v, "stepsine:") &&
            ltp::ParseFrequencyRange(v->substr(9), "--excitation").size() > 20)
          return true;
        if (StartsWith(*v, "multisine:") &&
            ltp::ParseFrequencyRange(v->substr(10), "--excitation").size() > kMaxPoints)
          return true;
        if (StartsWith(*v, "noise:")) {
          const auto [f0, f1] = ltp::ParseFrequencyBand(v->substr(6), "--excitation");
          if (f1 - f0 > 5) return true;  // every grid line of the band: thousands of lines
        }
      }
      // Fixed-step runs and tight tolerances: honest work proportional to the steps asked for
      // (flap, magnus6: 1e7 steps per period 7 s plain, minutes sanitized; expm at 1e-13 3 s
      // plain) — announced by the CLI's work estimate, not a finding.
      if (const std::string* v = ValueOf(args, i, "--steps", scratch))
        if (std::atof(v->c_str()) > 1e5) return true;
      if (const std::string* v = ValueOf(args, i, "--tol", scratch))
        if (std::atof(v->c_str()) < 1e-12) return true;
      if (const std::string* v = ValueOf(args, i, "--records", scratch))
        if (std::atof(v->c_str()) > 12) return true;
      for (const char* h : {"--harmonics", "--max-harmonics", "--htf-harmonics"})
        if (const std::string* v = ValueOf(args, i, h, scratch))
          if (std::atof(v->c_str()) > kMaxHarmonics) return true;
    } catch (...) {
      // unparsable: the CLI will refuse it, which is what we want to exercise
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Outputs (--csv, --json files, chart journals) land in a scratch directory.
  const auto dir =
      std::filesystem::temp_directory_path() / ("ltp-fuzz-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::filesystem::current_path(dir);
  std::cout.setstate(std::ios::failbit);  // results are not what is tested here
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 2000) return -1;
  std::vector<std::string> args = {"ltp"};
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  for (std::string line; std::getline(lines, line);) args.push_back(line);
  if (args.size() > 24 || TooMuchWork(args)) return -1;
  const bool chart = args.size() > 1 && args[1] == "chart";
  if (chart) {
    args.push_back("--stop-after");
    args.push_back("3");
  }
  // Commands whose own limit bounds their work get it tight here (an input that sets it itself
  // is skipped): the analyses that weigh their work refuse more than 0.1 s of it by their own
  // estimate (timed in this process, so the sanitizers' slowdown is in it), and
  // `floquet tower-rotor --method both` (5 s plain) is not a finding; a simulation's transient
  // (mathieu a=1 c=0.2: 34 000 periods per record, 2.7 s plain) stops at 2000 periods.
  struct Bound {
    const char* command;
    const char* option;
    const char* value;
  };
  static constexpr Bound kBounds[] = {{"floquet", "--max-work", "0.1"},
                                      {"hill", "--max-work", "0.1"},
                                      {"simulate", "--max-transient", "2000"}};
  for (const Bound& bound : kBounds) {
    if (args.size() < 2 || args[1] != bound.command) continue;
    for (const std::string& a : args)
      if (StartsWith(a, bound.option)) return -1;
    args.push_back(bound.option);
    args.push_back(bound.value);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  std::streambuf* err = std::cerr.rdbuf(nullptr);  // one-line messages: not checked here
  const int code = ltp::cli::RunLtp(static_cast<int>(args.size()), argv.data());
  std::cerr.rdbuf(err);
  const bool interrupted = chart && code == 130;  // --stop-after, as after Ctrl-C
  if ((code < 0 || code > 2) && !interrupted) {
    std::fprintf(stderr, "fuzz finding: exit code %d\n", code);
    std::abort();
  }
  return 0;
}
