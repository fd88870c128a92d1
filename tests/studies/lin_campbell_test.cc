// Campbell diagrams from OpenFAST operating-point sets: the `rotor` scene written as .lin files
// at several rotor speeds with ltp's own writer, read back, and MBC3 + tracking must give, at
// every speed, the exponents of the scene's own Floquet analysis (identical blades, N = 3: the
// multi-blade system is exactly time-invariant, so the two agree modulo jΩp to round-off).
#include "ltp/studies/lin_campbell.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
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
  LinCampbellOptions damped_options;
  damped_options.campbell.frequency = CampbellFrequency::kDamped;
  const LinCampbellResult r = MakeLinCampbell(ops, damped_options);
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

// Natural frequencies are |λ|/2π of the scene's own Floquet exponents (the round trip above makes
// the lines' λ those exponents), and the damped-line filter drops exactly the lines damped
// above the limit wherever tracked.
TEST(LinCampbell, NaturalFrequenciesAndTheDampingFilter) {
  const std::vector<double> speeds = {0.4, 0.8, 1.2, 1.6};
  std::vector<LinOperatingPoint> ops;
  for (const std::string& dir : WriteSets("lin_campbell_natural", speeds))
    ops.push_back(ReadLinOperatingPoint({dir}));
  LinCampbellOptions o;
  o.campbell.frequency = CampbellFrequency::kDamped;
  const LinCampbellResult damped = MakeLinCampbell(ops, o);
  const LinCampbellResult natural = MakeLinCampbell(ops);  // the default for .lin sets
  o.campbell.frequency = CampbellFrequency::kNatural;
  ASSERT_EQ(natural.diagram.lines.size(), damped.diagram.lines.size());
  EXPECT_EQ(natural.diagram.frequency, CampbellFrequency::kNatural);
  for (size_t k = 0; k < damped.diagram.lines.size(); ++k)
    for (size_t p = 0; p < speeds.size(); ++p) {
      const CampbellLine& a = damped.diagram.lines[k];
      const double wn = std::hypot(a.real_part[p], 2 * kPi * a.frequency_hz[p]) / (2 * kPi);
      EXPECT_NEAR(natural.diagram.lines[k].frequency_hz[p], wn, 1e-13 * wn);
      EXPECT_GE(natural.diagram.lines[k].frequency_hz[p], a.frequency_hz[p]);
    }
  // The filter: the median of the lines' smallest damping ratios as the limit.
  std::vector<double> least;
  for (const CampbellLine& line : damped.diagram.lines)
    least.push_back(*std::min_element(line.damping_ratio.begin(), line.damping_ratio.end()));
  std::vector<double> sorted = least;
  std::sort(sorted.begin(), sorted.end());
  o.campbell.max_damping_ratio = sorted[sorted.size() / 2];
  const LinCampbellResult filtered = MakeLinCampbell(ops, o);
  size_t kept = 0;
  for (double z : least) kept += z <= o.campbell.max_damping_ratio;
  EXPECT_EQ(filtered.diagram.lines.size(), kept);
  EXPECT_LT(kept, least.size());
  EXPECT_TRUE(HasCode(filtered.diagram.diagnostics, DiagnosticCode::kOverdampedLinesLeftOut));
}

// tests/data/openfast/rotor-speeds holds the sets docs/charts.md draws: they must be what the
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

// OpenFAST output as it comes: several simulations' <root>.<k>.lin files in one folder.
// Returns the folder; `roots[i]` names the simulation at speeds[i]. Headers may be edited first.
std::string WriteFlatFolder(const std::string& name, const std::vector<double>& speeds,
                            const std::vector<std::string>& roots,
                            const std::function<void(size_t, LinFile&)>& edit = {}) {
  const std::string dir = ::testing::TempDir() + name + "-" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (size_t i = 0; i < speeds.size(); ++i) {
    auto files = test::RotorLinFiles(Rotor(speeds[i]), {0.0, 2 * kPi / 3, 4 * kPi / 3});
    for (size_t k = 0; k < files.size(); ++k) {
      if (edit) edit(i, files[k]);
      WriteLinFile(dir + "/" + roots[i] + "." + std::to_string(k + 1) + ".lin", files[k]);
    }
  }
  return dir;
}

TEST(LinCampbell, FlatOutputFolderGivesOnePointPerSimulation) {
  // Reference: the same sets one directory per point, as before grouping existed.
  const std::vector<double> speeds = {0.4, 0.8, 1.2, 1.6};
  std::vector<LinOperatingPoint> ops;
  for (const std::string& dir : WriteSets("lin_campbell_flat_ref", speeds))
    ops.push_back(ReadLinOperatingPoint({dir}));
  const LinCampbellResult reference = MakeLinCampbell(ops);
  const std::string flat =
      WriteFlatFolder("lin_campbell_flat", speeds, {"ws04", "ws08", "ws12", "ws16"});
  std::vector<std::string> one_by_one;  // what an unquoted glob hands over
  for (const auto& e : std::filesystem::directory_iterator(flat)) one_by_one.push_back(e.path());
  for (const auto& arguments : {std::vector<std::string>{flat}, one_by_one}) {
    const LinCampbellResult r = ComputeLinCampbell(arguments);
    ASSERT_EQ(r.points.size(), speeds.size());
    EXPECT_EQ(r.axis, OperatingPointAxis::kRotorSpeed);
    ASSERT_EQ(r.diagram.lines.size(), reference.diagram.lines.size());
    for (size_t k = 0; k < r.diagram.lines.size(); ++k)
      EXPECT_EQ(r.diagram.lines[k].frequency_hz, reference.diagram.lines[k].frequency_hz);
    for (const LinCampbellPoint& p : r.points) EXPECT_EQ(p.files.size(), 3u);
  }
  // One analysis of the folder cannot be: the error says what it holds.
  try {
    ReadLinOperatingPoint({flat});
    ADD_FAILURE() << "a folder of four simulations read as one operating point";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("4 OpenFAST simulations"), std::string::npos) << e.what();
  }
}

