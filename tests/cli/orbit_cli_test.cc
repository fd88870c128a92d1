// End-to-end: `ltp orbit` as a user runs it, against routes it does not share — four SISO
// `ltp pfrf --route htf` calls combined by hand, and the isotropic rotor's closed form.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "support/ltp_cli.h"

namespace {

using cd = std::complex<double>;
using nlohmann::json;
using test::RunLtp;
constexpr double kTwoPi = 2 * std::numbers::pi;

std::string Tmp(const std::string& name) {
  return std::string(::testing::TempDir()) + "ltp-" + std::to_string(getpid()) + "-" + name;
}

cd Phasor(const json& j) { return {j["re"].get<double>(), j["im"].get<double>()}; }

// H_z of one channel from `ltp pfrf --json`, by (excitation frequency index, z).
std::map<std::pair<int, int>, cd> Pfrf(const std::string& scene, const std::string& input,
                                       const std::string& output) {
  const auto r = RunLtp("pfrf " + scene + " --route htf --freq 0.1:0.2:0.1 --orders -2:2 --input " +
                        input + " --output " + output + " --json");
  EXPECT_EQ(r.code, 0) << r.err;
  std::map<std::pair<int, int>, cd> h;
  const json j = json::parse(r.out);
  for (const json& v : j["values"]) {
    const int i = static_cast<int>(std::lround(v["f_exc_hz"].get<double>() / 0.1)) - 1;
    h[{i, v["z"].get<int>()}] = Phasor(v);
  }
  EXPECT_EQ(h.size(), 10u);  // 0.1 and 0.2 Hz, orders −2…2
  return h;
}

// The orbit phasors are the superposition of the SISO partial FRFs with the unbalance weights
// (1, −j): X_z = H_z[x, fx] − j H_z[x, fy], Y_z alike (DESIGN.md, "Partial FRF"). The four
// `ltp pfrf` calls run the HTF route (Hill, banded), `ltp orbit` reports the modal route; the
// circles follow from the phasors by hand: x + jy = A e^{jω_z t} + B e^{−jω_z t},
// A = (X + jY)/2, B = conj(X − jY)/2, forward the one turning like the rotor (ω_z > 0 for A).
TEST(OrbitCli, UnbalanceEqualsFourPfrfCallsCombined) {
  const std::string scene = "jeffcott --set c=0.05 --set Omega=0.5 --set k2=1.7";
  const auto xfx = Pfrf(scene, "fx", "x"), xfy = Pfrf(scene, "fy", "x");
  const auto yfx = Pfrf(scene, "fx", "y"), yfy = Pfrf(scene, "fy", "y");
  const auto r =
      RunLtp("orbit " + scene + " --unbalance fx,fy --freq 0.1,0.2 --orders -2:2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["route"], "modal");
  EXPECT_EQ(j["check_route"], "hill");
  EXPECT_EQ(j["route_reason"], "modal_resolved");  // the typed reason beside route_choice
  ASSERT_EQ(j["frequencies"].size(), 2u);
  const cd mj(0, -1);
  int compared = 0;
  double largest = 0;
  for (int i = 0; i < 2; ++i) {
    const json& f = j["frequencies"][i];
    EXPECT_DOUBLE_EQ(f["f_exc_hz"].get<double>(), 0.1 * (i + 1));
    for (const json& o : f["orders"]) {
      const int z = o["z"];
      const cd X = xfx.at({i, z}) + mj * xfy.at({i, z});
      const cd Y = yfx.at({i, z}) + mj * yfy.at({i, z});
      const double scale = std::max(std::abs(X) + std::abs(Y), 1.0);
      // 1e-10: the HTF and modal routes agree to ~1e-13 here (the orbit's own check says so).
      EXPECT_LT(std::abs(Phasor(o["x"]) - X), 1e-10 * scale) << i << " z " << z;
      EXPECT_LT(std::abs(Phasor(o["y"]) - Y), 1e-10 * scale) << i << " z " << z;
      const double a = std::abs(X + cd(0, 1) * Y) / 2, b = std::abs(X - cd(0, 1) * Y) / 2;
      const bool turns_positive = o["f_resp_hz"].get<double>() > 0;
      EXPECT_NEAR(o["forward"].get<double>(), turns_positive ? a : b, 1e-10 * scale);
      EXPECT_NEAR(o["backward"].get<double>(), turns_positive ? b : a, 1e-10 * scale);
      EXPECT_NEAR(o["semi_major"].get<double>(), a + b, 2e-10 * scale);
      EXPECT_NEAR(o["semi_minor"].get<double>(), std::abs(a - b), 2e-10 * scale);
      largest = std::max(largest, a + b);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 10);
  EXPECT_GT(largest, 0.1);  // the comparison is not of zeros only
}

// An isotropic shaft (k1 = k2 = k) is m p'' + c p' + k p = f: the unit unbalance
// (cos ωt, sin ωt) gives x + jy = e^{jωt}/(k − mω² + jcω) (closed form), a forward circle of
// radius 1/|k − mω² + jcω| at order 0 and nothing at any other order.
TEST(OrbitCli, IsotropicRotorUnbalanceIsAForwardCircle) {
  const double m = 2, k = 3, c = 0.1;
  const std::string scene = "jeffcott --set m=2 --set k1=3 --set k2=3 --set c=0.1 --set Omega=0.8";
  const std::string freq = " --freq 0.05,0.195,0.3 --orders -2:2 --json";
  const auto r = RunLtp("orbit " + scene + " --unbalance fx,fy" + freq);
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  for (const json& f : j["frequencies"]) {
    const double w = kTwoPi * f["f_exc_hz"].get<double>();
    const double radius = 1 / std::abs(cd(k - m * w * w, c * w));
    for (const json& o : f["orders"]) {
      const bool zero = o["z"] == 0;
      EXPECT_NEAR(o["forward"].get<double>(), zero ? radius : 0, 1e-10 * radius) << w;
      EXPECT_NEAR(o["backward"].get<double>(), 0, 1e-12 * radius) << w;
      EXPECT_EQ(o["whirl"], zero ? "FW" : "still") << w << " z " << o["z"];
      EXPECT_TRUE(o["tilt_deg"].is_null());  // a circle's axis has no direction
    }
  }
  // The same input spelled as weights, and twice it (linear: twice the radius).
  const auto same = RunLtp("orbit " + scene + " --input fx=1,fy=-1j" + freq);
  ASSERT_EQ(same.code, 0) << same.err;
  EXPECT_EQ(json::parse(same.out)["frequencies"], j["frequencies"]);
  for (const char* spelling : {"fx=1+0j,fy=-j", "fx=1-0j,fy=0-1j", "fy=-1j,fx=1e0"}) {
    const auto again = RunLtp("orbit " + scene + " --input " + spelling + freq);
    ASSERT_EQ(again.code, 0) << spelling << ": " << again.err;
    EXPECT_EQ(json::parse(again.out)["frequencies"], j["frequencies"]) << spelling;
  }
  const auto twice = RunLtp("orbit " + scene + " --input fy=2@-90,fx=2" + freq);
  ASSERT_EQ(twice.code, 0) << twice.err;
  const json t = json::parse(twice.out);
  const json& o0 = t["frequencies"][1]["orders"][2];
  ASSERT_EQ(o0["z"], 0);
  EXPECT_NEAR(o0["forward"].get<double>(),
              2 * j["frequencies"][1]["orders"][2]["forward"].get<double>(), 1e-12);
}

// tests/data/gyroscopic-rotor.yaml: Id θ'' + c θ' + Ip Ω φ' + k θ = M_θ, Id φ'' − Ip Ω θ' + c φ' +
// k φ = M_φ. With z = θ + jφ: Id z'' + (c − j Ip Ω) z' + k z = M_θ + j M_φ, so the unbalance
// moment e^{jωt} gives z = e^{jωt}/(k − Id ω² + Ip Ω ω + jcω) (closed form): a forward circle
// that the gyroscopic term stiffens (Ip Ω ω > 0), no backward circle. A YAML scene, a rotor speed
// from the file.
TEST(OrbitCli, GyroscopicRotorForwardCircleIsStiffenedBySpin) {
  const double Id = 1, Ip = 0.5, k = 100, c = 0.5, Omega = 5;
  const auto r = RunLtp("orbit " + test::Src("tests/data/gyroscopic-rotor.yaml") +
                        " --set c=0.5 --unbalance M_theta,M_phi --freq 0.5,0.795774715459477,1.5"
                        " --orders 0 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["frequencies"].size(), 3u);
  for (const json& f : j["frequencies"]) {
    const double w = kTwoPi * f["f_exc_hz"].get<double>();
    const double radius = 1 / std::abs(cd(k - Id * w * w + Ip * Omega * w, c * w));
    const json& o = f["orders"][0];
    EXPECT_NEAR(o["forward"].get<double>(), radius, 1e-10 * radius) << w;
    EXPECT_NEAR(o["backward"].get<double>(), 0, 1e-12 * radius) << w;
    EXPECT_EQ(o["whirl"], "FW");
  }
}

TEST(OrbitCli, TableCsvAndPlot) {
  const std::string csv = Tmp("orbit.csv"), plot = Tmp("orbit.svg");
  const auto r = RunLtp(
      "orbit jeffcott --set c=0.05 --set Omega=0.5 --unbalance fx,fy --freq 0.2"
      " --csv " +
      csv + " --plot " + plot);
  if (r.code == 2 && r.err.find("gnuplot is not installed") != std::string::npos) GTEST_SKIP();
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* want : {"f = 0.2 Hz", "forward", "backward", "semi-major", "tilt [°]", " FW",
                           " BW", "checked by hill"})
    EXPECT_NE(r.out.find(want), std::string::npos) << want << "\n" << r.out;
  std::ifstream f(csv);
  std::string header, line;
  std::getline(f, header);
  EXPECT_EQ(header,
            "f_exc_hz,z,f_resp_hz,x_re,x_im,y_re,y_im,forward,backward,semi_major,semi_minor,"
            "tilt_deg,whirl,error_estimate");
  int rows = 0;
  while (std::getline(f, line)) ++rows;
  EXPECT_EQ(rows, 5);  // one frequency, orders −2…2
  EXPECT_NE(test::ReadFile(plot).find("<svg"), std::string::npos);
  std::remove(csv.c_str());
  std::remove(plot.c_str());
}

TEST(OrbitCli, BadInputExitTwoOneLine) {
  const std::string j = "orbit jeffcott --freq 0.1 ";
  for (const std::string& args : std::vector<std::string>{
           j + "--unbalance fx,fy --x nope", j + "--unbalance fx,fy --x x --y x",
           j + "--unbalance fx,fy --y 0", "orbit mathieu --freq 0.1 --unbalance u,u",
           "orbit rotor --freq 0.1 --x x --y y --unbalance fx", j + "--unbalance fx,fx",
           j + "--unbalance fx,fz", j, j + "--unbalance fx,fy --input fx=1", j + "--input fx=abc",
           j + "--input fx=1,fx=2", j + "--input fx=0", j + "--input fx", j + "--input fx=1,",
           j + "--unbalance fx,fy,", j + "--unbalance fx,fy --route fast",
           j + "--unbalance fx,fy --orders 2:-2",
           "orbit jeffcott --freq 0.1,,0.2 --unbalance fx,fy",
           j + "--unbalance fx,fy --plot o.txt"}) {
    const auto r = RunLtp(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ltp: error: ", 0), 0u) << args << ": " << r.err;
  }
  // A scene with one output: the message says what an orbit needs.
  const auto m = RunLtp("orbit mathieu --freq 0.1 --input u=1");
  EXPECT_EQ(m.code, 2);
  EXPECT_NE(m.err.find("an orbit needs two"), std::string::npos) << m.err;
  // Two outputs but one force: --unbalance is refused, --input on that force is an orbit.
  const std::string scene = Tmp("one-force.yaml");
  std::ofstream(scene) << "name: one-force\nperiod: 2*pi\nrotor_speed: 1\nparameters: {c: 0.1}\n"
                          "states: [x, y, x_dot, y_dot]\ninputs: [fx]\noutputs: [x, y]\n"
                          "second_order:\n  M: [[1, 0], [0, 1]]\n  D: [[c, 0], [0, c]]\n"
                          "  K: [[2, 0], [0, 2]]\n  F: [[1], [0]]\n  outputs:\n"
                          "    displacement: [[1, 0], [0, 1]]\n";
  const auto one = RunLtp("orbit " + scene + " --freq 0.1 --unbalance fx,fx");
  EXPECT_EQ(one.code, 2);
  EXPECT_EQ(std::count(one.err.begin(), one.err.end(), '\n'), 1) << one.err;
  EXPECT_NE(one.err.find("--unbalance needs two force inputs"), std::string::npos) << one.err;
  // fx = cos ωt alone on an isotropic support: a line along x (closed form: y stays 0).
  const auto line = RunLtp("orbit " + scene + " --freq 0.1 --input fx=1 --orders 0 --json");
  ASSERT_EQ(line.code, 0) << line.err;
  const json o = json::parse(line.out)["frequencies"][0]["orders"][0];
  EXPECT_EQ(o["whirl"], "line");
  EXPECT_NEAR(o["semi_minor"].get<double>(), 0, 1e-12);
  std::remove(scene.c_str());
}

}  // namespace
