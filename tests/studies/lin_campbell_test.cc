// Campbell diagrams from OpenFAST operating-point sets: the `rotor` scene written as .lin files
// at several rotor speeds with ltp's own writer, read back, and MBC3 + tracking must give, at
// every speed, the exponents of the scene's own Floquet analysis (identical blades, N = 3: the
// multi-blade system is exactly time-invariant, so the two agree modulo jΩp to round-off).
#include "ltp/studies/lin_campbell.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "ltp/models/rotor.h"
#include "support/rotor_lin.h"

namespace ltp {
namespace {

constexpr double kPi = std::numbers::pi;

RotorParameters Rotor(double omega) {
  RotorParameters rotor;
  rotor.blades = 3;
  rotor.omega = omega;
  return rotor;
}

// One directory of azimuth files per speed; returns the directories.
std::vector<std::string> WriteSets(const std::string& name, const std::vector<double>& speeds) {
  std::vector<std::string> dirs;
  for (size_t i = 0; i < speeds.size(); ++i) {
    const std::string dir = ::testing::TempDir() + name + "/point" + std::to_string(i);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto files = test::RotorLinFiles(Rotor(speeds[i]), {0.0, 2 * kPi / 3, 4 * kPi / 3});
    for (size_t k = 0; k < files.size(); ++k)
      WriteLinFile(dir + "/rotor." + std::to_string(k + 1) + ".lin", files[k]);
    dirs.push_back(dir);
  }
  return dirs;
}

TEST(LinCampbell, RotorSetsRoundTripToTheScenesFloquetExponents) {
  // Given out of order: the diagram sorts by rotor speed.
  const std::vector<double> speeds = {1.2, 0.4, 0.8, 1.6, 0.6, 1.0, 1.4};
  std::vector<LinOperatingPoint> ops;
  for (const std::string& dir : WriteSets("lin_campbell_rotor", speeds))
    ops.push_back(ReadLinOperatingPoint({dir}));
  const LinCampbellResult r = MakeLinCampbell(ops);
  ASSERT_EQ(r.points.size(), speeds.size());
  ASSERT_EQ(r.diagram.lines.size(), 5u);  // 10 states: five oscillatory MBC modes
  EXPECT_EQ(r.diagram.blades, 3);
  for (size_t p = 0; p < r.points.size(); ++p) {
    const double omega = r.points[p].rotor_speed;
    if (p > 0) {
      EXPECT_GT(omega, r.points[p - 1].rotor_speed);
    }
    EXPECT_NEAR(r.diagram.parameter[p], omega * 30 / kPi, 1e-12);
    FloquetOptions fo;
    fo.integrator.rel_tol = 1e-12;
    fo.integrator.abs_tol = 1e-15;
    const PeriodicSystem system = BuildRotorSystem(Rotor(omega));
    const FloquetResult f = AnalyzeFloquet(system, fo);
    ASSERT_TRUE(f.ok);
    std::vector<std::complex<double>> floquet, lines;
    for (const FloquetMode& m : f.modes) floquet.push_back(m.exponent);
    for (const CampbellLine& line : r.diagram.lines) {
      ASSERT_TRUE(std::isfinite(line.frequency_hz[p]));
      lines.push_back({line.real_part[p], 2 * kPi * line.frequency_hz[p]});
    }
    // Each line's λ is one of the scene's exponents (mod jΩp): the files, MBC3 and tracking
    // lose nothing. The .lin files hold 13 significant digits.
    const double wp = 2 * kPi / system.period();
    for (double d : MatchExponents(lines, floquet, wp)) EXPECT_LT(d, 1e-9) << "Ω = " << omega;
  }
  for (const CampbellLine& line : r.diagram.lines) {
    EXPECT_FALSE(line.description.empty());
    EXPECT_FALSE(line.lost_after.has_value());
  }
}

// tests/data/openfast/rotor-speeds holds the sets the README draws: they must be what the
// writer produces today (a regression pin on the data, not a reference for the numbers).
TEST(LinCampbell, ShippedRotorSetsAreTheWritersOutput) {
  const std::string root = test::SourceDir() + "/tests/data/openfast/rotor-speeds";
  for (const char* speed : {"0.4", "0.6", "0.8", "1.0", "1.2", "1.4", "1.6"}) {
    const auto files =
        test::RotorLinFiles(Rotor(std::stod(speed)), {0.0, 2 * kPi / 3, 4 * kPi / 3});
    for (size_t k = 0; k < files.size(); ++k) {
      const std::string path =
          root + "/omega-" + speed + "/rotor." + std::to_string(k + 1) + ".lin";
      std::ifstream in(path);
      std::stringstream text;
      text << in.rdbuf();
      EXPECT_EQ(text.str(), FormatLinFile(files[k])) << path;
    }
  }
}

TEST(LinCampbell, RefusesMixedModelsAndRepeatedPoints) {
  const auto dirs = WriteSets("lin_campbell_bad", {0.5, 0.5});
  std::vector<LinOperatingPoint> ops = {ReadLinOperatingPoint({dirs[0]}),
                                        ReadLinOperatingPoint({dirs[1]})};
  EXPECT_THROW(MakeLinCampbell(ops), InputError);  // same rotor speed twice
  EXPECT_THROW(MakeLinCampbell({}), InputError);
  LinCampbellOptions by_wind;
  by_wind.axis = OperatingPointAxis::kWindSpeed;  // the rotor files have no wind speed
  EXPECT_THROW(MakeLinCampbell({ops[0]}, by_wind), InputError);
}

TEST(LinCampbell, TheNrel5MwFilesAreAOnePointSet) {
  const LinCampbellResult r = MakeLinCampbell({ReadLinOperatingPoint({test::FiveMwDir()})});
  ASSERT_EQ(r.points.size(), 1u);
  const Mbc3Result& mbc = r.points[0].mbc;
  EXPECT_EQ(static_cast<int>(r.diagram.lines.size()) + mbc.rigid_body_modes,
            static_cast<int>(mbc.modes.size()));
  EXPECT_TRUE(r.diagram.crossings.empty());  // one point: nothing to bracket
  bool rigid_noted = false;
  for (const auto& note : r.points[0].notes)
    rigid_noted = rigid_noted || note.find("rigid-body") != std::string::npos;
  EXPECT_EQ(rigid_noted, mbc.rigid_body_modes > 0);
}

}  // namespace
}  // namespace ltp
