// Campbell diagrams: whirl lines and per-rev crossings of a gyroscopic rotor against their
// closed forms (tests/data/gyroscopic-rotor.yaml), one line per conjugate pair, descriptions,
// lost lines and weak-damping shading.
#include "ltp/studies/campbell.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <mutex>
#include <numbers>

#include "ltp/core/error.h"
#include "ltp/models/scene.h"
#include "ltp/studies/chart_options.h"
#include "support/rotor_lin.h"

namespace ltp {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double Id = 1, Ip = 0.5, k = 100;  // the scene's defaults

// Whirl frequencies (rad/s) and per-rev crossing speeds from the closed form in the scene file.
double Whirl(double omega, bool forward) {
  const double s = std::sqrt(Ip * Ip * omega * omega + 4 * Id * k);
  return ((forward ? Ip : -Ip) * omega + s) / (2 * Id);
}
double CrossingSpeed(int n, bool forward) {
  return std::sqrt(k / (n * (n * Id + (forward ? -Ip : Ip))));
}

struct Chart {
  std::vector<SweepPoint> points;
  ModeTracking tracking;
  SystemLabels labels;
};

Chart Sweep(const std::string& spec,
            const std::vector<std::pair<std::string, std::string>>& set = {}) {
  const Scene scene = LoadScene(test::SourceDir() + "/tests/data/gyroscopic-rotor.yaml");
  const ParameterMap base = scene.Resolve(set);
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse(spec)});
  Chart c;
  c.labels = scene.build(base).labels();
  c.points.resize(grid.size());
  std::vector<size_t> all(grid.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::mutex m;
  RunSweep(scene, base, grid, all, ChartSweepOptions(ChartOptions{}, false, scene.build(base)),
           [&](SweepPoint&& p) {
             std::lock_guard<std::mutex> lock(m);
             c.points[p.index] = std::move(p);
           });
  c.tracking = TrackModes(c.points);
  return c;
}

TEST(Campbell, GyroscopicRotorWhirlLinesAndCrossingsMatchTheClosedForm) {
  const Chart c = Sweep("Omega=1:20:0.1");
  CampbellOptions o;
  o.max_per_rev = 3;
  const CampbellDiagram d = MakeCampbellDiagram(c.points, c.tracking, c.labels, o);
  // Four exponents ±jω_f, ±jω_b: two physical modes.
  ASSERT_EQ(d.lines.size(), 2u);
  EXPECT_EQ(d.per_rev, (std::vector<int>{1, 2, 3}));
  for (const CampbellLine& line : d.lines) {
    EXPECT_FALSE(line.lost_after.has_value());
    EXPECT_EQ(line.description, "theta 50%, phi 50%");  // circular whirl: equal tilt energy
  }
  // Which line is forward: the one whose frequency grows with speed.
  const size_t P = d.parameter.size();
  const size_t forward = d.lines[0].frequency_hz[P - 1] > d.lines[0].frequency_hz[0] ? 0 : 1;
  for (size_t p = 0; p < P; ++p) {
    const double omega = d.parameter[p];
    EXPECT_NEAR(d.rotor_speed[p], omega, 0);
    EXPECT_NEAR(d.lines[forward].frequency_hz[p], Whirl(omega, true) / (2 * kPi), 1e-8) << omega;
    EXPECT_NEAR(d.lines[1 - forward].frequency_hz[p], Whirl(omega, false) / (2 * kPi), 1e-8)
        << omega;
    EXPECT_NEAR(d.lines[forward].damping_ratio[p], 0, 1e-8);
  }
  // Each whirl line crosses 1P, 2P and 3P once in the sweep (Ω* from 3.09 to 14.1 rad/s).
  ASSERT_EQ(d.crossings.size(), 6u);
  for (const CampbellCrossing& x : d.crossings) {
    const bool is_forward = x.line == forward;
    const double exact = CrossingSpeed(x.per_rev, is_forward);
    const double error = std::abs(x.parameter - exact);
    // The estimate bounds the true error, and the quadratic through three points of a
    // 0.1-step sweep is accurate to better than 1e-3 rad/s here.
    EXPECT_LE(error, x.parameter_error) << x.per_rev << (is_forward ? " forward" : " backward");
    EXPECT_LT(error, 1e-3);
    EXPECT_NEAR(x.rotor_speed, x.parameter, 1e-12);
    EXPECT_NEAR(x.frequency_hz, x.per_rev * x.rotor_speed / (2 * kPi), 1e-12);
    EXPECT_NEAR(x.real_part, 0, 1e-8);
  }
  // Undamped: marginal everywhere, so nothing is shaded as "stable but weakly damped".
  EXPECT_TRUE(d.weakly_damped.empty());
}

