// `ltp simulate` then `ltp identify` end to end: the estimates from the CSV against the
// model's partial FRFs (--compare, modal route checked by htf), noise bounds, and refused data.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <complex>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "support/ltp_cli.h"
#include "support/rig.h"
#include "uff58.h"

namespace {

using nlohmann::json;
using test::RunLtp;

// Per process: two test runs on one machine (plain and sanitized builds) must not share files.
std::string Tmp(const std::string& name) {
  return std::string(::testing::TempDir()) + "ltp-" + std::to_string(getpid()) + "-" + name;
}
const std::string kScene = "mathieu --set a=2 --set c=0.2 --set q=0.3";  // stable, between tongues

TEST(IdentifyCli, SimulatedStepSineIdentifiesTheModel) {
  const std::string csv = Tmp("identify_sim.csv");
  const auto sim =
      RunLtp("simulate " + kScene + " --excitation stepsine:0.05:0.45:0.1 --periods 16 --out " +
             csv + " --json");
  ASSERT_EQ(sim.code, 0) << sim.err;
  EXPECT_EQ(json::parse(sim.out)["records"].get<int>(), 5);
  const auto id = RunLtp("identify " + csv + " --orders -1:1 --compare " + kScene + " --json");
  ASSERT_EQ(id.code, 0) << id.err;
  const json j = json::parse(id.out);
  ASSERT_EQ(j["frequencies"].size(), 5u);
  int compared = 0;
  for (const json& f : j["frequencies"]) {
    if (!f["separable"].get<bool>()) continue;
    for (const json& h : f["H"]) {
      const double dre = h["re"].get<double>() - h["model"][0].get<double>();
      const double dim = h["im"].get<double>() - h["model"][1].get<double>();
      EXPECT_LT(std::hypot(dre, dim), 1e-6) << f["excitation_hz"] << " z=" << h["z"];
      ++compared;
    }
  }
  EXPECT_GE(compared, 12);
}

// Multisine records through the CSV: `--method auto` picks broadband (every record has
// excitation_hz 0), the estimates meet the model (modal route) within their 95 % bounds plus
// 1e-9, and an explicit step-sine method on broadband data is refused with the reason.
TEST(IdentifyCli, SimulatedMultisineIdentifiesTheModelByLeastSquares) {
  const std::string csv = Tmp("identify_multisine.csv");
  const auto sim = RunLtp("simulate " + kScene +
                          " --excitation multisine:0.05:0.45:0.08 --records 6 --periods 16 "
                          "--noise 40 --seed 3 --out " +
                          csv + " --json");
  ASSERT_EQ(sim.code, 0) << sim.err;
  EXPECT_EQ(json::parse(sim.out)["records"].get<int>(), 6);
  const auto id = RunLtp("identify " + csv + " --orders -1:1 --compare " + kScene + " --json");
  ASSERT_EQ(id.code, 0) << id.err;
  const json j = json::parse(id.out);
  EXPECT_EQ(j["method"], "broadband");
  int compared = 0, inside = 0;
  for (const json& f : j["frequencies"])
    for (const json& h : f["H"]) {
      const double dre = h["re"].get<double>() - h["model"][0].get<double>();
      const double dim = h["im"].get<double>() - h["model"][1].get<double>();
      inside += std::hypot(dre, dim) <= h["bound_95"].get<double>() + 1e-9;
      ++compared;
      EXPECT_LT(h["condition"].get<double>(), 100);
    }
  EXPECT_GE(compared, 12);
  EXPECT_GE(inside, compared - 2) << inside << " of " << compared;  // 95 % bounds
  EXPECT_EQ(RunLtp("identify " + csv + " --method stepsine").code, 2);
  // The convergence plot adds the records one by one (gnuplot draws it, or its script is
  // written when gnuplot is missing); step-sine data have nothing to add.
  const std::string plot = Tmp("identify_convergence.svg");
  std::remove(plot.c_str());
  std::remove((plot + ".gp").c_str());
  const auto conv = RunLtp("identify " + csv + " --orders -1:1 --convergence " + plot);
  ASSERT_EQ(conv.code, 0) << conv.err;
  EXPECT_TRUE(std::ifstream(plot).good() || std::ifstream(plot + ".gp").good());
  const std::string steps = Tmp("identify_convergence_steps.csv");
  ASSERT_EQ(
      RunLtp("simulate " + kScene + " --excitation sine:0.13 --periods 8 --out " + steps).code, 0);
  EXPECT_EQ(RunLtp("identify " + steps + " --convergence " + plot).code, 2);
}

// Periodic Gaussian noise on every line of the record's grid (noise:F0:F1): noise-free output,
// so the least-squares estimates meet the model to 1e-6 of the response (orders −4..4; orders
// beyond those feed the edge orders at ~1e-6).
TEST(IdentifyCli, SimulatedNoiseExcitationIdentifiesTheModel) {
  const std::string csv = Tmp("identify_noise.csv");
  const auto sim = RunLtp("simulate " + kScene +
                          " --excitation noise:0.05:0.3 --records 12 --periods 16 --out " + csv);
  ASSERT_EQ(sim.code, 0) << sim.err;
  const auto id = RunLtp("identify " + csv + " --orders -4:4 --compare " + kScene + " --json");
  ASSERT_EQ(id.code, 0) << id.err;
  const json j = json::parse(id.out);
  EXPECT_GE(j["frequencies"].size(), 10u);  // 0.02 Hz apart
  for (const json& f : j["frequencies"]) {
    double scale = 0;
    for (const json& h : f["H"])
      scale = std::max(scale, std::hypot(h["model"][0].get<double>(), h["model"][1].get<double>()));
    for (const json& h : f["H"]) {
      const double dre = h["re"].get<double>() - h["model"][0].get<double>();
      const double dim = h["im"].get<double>() - h["model"][1].get<double>();
      EXPECT_LT(std::hypot(dre, dim), 1e-6 * scale) << f["excitation_hz"] << " z=" << h["z"];
    }
  }
  EXPECT_EQ(RunLtp("simulate " + kScene + " --excitation noise:0.5:0.1 --out " + csv).code, 2);
}

TEST(IdentifyCli, NoisyDataCarryBoundsAndBadFilesAreRefused) {
  const std::string csv = Tmp("identify_noisy.csv");
  ASSERT_EQ(RunLtp("simulate " + kScene +
                   " --excitation sine:0.13 --periods 8 --noise 30 --seed 7 --out " + csv)
                .code,
            0);
  const auto id = RunLtp("identify " + csv + " --orders 0 --json");
  ASSERT_EQ(id.code, 0) << id.err;
  const double bound = json::parse(id.out)["frequencies"][0]["H"][0]["bound_95"].get<double>();
  EXPECT_GT(bound, 1e-4);  // 30 dB of noise is seen
  EXPECT_LT(bound, 0.1);
  // A file without a period, and one with a gap in time for the broadband method (step-sine
  // fits the times as written).
  const std::string no_period = Tmp("identify_no_period.csv");
  std::ofstream(no_period) << "record,excitation_hz,t,in:u,out:y\n1,0.1,0,1,0\n1,0.1,0.1,1,0\n";
  const auto r = RunLtp("identify " + no_period);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("period"), std::string::npos) << r.err;
  const std::string gap = Tmp("identify_gap.csv");
  std::ofstream(gap)
      << "# period_s: 1\nrecord,excitation_hz,t,in:u,out:y\n1,0,0,1,0\n1,0,0.1,1,0\n1,0,0.2,1,0\n"
      << "1,0,0.3,1,0\n1,0,0.5,1,0\n1,0,0.6,1,0\n";
  const auto g = RunLtp("identify " + gap + " --method broadband");
  EXPECT_EQ(g.code, 2);
  EXPECT_NE(g.err.find("unequal sampling at sample 5"), std::string::npos) << g.err;
}