TEST(LinCampbell, WindSweepAtConstantRotorSpeedIsOrderedByWindSpeed) {
  // Above rated the rotor speed is constant: every header says 1.2 rad/s, the wind speeds
  // (written out of order) tell the points apart.
  // The pitch rises with the wind: OpenFAST writes it as the operating point of ElastoDyn's
  // collective-pitch input when the files have inputs.
  const std::vector<double> winds = {18, 12, 24, 15}, pitches = {0.25, 0.07, 0.38, 0.17};
  const std::string flat = WriteFlatFolder(
      "lin_campbell_wind", {0.4, 0.8, 1.2, 1.6}, {"a", "b", "c", "d"}, [&](size_t i, LinFile& f) {
        f.rotor_speed = 1.2;
        f.wind_speed = winds[i];
        LinChannel pitch;
        pitch.operating_point = pitches[i];
        pitch.operating_point_values = {pitches[i]};
        pitch.description = "ED Extended input: collective blade-pitch command, rad";
        f.input_channels.push_back(pitch);  // beside the rotor's own two inputs
        f.inputs = static_cast<int>(f.input_channels.size());
        f.B.conservativeResize(Eigen::NoChange, f.inputs);
        f.B.col(f.inputs - 1).setZero();
        f.D.conservativeResize(Eigen::NoChange, f.inputs);
        f.D.col(f.inputs - 1).setZero();
      });
  const LinCampbellResult r = ComputeLinCampbell({flat});
  EXPECT_EQ(r.axis, OperatingPointAxis::kWindSpeed);
  EXPECT_EQ(r.axis_label, "wind speed [m/s]");
  EXPECT_EQ(r.diagram.parameter, (std::vector<double>{12, 15, 18, 24}));
  ASSERT_EQ(r.points.size(), 4u);
  const std::vector<double> sorted_pitches = {0.07, 0.17, 0.25, 0.38};
  for (size_t k = 0; k < 4; ++k) {
    ASSERT_TRUE(r.points[k].collective_pitch) << k;
    EXPECT_EQ(*r.points[k].collective_pitch, sorted_pitches[k]) << k;
  }
  LinCampbellOptions by_rotor;
  by_rotor.axis = OperatingPointAxis::kRotorSpeed;
  try {
    ComputeLinCampbell({flat}, by_rotor);
    ADD_FAILURE() << "four points at one rotor speed ordered by rotor speed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--by wind-speed"), std::string::npos) << e.what();
  }
}

// The band filter leaves out exactly the lines of the unfiltered diagram that are above the band
// wherever tracked, and says how many.
TEST(LinCampbell, BandFilterLeavesOutTheLinesAboveIt) {
  const std::string flat =
      WriteFlatFolder("lin_campbell_band", {0.4, 0.8, 1.2, 1.6}, {"a", "b", "c", "d"});
  const LinCampbellResult all = ComputeLinCampbell({flat});
  LinCampbellOptions banded;
  banded.campbell.max_frequency_hz = 0.5 * (all.diagram.lines.front().frequency_hz.front() +
                                            all.diagram.lines.back().frequency_hz.front());
  std::vector<std::string> expected;
  for (const CampbellLine& line : all.diagram.lines)
    if (std::any_of(line.frequency_hz.begin(), line.frequency_hz.end(),
                    [&](double f) { return f <= banded.campbell.max_frequency_hz; }))
      expected.push_back(line.description);
  ASSERT_GT(expected.size(), 0u);
  ASSERT_LT(expected.size(), all.diagram.lines.size());
  const LinCampbellResult r = ComputeLinCampbell({flat}, banded);
  std::vector<std::string> kept;
  for (const CampbellLine& line : r.diagram.lines) kept.push_back(line.description);
  EXPECT_EQ(kept, expected);
  EXPECT_TRUE(HasCode(r.diagram.diagnostics, DiagnosticCode::kLinesAboveBandLeftOut));
  EXPECT_FALSE(HasCode(all.diagram.diagnostics, DiagnosticCode::kLinesAboveBandLeftOut));
}