TEST(Campbell, WeakDampingIsShadedWhereTheDampingRatioIsBelowTheThreshold) {
  // c = 0.1: the tilt modes' damping ratio is c/(2 Id ω) ≈ 0.5 % at ω ≈ 10 rad/s (no spin);
  // with spin the two whirls split and the ratio drops as Ω grows.
  const Chart c = Sweep("Omega=1:20:1", {{"c", "0.1"}});
  CampbellOptions o;
  o.weak_damping_ratio = 0.01;
  const CampbellDiagram weak = MakeCampbellDiagram(c.points, c.tracking, c.labels, o);
  // Closed form: in z = θ + jφ, Id s² + (c − j Ip Ω) s + k = 0; the root with Im s > 0 is the
  // forward whirl, the other is the conjugate of the backward one. ζ = −Re s/|s| ≈ 0.45..0.50 %.
  ASSERT_EQ(weak.lines.size(), 2u);
  const size_t forward =
      weak.lines[0].frequency_hz.back() > weak.lines[0].frequency_hz.front() ? 0 : 1;
  for (size_t p = 0; p < weak.parameter.size(); ++p) {
    const std::complex<double> b(0.1, -Ip * weak.parameter[p]);
    const std::complex<double> root = std::sqrt(b * b - 4 * Id * k);
    std::complex<double> s1 = (-b + root) / (2 * Id), s2 = (-b - root) / (2 * Id);
    if (s1.imag() < 0) std::swap(s1, s2);
    EXPECT_NEAR(weak.lines[forward].damping_ratio[p], -s1.real() / std::abs(s1), 1e-9);
    EXPECT_NEAR(weak.lines[1 - forward].damping_ratio[p], -s2.real() / std::abs(s2), 1e-9);
  }
  ASSERT_EQ(weak.weakly_damped.size(), 1u);
  EXPECT_EQ(weak.weakly_damped[0], std::make_pair(1.0, 20.0));
  o.weak_damping_ratio = 1e-4;
  EXPECT_TRUE(MakeCampbellDiagram(c.points, c.tracking, c.labels, o).weakly_damped.empty());
}

TEST(Campbell, AFailedPointEndsTheLineWithADiagnostic) {
  Chart c = Sweep("Omega=1:5:1");
  c.points[3].ok = false;
  c.points[3].failure = "integration failed";
  c.points[3].modes.clear();
  c.tracking = TrackModes(c.points);
  const CampbellDiagram d = MakeCampbellDiagram(c.points, c.tracking, c.labels);
  ASSERT_EQ(d.lines.size(), 2u);
  for (const CampbellLine& line : d.lines) {
    EXPECT_EQ(line.lost_after, 2u);
    EXPECT_TRUE(std::isnan(line.frequency_hz[3]));
    EXPECT_TRUE(std::isfinite(line.frequency_hz[4]));
  }
  ASSERT_FALSE(d.diagnostics.empty());
  EXPECT_EQ(d.diagnostics[0].code, DiagnosticCode::kLineLost) << d.diagnostics[0].text;
}

// Undamped asymmetric shaft (jeffcott, k2 = 1.5): unstable for 1 < Ω < sqrt(1.5) (closed
// form), where the multipliers are real and negative, so the frequency sits on Ωp/2 = Ω/2π,
// the 1P line itself, to round-off. That is a lock, not a string of crossings.
TEST(Campbell, AFrequencyLockedToAPerRevLineIsNotCounted) {
  const Scene scene = LoadScene("jeffcott");
  const ParameterMap base = scene.Resolve({{"k2", "1.5"}});
  const SweepGrid grid = MakeSweepGrid(scene, {SweepAxis::Parse("Omega=0.8:1.4:0.01")});
  std::vector<SweepPoint> points(grid.size());
  std::vector<size_t> all(grid.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::mutex m;
  RunSweep(scene, base, grid, all, ChartSweepOptions(ChartOptions{}, false, scene.build(base)),
           [&](SweepPoint&& p) {
             std::lock_guard<std::mutex> lock(m);
             points[p.index] = std::move(p);
           });
  CampbellOptions o;
  o.max_per_rev = 1;
  const CampbellDiagram d =
      MakeCampbellDiagram(points, TrackModes(points), scene.build(base).labels(), o);
  // The locked line: on 1P at Ω = 1.1 (the other mode, near 0.178 Hz, truly crosses 1P at
  // Ω ≈ 1.12 and is counted).
  const size_t mid = 30;  // Ω = 1.1
  ASSERT_NEAR(d.parameter[mid], 1.1, 1e-12);
  size_t locked = d.lines.size();
  for (size_t k = 0; k < d.lines.size(); ++k)
    if (std::abs(d.lines[k].frequency_hz[mid] - 1.1 / (2 * kPi)) < 1e-9) locked = k;
  ASSERT_LT(locked, d.lines.size());
  for (const CampbellCrossing& c : d.crossings) {
    if (c.line == locked) {
      EXPECT_FALSE(c.parameter > 1.0 + 1e-3 && c.parameter < std::sqrt(1.5) - 1e-3) << c.parameter;
    }
  }
  EXPECT_TRUE(HasCode(d.diagnostics, DiagnosticCode::kLineLockedToHarmonic));
}

TEST(Campbell, OptionsAreValidated) {
  CampbellOptions o;
  o.max_per_rev = -1;
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.weak_damping_ratio = 1;
  EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace ltp
