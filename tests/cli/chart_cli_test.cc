// `ltp chart` end to end: intervals in the JSON summary, the CSV columns, failed points,
// resume after an interruption, and MPI ranks against threads.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/ltp_cli.h"

namespace {

using nlohmann::json;
using test::ReadFile;
using test::RunLtp;

// Per process: two test runs on one machine (plain and sanitized builds) must not share files.
std::string Tmp(const std::string& name) {
  return std::string(::testing::TempDir()) + "ltp-" + std::to_string(getpid()) + "-" + name;
}

// Asymmetric shaft, undamped: unstable for 1 < Ω < sqrt(1.5) (closed form).
TEST(ChartCli, JsonListsRefinedIntervalAndCsvHasTrackedColumns) {
  const std::string csv = Tmp("chart_jeffcott.csv");
  const auto r =
      RunLtp("chart jeffcott --set k2=1.5 --sweep Omega=0.8:1.4:0.05 --csv " + csv + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["unstable_intervals"].size(), 1u);
  EXPECT_NEAR(j["unstable_intervals"][0][0].get<double>(), 1.0, 1e-8);
  EXPECT_NEAR(j["unstable_intervals"][0][1].get<double>(), std::sqrt(1.5), 1e-8);
  EXPECT_EQ(j["points"].get<int>(), 13);
  const std::string text = ReadFile(csv);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "Omega,max_real_exponent,stable,verdict,error_estimate,freq_hz_1,real_1,damping_1,"
            "freq_hz_2,real_2,damping_2,failure");  // one column set per conjugate pair (2 modes)
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 14);  // header + 13 rows
  EXPECT_FALSE(std::filesystem::exists(csv + ".journal"));    // journal gone when complete
}

// Maps say when their points integrate half a period: the damped Mathieu equation is
// time-reversible (docs/time-reversal.md), the Meissner equation's time functions are not
// inspected. The map's counts equal those of the full-period route (--check-every 1: every
// point by the full analysis over the period).
TEST(ChartCli, MapSaysWhenItIntegratesHalfAPeriod) {
  const std::string map = "chart mathieu --sweep a=-1:3:0.25 --sweep2 q=0:2:0.25 --json";
  const auto half = RunLtp(map);
  ASSERT_EQ(half.code, 0) << half.err;
  const json h = json::parse(half.out);
  EXPECT_TRUE(h["half_period"].get<bool>());
  const auto full = RunLtp(map + " --check-every 1");
  ASSERT_EQ(full.code, 0) << full.err;
  const json f = json::parse(full.out);
  for (const char* key : {"stable", "marginal", "unstable"})
    EXPECT_EQ(h[key].get<int>(), f[key].get<int>()) << key;
  const auto meissner = RunLtp("chart meissner --sweep a=0.5:1:0.25 --sweep2 b=0:0.5:0.25 --json");
  ASSERT_EQ(meissner.code, 0) << meissner.err;
  EXPECT_FALSE(json::parse(meissner.out)["half_period"].get<bool>());
  EXPECT_NE(RunLtp("chart mathieu --sweep a=-1:3:0.25 --sweep2 q=0:2:0.25")
                .out.find("half a period per unchecked point"),
            std::string::npos);
}

