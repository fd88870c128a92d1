// The `ltp` command (exit codes: cli/run_ltp.cc).
#include "run_ltp.h"

int main(int argc, char** argv) { return ltp::cli::RunLtp(argc, argv); }
