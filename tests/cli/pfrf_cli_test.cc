// End-to-end: `ltp pfrf` and `ltp snapshot` as a user runs them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/ltp_cli.h"

namespace {

using CliRun = test::LtpRun;
CliRun Ltp(const std::string& args) { return test::RunLtp(args); }

TEST(PfrfCli, JsonAndCsv) {
  const std::string csv = std::string(::testing::TempDir()) + "pfrf.csv";
  const CliRun r =
      Ltp("pfrf jeffcott --set c=0.05 --set Omega=0.6 --input fy --output x "
          "--freq 0:0.5:0.01 --orders -2:2 --json --csv " +
          csv);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["input"], 1);  // "fy" by name
  EXPECT_EQ(j["values"].size(), 51u * 5u);
  EXPECT_LT(j["max_relative_disagreement"].get<double>(), 1e-9);  // modal vs htf
  std::ifstream f(csv);
  std::string header;
  std::getline(f, header);
  EXPECT_EQ(header.rfind("f_exc_hz,z,f_resp_hz,re,im,abs,phase_deg,error_estimate", 0), 0u)
      << header;
}

TEST(PfrfCli, OneFrequencyTable) {
  const CliRun r =
      Ltp("pfrf mathieu --set a=2 --set c=0.2 --freq 0.3:0.3:1 --route all --orders -1:1");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* want : {"modal", "htf", "shooting", "time", "max disagreement"})
    EXPECT_NE(r.out.find(want), std::string::npos) << want;
}

TEST(PfrfCli, SnapshotCompare) {
  const CliRun r =
      Ltp("snapshot jeffcott --set c=0.05 --angle 30 --freq 0:0.5:0.05 --compare --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["values"].size(), 11u);
  EXPECT_LT(j["max_summed_disagreement"].get<double>(), 1e-9);
}

TEST(PfrfCli, BadInputExitTwoOneLine) {
  for (const char* args :
       {"pfrf mathieu --freq 1:0:0.1", "pfrf mathieu --freq 0:1:0.1 --input nope",
        "pfrf mathieu --freq 0:1:0.1 --route fast", "pfrf mathieu --freq a:b:c",
        "pfrf mathieu --freq 0:1:0.1 --orders 3:-3", "snapshot mathieu --angle 10 --freq 0:1:0.1",
        "snapshot mathieu --freq 0:1:0.1"}) {
    const CliRun r = Ltp(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

}  // namespace