// Gyroscopic rotor (tests/data/gyroscopic-rotor.yaml): whirl lines cross nΩ at
// Ω² = k / (n (n Id ∓ Ip)), closed form; text, JSON and the crossings CSV agree with it.
TEST(ChartCli, CampbellCrossingsInTextJsonAndCsv) {
  const std::string csv = Tmp("chart_gyro.csv");
  const std::string args = "chart " + test::Src("tests/data/gyroscopic-rotor.yaml") +
                           " --sweep Omega=2:16:0.1 --per-rev 2 --csv " + csv;
  const auto r = RunLtp(args + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json c = json::parse(r.out)["campbell"];
  ASSERT_EQ(c["lines"].size(), 2u);
  EXPECT_EQ(c["lines"][0]["description"], "theta 50%, phi 50%");
  ASSERT_EQ(c["crossings"].size(), 4u);
  std::vector<double> exact;
  for (int n : {1, 2})
    for (double ip : {0.5, -0.5}) exact.push_back(std::sqrt(100 / (n * (n - ip))));
  for (const json& x : c["crossings"]) {
    const double at = x["parameter"].get<double>();
    double nearest = 1e9;
    for (double e : exact) nearest = std::min(nearest, std::abs(at - e));
    EXPECT_LE(nearest, x["parameter_error"].get<double>()) << at;
    EXPECT_LT(nearest, 1e-3) << at;
  }
  const std::string crossings = ReadFile(Tmp("chart_gyro-crossings.csv"));
  EXPECT_EQ(crossings.substr(0, crossings.find('\n')),
            "mode,description,per_rev,Omega,Omega_error,rotor_speed_rad_s,frequency_hz,real_part,"
            "damping_ratio");
  EXPECT_EQ(std::count(crossings.begin(), crossings.end(), '\n'), 5);
  const auto text = RunLtp(args);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("crossings with the per-rev lines n·Ω/2π (4)"), std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("theta 50%, phi 50%"), std::string::npos);
}

// `ltp campbell` on the rotor's operating-point set (tests/data/openfast/rotor-speeds, given
// out of order): sorted by rotor speed, five MBC3 lines, crossings, CSV files; bad sets refused.
TEST(ChartCli, CampbellOfAnOperatingPointSet) {
  const std::string root = test::Src("tests/data/openfast/rotor-speeds");
  std::string dirs;
  for (const char* w : {"1.2", "0.4", "0.8", "1.6", "0.6", "1.0", "1.4"})
    dirs += " " + root + "/omega-" + w;
  const std::string csv = Tmp("campbell_set.csv");
  const auto r = RunLtp("campbell" + dirs + " --frequency damped --csv " + csv + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["points"].size(), 7u);
  for (size_t p = 1; p < 7; ++p)
    EXPECT_GT(j["points"][p]["rotor_speed_rad_s"].get<double>(),
              j["points"][p - 1]["rotor_speed_rad_s"].get<double>());
  EXPECT_NEAR(j["points"][0]["parameter"].get<double>(), 0.4 * 30 / M_PI, 1e-12);  // rpm
  ASSERT_EQ(j["campbell"]["lines"].size(), 5u);
  EXPECT_NE(j["campbell"]["lines"][0]["description"].get<std::string>().find("lag angle of blade"),
            std::string::npos);
  EXPECT_FALSE(j["campbell"]["crossings"].empty());
  const std::string table = ReadFile(csv);
  // Ordered by rotor speed: rpm first and only once; columns named by mode.
  EXPECT_EQ(table.rfind("rotor_speed_rpm,wind_speed_m_s,pitch_deg,\"mode 1 (", 0), 0u) << table;
  EXPECT_NE(table.find("damped frequency [Hz]\""), std::string::npos);
  const std::string header = table.substr(0, table.find('\n'));
  EXPECT_EQ(header.find("rpm", header.find("rpm") + 1), std::string::npos) << header;
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 8);  // header + 7 points
  EXPECT_TRUE(std::filesystem::exists(Tmp("campbell_set-crossings.csv")));
  // Each line carries its values per point; the CSV's columns are the JSON's numbers.
  EXPECT_EQ(j["campbell"]["frequency"], "damped");
  for (const json& line : j["campbell"]["lines"]) {
    ASSERT_EQ(line["frequency_hz"].size(), 7u);
    ASSERT_EQ(line["damping_ratio"].size(), 7u);
  }
  // Natural frequencies |λ|/2π = sqrt(f_d² + (Re λ/2π)²) of the same eigenvalues.
  // The default for .lin sets, as ACDC and openfast_toolbox draw them.
  const auto natural = RunLtp("campbell" + dirs + " --json");
  ASSERT_EQ(natural.code, 0) << natural.err;
  const json n = json::parse(natural.out)["campbell"];
  EXPECT_EQ(n["frequency"], "natural");
  for (size_t k = 0; k < 5; ++k)
    for (size_t p = 0; p < 7; ++p) {
      const double fd = j["campbell"]["lines"][k]["frequency_hz"][p].get<double>();
      const double re = j["campbell"]["lines"][k]["real_part"][p].get<double>();
      EXPECT_NEAR(n["lines"][k]["frequency_hz"][p].get<double>(), std::hypot(fd, re / (2 * M_PI)),
                  1e-12 * fd);
    }
  EXPECT_EQ(RunLtp("campbell" + dirs + " --frequency undamped").code, 2);
  // A copy of a point elsewhere is one operating point twice: refused, naming the files.
  const std::string copy = Tmp("omega-0.4-copy");
  std::filesystem::remove_all(copy);
  std::filesystem::copy(root + "/omega-0.4", copy);
  const auto twice = RunLtp("campbell " + root + "/omega-0.4 " + copy);
  EXPECT_EQ(twice.code, 2);
  EXPECT_NE(twice.err.find("same rotor speed [rpm]"), std::string::npos) << twice.err;
}

