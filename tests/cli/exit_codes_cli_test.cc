// The exit-code contract (cli/main.cc): 0 done; 1 the analysis ran and its result is unusable,
// with one line `ltp: failed: …` on stderr naming the cause; 2 input refused, one line
// `ltp: error: …`. Inputs from the robustness reproducers that used to answer unclearly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/ltp_cli.h"

namespace {

using test::RunLtp;
using test::Src;
int Lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

TEST(ExitCodes, FailedAnalysisSaysWhyOnStderr) {
  // Result that fails its own Liouville check (see cli_test.cc), and a time route with no
  // steady state (undamped Mathieu inside a tongue).
  // The reason is the result's typed `failure`, also in its JSON.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"floquet " + Src("tests/data/stiff-rotating.yaml") +
           " --segments 1 --multipliers single-shot",
       "ltp: failed: floquet: monodromy route: Liouville check failed"},
      {"pfrf mathieu --freq 0:1:0.25 --route time --set c=0 --set q=2 --set a=1.5",
       "ltp: failed: pfrf: partial FRFs: primary route time failed at "}};
  for (const auto& [args, reason] : cases) {
    const auto r = RunLtp(args);
    EXPECT_EQ(r.code, 1) << args;
    EXPECT_EQ(Lines(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind(reason, 0), 0u) << r.err;
    const auto j = RunLtp(args + " --json");
    const std::string failure = nlohmann::json::parse(j.out)["failure"];
    EXPECT_NE(reason.find(failure.substr(0, 20)), std::string::npos) << failure;
  }
}

