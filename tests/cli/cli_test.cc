// End-to-end: run the `ltp` binary as a user would and check its output and exit codes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "support/ltp_cli.h"

namespace {

using Outcome = test::LtpRun;
Outcome Ltp(const std::string& args) { return test::RunLtp(args); }

using test::Src;

TEST(Cli, VersionAndHelp) {
  EXPECT_EQ(Ltp("--version").code, 0);
  const Outcome h = Ltp("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("floquet"), std::string::npos);
  EXPECT_EQ(Ltp("floquet --help").code, 0);
}

TEST(Cli, ScenesListsBuiltins) {
  const Outcome r = Ltp("scenes --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  std::vector<std::string> names;
  for (const auto& s : j) names.push_back(s["name"]);
  for (const char* want : {"mathieu", "meissner", "jeffcott"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
}

// Each Floquet mode names the states that carry it; the MBC cross-check of the same run says
// which exponent is the collective lag mode: the named one must be it.
TEST(Cli, FloquetModesAreNamedByTheirStates) {
  const Outcome r = Ltp("floquet rotor --set blades=3 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["modes"].size(), 10u);
  int collective = 0;
  for (size_t k = 0; k < 10; ++k) {
    const std::string d = j["modes"][k]["description"];
    EXPECT_FALSE(d.empty()) << k;
    // The collective lag mode of identical blades is decoupled from the support (closed form:
    // Re λ = −C_ζ/(2 I_b) = −0.095 1/s with the scene's C_ζ = 0.19, I_b = 1).
    if (d == "zeta collective 100%") {
      ++collective;
      EXPECT_NEAR(j["exponents"][k]["re"].get<double>(), -0.095, 1e-9);
    }
  }
  EXPECT_EQ(collective, 2);  // the conjugate pair
  // The hub's (x, y) are the rotor scene's whirl plane: the collective mode leaves the hub
  // still, so it has no whirl; the others say how much of their hub motion turns with the
  // rotor (the share itself is tested against the rotating frame in floquet_test.cc).
  for (size_t k = 0; k < 10; ++k) {
    const auto& mode = j["modes"][k];
    if (mode["description"] == "zeta collective 100%") {
      EXPECT_EQ(mode["forward_whirl"], "nan") << k;  // JSON numbers write NaN as "nan"
    } else {
      const double share = mode["forward_whirl"];
      EXPECT_TRUE(share >= 0 && share <= 1) << k;
    }
  }
}

TEST(Cli, ModesCsvColumnsNameModeAndState) {
  // Per process: the plain and sanitized test runs must not share files.
  const std::string csv =
      std::string(::testing::TempDir()) + "ltp-" + std::to_string(getpid()) + "-modes.csv";
  const Outcome r = Ltp("floquet jeffcott --set c=0.05 --set Omega=0.5 --modes-csv " + csv);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = test::ReadFile(csv);
  EXPECT_EQ(
      text.rfind(
          "t,\"re_mode1_x\",\"im_mode1_x\",\"re_mode1_y\",\"im_mode1_y\",\"re_mode1_x_dot\",", 0),
      0u)
      << text.substr(0, 120);
  // The table says which way each mode whirls (Jeffcott below its critical speeds: the lower
  // mode forward, the upper backward; the shares in floquet_test.cc against the rotating frame).
  EXPECT_NE(r.out.find("; forward whirl 96.1%"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; backward whirl 99.4%"), std::string::npos) << r.out;
  // Hill's route alone has no mode shapes to write: refused, not silently skipped.
  const Outcome hill = Ltp("floquet jeffcott --method hill --modes-csv " + csv);
  EXPECT_EQ(hill.code, 2);
  EXPECT_NE(hill.err.find("--modes-csv needs the monodromy route"), std::string::npos) << hill.err;
}

// --deflection-csv: one row per mode, sample time, body and node; the rest positions are the
// scene's geometry in closed form (cantilever tip at (L, 0, 0), blade 1's tip at ψ = 0 at
// (L, d, r_h + L_b) with the defaults L = 0.47, d = 0.03, r_h + L_b = 0.207 m).
TEST(Cli, DeflectionCsvDrawsTheTowerRotorOverAPeriod) {
  const std::string csv =
      std::string(::testing::TempDir()) + "ltp-" + std::to_string(getpid()) + "-deflection.csv";
  const Outcome r = Ltp("floquet tower-rotor --mode-samples 8 --deflection-csv " + csv +
                        " --deflection-mode 1 --deflection-mode 3");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = test::ReadFile(csv);
  ASSERT_EQ(text.rfind("mode,t,body,node,x_rest,y_rest,z_rest,x,y,z\n", 0), 0u)
      << text.substr(0, 80);
  // 2 modes × 8 times × (21 cantilever + 2 shaft + 2 × 12 blade) nodes, and the header.
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2 * 8 * 47 + 1);
  EXPECT_NE(text.find("\n1,0,\"cantilever\",20,0.47,0,0,"), std::string::npos);
  EXPECT_NE(text.find("\n1,0,\"blade1\",11,0.47,0.03,0.207,"), std::string::npos);
  EXPECT_NE(text.find("\n3,"), std::string::npos);
  EXPECT_EQ(text.find("\n2,"), std::string::npos);
  // A scene without a structure is refused with what works instead.
  const Outcome mathieu = Ltp("floquet mathieu --deflection-csv " + csv);
  EXPECT_EQ(mathieu.code, 2);
  EXPECT_NE(mathieu.err.find("scene 'mathieu' has no structure to draw"), std::string::npos)
      << mathieu.err;
  // The picture: chosen modes only (at most 4 rows), drawn by gnuplot.
  const std::string svg = csv + ".svg";
  const Outcome plot =
      Ltp("floquet tower-rotor --mode-samples 8 --deflection-plot " + svg + " --deflection-mode 1");
  ASSERT_EQ(plot.code, 0) << plot.err;
  EXPECT_NE(test::ReadFile(svg).find("<svg"), std::string::npos);
  const Outcome many = Ltp("floquet tower-rotor --deflection-plot " + svg);
  EXPECT_EQ(many.code, 2);
  EXPECT_NE(many.err.find("draws at most 4 modes, 22 chosen"), std::string::npos) << many.err;
  const Outcome orphan = Ltp("floquet tower-rotor --deflection-mode 2");
  EXPECT_EQ(orphan.code, 2);
  EXPECT_NE(orphan.err.find("give one"), std::string::npos) << orphan.err;
}

TEST(Cli, InfoMathieu) {
  const Outcome r = Ltp("info mathieu --set q=2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["states"], 2);
  EXPECT_NEAR(j["period"].get<double>(), std::numbers::pi, 1e-15);  // Mathieu: period π
  EXPECT_EQ(j["parameters"]["q"], 2.0);
  // Snapshot at t = 0: A = [[0,1],[-(a-2q), -c]] (hand-computed from the scene definition).
  ASSERT_EQ(j["snapshot_eigenvalues"].size(), 2u);
  EXPECT_EQ(Ltp("info mathieu --set q=2").code, 0);
}

// The JSON object of `ltp floquet --json`, with a value checked against GSL-independent physics:
// for a = 1.5, q = 2 (inside the first Mathieu tongue, a_1(2) ≈ 1.859 > 1.5 > b_1(2) ≈ -0.110), the
// undamped system is unstable with multipliers ρ, 1/ρ real negative.
TEST(Cli, FloquetJsonHasTheDocumentedKeys) {
  const Outcome r = Ltp("floquet mathieu --set a=1.5 --set q=2 --set c=0 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key :
       {"scene", "parameters", "states", "period", "method", "integrator", "segments", "exponents",
        "multipliers", "max_real_exponent", "stable", "error_estimate", "elapsed_s", "diagnostics"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["method"], "monodromy");
  ASSERT_EQ(j["exponents"].size(), 2u);
  for (const char* key : {"re", "im", "frequency_hz", "damping_ratio"})
    EXPECT_TRUE(j["exponents"][0].contains(key)) << key;
  for (const char* key : {"re", "im", "log_abs", "arg"})
    EXPECT_TRUE(j["multipliers"][0].contains(key)) << key;
  EXPECT_FALSE(j["stable"].get<bool>());
  EXPECT_GT(j["max_real_exponent"].get<double>(), 0.1);
  // Liouville for c = 0: log|ρ1| + log|ρ2| = 0.
  EXPECT_NEAR(
      j["multipliers"][0]["log_abs"].get<double>() + j["multipliers"][1]["log_abs"].get<double>(),
      0, 1e-8);
  // Negative real multipliers: arg = ±π.
  EXPECT_NEAR(std::abs(j["multipliers"][0]["arg"].get<double>()), std::numbers::pi, 1e-8);
}

// A user YAML scene whose multipliers under- and overflow a double: exponents are the
// period averages of the diagonal (closed form for a triangular A): -800, 150, -3.
TEST(Cli, StiffYamlSceneKeepsEveryExponent) {
  const Outcome r = Ltp("floquet " + Src("tests/data/stiff.yaml") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  std::vector<double> re;
  for (const auto& e : j["exponents"]) re.push_back(e["re"].get<double>());
  std::sort(re.begin(), re.end());
  ASSERT_EQ(re.size(), 3u);
  EXPECT_NEAR(re[0], -800, 800 * 1e-9);
  EXPECT_NEAR(re[1], -3, 3 * 1e-9);
  EXPECT_NEAR(re[2], 150, 150 * 1e-9);
  bool underflow = false, overflow = false;
  for (const auto& m : j["multipliers"]) {
    if (m["re"] == 0.0 && m["log_abs"].get<double>() < -5000) underflow = true;
    if (m["re"] == "inf" && m["log_abs"].get<double>() > 900) overflow = true;
  }
  EXPECT_TRUE(underflow);
  EXPECT_TRUE(overflow);
  EXPECT_FALSE(j["stable"].get<bool>());
}

// Forced bad settings: one segment with single-shot multipliers loses the multiplier e^{-120π}
// of a closed-form system (exponents −60 and 2, see the scene file). The result fails its own
// Liouville check, so it is not ok: exit 1 and says so, unless --keep-going.
TEST(Cli, ResultThatFailsItsChecksIsNotOk) {
  const std::string scene = Src("tests/data/stiff-rotating.yaml");
  const Outcome good = Ltp("floquet " + scene + " --json");
  ASSERT_EQ(good.code, 0) << good.err;
  std::vector<double> re;
  const auto g = nlohmann::json::parse(good.out);
  for (const auto& e : g["exponents"]) re.push_back(e["re"].get<double>());
  std::sort(re.begin(), re.end());
  ASSERT_EQ(re.size(), 2u);
  EXPECT_NEAR(re[0], -60, 60 * 1e-8);
  EXPECT_NEAR(re[1], 2, 2 * 1e-8);

  const Outcome bad = Ltp("floquet " + scene + " --segments 1 --multipliers single-shot");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.out.find("FAILED its own checks"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("Liouville check failed"), std::string::npos) << bad.out;
  EXPECT_EQ(bad.out.find("→  UNSTABLE"), std::string::npos) << bad.out;
  const Outcome kept =
      Ltp("floquet " + scene + " --segments 1 --multipliers single-shot --json --keep-going");
  EXPECT_EQ(kept.code, 0);
  const auto j = nlohmann::json::parse(kept.out);
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["verdict"], "failed");
}

// Verdicts use the error estimate: the undamped Mathieu oscillator between its tongues
// (a = 2, q = 0.1) has max Re λ = 0 exactly (multipliers on the unit circle), so both routes
// must say "marginal", not UNSTABLE from a round-off of +1e-15.
TEST(Cli, ConservativeSystemIsMarginalOnBothRoutes) {
  const Outcome r = Ltp("floquet mathieu --set a=2 --set q=0.1 --set c=0 --method both --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["monodromy"]["verdict"], "marginal");
  EXPECT_EQ(j["hill"]["verdict"], "marginal");
  EXPECT_FALSE(j["monodromy"]["stable"].get<bool>());
  const Outcome t = Ltp("floquet mathieu --set a=2 --set q=0.1 --set c=0");
  EXPECT_NE(t.out.find("MARGINAL"), std::string::npos) << t.out;
}

// The 2:1 parametric resonance (Mathieu inside its first tongue, a = 1, q = 0.5): both routes
// report the T-periodic system's exponents, Im λ = Ωp/2 = 1 rad/s (0.159155 Hz), and T
// multipliers (arg ρ = π). Hill used to double the period and print 0 Hz.
TEST(Cli, StripEdgeFrequencyIsHalfTheParametricFrequencyOnBothRoutes) {
  const Outcome r = Ltp("floquet mathieu --set a=1 --set q=0.5 --method both --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* route : {"monodromy", "hill"}) {
    EXPECT_NEAR(j[route]["period"].get<double>(), std::numbers::pi, 1e-15) << route;
    for (const auto& e : j[route]["exponents"])
      EXPECT_NEAR(e["frequency_hz"].get<double>(), 1 / (2 * std::numbers::pi), 1e-9) << route;
    for (const auto& m : j[route]["multipliers"])
      EXPECT_NEAR(m["arg"].get<double>(), std::numbers::pi, 1e-9) << route;
  }
  EXPECT_LT(j["disagreement"].get<double>(), 1e-10);
}

// `--method both` on the classes where Hill used to go wrong: a double negative multiplier
// (10 states), a discontinuous A(t) (square wave). Both routes ok, and their disagreement within
// the sum of their own estimates.
TEST(Cli, BothRoutesAgreeOnRepeatedMultipliersAndJumps) {
  for (const std::string& scene :
       {Src("tests/data/double-negative-multiplier.yaml"), Src("scenes/meissner.yaml")})
    for (const char* solver : {"auto", "structured", "dense"}) {
      const Outcome r =
          Ltp("floquet " + scene + " --method both --hill-solver " + solver + " --json");
      ASSERT_EQ(r.code, 0) << scene << " " << solver << ": " << r.err;
      const auto j = nlohmann::json::parse(r.out);
      EXPECT_TRUE(j["hill"]["ok"].get<bool>()) << scene << " " << solver;
      const double d = j["disagreement"].get<double>();
      EXPECT_LE(d, j["monodromy"]["error_estimate"].get<double>() +
                       j["hill"]["error_estimate"].get<double>())
          << scene << " " << solver;
      EXPECT_EQ(j["hill"]["exponents"].size(), j["monodromy"]["exponents"].size());
    }
}

// Huge coefficients used to crash (SIGSEGV: every periodic mode shape failed and the empty mode
// matrix was decomposed). Now the exponents stand, and the periodic Schur route delivers the
// shapes too (each satisfying Φ_i v_i = σ_i v_{i+1} to round-off), with the note that the
// default mode samples do not resolve them.
// Reference: WKB, leading order — the growth over a period is ∫ √(k(t)) dt where k(t) > 0:
// y'' = 1e6 |sin t| y, over [0, π]: 1000 ∫_0^π √(sin t) dt = 2396.3; Mathieu q = 1e5 (a = 1):
// ∫_{|t|<π/4} √(2q cos 2t) dt = 1.1981 √(2q) = 535.8.
TEST(Cli, HugeCoefficientsAnalyseWithModeShapes) {
  const struct {
    std::string args;
    double log_rho;
  } cases[] = {{Src("tests/data/robustness/crash_segv_all_modes_failed.yaml"), 2396.3},
               {"mathieu --set q=1e5", 535.8}};
  for (const auto& c : cases) {
    const Outcome r = Ltp("floquet " + c.args + " --json");
    ASSERT_EQ(r.code, 0) << c.args << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j["max_log_abs_multiplier"].get<double>(), c.log_rho, 0.005 * c.log_rho) << c.args;
    for (const auto& m : j["modes"]) EXPECT_LE(m["eigenvector_residual"].get<double>(), 1e-12);
    bool said = false;
    for (const auto& d : j["diagnostics"])
      said = said || d.get<std::string>().find("mode shapes under-resolved") != std::string::npos;
    EXPECT_TRUE(said) << c.args;
  }
}

// Two independent routes (monodromy, Hill) on a smooth scene: their disagreement must lie
// within the sum of their own error estimates (each estimate covers its own route's error).
TEST(Cli, FloquetBothRoutesAgreeWithinTheirEstimates) {
  const Outcome r = Ltp("floquet jeffcott --set c=0.02 --set Omega=0.8 --method both --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "both");
  const double d = j["disagreement"].get<double>();
  const double e1 = j["monodromy"]["error_estimate"].get<double>();
  const double e2 = j["hill"]["error_estimate"].get<double>();
  EXPECT_LE(d, e1 + e2);
  EXPECT_LT(d, 1e-9);
  const Outcome h =
      Ltp("floquet mathieu --set a=2.5 --set q=0.7 --method hill --harmonics 12 --json");
  ASSERT_EQ(h.code, 0) << h.err;
  const auto k = nlohmann::json::parse(h.out);
  EXPECT_EQ(k["method"], "hill");
  EXPECT_EQ(k["harmonics"], 12);
  EXPECT_TRUE(k.contains("selection_margin"));
  EXPECT_TRUE(k.contains("truncation_estimate"));
}

// `--estimate local-errors`: one Bulirsch–Stoer run whose carried local errors are the
// estimate. Independent check: Hill's method on the same system agrees within the two
// estimates; the text says where the estimate comes from; a wrong name is exit 2.
TEST(Cli, LocalErrorEstimateCoversTheDistanceToHill) {
  const Outcome r =
      Ltp("floquet jeffcott --set c=0.02 --set Omega=0.8 --method both --integrator bs "
          "--estimate local-errors --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["monodromy"]["error_estimate_method"], "local-errors");
  EXPECT_LE(j["disagreement"].get<double>(), j["monodromy"]["error_estimate"].get<double>() +
                                                 j["hill"]["error_estimate"].get<double>());
  const Outcome text = Ltp("floquet mathieu --integrator bs --estimate local-errors");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("local errors"), std::string::npos) << text.out;
  const Outcome bad = Ltp("floquet mathieu --estimate twice");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--estimate must be auto, refined-run or local-errors"), std::string::npos)
      << bad.err;
}

// The rotor scene's multi-blade-coordinate cross-check: for N >= 3 identical blades the MBC
// system is constant and its eigenvalues equal the Floquet exponents modulo jΩ (an independent
// route: one constant eigenproblem, no integration); for N = 2 MBC does not apply.
TEST(Cli, RotorMbcCrossCheck) {
  for (int blades : {3, 4}) {
    const Outcome r = Ltp("floquet rotor --set blades=" + std::to_string(blades) + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.contains("mbc_check"));
    EXPECT_TRUE(j["mbc_check"]["applicable"].get<bool>());
    EXPECT_LT(j["mbc_check"]["max_difference"].get<double>(), 1e-9) << blades;
  }
  const Outcome two = Ltp("floquet rotor --set blades=2 --set Omega=0.9 --json");
  ASSERT_EQ(two.code, 0) << two.err;
  EXPECT_FALSE(nlohmann::json::parse(two.out)["mbc_check"]["applicable"].get<bool>());
}

TEST(Cli, BadInputGivesExitTwoAndOneLine) {
  for (const std::string& args : std::vector<std::string>{
           "floquet nosuchscene", "floquet mathieu --set nosuch=1", "floquet mathieu --set a=nan",
           "floquet mathieu --integrator euler", "floquet mathieu --segments 0",
           "floquet mathieu --tol -1", "info " + Src("tests/data/does-not-exist.yaml"),
           "frobnicate", "floquet mathieu --plot out.jpg", "floquet mathieu --method magic",
           "floquet mathieu --method hill --harmonics -3"}) {
    const Outcome r = Ltp(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << args;
  }
}

}  // namespace