// OpenFAST's own layout: the seven simulations' <root>.<k>.lin files in one folder. ltp
// campbell groups them by root (the same diagram as one directory per point); ltp mbc, which
// analyses one point, says what the folder holds; --keep-going leaves out a broken simulation.
TEST(ChartCli, CampbellOfAFlatOpenFastFolder) {
  const std::string root = test::Src("tests/data/openfast/rotor-speeds");
  const std::string flat = Tmp("campbell_flat");
  std::filesystem::remove_all(flat);
  std::filesystem::create_directories(flat);
  std::string dirs;
  for (const char* w : {"0.4", "0.6", "0.8", "1.0", "1.2", "1.4", "1.6"}) {
    dirs += " " + root + "/omega-" + w;
    for (int k = 1; k <= 3; ++k)
      std::filesystem::copy_file(root + "/omega-" + w + "/rotor." + std::to_string(k) + ".lin",
                                 flat + "/omega" + w + "." + std::to_string(k) + ".lin");
  }
  const auto per_directory = RunLtp("campbell" + dirs + " --json");
  const auto folder = RunLtp("campbell " + flat + " --json");
  ASSERT_EQ(folder.code, 0) << folder.err;
  ASSERT_EQ(per_directory.code, 0) << per_directory.err;
  EXPECT_EQ(json::parse(folder.out)["campbell"], json::parse(per_directory.out)["campbell"]);
  const auto mbc = RunLtp("mbc " + flat + " --no-floquet");
  EXPECT_EQ(mbc.code, 2);
  EXPECT_NE(mbc.err.find("7 OpenFAST simulations"), std::string::npos) << mbc.err;
  std::ofstream(flat + "/broken.1.lin") << "not a linearisation\n";
  EXPECT_EQ(RunLtp("campbell " + flat).code, 2);
  const auto kept = RunLtp("campbell " + flat + " --keep-going");
  ASSERT_EQ(kept.code, 0) << kept.err;
  EXPECT_NE(kept.out.find("left out (--keep-going): "), std::string::npos) << kept.out;
  EXPECT_NE(kept.out.find("broken.1.lin"), std::string::npos) << kept.out;
}

TEST(ChartCli, FailedPointsAreRowsWithTheirReason) {
  const std::string csv = Tmp("chart_failed.csv");
  const auto r = RunLtp("chart jeffcott --sweep m=-0.5:1:0.5 --csv " + csv);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("2 failed"), std::string::npos) << r.out;
  const std::string text = ReadFile(csv);
  EXPECT_NE(text.find(",failed,"), std::string::npos);
}

