#pragma once
// Runs the `ltp` binary (LTP_BINARY, set by tests/CMakeLists.txt) as a user would.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace test {

struct LtpRun {
  int code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

inline LtpRun RunLtp(const std::string& args, const std::string& prefix = "") {
  // One stderr file per process and call: ctest runs tests in parallel processes.
  static int calls = 0;
  const std::string err_file = std::string(::testing::TempDir()) + "ltp_stderr_" +
                               std::to_string(getpid()) + "_" + std::to_string(++calls) + ".txt";
  const std::string cmd = prefix + std::string(LTP_BINARY) + " " + args + " 2>" + err_file;
  LtpRun r;
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf;
  while (p && fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int status = p ? pclose(p) : -1;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_file);
  std::stringstream s;
  s << e.rdbuf();
  r.err = s.str();
  std::remove(err_file.c_str());
  return r;
}

/// A path in the source tree (LTP_SOURCE_DIR, set by tests/CMakeLists.txt).
inline std::string Src(const std::string& relative) {
  return std::string(LTP_SOURCE_DIR) + "/" + relative;
}

inline std::string ReadFile(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace test
