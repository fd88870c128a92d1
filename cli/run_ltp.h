#pragma once
// The whole `ltp` command line as a function: parses argv, runs the chosen command and returns its
// exit code (0 done, 1 result unusable, 2 input refused), printing as the executable does.

namespace ltp::cli {

int RunLtp(int argc, char** argv);

}  // namespace ltp::cli