TEST(ChartCli, BadInputIsOneLineExitTwo) {
  for (const char* args : {"chart mathieu --sweep a=1:0:0.1", "chart mathieu --sweep zz=0:1:0.1",
                           "chart mathieu --sweep a=0:1:0.1 --plot x.jpg",
                           "chart mathieu --sweep a=0:1:0.1 --resume"}) {
    const auto r = RunLtp(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// Without gnuplot on PATH the picture is a script with the data inline, and ltp says so.
TEST(ChartCli, WithoutGnuplotWritesTheScript) {
  const std::string png = Tmp("chart_nognuplot.png");
  std::filesystem::remove(png + ".gp");
  const auto r = RunLtp("chart mathieu --sweep a=0:2:0.5 --plot " + png, "PATH=/nonexistent ");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("gnuplot " + png + ".gp"), std::string::npos) << r.out;
  const std::string script = ReadFile(png + ".gp");
  EXPECT_NE(script.find("set output '" + png + "'"), std::string::npos);
  EXPECT_NE(script.find("$M << EOD"), std::string::npos);
}

// Maps: the boundary curves in the JSON and FILE-curves.csv, drawn into a PDF; --plot-x puts
// the chosen parameter on the horizontal axis. Reference: the undamped Mathieu tongues reach
// the a axis at a_m(0) = b_m(0) = m² (DLMF 28.6.1–28.6.4 at q = 0).
TEST(ChartCli, MapCurvesInJsonCsvAndPdf) {
  const std::string csv = Tmp("chart_curves.csv"), pdf = Tmp("chart_curves.pdf");
  std::filesystem::remove(pdf);
  const std::string map = "chart mathieu --set c=0 --sweep q=0:3:0.25 --sweep2 a=-1:5:0.25 ";
  const auto r = RunLtp(map + "--json --csv " + csv + " --plot " + pdf + " --plot-x a");
  ASSERT_EQ(r.code, 0) << r.err;
  const json curves = json::parse(r.out)["boundary_curves"]["curves"];
  ASSERT_EQ(curves.size(), 5u);  // a_0, b_1, a_1, b_2, a_2
  std::vector<double> tips;
  size_t points = 0;
  for (const json& c : curves) {
    EXPECT_TRUE(c["kind"] == "+1" || c["kind"] == "-1");
    ASSERT_EQ(c["points"].size(), c["bracket"].size());
    points += c["points"].size();
    for (const json& p : c["points"])
      if (p[0].get<double>() == 0) tips.push_back(p[1].get<double>());
  }
  std::sort(tips.begin(), tips.end());
  const double expected[] = {0, 1, 1, 4, 4};
  ASSERT_EQ(tips.size(), 5u);
  for (size_t k = 0; k < 5; ++k) EXPECT_NEAR(tips[k], expected[k], 1e-8);
  const std::string table = ReadFile(Tmp("chart_curves-curves.csv"));
  EXPECT_EQ(table.rfind("curve,kind,symmetry,q,a,across,bracket,merged\n", 0), 0u)
      << table.substr(0, 80);
  EXPECT_EQ(static_cast<size_t>(std::count(table.begin(), table.end(), '\n')), points + 1);
  if (std::system("gnuplot -e 'set terminal pdfcairo' >/dev/null 2>&1") == 0) {
    EXPECT_EQ(ReadFile(pdf).substr(0, 4), "%PDF");
  }
  // The script (no gnuplot on the PATH): a horizontal, the curves as lines, every parameter.
  const auto gp = RunLtp(map + "--plot " + pdf + " --plot-x a", "PATH=/nonexistent ");
  ASSERT_EQ(gp.code, 0) << gp.err;
  const std::string script = ReadFile(pdf + ".gp");
  EXPECT_NE(script.find("set xlabel \"a"), std::string::npos);
  EXPECT_NE(script.find("set terminal pdfcairo"), std::string::npos);
  EXPECT_NE(script.find("transition curve: multiplier +1"), std::string::npos);
  EXPECT_NE(script.find("c = 0; swept: q, a"), std::string::npos);
}

// An interrupted 2-D sweep leaves a valid CSV and its journal; --resume computes only the
// missing points and ends with exactly the file an uninterrupted run writes.
TEST(ChartCli, ResumeAfterInterruptionEqualsUninterrupted) {
  const std::string sweep = "chart mathieu --sweep a=-1:3:0.25 --sweep2 q=0:2:0.25 --threads 2 ";
  const std::string whole = Tmp("chart_whole.csv"), cut = Tmp("chart_cut.csv");
  ASSERT_EQ(RunLtp(sweep + "--csv " + whole).code, 0);
  const auto first = RunLtp(sweep + "--csv " + cut + " --stop-after 40");
  EXPECT_EQ(first.code, 130) << first.err;
  EXPECT_NE(first.err.find("--resume"), std::string::npos) << first.err;
  ASSERT_TRUE(std::filesystem::exists(cut + ".journal"));
  const std::string partial = ReadFile(cut);
  const long rows = std::count(partial.begin(), partial.end(), '\n') - 1;
  EXPECT_GE(rows, 40);
  EXPECT_LT(rows, 153);  // 17 × 9 points in all
  const auto second = RunLtp(sweep + "--csv " + cut + " --resume --json");
  ASSERT_EQ(second.code, 0) << second.err;
  EXPECT_EQ(json::parse(second.out)["resumed_points"].get<long>(), rows);
  EXPECT_EQ(ReadFile(cut), ReadFile(whole));
  // A journal from another sweep is refused.
  RunLtp(sweep + "--csv " + cut + " --stop-after 5");
  const auto other =
      RunLtp("chart mathieu --sweep a=-1:3:0.5 --sweep2 q=0:2:0.25 --csv " + cut + " --resume");
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("different sweep"), std::string::npos) << other.err;
}

// A 1-D sweep journals mode shapes (the Campbell lines are tracked by them) and snapshot
// eigenvalues: resumed, it still writes the uninterrupted file and the same Campbell lines.
TEST(ChartCli, ResumeOfA1DSweepKeepsShapesAndSnapshots) {
  const std::string sweep = "chart jeffcott --set k2=1.5 --sweep Omega=0.8:1.4:0.05 --compare ";
  const std::string whole = Tmp("chart_whole1d.csv"), cut = Tmp("chart_cut1d.csv");
  const auto full = RunLtp(sweep + "--csv " + whole + " --json");
  ASSERT_EQ(full.code, 0) << full.err;
  ASSERT_EQ(RunLtp(sweep + "--csv " + cut + " --stop-after 5 --threads 1").code, 130);
  const auto resumed = RunLtp(sweep + "--csv " + cut + " --resume --json");
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_GE(json::parse(resumed.out)["resumed_points"].get<long>(), 5);
  EXPECT_EQ(ReadFile(cut), ReadFile(whole));
  EXPECT_EQ(json::parse(resumed.out)["campbell"], json::parse(full.out)["campbell"]);
}

// The journal survives damage: a forged value (checksum mismatch), a torn last record, a record
// with an index the grid does not have, and a duplicate are each dropped and recomputed, and
// the resumed file still equals the uninterrupted one. (A torn line plus a bad index used to
// hang --resume.) The records are walked by the framing documented in cli/chart_journal.h:
// u32 length, u64 checksum, payload ('H' header, 'D' diagnostic text, 'P' point whose first
// field is its u64 grid index).
TEST(ChartCli, ResumeDropsDamagedJournalRecords) {
  const std::string sweep = "chart mathieu --sweep a=-1:3:0.25 --sweep2 q=0:2:0.25 --threads 2 ";
  const std::string whole = Tmp("chart_whole2.csv"), cut = Tmp("chart_damaged.csv");
  ASSERT_EQ(RunLtp(sweep + "--csv " + whole).code, 0);
  ASSERT_EQ(RunLtp(sweep + "--csv " + cut + " --stop-after 40").code, 130);
  const std::string journal = cut + ".journal";
  const std::string bytes = ReadFile(journal);
  const std::string magic = "ltp-journal 3\n";
  ASSERT_EQ(bytes.compare(0, magic.size(), magic), 0);
  std::vector<std::string> records;  // whole frames, in order
  for (size_t at = magic.size(); at + 12 <= bytes.size();) {
    std::uint32_t size = 0;
    std::memcpy(&size, bytes.data() + at, 4);
    ASSERT_LE(at + 12 + size, bytes.size());
    records.push_back(bytes.substr(at, 12 + size));
    at += 12 + size;
  }
  std::vector<size_t> points;  // the others are the header and diagnostic texts
  for (size_t i = 0; i < records.size(); ++i)
    if (records[i][12] == 'P') points.push_back(i);
  ASSERT_GE(points.size(), 5u);
  ASSERT_EQ(points.back(), records.size() - 1);  // the last record, torn below, is a point
  const long good = static_cast<long>(points.size()) - 2;  // two records damaged below
  // Forge a record: change a byte of its max Re λ (after type, index, ok, verdict, period and
  // rotor speed) but keep the old checksum.
  std::string& forged = records[points[0]];
  forged[12 + 1 + 8 + 1 + 4 + 8 + 8 + 3] ^= 0x10;
  const std::string duplicate = records[points[1]];
  std::string bad_index = records[points[2]];
  bad_index[12 + 1 + 6] = 0x7f;  // index far out of range; checksum recomputed below
  {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a of the payload, as the journal does
    for (size_t k = 12; k < bad_index.size(); ++k) {
      h ^= static_cast<unsigned char>(bad_index[k]);
      h *= 1099511628211ull;
    }
    std::memcpy(bad_index.data() + 4, &h, 8);
  }
  records.back().resize(records.back().size() / 2);  // torn
  {
    std::ofstream out(journal, std::ios::binary | std::ios::trunc);
    out << magic;
    for (size_t i = 0; i + 1 < records.size(); ++i) out << records[i];
    out << duplicate << bad_index << records.back();  // the torn record last
  }
  const auto resumed = RunLtp(sweep + "--csv " + cut + " --resume --json");
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(json::parse(resumed.out)["resumed_points"].get<long>(),
            good);  // forged, torn, bad, duplicate out
  EXPECT_EQ(ReadFile(cut), ReadFile(whole));
  // A file that is not a journal (e.g. one of an older ltp) is refused with a reason.
  RunLtp(sweep + "--csv " + cut + " --stop-after 5");
  {
    std::ofstream out(journal, std::ios::trunc);
    out << "{\"identity\":{}}\t0123456789abcdef\n";
  }
  const auto old = RunLtp(sweep + "--csv " + cut + " --resume");
  EXPECT_EQ(old.code, 2);
  EXPECT_NE(old.err.find("not a journal"), std::string::npos) << old.err;
}

// Journals that are not what they seem (the round-2 reproducers): a header record whose identity
// is not JSON (re-checksummed) was waved through and a c = 0.5 sweep's points were resumed into
// another; a directory gave libstdc++'s raw text; /dev/zero read until memory ran out.
TEST(ChartCli, ResumeRefusesJournalsThatAreNotJournals) {
  const std::string sweep = "chart mathieu --sweep a=0:3:0.05 --threads 1 ";
  const std::string csv = Tmp("chart_header.csv"), journal = csv + ".journal";
  ASSERT_EQ(RunLtp(sweep + "--set c=0.5 --csv " + csv + " --stop-after 20").code, 130);
  {  // the header's identity replaced by an empty text, its checksum made right again
    const std::string bytes = ReadFile(journal);
    const size_t magic = std::string("ltp-journal 3\n").size();
    std::uint32_t size = 0;
    std::memcpy(&size, bytes.data() + magic, 4);
    std::string payload = "H";
    const std::uint32_t empty = 0;
    payload.append(reinterpret_cast<const char*>(&empty), 4);
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a, as the journal frames it
    for (unsigned char c : payload) {
      h ^= c;
      h *= 1099511628211ull;
    }
    const auto length = static_cast<std::uint32_t>(payload.size());
    std::string frame(reinterpret_cast<const char*>(&length), 4);
    frame.append(reinterpret_cast<const char*>(&h), 8);
    std::ofstream out(journal, std::ios::binary | std::ios::trunc);
    out << bytes.substr(0, magic) << frame << payload << bytes.substr(magic + 12 + size);
  }
  const auto damaged = RunLtp(sweep + "--csv " + csv + " --resume");
  EXPECT_EQ(damaged.code, 2);
  EXPECT_NE(damaged.err.find("damaged header record"), std::string::npos) << damaged.err;
  std::filesystem::remove(journal);
  std::filesystem::create_directory(journal);
  const auto directory = RunLtp(sweep + "--csv " + csv + " --resume");
  EXPECT_EQ(directory.code, 2);
  EXPECT_NE(directory.err.find("not a regular file"), std::string::npos) << directory.err;
  std::filesystem::remove(journal);
  std::filesystem::create_symlink("/dev/zero", journal);
  const auto zero = RunLtp(sweep + "--csv " + csv + " --resume");
  EXPECT_EQ(zero.code, 2);
  EXPECT_NE(zero.err.find("not a regular file"), std::string::npos) << zero.err;
  std::filesystem::remove(journal);
}

// One writer per CSV: a live ltp's lock refuses a second run; a lock left by a killed process
// (its pid gone) or holding the pid of a process that is not ltp (pid 1; a reused pid) is taken
// over.
TEST(ChartCli, OneWriterPerCsv) {
  const std::string csv = Tmp("chart_locked.csv");
  // A live process whose command name starts with "ltp": /bin/sleep run through a link.
  const std::string holder = Tmp("ltp-holder");
  std::filesystem::remove(holder);
  std::filesystem::create_symlink("/bin/sleep", holder);
  const pid_t pid = fork();
  if (pid == 0) {
    execl(holder.c_str(), holder.c_str(), "30", static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_GT(pid, 0);
  {
    std::ofstream lock(csv + ".lock");
    lock << pid << "\n";
  }
  const auto busy = RunLtp("chart mathieu --sweep a=0:1:0.5 --csv " + csv);
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  std::filesystem::remove(holder);
  EXPECT_EQ(busy.code, 2);
  EXPECT_NE(busy.err.find("another ltp chart"), std::string::npos) << busy.err;
  {
    std::ofstream lock(csv + ".lock", std::ios::trunc);
    lock << 1 << "\n";  // alive, but not ltp: stale
  }
  EXPECT_EQ(RunLtp("chart mathieu --sweep a=0:1:0.5 --csv " + csv).code, 0);
  {
    std::ofstream lock(csv + ".lock", std::ios::trunc);
    lock << 999999999 << "\n";  // no such process
  }
  EXPECT_EQ(RunLtp("chart mathieu --sweep a=0:1:0.5 --csv " + csv).code, 0);
  EXPECT_FALSE(std::filesystem::exists(csv + ".lock"));
}

// Two MPI ranks write the same file as one process with two threads.
TEST(ChartCli, MpiRanksEqualThreads) {
#ifndef LTP_WITH_MPI
  GTEST_SKIP() << "built without -DLTP_WITH_MPI=ON";
#else
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  const std::string sweep = "chart mathieu --sweep a=-1:3:0.1 --sweep2 q=0:2:0.2 ";
  const std::string threads = Tmp("chart_threads.csv"), ranks = Tmp("chart_ranks.csv");
  ASSERT_EQ(RunLtp(sweep + "--threads 2 --csv " + threads).code, 0);
  // Root in a container is common on CI machines; Open MPI refuses it unless told.
  const auto r = RunLtp(sweep + "--threads 1 --csv " + ranks,
                        "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                        "mpirun -n 2 --oversubscribe ");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("2 MPI ranks"), std::string::npos) << r.out;
  EXPECT_EQ(ReadFile(ranks), ReadFile(threads));
#endif
}

}  // namespace