TEST(ExitCodes, ImpossibleToleranceIsRefusedUpFront) {
  const auto r = RunLtp("floquet mathieu --tol 1e-300");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(Lines(r.err), 1);
  EXPECT_NE(r.err.find("double precision"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  // CLI11's own range check used to name its bound as the 309 digits of DBL_MAX.
  const auto negative = RunLtp("floquet mathieu --tol -1");
  EXPECT_EQ(negative.code, 2);
  EXPECT_EQ(negative.err,
            "ltp: error: --tol: must be a finite number > 0, got -1 (see `ltp --help`)\n");
  const auto work = RunLtp("hill mathieu --max-work -0.5");
  EXPECT_EQ(work.code, 2);
  EXPECT_NE(work.err.find("--max-work: must be a finite number >= 0, got -0.5"), std::string::npos)
      << work.err;
}

// A lightly damped system's transient (Mathieu a = 1, c = 0.2: slowest exponent −2.17e-4 1/s by
// `ltp floquet`, so ln(cond Ξ / 1e-10)/2.17e-4 ≈ 1.06e5 s ≈ 33 900 periods of π) is weighed
// before any integration: refused under --max-transient with the count, run above it (the
// fuzzer's timeout: 2.7 s plain, beyond 20 s under the sanitizers).
TEST(ExitCodes, ALongTransientIsRefusedBeforeTheSimulation) {
  const std::string sim =
      "simulate mathieu --set a=1 --set c=0.2 --excitation sine:0.1 --periods 4 "
      "--samples-per-period 16 --out " +
      ::testing::TempDir() + "ltp-transient.csv";
  const auto refused = RunLtp(sim + " --max-transient 2000");
  EXPECT_EQ(refused.code, 2);
  EXPECT_EQ(Lines(refused.err), 1);
  EXPECT_NE(refused.err.find("periods to decay, more than SimulateOptions::max_settle_periods = "
                             "2000 (ltp: --max-transient PERIODS)"),
            std::string::npos)
      << refused.err;
  const auto bad = RunLtp(sim + " --max-transient 0");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--max-transient: must be a finite number > 0"), std::string::npos)
      << bad.err;
}

TEST(ExitCodes, SnapshotTimesAreFiniteAndReducedModuloThePeriod) {
  for (const char* at : {"nan", "inf", "-inf"}) {
    const auto r = RunLtp(std::string("info mathieu --at ") + at);
    EXPECT_EQ(r.code, 2) << at;
    EXPECT_NE(r.err.find("finite"), std::string::npos) << r.err;
  }
  // A huge angle is a valid number: the frozen system is the one at angle mod 360°, so the
  // FRF equals the one at that reduced angle (fmod is exact) and contains no NaN.
  const auto big = RunLtp("snapshot jeffcott --angle 1e308 --freq 0:0.2:0.1 --json");
  ASSERT_EQ(big.code, 0) << big.err;
  EXPECT_EQ(big.out.find("nan"), std::string::npos);
  const double reduced = std::fmod(1e308, 360.0);
  const auto same =
      RunLtp("snapshot jeffcott --angle " + std::to_string(reduced) + " --freq 0:0.2:0.1 --json");
  const auto a = nlohmann::json::parse(big.out), b = nlohmann::json::parse(same.out);
  EXPECT_NEAR(a["time"].get<double>(), b["time"].get<double>(), 1e-9);
}

}  // namespace

namespace {

TEST(ExitCodes, BadSceneTextAndPeriodsAreRefusedWithTheirReason) {
  // A 0xFF byte in the scene name used to surface as nlohmann's raw type_error.316.
  const auto utf =
      RunLtp("floquet " + Src("tests/data/robustness/json_invalid_utf8_name.yaml") + " --json");
  EXPECT_EQ(utf.code, 2);
  EXPECT_NE(utf.err.find("not valid UTF-8"), std::string::npos) << utf.err;
  EXPECT_EQ(utf.err.find("json.exception"), std::string::npos) << utf.err;
  // Byte patterns of UTF-8's shape that are not UTF-8: an encoded surrogate (ED A0 80) and a
  // code point above U+10FFFF (F4 90 80 80) passed the check, then broke the JSON writer.
  for (const char* file : {"json_surrogate_name.yaml", "json_above_unicode_name.yaml"}) {
    const auto bad =
        RunLtp("floquet " + Src(std::string("tests/data/robustness/") + file) + " --json");
    EXPECT_EQ(bad.code, 2) << file;
    EXPECT_NE(bad.err.find("not valid UTF-8"), std::string::npos) << bad.err;
  }
  // sign(sin(1e9 t)): more jumps than the scan locates; it used to run 21 s and then fail.
  const auto jumps = RunLtp("floquet " + Src("tests/data/robustness/hang_sign_sin_1e9t.yaml"));
  EXPECT_EQ(jumps.code, 2);
  EXPECT_NE(jumps.err.find("more jumps than can be located"), std::string::npos) << jumps.err;
  // T = 1e-320 s (subnormal): Ωp = inf, every exponent NaN — used to exit 0 saying UNSTABLE.
  const auto tiny = RunLtp("floquet " + Src("tests/data/robustness/nonsense_denormal_period.yaml"));
  EXPECT_EQ(tiny.code, 2);
  EXPECT_NE(tiny.err.find("period"), std::string::npos) << tiny.err;
}

TEST(ExitCodes, ThreadsAreCappedAtTheMachine) {
  // 10000 threads used to end in libgomp's "Thread creation failed" (exit 1). Same answer as
  // the default now.
  const auto many = RunLtp("floquet mathieu --threads 10000 --json");
  const auto usual = RunLtp("floquet mathieu --json");
  ASSERT_EQ(many.code, 0) << many.err;
  const auto a = nlohmann::json::parse(many.out), b = nlohmann::json::parse(usual.out);
  EXPECT_EQ(a["exponents"], b["exponents"]);
  const auto chart = RunLtp("chart mathieu --sweep a=0:1:0.25 --threads 10000");
  EXPECT_EQ(chart.code, 0) << chart.err;
}

TEST(ExitCodes, SizesBeyondTheLimitsAreRefusedUpFront) {
  // 10^8 chart points and 10^9 segments used to end in `ltp: error: std::bad_alloc`.
  const auto map = RunLtp("chart mathieu --sweep a=0:1:1e-4 --sweep2 q=0:1:1e-4");
  EXPECT_EQ(map.code, 2);
  EXPECT_NE(map.err.find("limit of 10^7"), std::string::npos) << map.err;
  const auto segments = RunLtp("floquet mathieu --segments 1000000000");
  EXPECT_EQ(segments.code, 2);
  EXPECT_NE(segments.err.find("max_segments"), std::string::npos) << segments.err;
  // 5000 × 5000 zeros written compactly with YAML aliases (35 KB): used to hang compiling 25
  // million expressions.
  const auto alias = RunLtp("floquet " + Src("tests/data/robustness/bad_alloc_alias_5000.yaml"));
  EXPECT_EQ(alias.code, 2);
  EXPECT_NE(alias.err.find("limit for expression scenes"), std::string::npos) << alias.err;
  for (const auto& r : {map, segments, alias})
    EXPECT_EQ(r.err.find("std::bad_alloc"), std::string::npos);
}

TEST(ExitCodes, SingularitiesInsideThePeriodAreFoundWhereTheyAre) {
  // A pole at t = 1 and a mass matrix cos(t) singular at π/2 used to hang `floquet` (steps
  // shrinking without end) while `info` said nothing.
  const struct {
    const char* file;
    const char* at;
  } cases[] = {{"hang_pole_inside_period.yaml", "near t = 1 "},
               {"hang_mass_singular_between_checks.yaml", "near t = 1.570796327"}};
  for (const auto& c : cases)
    for (const char* command : {"floquet", "info"}) {
      const auto r =
          RunLtp(std::string(command) + " " + Src(std::string("tests/data/robustness/") + c.file));
      EXPECT_EQ(r.code, 2) << command << " " << c.file;
      EXPECT_NE(r.err.find(c.at), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("unbounded"), std::string::npos) << r.err;
    }
}

TEST(ExitCodes, OutOfScaleSystemsAreRefusedNotIntegratedForHours) {
  // a = 1e200, q = 1e308 and a rotor speed of 1e-300 used to run past 20 s (killed); they are
  // refused up front with T·max‖A‖. Huge but feasible coefficients (q = a = 1e6) still analyse.
  for (const char* args : {"floquet mathieu --set a=1e200", "floquet mathieu --set q=1e308",
                           "floquet rotor --set Omega=1e-300"}) {
    const auto r = RunLtp(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find("max_period_scale"), std::string::npos) << r.err;
  }
  EXPECT_EQ(RunLtp("floquet mathieu --set a=1e6 --set q=1e6").code, 0);
  // A pipe given as the scene used to block forever.
  EXPECT_EQ(RunLtp("info /dev/stdin < /dev/null").code, 2);
}

}  // namespace
