// End-to-end: `ltp mbc` and the scene commands on OpenFAST .lin files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/isotropic_rotor_lin.h"
#include "support/ltp_cli.h"

namespace {

using Outcome = test::LtpRun;
Outcome Ltp(const std::string& args) { return test::RunLtp(args); }

const std::string kData = std::string(LTP_SOURCE_DIR) + "/tests/data/openfast/nrel5mw-rotating";

// Keys of `ltp mbc --json`; the first four oscillatory modes against OpenFAST's published
// numbers for these files (openfast_toolbox ex2a_MultiLinFiles_OneOP.py, 3 decimals).
TEST(MbcCli, JsonCampbellTable) {
  const Outcome r = Ltp("mbc " + kData + "/Main.1.lin " + kData + "/Main.12.lin " + kData +
                        "/Main.24.lin --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"rotor_speed_rad_s", "azimuths_rad", "blades", "modes", "floquet"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["blades"], 3);
  EXPECT_EQ(j["rotor_speed_rad_s"], 0.9425);  // header "Rotor Speed: 0.9425 rad/s"
  EXPECT_EQ(j["azimuths_rad"], nlohmann::json({0.0092, 1.9224, 4.0147}));
  const auto& modes = j["modes"];
  ASSERT_EQ(modes.size(), 11u);
  double last = -1;
  int rigid = 0;
  std::vector<nlohmann::json> oscillatory;
  for (const auto& m : modes) {
    for (const char* key : {"natural_frequency_hz", "damped_frequency_hz", "damping_ratio",
                            "description", "rigid_body"})
      EXPECT_TRUE(m.contains(key)) << key;
    EXPECT_GE(m["natural_frequency_hz"].get<double>(), last);
    last = m["natural_frequency_hz"];
    rigid += m["rigid_body"].get<bool>();
    if (m["kind"] == "oscillatory") oscillatory.push_back(m);
  }
  EXPECT_EQ(rigid, 1);
  const double freq[] = {0.588, 0.722, 0.842, 0.937}, damp[] = {63.106, 52.529, 44.01, 1.634};
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(oscillatory[k]["natural_frequency_hz"].get<double>(), freq[k], 1.5e-3);
    EXPECT_NEAR(100 * oscillatory[k]["damping_ratio"].get<double>(), damp[k], 1.5e-3);
  }
  EXPECT_EQ(j["floquet"]["modes"].size(), 11u);
  EXPECT_TRUE(j["floquet"]["stable"].get<bool>());
}

TEST(MbcCli, TextTableCsvAndGlob) {
  const std::string csv = std::string(::testing::TempDir()) + "campbell.csv";
  const Outcome r = Ltp("mbc '" + kData + "/*.lin' --csv " + csv);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("rigid body"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Floquet analysis of the same 3 samples"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 azimuths hold only harmonics 0 and ±1"), std::string::npos) << r.out;
  std::ifstream in(csv);
  std::string line;
  int rows = 0;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("mode,natural_frequency_hz,damped_frequency_hz,damping_ratio", 0), 0u)
      << line;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 11);
}

TEST(MbcCli, SceneCommandsTakeLinFiles) {
  // A directory, and the files one by one; the caveats go to stderr, stdout stays JSON.
  Outcome r = Ltp("floquet " + kData + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["states"], 20);
  EXPECT_NEAR(j["period"].get<double>(), 2 * 3.141592653589793 / 0.9425, 1e-12);
  EXPECT_NE(r.err.find("rigid"), std::string::npos) << r.err;
  r = Ltp("info " + kData + "/Main.1.lin " + kData + "/Main.12.lin " + kData +
          "/Main.24.lin --set trig=1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["form"], "Fourier series");
  EXPECT_EQ(j["harmonics"]["A"]["harmonics"], 1);  // 3 samples: harmonics 0 and ±1 only
}

TEST(MbcCli, MalformedFileIsOneErrorLineAndExitTwo) {
  const std::string bad = std::string(::testing::TempDir()) + "bad.1.lin";
  {
    std::ifstream in(kData + "/Main.1.lin");
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    s.replace(s.find("A: 20 x 20"), 10, "A: 20 x 21");
    std::ofstream(bad) << s;
  }
  for (const std::string& cmd : {"mbc " + bad, "floquet " + bad}) {
    const Outcome r = Ltp(cmd);
    EXPECT_EQ(r.code, 2) << cmd;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(bad + ":71: expected 21 numbers in row 1 of matrix A"), std::string::npos)
        << r.err;
  }
  const Outcome missing = Ltp("mbc " + kData + "/Main.99.lin");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("no such file"), std::string::npos) << missing.err;
}

}  // namespace