// Edited copies of a simulated CSV (the round-2 hostile-input reproducers): each is refused with
// one line naming its cause, never ignored, guessed or answered with NaN.
TEST(IdentifyCli, HostileTimeDataGetsOneClearLine) {
  const std::string csv = Tmp("identify_hostile.csv");
  ASSERT_EQ(
      RunLtp("simulate " + kScene + " --excitation stepsine:0.1:0.5:0.2 --periods 10 --out " + csv)
          .code,
      0);
  std::vector<std::string> lines;
  {
    std::ifstream in(csv);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  ASSERT_GT(lines.size(), 300u);
  ASSERT_EQ(lines[1].rfind("# period_s:", 0), 0u);
  // Writes the lines with `edit` applied, runs identify on them, returns the result.
  const auto run = [&](const std::function<void(std::vector<std::string>&)>& edit,
                       const std::string& options = "") {
    std::vector<std::string> edited = lines;
    edit(edited);
    const std::string path = Tmp("identify_edited.csv");
    std::ofstream out(path);
    for (const std::string& l : edited) out << l << "\n";
    out.close();
    return RunLtp("identify " + path + " " + options);
  };
  const auto cell = [](std::string& line, size_t column, const std::string& value) {
    size_t start = 0;
    for (size_t c = 0; c < column; ++c) start = line.find(',', start) + 1;
    const size_t end = line.find(',', start);
    line.replace(start, end == std::string::npos ? std::string::npos : end - start, value);
  };
  const auto expect = [](const test::LtpRun& r, const std::string& text) {
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
  };
  for (const char* bad : {"0", "-1", "nan"})
    expect(run([&](auto& l) { l[1] = std::string("# period_s: ") + bad; }),
           "must be finite and > 0");
  expect(run([](auto&) {}, "--period 0"), "--period must be a finite number > 0");
  expect(run([](auto&) {}, "--period nan"), "--period must be a finite number > 0");
  expect(run([](auto& l) { l.insert(l.begin() + 2, "# period_s: 6.28318530717959"); }),
         "disagrees with the first");
  expect(run([&](auto& l) { cell(l[199], 0, "1.5"); }), "is not a whole number");
  expect(run([&](auto& l) { cell(l[199], 1, "nan"); }), "one frequency per record");
  expect(run([&](auto& l) {
           for (size_t i = 3; i < l.size(); ++i) cell(l[i], 4, "1e308");
         }),
         "rescale the channel");
  expect(run(
             [&](auto& l) {
               l[2] += ",out:y";
               for (size_t i = 3; i < l.size(); ++i) l[i] += ",0";
             },
             "--output y"),
         "two columns are named 'y'");
  expect(run([](auto&) {}, "--orders -1000:1000"), "--orders -1000:1000: at most 201 orders");
  expect(run([](auto&) {}, "--plot p.svg --plot-orders 5:9"), "lies outside the estimated orders");
  expect(RunLtp("identify /dev/zero"), "is not a regular file");
  // A channel name in Latin-1 (0xB5 for µ): refused by the reader, not by the JSON writer.
  expect(run([](auto& l) { l[2] += "\xB5"; }, "--json"), "not valid UTF-8 text (byte 0xb5");
}

// The identified frequencies (as measured) and H_z, |z| ≤ 2, against the rig's closed form.
void ExpectTheRigsPartialFrfs(const ltp::testing::Rig& rig, const json& j,
                              const double (&truth_hz)[2]) {
  ASSERT_EQ(j["frequencies"].size(), 2u);
  for (size_t f = 0; f < 2; ++f) {
    const json& e = j["frequencies"][f];
    EXPECT_NEAR(e["excitation_hz"].get<double>(), truth_hz[f], 1e-9);
    const auto truth = rig.PartialFrf(truth_hz[f], rig.Speed());
    for (size_t z = 0; z < 5; ++z) {
      const std::complex<double> h(e["H"][z]["re"].get<double>(), e["H"][z]["im"].get<double>());
      EXPECT_LT(std::abs(h - truth[z]), 1e-6 * std::abs(truth[2])) << f << " z=" << int(z) - 2;
    }
  }
}

// Rig data as a rig writes them: no period line, a tacho column, the rotor 1 % fast, shakers
// off any grid with rounded frequencies in the log, 20.3 periods per record (tests/support/rig.h,
// closed-form partial FRFs at the rig's speed).
TEST(IdentifyCli, ATachoChannelGivesTheRigsPartialFrfs) {
  const ltp::testing::Rig rig;
  const std::string csv = Tmp("identify_rig.csv");
  {
    std::ofstream out(csv);
    out.precision(17);
    out << "record,excitation_hz,t,in:force,out:accel,aux:tacho\n";
    int record = 1;
    for (const auto& [f, written] : {std::pair{0.1373, 0.14}, {0.6121, 0.61}}) {
      const ltp::TimeRecord r = rig.Record(f, written);
      for (size_t i = 0; i < r.time.size(); ++i) {
        const auto s = static_cast<Eigen::Index>(i);
        out << record << "," << written << "," << r.time[i] << "," << r.inputs(s, 0) << ","
            << r.outputs(s, 0) << "," << r.auxiliary(s, 0) << "\n";
      }
      ++record;
    }
  }
  const double pulse_deg = rig.PulseAngle() * 180 / std::numbers::pi;
  const auto id = RunLtp("identify " + csv + " --tacho tacho --tacho-angle " +
                         std::to_string(pulse_deg) + " --json");
  ASSERT_EQ(id.code, 0) << id.err;
  const json j = json::parse(id.out);
  EXPECT_NEAR(j["measured_speed_rad_s"]["mean"].get<double>() / rig.Speed(), 1, 1e-6);
  EXPECT_NEAR(j["period_s"].get<double>() * rig.Speed() / (2 * std::numbers::pi), 1, 1e-6);
  const double truth_hz[] = {0.1373, 0.6121};
  ExpectTheRigsPartialFrfs(rig, j, truth_hz);
  // Without a period line, no tacho: the period is asked for; a tacho that is not a channel.
  EXPECT_EQ(RunLtp("identify " + csv).code, 2);
  const auto wrong = RunLtp("identify " + csv + " --tacho nope");
  EXPECT_EQ(wrong.code, 2);
  EXPECT_NE(wrong.err.find("nope"), std::string::npos) << wrong.err;
}

// The same rig's records as a DAQ exports them: one file per step, a preamble line, a header of
// names with units, semicolons and decimal commas (a German-locale export) in one file, tabs and
// no time column (--sample-rate) in the other; no frequencies written.
TEST(IdentifyCli, DaqFilesAreRecordsAndTheirFrequenciesComeFromTheInput) {
  const ltp::testing::Rig rig;
  const double fs = rig.samples_per_period / rig.model_period;
  const double truth_hz[] = {0.1373, 0.6121};
  std::vector<std::string> files;
  for (int k = 0; k < 2; ++k) {
    const ltp::TimeRecord r = rig.Record(truth_hz[k], 0);
    files.push_back(Tmp("daq" + std::to_string(k) + (k == 0 ? ".csv" : ".txt")));
    std::ofstream out(files.back());
    out.precision(17);
    const std::string sep = k == 0 ? ";" : "\t";
    out << "Exported by a DAQ, channel list follows\n";
    out << (k == 0 ? "Time [s];" : "") << "Force [N]" << sep << "Accel [m/s^2]" << sep
        << "Tacho (V)\n";
    for (size_t i = 0; i < r.time.size(); ++i) {
      const auto s = static_cast<Eigen::Index>(i);
      std::ostringstream row;
      row.precision(17);
      if (k == 0) row << r.time[i] << sep;
      row << r.inputs(s, 0) << sep << r.outputs(s, 0) << sep << r.auxiliary(s, 0);
      std::string text = row.str();
      if (k == 0) std::replace(text.begin(), text.end(), '.', ',');  // decimal commas
      out << text << "\n";
    }
  }
  const double pulse_deg = rig.PulseAngle() * 180 / std::numbers::pi;
  // The second file has no time column: its samples are counted from 0 at the rate given.
  const auto id = RunLtp("identify " + files[0] + " " + files[1] + " --sample-rate " +
                         std::to_string(fs) + " --input Force --output Accel --tacho Tacho " +
                         "--tacho-angle " + std::to_string(pulse_deg) + " --json");
  ASSERT_EQ(id.code, 0) << id.err;
  const json j = json::parse(id.out);
  ASSERT_EQ(j["frequencies"].size(), 2u);
  ExpectTheRigsPartialFrfs(rig, j, truth_hz);
  // Channels not named: input and output would be one channel.
  const auto unnamed = RunLtp("identify " + files[0] + " --tacho Tacho");
  EXPECT_EQ(unnamed.code, 2);
  EXPECT_NE(unnamed.err.find("name the excitation and the response"), std::string::npos)
      << unnamed.err;
  // No period and no tacho: asked for.
  const auto no_period = RunLtp("identify " + files[0] + " --input Force --output Accel");
  EXPECT_EQ(no_period.code, 2);
  EXPECT_NE(no_period.err.find("--period"), std::string::npos) << no_period.err;
}

// An estimate of `ltp identify --json` and the model's value beside it (--compare).
std::complex<double> Estimated(const json& h) {
  return {h["re"].get<double>(), h["im"].get<double>()};
}
std::complex<double> Modelled(const json& h) {
  return {h["model"][0].get<double>(), h["model"][1].get<double>()};
}

// The largest |estimate − model| over a run's frequencies and orders, and the largest |model|.
std::pair<double, double> LargestModelError(const json& run) {
  double worst = 0, largest = 0;
  for (const json& f : run["frequencies"])
    for (const json& h : f["H"]) {
      worst = std::max(worst, std::abs(Estimated(h) - Modelled(h)));
      largest = std::max(largest, std::abs(Modelled(h)));
    }
  return {worst, largest};
}

// UFF 58 as the format's description lays it out (written here field by field, not by ltp's
// writer): records 1–11 of each function, then record 12's values; the rig's two step-sine
// records, three channels each, in one file (a channel name met again starts the next record).
// `binary`: dataset 58b with big-endian single-precision floats; else ASCII 4E20.12 (case 5)
// with Windows line ends and a dataset 151 (a header ltp skips) in front.
std::string RigUff(const ltp::testing::Rig& rig, const double (&truth_hz)[2], bool binary) {
  const std::string path = Tmp(binary ? "rig-b.uff" : "rig-a.uff");
  std::ofstream out(path, std::ios::binary);
  const std::string eol = binary ? "\n" : "\r\n";
  char line[128];
  if (!binary)
    out << "    -1" << eol << "   151" << eol << "rig test" << eol << "NONE" << eol << "ltp" << eol
        << "27-Nov-26 10:00:00" << eol << "    -1" << eol;
  const double dt = rig.model_period / rig.samples_per_period;  // 3.125E-02: exact in E13.5
  for (const double f : truth_hz) {
    const ltp::TimeRecord r = rig.Record(f, 0);
    const Eigen::Index n = r.inputs.rows();
    const std::vector<std::pair<std::string, Eigen::VectorXd>> channels = {
        {"Force", r.inputs.col(0)}, {"Accel", r.outputs.col(0)}, {"Tacho", r.auxiliary.col(0)}};
    for (const auto& [name, v] : channels) {
      out << "    -1" << eol;
      if (binary)
        std::snprintf(line, sizeof line, "%6d%c%6d%6d%12d%12ld%6d%6d%12d%12d", 58, 'b', 2, 2, 11,
                      4 * static_cast<long>(n), 0, 0, 0, 0);
      else
        std::snprintf(line, sizeof line, "%6d", 58);
      out << line << eol << name << eol << "NONE" << eol << "NONE" << eol << "NONE" << eol << "NONE"
          << eol;
      std::snprintf(line, sizeof line, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d", 1, 0, 0, 0,
                    name.c_str(), 1, 3, "NONE", 0, 0);
      out << line << eol;
      std::snprintf(line, sizeof line, "%10d%10ld%10d%13.5E%13.5E%13.5E", binary ? 2 : 4,
                    static_cast<long>(n), 1, 0.0, dt, 0.0);
      out << line << eol;
      for (const char* axis : {"17", "12", "0", "0"}) {
        std::snprintf(line, sizeof line, "%10s%5d%5d%5d %-20s %-20s", axis, 0, 0, 0, "NONE",
                      "NONE");
        out << line << eol;
      }
      if (binary) {
        for (Eigen::Index k = 0; k < n; ++k) {
          const float x = static_cast<float>(v(k));
          unsigned char b[4];
          std::memcpy(b, &x, 4);
          std::reverse(b, b + 4);  // this machine is little-endian (x86, ARM as Debian runs it)
          out.write(reinterpret_cast<const char*>(b), 4);
        }
      } else {
        for (Eigen::Index k = 0; k < n; ++k) {
          std::snprintf(line, sizeof line, "%20.12E", v(k));
          out << line << ((k % 4 == 3 || k + 1 == n) ? eol : "");
        }
      }
      out << "    -1" << eol;
    }
  }
  return path;
}

// The rig's records from UFF files written by the format's description: ASCII doubles give the
// closed form as a CSV does (1e-6 of |H_0|); big-endian floats carry 7 digits, and the
// estimates stay within twice their 95 % bounds and 1e-5 of |H_0|.
TEST(IdentifyCli, UffFilesAsTheFormatDescribesThemAreRead) {
  const ltp::testing::Rig rig;
  const double truth_hz[] = {0.1373, 0.6121};
  const double pulse_deg = rig.PulseAngle() * 180 / std::numbers::pi;
  const std::string options = " --input Force --output Accel --tacho Tacho --tacho-angle " +
                              std::to_string(pulse_deg) + " --json";
  const auto ascii = RunLtp("identify " + RigUff(rig, truth_hz, false) + options);
  ASSERT_EQ(ascii.code, 0) << ascii.err;
  ExpectTheRigsPartialFrfs(rig, json::parse(ascii.out), truth_hz);
  const auto floats = RunLtp("identify " + RigUff(rig, truth_hz, true) + options);
  ASSERT_EQ(floats.code, 0) << floats.err;
  const json j = json::parse(floats.out);
  ASSERT_EQ(j["frequencies"].size(), 2u);
  for (size_t f = 0; f < 2; ++f) {
    const auto truth = rig.PartialFrf(truth_hz[f], rig.Speed());
    for (size_t z = 0; z < 5; ++z) {
      const json& e = j["frequencies"][f]["H"][z];
      const double error = std::abs(Estimated(e) - truth[z]);
      // The rounding is noise to the fit: its 95 % bounds are of the error's size.
      EXPECT_LT(error, 2 * e["bound_95"].get<double>()) << f << " z=" << int(z) - 2;
      EXPECT_LT(error, 1e-5 * std::abs(truth[2])) << f << " z=" << int(z) - 2;
    }
  }
}

// ltp's own UFF: simulate writes time records (ASCII and 58b) with a tacho, identify reads
// them (as a rig's) and writes H_z and its bounds as UFF; read back, the file holds the JSON's
// numbers (frequencies to the 7 digits of the abscissa field, values to 13). Reference for
// the estimates: the model's partial FRFs (--compare, routes of ltp pfrf).
TEST(IdentifyCli, UffRoundTripsThroughSimulateAndIdentify) {
  for (const bool binary : {false, true}) {
    const std::string records = Tmp(binary ? "sim-b.uff" : "sim-a.uff");
    const auto sim = RunLtp("simulate " + kScene +
                            " --excitation stepsine:0.05:0.45:0.1 --periods 16 --tacho --out " +
                            records + (binary ? " --binary" : ""));
    ASSERT_EQ(sim.code, 0) << sim.err;
    const std::string h_file = Tmp(binary ? "h-b.uff" : "h-a.uff");
    const auto id = RunLtp("identify " + records +
                           " --input u --output y --tacho tacho --period 3.141592653589793 "
                           "--orders -1:1 --compare " +
                           kScene + " --json --uff " + h_file + (binary ? " --binary" : ""));
    ASSERT_EQ(id.code, 0) << id.err;
    const json j = json::parse(id.out);
    ASSERT_EQ(j["frequencies"].size(), 5u);
    std::map<std::pair<int, long>, std::complex<double>> estimates;  // (z, frequency in 1e-7 Hz)
    for (const json& f : j["frequencies"])
      for (const json& h : f["H"]) {
        // The 7-digit time step moves the frequencies by ~1e-7: H_z with them.
        EXPECT_LT(std::abs(Estimated(h) - Modelled(h)), 2e-6)
            << f["excitation_hz"] << " z=" << h["z"];
        estimates[{h["z"].get<int>(), std::lround(f["excitation_hz"].get<double>() * 1e7)}] =
            Estimated(h);
      }
    const std::vector<ltp::cli::Uff58Function> read = ltp::cli::ReadUff58(h_file);
    ASSERT_EQ(read.size(), 6u);  // H_z and its bound, z = −1, 0, 1
    for (const ltp::cli::Uff58Function& fn : read) {
      if (fn.function_type != 4) continue;
      EXPECT_EQ(fn.response_name, "y");
      EXPECT_EQ(fn.reference_name, "u");
      ASSERT_EQ(fn.complex.size(), 5u);
      for (size_t k = 0; k < 5; ++k) {
        const auto it = estimates.find({fn.sequence, std::lround(fn.x[k] * 1e7)});
        ASSERT_NE(it, estimates.end()) << fn.description << " " << fn.x[k];
        EXPECT_LT(std::abs(fn.complex[k] - it->second), 1e-11 * std::abs(it->second));
      }
    }
  }
}

// Several outputs in one run (the Jeffcott rotor's x and y) give what one run per output gives;
// a delayed output is put back by --delay (multisine records repeat over their length, so a
// circular shift is the exact delayed record; reference: the model's partial FRFs).
TEST(IdentifyCli, SeveralOutputsAndAChannelDelay) {
  const std::string jeff = "jeffcott --set c=0.1 --set Omega=0.5";
  const std::string csv = Tmp("identify_xy.csv");
  ASSERT_EQ(RunLtp("simulate " + jeff +
                   " --excitation multisine:0.05:0.45:0.1 --records 8 --periods 8 --out " + csv)
                .code,
            0);
  const auto both = RunLtp("identify " + csv + " --output 1,0 --orders -2:2 --json");
  ASSERT_EQ(both.code, 0) << both.err;
  const json j = json::parse(both.out);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 2u);
  for (int k : {0, 1}) {
    const auto one =
        RunLtp("identify " + csv + " --output " + std::to_string(1 - k) + " --orders -2:2 --json");
    ASSERT_EQ(one.code, 0) << one.err;
    EXPECT_EQ(json::parse(one.out), j[static_cast<size_t>(k)]);
  }
  // Output 1 sampled 3 steps late.
  std::vector<std::string> lines;
  {
    std::ifstream in(csv);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  const size_t header =
      std::find_if(lines.begin(), lines.end(), [](const auto& l) { return l[0] == 'r'; }) -
      lines.begin();
  std::vector<std::vector<std::string>> rows;
  for (size_t i = header + 1; i < lines.size(); ++i) {
    std::vector<std::string> cells;
    std::stringstream ss(lines[i]);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  const size_t per_record = rows.size() / 8, column = rows[0].size() - 1;  // the last out:
  std::ofstream out(csv);
  for (size_t i = 0; i <= header; ++i) out << lines[i] << "\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const size_t start = i / per_record * per_record;
    std::vector<std::string> row = rows[i];
    row[column] = rows[start + (i - start + per_record - 3) % per_record][column];
    for (size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << row[c];
    out << "\n";
  }
  out.close();
  const double dt = std::stod(rows[1][2]) - std::stod(rows[0][2]);
  const std::string name = json::parse(both.out)[0]["output_name"];
  const auto error = [&](const std::string& extra) {
    const auto r = RunLtp("identify " + csv + " --output " + name + " --orders -2:2 --compare " +
                          jeff + " --json" + extra);
    EXPECT_EQ(r.code, 0) << r.err;
    return LargestModelError(json::parse(r.out)).first;
  };
  EXPECT_GT(error(""), 1e-2);
  std::ostringstream delay;
  delay.precision(17);
  delay << " --delay " << name << "=" << 3 * dt;
  EXPECT_LT(error(delay.str()), 1e-6);
  const auto unknown = RunLtp("identify " + csv + " --delay nope=1e-3");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("neither the input, an output"), std::string::npos) << unknown.err;
}

// Broken UFF files get one line naming what is wrong, never a crash or a hang.
TEST(IdentifyCli, BrokenUffFilesGetOneClearLine) {
  const ltp::testing::Rig rig;
  const double truth_hz[] = {0.1373, 0.6121};
  std::string text;
  {
    std::ifstream in(RigUff(rig, truth_hz, false), std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::string binary;
  {
    std::ifstream in(RigUff(rig, truth_hz, true), std::ios::binary);
    binary.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto run = [&](const std::string& content) {
    const std::string path = Tmp("broken.uff");
    std::ofstream(path, std::ios::binary) << content;
    return RunLtp("identify " + path + " --input Force --output Accel --tacho Tacho");
  };
  const auto expect = [](const test::LtpRun& r, const std::string& words) {
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  };
  expect(run(text.substr(0, text.size() / 3)), "the file ends inside");
  expect(run(binary.substr(0, binary.size() / 3 + 500)), "bytes, the file holds");
  std::string wrong_type = text;
  wrong_type.replace(wrong_type.find("         4      "), 10, "         9");
  expect(run(wrong_type), "ordinate data type 9");
  std::string frf = text;
  frf.replace(frf.find("    1         0    0"), 5, "    4");
  expect(run(frf), "is not a time record");
  expect(run("    -1\r\n   151\r\nonly a header\r\n    -1\r\n"), "no dataset 58");
  // A file without line ends (a binary dump) is refused at its first MiB, not read to its end.
  const std::string endless = Tmp("endless.csv");
  std::ofstream(endless, std::ios::binary) << std::string(3 << 20, '1');
  expect(RunLtp("identify " + endless + " --input 0 --output 1 --period 1"),
         "a line longer than 1 MiB");
  std::string letters = text;
  letters.replace(letters.find("E-0", letters.find("    17 ") + 500), 3, "XYZ");
  expect(run(letters), "is not a number");
}

// Multisine records with a tacho channel: `--tacho` sends broadband identification to the fit on
// the measured angle; at the model's speed it meets the model's partial FRFs (routes of ltp
// pfrf) as the constant-speed route does.
TEST(IdentifyCli, BroadbandRecordsOnATacho) {
  const std::string csv = Tmp("identify_ms_tacho.csv");
  ASSERT_EQ(RunLtp("simulate " + kScene +
                   " --excitation multisine:0.05:0.45:0.08 --records 12 --periods 16 --tacho "
                   "--out " +
                   csv)
                .code,
            0);
  const auto id =
      RunLtp("identify " + csv + " --tacho tacho --orders -3:3 --compare " + kScene + " --json");
  ASSERT_EQ(id.code, 0) << id.err;
  const json j = json::parse(id.out);
  EXPECT_EQ(j["method"], "broadband");
  bool said = false;
  for (const json& d : j["diagnostics"])
    said =
        said || d.get<std::string>().find("broadband on the measured angle") != std::string::npos;
  EXPECT_TRUE(said) << j["diagnostics"];
  const auto [worst, largest] = LargestModelError(j);
  EXPECT_LT(worst, 1e-6 * largest);
}

}  // namespace