// Excluding a module leaves out, at each point, the modes whose participation in that module's
// states exceeds one half — checked by summing MBC3's participation factors here.
TEST(LinCampbell, ModuleFilterLeavesOutModesCarriedByThatModule) {
  // The hub becomes an "ED" module after the blades' "RT" module, each as OpenFAST orders a
  // module's states (displacements, then their rates): [lag 1..3, rates; hub x, y, rates].
  const std::vector<int> order = {0, 1, 2, 5, 6, 7, 3, 4, 8, 9};
  const std::string flat = WriteFlatFolder("lin_campbell_modules", {0.4, 0.8, 1.2}, {"a", "b", "c"},
                                           [&](size_t, LinFile& f) {
                                             std::vector<LinChannel> states;
                                             for (int i : order)
                                               states.push_back(f.states[static_cast<size_t>(i)]);
                                             for (LinChannel& c : states)
                                               if (c.description.find("hub") != std::string::npos)
                                                 c.description.replace(0, 2, "ED");
                                             f.states = states;
                                             f.A = Eigen::MatrixXd(f.A(order, order));
                                             f.B = Eigen::MatrixXd(f.B(order, Eigen::all));
                                             f.C = Eigen::MatrixXd(f.C(Eigen::all, order));
                                           });
  const LinCampbellResult all = ComputeLinCampbell({flat});
  LinCampbellOptions no_blades;
  no_blades.exclude_modules = {"RT"};
  const LinCampbellResult r = ComputeLinCampbell({flat}, no_blades);
  ASSERT_EQ(r.points.size(), all.points.size());
  size_t left_out = 0;
  for (size_t p = 0; p < all.points.size(); ++p) {
    const Mbc3Result& mbc = all.points[p].mbc;
    size_t kept = 0;
    for (const MbcMode& m : mbc.modes) {
      if (m.rigid_body) continue;
      std::complex<double> blade = 0;
      for (size_t i = 0; i < mbc.states.size(); ++i)
        if (mbc.states[i].description.rfind("RT ", 0) == 0)
          blade += m.participation(static_cast<Eigen::Index>(i));
      kept += std::abs(blade) <= 0.5;
    }
    EXPECT_EQ(r.sweep[p].modes.size(), kept) << p;
    left_out += all.sweep[p].modes.size() - kept;
  }
  EXPECT_GT(left_out, 0u);
  EXPECT_LT(r.diagram.lines.size(), all.diagram.lines.size());
  ASSERT_TRUE(HasCode(r.diagram.diagnostics, DiagnosticCode::kModulesLeftOut));
  for (const Diagnostic& d : r.diagram.diagnostics) {
    if (d.code == DiagnosticCode::kModulesLeftOut) {
      EXPECT_EQ(d.text.rfind(std::to_string(left_out) + " modes over 3 points left out", 0), 0u)
          << d.text;
    }
  }
  LinCampbellOptions bad;
  bad.exclude_modules = {"A D"};
  EXPECT_THROW(ComputeLinCampbell({flat}, bad), InputError);
}

TEST(LinCampbell, KeepGoingLeavesOutPointsThatCannotBeUsed) {
  const std::string flat =
      WriteFlatFolder("lin_campbell_keep", {0.4, 0.8, 1.2}, {"op1", "op2", "op3"});
  std::ofstream(flat + "/op4.1.lin") << "not an OpenFAST file\n";  // a broken simulation
  {  // and one of another model: two blades, where MBC3 does not apply
    RotorParameters two = Rotor(1.6);
    two.blades = 2;
    const auto files = test::RotorLinFiles(two, {0.0, 2 * kPi / 3, 4 * kPi / 3});
    for (size_t k = 0; k < files.size(); ++k)
      WriteLinFile(flat + "/op5." + std::to_string(k + 1) + ".lin", files[k]);
  }
  EXPECT_THROW(ComputeLinCampbell({flat}), InputError);
  LinCampbellOptions o;
  o.keep_going = true;
  const LinCampbellResult r = ComputeLinCampbell({flat}, o);
  EXPECT_EQ(r.points.size(), 3u);
  ASSERT_EQ(r.skipped.size(), 2u);
  EXPECT_NE(r.skipped[0].find("op4.1.lin"), std::string::npos) << r.skipped[0];
  EXPECT_NE(r.skipped[1].find("op5."), std::string::npos) << r.skipped[1];
}

TEST(LinCampbell, TheNrel5MwFilesAreAOnePointSet) {
  const LinCampbellResult r = MakeLinCampbell({ReadLinOperatingPoint({test::FiveMwDir()})});
  ASSERT_EQ(r.points.size(), 1u);
  const Mbc3Result& mbc = r.points[0].mbc;
  EXPECT_EQ(static_cast<int>(r.diagram.lines.size()) + mbc.rigid_body_modes,
            static_cast<int>(mbc.modes.size()));
  EXPECT_TRUE(r.diagram.crossings.empty());  // one point: nothing to bracket
  EXPECT_EQ(HasCode(r.points[0].diagnostics, DiagnosticCode::kRigidBodyMode),
            mbc.rigid_body_modes > 0);
  // Three azimuths are enough to average: no warning about too few.
  EXPECT_FALSE(HasCode(r.points[0].diagnostics, DiagnosticCode::kTooFewAzimuths));
}

}  // namespace
}  // namespace ltp