namespace sampled {

// Generated rotating-frame files of an isotropic rotor (tests/support/isotropic_rotor_lin.h):
// exact exponents are the eigenvalues of its constant multi-blade matrix.
const ltp::test::IsotropicRotorLin& Rotor() {
  static const auto model = ltp::test::MakeIsotropicRotorLin(4, 4, ltp::test::EvenAzimuths(3));
  return model;
}
std::string RotorDir() {
  static const std::string dir =
      ltp::test::WriteLinDirectory(Rotor().files, std::string(::testing::TempDir()) + "iso-cli");
  return dir;
}
double ExactMaxReal() {
  double m = -1e300;
  for (auto l : Rotor().exponents) m = std::max(m, l.real());
  return m;
}

TEST(MbcCli, FloquetOnLinFilesDefaultsToTheExactRouteAndCountsTheModelError) {
  Outcome r = Ltp("floquet " + RotorDir() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["verdict"], "stable");
  ASSERT_TRUE(j["model_error"].is_number());
  const double estimate = j["error_estimate"].get<double>();
  EXPECT_GE(estimate, j["model_error"].get<double>());
  EXPECT_LE(std::abs(j["max_real_exponent"].get<double>() - ExactMaxReal()), estimate);
  // The old default, held samples in blade coordinates, is far off (+0.02 for an exact −0.01
  // here): its estimate now covers that and the verdict is not "unstable".
  r = Ltp("floquet " + RotorDir() + " --set trig=0 --set mbc=0 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_LE(std::abs(j["max_real_exponent"].get<double>() - ExactMaxReal()),
            j["error_estimate"].get<double>());
  EXPECT_NE(j["verdict"], "unstable");
}

TEST(MbcCli, FloquetOfTheModesBelowAFrequency) {
  // Modes 0.05…50 Hz, log-uniform, Ω = 1 rad/s, constant in multi-blade coordinates: the
  // exponents below 1 Hz are eig(A_MBC) modulo jΩ (tests/support/isotropic_rotor_lin.h).
  const auto model = ltp::test::MakeIsotropicRotorLin(5, 2, ltp::test::EvenAzimuths(3), 1.0, 5, 0.0,
                                                      0.02, 0.3, 300.0, true);
  const std::string dir =
      ltp::test::WriteLinDirectory(model.files, std::string(::testing::TempDir()) + "below-cli");
  Outcome r = Ltp("floquet " + dir + " --modes-below 1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  const int kept = j["modes_below"]["states"].get<int>();
  int slow = 0;
  for (auto l : model.exponents) slow += std::abs(l) <= 2 * 3.141592653589793;
  EXPECT_EQ(kept, slow);
  EXPECT_EQ(j["exponents"].size(), static_cast<size_t>(kept));
  EXPECT_EQ(j["modes_below"]["dropped_mean_eigenvalues"].size(),
            model.exponents.size() - static_cast<size_t>(kept));
  EXPECT_GT(j["modes_below"]["check_states"].get<int>(), kept);
  EXPECT_EQ(j["verdict"], "stable");
  for (const auto& e : j["exponents"]) {
    double nearest = 1e300;
    for (auto l : model.exponents)
      nearest =
          std::min(nearest, std::hypot(e["re"].get<double>() - l.real(),
                                       std::remainder(e["im"].get<double>() - l.imag(), 1.0)));
    EXPECT_LE(nearest, e["error_estimate"].get<double>());
  }
  r = Ltp("floquet " + dir + " --modes-below 1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("modes below 1 Hz only: " + std::to_string(kept) + " of"), std::string::npos)
      << r.out;
  r = Ltp("floquet " + dir + " --modes-below 1 --method hill");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--modes-below works with --method monodromy"), std::string::npos) << r.err;
}

TEST(MbcCli, MbcFloquetPartOfTheModesBelowAFrequency) {
  // The same generated rotor as above (modes 0.05…50 Hz, constant in multi-blade coordinates,
  // exact exponents eig(A_MBC) modulo jΩ): ltp mbc's Floquet part of the modes below 1 Hz lists
  // exactly the MBC modes below it, each route's exponent within its estimate of the exact one.
  const auto model = ltp::test::MakeIsotropicRotorLin(5, 2, ltp::test::EvenAzimuths(3), 1.0, 5, 0.0,
                                                      0.02, 0.3, 300.0, true);
  const std::string dir =
      ltp::test::WriteLinDirectory(model.files, std::string(::testing::TempDir()) + "below-mbc");
  Outcome r = Ltp("mbc " + dir + " --modes-below 1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& f = j["floquet"];
  int slow = 0, slow_listed = 0;
  for (auto l : model.exponents) {
    slow += std::abs(l) <= 2 * 3.141592653589793;
    slow_listed += std::abs(l) <= 2 * 3.141592653589793 && l.imag() >= 0;
  }
  EXPECT_EQ(f["modes_below"]["states"].get<int>(), slow);
  ASSERT_EQ(f["modes"].size(), static_cast<size_t>(slow_listed));
  EXPECT_EQ(f["verdict"], "stable");
  const double estimate = f["error_estimate"].get<double>();
  for (const auto& m : f["modes"]) {
    const double re = m["trig"]["re"].get<double>(), im = m["trig"]["im"].get<double>();
    double nearest = 1e300;
    for (auto l : model.exponents)
      nearest = std::min(nearest, std::hypot(re - l.real(), std::remainder(im - l.imag(), 1.0)));
    EXPECT_LE(nearest, estimate);
  }
  r = Ltp("mbc " + dir + " --modes-below 1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("modes below 1 Hz only: " + std::to_string(slow) + " of"), std::string::npos)
      << r.out;
}

TEST(MbcCli, PfrfOfLinFilesCountsTheSamplingError) {
  // A gravity rotor with blade force inputs and deflection outputs (tests/support/
  // isotropic_rotor_lin.h) at 3 azimuths: the multi-blade model's 3P content folds onto a
  // constant, the routes agree with one another on a model that is off. Reference: 9 azimuths
  // (exact; the library test checks 9 against 12).
  auto written = [](int azimuths, const std::string& name) {
    auto model =
        ltp::test::MakeIsotropicRotorLin(2, 2, ltp::test::EvenAzimuths(azimuths), 1.0, 5, 0.4);
    ltp::test::AddBladeChannels(model);
    return ltp::test::WriteLinDirectory(model.files, std::string(::testing::TempDir()) + name);
  };
  const std::string sweep = " --freq 0.1:0.6:0.1 --orders -1:1 --output 1";
  const std::string dir3 = written(3, "pfrf-cli3");
  const Outcome three = Ltp("pfrf " + dir3 + sweep + " --json");
  const Outcome nine = Ltp("pfrf " + written(9, "pfrf-cli9") + sweep + " --json");
  ASSERT_EQ(three.code, 0) << three.err;
  ASSERT_EQ(nine.code, 0) << nine.err;
  const auto j = nlohmann::json::parse(three.out), ref = nlohmann::json::parse(nine.out);
  ASSERT_TRUE(j["model_error"].is_number());
  ASSERT_EQ(j["values"].size(), ref["values"].size());
  double worst = 0;
  for (size_t i = 0; i < j["values"].size(); ++i) {
    const auto& v = j["values"][i];
    const auto& w = ref["values"][i];
    const double error = std::hypot(v["re"].get<double>() - w["re"].get<double>(),
                                    v["im"].get<double>() - w["im"].get<double>());
    worst = std::max(worst, error);
    EXPECT_GE(v["error_estimate"].get<double>() + w["error_estimate"].get<double>(), error) << i;
  }
  EXPECT_GT(worst, 1e-3);  // a real sampling error, not round-off
  const Outcome text = Ltp("pfrf " + dir3 + sweep);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("sampling error of the model"), std::string::npos) << text.out;
}

TEST(MbcCli, ClusteredAzimuthsRefusedByFloquetSkippedByMbc) {
  const double deg = 3.141592653589793 / 180;
  const auto model = ltp::test::MakeIsotropicRotorLin(2, 2, {0.5 * deg, 10 * deg, 20 * deg});
  const std::string dir =
      ltp::test::WriteLinDirectory(model.files, std::string(::testing::TempDir()) + "clus-cli");
  Outcome r = Ltp("floquet " + dir);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("leave part of the revolution unresolved"), std::string::npos) << r.err;
  r = Ltp("mbc " + dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("STABLE (MBC3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Floquet analysis: not done: the azimuths 0.5°, 10.0°, 20.0°"),
            std::string::npos)
      << r.out;
}

TEST(MbcCli, TablePrintedBeforeTheFloquetPart) {
  const Outcome r = Ltp("mbc " + RotorDir());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto table = r.out.find("(MBC3, azimuth-averaged)");
  const auto floquet = r.out.find("Floquet analysis of the same");
  ASSERT_NE(table, std::string::npos) << r.out;
  ASSERT_NE(floquet, std::string::npos) << r.out;
  EXPECT_LT(table, floquet);
  EXPECT_NE(r.out.find("STABLE (trig, error estimate"), std::string::npos) << r.out;
}

}  // namespace sampled
