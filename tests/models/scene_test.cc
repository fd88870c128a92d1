#include "ltp/models/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "ltp/core/error.h"
#include "support/throws.h"

namespace ltp {
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;

using test::ThrownMessage;

std::string ScenesDir() {
  if (const char* dir = std::getenv("LTP_SOURCE_DIR")) return std::string(dir) + "/scenes";
  return (std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "scenes")
      .string();
}

// The example of the scene-file format, verbatim.
const char* kColaneri = R"yaml(name: colaneri-like example
period: 2*pi                 # expression; alternatively  omega: <expr>  (T = 2*pi/omega)
parameters: {k: 10}          # defaults; `--set k=12` overrides
state_space:                 # x' = A x + B u ;  y = C x + D u   (B, C, D optional)
  A: [["0", "1"], ["-k*cos(t)", "-24 - k*sin(t)"]]
  B: [["0"], ["1"]]
  C: [["1", "0"]]
)yaml";

// A(t) of the example, by hand from its A entries.
MatrixXd ColaneriA(double k, double t) {
  return (MatrixXd(2, 2) << 0, 1, -k * std::cos(t), -24 - k * std::sin(t)).finished();
}

TEST(SceneFile, ExampleLoadsAndMatchesHandValues) {
  const Scene scene = ParseSceneYaml(kColaneri, "scene.yaml");
  EXPECT_EQ(scene.name, "colaneri-like example");
  EXPECT_EQ(scene.source, "scene.yaml");
  ASSERT_EQ(scene.parameters.size(), 1u);
  EXPECT_EQ(scene.parameters[0].name, "k");
  EXPECT_EQ(scene.parameters[0].value, 10);

  const PeriodicSystem sys = scene.Build();
  EXPECT_DOUBLE_EQ(sys.period(), 2 * pi);
  EXPECT_EQ(sys.states(), 2);
  EXPECT_EQ(sys.inputs(), 1);
  EXPECT_EQ(sys.outputs(), 1);
  EXPECT_TRUE(sys.breakpoints().empty());
  for (double t : {0.0, 0.5, 1.0, 2.5, 4.0, 6.0})
    EXPECT_LT((sys.A(t) - ColaneriA(10, t)).norm(), 1e-14) << "t = " << t;
  EXPECT_EQ(sys.B(1.0), (MatrixXd(2, 1) << 0, 1).finished());
  EXPECT_EQ(sys.C(1.0), (MatrixXd(1, 2) << 1, 0).finished());
  EXPECT_EQ(sys.D(1.0), MatrixXd::Zero(1, 1));
}

TEST(SceneFile, SetOverridesDefaults) {
  const Scene scene = ParseSceneYaml(kColaneri, "scene.yaml");
  const PeriodicSystem sys = scene.Build({{"k", "12"}});
  EXPECT_LT((sys.A(1.0) - ColaneriA(12, 1.0)).norm(), 1e-14);
  // Values may be expressions in numbers and pi.
  const PeriodicSystem sys2 = scene.Build({SplitAssignment("k = 2*pi")});
  EXPECT_LT((sys2.A(1.0) - ColaneriA(2 * pi, 1.0)).norm(), 1e-14);
}

TEST(SceneFile, OmegaAndParameterDependentPeriod) {
  // omega: 2*w with w = 1.5 gives T = 2π/3.
  const Scene scene = ParseSceneYaml(
      "omega: 2*w\nparameters: {w: 1.5}\nstate_space:\n  A: [[\"-1 + cos(3*t)\"]]\n", "s.yaml");
  EXPECT_DOUBLE_EQ(scene.Build().period(), 2 * pi / 3);
  EXPECT_DOUBLE_EQ(scene.Build({{"w", "0.5"}}).period(), 2 * pi);
  EXPECT_EQ(scene.name, "s");  // no name: the file stem
}

TEST(SceneFile, OptionalKeys) {
  const Scene scene = ParseSceneYaml(R"yaml(
name: opt
description: all optional keys
period: 1
parameters: {g: pi/2, r: 3}
parameter_descriptions: {g: "gain (1)"}
rotor_speed: 2*r
states: [a, b]
inputs: [u]
outputs: [y1, y2]
state_space:
  A: [[0, 1], [-g, 0]]
  B: [[0], [1]]
  C: [[1, 0], [0, 1]]
  D: [[0], [g]]
)yaml",
                                     "opt.yaml");
  EXPECT_EQ(scene.description, "all optional keys");
  EXPECT_EQ(scene.parameters[0].description, "gain (1)");
  EXPECT_DOUBLE_EQ(scene.parameters[0].value, pi / 2);
  const PeriodicSystem sys = scene.Build();
  EXPECT_EQ(sys.rotor_speed(), 6.0);
  EXPECT_EQ(sys.labels().states, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(sys.labels().outputs, (std::vector<std::string>{"y1", "y2"}));
  EXPECT_DOUBLE_EQ(sys.D(0.2)(1, 0), pi / 2);
  EXPECT_DOUBLE_EQ(sys.A(0.2)(1, 0), -pi / 2);
}

TEST(SceneFile, SecondOrderBlock) {
  // M = [[2, 1], [1, 3]], K = diag(k, 1) with k = 4, F = [1; 0]: as in second_order_test,
  // M⁻¹K = (1/5) [[12, -1], [-4, 2]], M⁻¹F = (1/5) [3; -1].
  const Scene scene = ParseSceneYaml(R"yaml(
period: 1
parameters: {k: 4}
second_order:
  M: [[2, 1], [1, 3]]
  K: [[k, 0], [0, 1]]
  F: [[1], [0]]
  outputs: {velocity: [[0, 1]]}
)yaml",
                                     "so.yaml");
  const PeriodicSystem sys = scene.Build();
  MatrixXd a(4, 4);
  a << 0, 0, 1, 0, 0, 0, 0, 1, -2.4, 0.2, 0, 0, 0.8, -0.4, 0, 0;
  EXPECT_LT((sys.A(0.3) - a).norm(), 1e-14);
  EXPECT_LT((sys.B(0.3) - (MatrixXd(4, 1) << 0, 0, 0.6, -0.2).finished()).norm(), 1e-15);
  EXPECT_EQ(sys.C(0.3), (MatrixXd(1, 4) << 0, 0, 0, 1).finished());
}

TEST(SceneFile, SingularMassInFileNamesTheEntry) {
  const std::string message = ThrownMessage<SingularMassError>([] {
    ParseSceneYaml(
        "period: 2*pi\nsecond_order:\n  M: [[1, 0], [0, cos(t)]]\n  K: [[1, 0], [0, 1]]\n",
        "m.yaml");
  });
  EXPECT_NE(message.find("m.yaml:3: second_order.M: mass matrix M(t) is singular at t = 1.5708"),
            std::string::npos)
      << message;
}

struct BadCase {
  const char* yaml;
  const char* expected;  // part of the message
};

// Entries that are plain numbers skip the expression parser (a 1000-state scene has a million
// of them): they must give what muParser gives, and what is not a plain number still goes to
// it. Reference: the numbers written.
TEST(SceneFile, PlainNumbersAreReadAsTheParserWould) {
  const Scene scene = ParseSceneYaml(R"yaml(
period: 1
state_space:
  A: [[0, " 1.5 ", "-2e3"], ["+4", "1e-3", ".5"], ["3.", "2*3", "-(1)"]]
)yaml",
                                     "plain.yaml");
  Eigen::MatrixXd expected(3, 3);
  expected << 0, 1.5, -2000, 4, 1e-3, 0.5, 3, 6, -1;
  EXPECT_EQ(scene.Build().A(0.3), expected);
  EXPECT_NE(ThrownMessage<SceneError>([] {
              ParseSceneYaml("period: 1\nstate_space:\n  A: [[\"1e999\"]]\n", "big.yaml");
            }).find("evaluates to inf"),
            std::string::npos);
  EXPECT_NE(ThrownMessage<SceneError>([] {
              ParseSceneYaml("period: 1\nstate_space:\n  A: [[\"5e\"]]\n", "e.yaml");
            }).find("in expression '5e'"),
            std::string::npos);
}

TEST(SceneFile, MalformedFilesGiveSceneErrorsNamingFileLineAndEntry) {
  const BadCase cases[] = {
      {"period: [1, 2\n", "bad.yaml:2: YAML syntax error"},
      {"- 1\n- 2\n", "bad.yaml:1: a scene file must be a mapping"},
      {"period: 1\n", "bad.yaml:1: missing 'state_space'"},
      {"state_space:\n  A: [[0]]\n", "bad.yaml:1: missing 'period'"},
      {"period: 1\nomega: 1\nstate_space:\n  A: [[0]]\n", "bad.yaml:2: omega: give either"},
      {"period: 1\nstate_space:\n  A: [[0, 1]]\n", "bad.yaml:3: state_space.A: must be square"},
      {"period: 1\nstate_space:\n  A: [[0, 1],\n      [2]]\n",
       "bad.yaml:4: state_space.A[1]: row has 1 entries but row 0 has 2"},
      {"period: 1\nstate_space:\n  A: [[0, 1], [2, 3]]\n  B: [[1]]\n",
       "bad.yaml:4: state_space.B: is 1x1 but must be 2xany"},
      {"period: 1\nstate_space:\n  A: [[0, 1], [2, 3]]\n  C: [[1, 0, 0]]\n",
       "bad.yaml:4: state_space.C: is 1x3 but must be anyx2"},
      {"period: 1\nstate_space:\n  A: [[0]]\n  B: [[1]]\n  C: [[1]]\n  D: [[1, 2]]\n",
       "bad.yaml:6: state_space.D: is 1x2 but must be 1x1"},
      {"period: 1\nstate_space:\n  A: [[0]]\n  D: [[1]]\n",
       "bad.yaml:4: state_space.D: feedthrough D needs both B and C"},
      {"period: 1\nstate_space:\n  A: [[\"0\", \"1 +* t\"], [0, 0]]\n",
       "bad.yaml:3: state_space.A[0][1]: bad expression '1 +* t'"},
      {"name: x\nperiod: 2*pi\nparameters: {k: 10}\nstate_space:\n  A: [[\"0\", \"1\"],\n"
       "      [\"-kk*cos(t)\", \"0\"]]\n",
       "bad.yaml:6: state_space.A[1][0]: unknown variable 'kk' in expression '-kk*cos(t)'"},
      {"period: 1\nparameters: {t: 1}\nstate_space:\n  A: [[t]]\n",
       "bad.yaml:2: parameters.t: parameter 't' would shadow"},
      {"period: 1\nparameters: {k: 1, pi: 3}\nstate_space:\n  A: [[k]]\n",
       "bad.yaml:2: parameters.pi: parameter 'pi' would shadow"},
      {"period: 1\nstate_space:\n  A: [[\"sqrt(-1)\"]]\n",
       "bad.yaml:3: state_space.A[0][0]: 'sqrt(-1)' evaluates to"},
      {"period: 1\nstate_space:\n  A: [[\"1/t\"]]\n",
       "bad.yaml:3: state_space.A[0][0]: '1/t' evaluates to inf at t = 0"},
      {"period: -1\nstate_space:\n  A: [[0]]\n", "bad.yaml:1: period: must be > 0"},
      {"omega: 0\nstate_space:\n  A: [[0]]\n", "bad.yaml:1: omega: must be > 0"},
      {"period: 1\nstate_spac:\n  A: [[0]]\n", "bad.yaml:2: state_spac: unknown key"},
      {"period: 1\nstate_space:\n  A: [[0]]\nstates: [a, b]\n",
       "bad.yaml:4: states: gives 2 names but the system has 1 states"},
      {"period: 1\nbreakpoints: [2]\nstate_space:\n  A: [[0]]\n",
       "bad.yaml:2: breakpoints[0]: breakpoint 2 is outside [0, T)"},
      {"period: 1\nsecond_order:\n  M: [[1]]\n", "bad.yaml:2: second_order: missing the stiffness"},
      {"period: 1\nsecond_order:\n  M: [[1]]\n  K: [[1, 2]]\n",
       "bad.yaml:4: second_order.K: is 1x2 but must be 1x1"},
  };
  for (const BadCase& c : cases) {
    const std::string message =
        ThrownMessage<SceneError>([&] { ParseSceneYaml(c.yaml, "bad.yaml"); });
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "yaml:\n"
        << c.yaml << "message: " << message << "\nexpected: " << c.expected;
  }
}

TEST(SceneFile, ErrorsAfterOverridesStillNameTheEntry) {
  // sqrt(k) is fine for the default k = 1 but NaN for k = -1.
  const Scene scene = ParseSceneYaml(
      "period: 1\nparameters: {k: 1}\nstate_space:\n  A: [[\"sqrt(k)\"]]\n", "s.yaml");
  const std::string message = ThrownMessage<SceneError>([&] { scene.Build({{"k", "-1"}}); });
  EXPECT_NE(message.find("s.yaml:4: state_space.A[0][0]: 'sqrt(k)' evaluates to"),
            std::string::npos)
      << message;
}

TEST(SceneFile, MissingFile) {
  const std::string path = "/nonexistent-dir/scene.yaml";
  const std::string message = ThrownMessage<SceneError>([&] { LoadSceneFile(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(SceneFile, SignEntriesJumpAtDetectedBreakpoints) {
  // No explicit breakpoints: sign(cos t) jumps at π/2 and 3π/2, found by the scan.
  const Scene scene = ParseSceneYaml(
      "period: 2*pi\nparameters: {a: 1, b: 0.3}\n"
      "state_space:\n  A: [[0, 1], [\"-(a + b*sign(cos(t)))\", 0]]\n",
      "sign.yaml");
  const PeriodicSystem sys = scene.Build();
  ASSERT_EQ(sys.breakpoints().size(), 2u);
  EXPECT_NEAR(sys.breakpoints()[0], pi / 2, 1e-12);
  EXPECT_NEAR(sys.breakpoints()[1], 3 * pi / 2, 1e-12);
  // Either side of π/2 and 3π/2: cos t > 0 gives -(a + b), cos t < 0 gives -(a - b).
  EXPECT_DOUBLE_EQ(sys.A(pi / 2 - 1e-9)(1, 0), -1.3);
  EXPECT_DOUBLE_EQ(sys.A(pi / 2 + 1e-9)(1, 0), -0.7);
  EXPECT_DOUBLE_EQ(sys.A(3 * pi / 2 - 1e-9)(1, 0), -0.7);
  EXPECT_DOUBLE_EQ(sys.A(3 * pi / 2 + 1e-9)(1, 0), -1.3);
}

TEST(SceneFile, ExplicitBreakpointsAreKeptAndMergedWithDetectedOnes) {
  // The explicit π/2 replaces the detected one; 3π/2 is still detected; 1 is only explicit.
  const Scene scene = ParseSceneYaml(
      "period: 2*pi\nbreakpoints: [pi/2, 1]\n"
      "state_space:\n  A: [[\"sign(cos(t))\"]]\n",
      "sign.yaml");
  const PeriodicSystem sys = scene.Build();
  const std::vector<double>& b = sys.breakpoints();
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0], 1.0);
  EXPECT_EQ(b[1], pi / 2);
  EXPECT_NEAR(b[2], 3 * pi / 2, 1e-12);
}

TEST(SceneFile, JumpAtTimeZeroIsFound) {
  // sign(sin t) jumps at 0 (≡ 2π) and at π; a smooth entry adds no breakpoint.
  const Scene scene = ParseSceneYaml(
      "period: 2*pi\nstate_space:\n  A: [[\"sign(sin(t))\", \"abs(cos(t)) > 2\"], "
      "[\"sin(t)^2\", \"0\"]]\n",
      "zero.yaml");
  const PeriodicSystem sys = scene.Build();
  const std::vector<double>& b = sys.breakpoints();
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0], 0.0);
  EXPECT_NEAR(b[1], pi, 1e-12);
}

TEST(SceneFile, ConcurrentEvaluationMatchesSerial) {
  const Scene scene = ParseSceneYaml(kColaneri, "scene.yaml");
  const int count = 20000;
  std::vector<double> times(count);
  for (int i = 0; i < count; ++i) times[i] = 0.001 * i;
  // A fresh system per round, so that both threads also race to create their parsers.
  for (int round = 0; round < 3; ++round) {
    const PeriodicSystem sys = scene.Build({{"k", std::to_string(10 + round)}});
    std::vector<MatrixXd> serial, first(count), second(count);
    auto run = [&](std::vector<MatrixXd>& out) {
      for (int i = 0; i < count; ++i) out[i] = sys.A(times[i]);
    };
    std::thread a(run, std::ref(first)), b(run, std::ref(second));
    a.join();
    b.join();
    for (double t : times) serial.push_back(sys.A(t));
    for (int i = 0; i < count; ++i) {
      ASSERT_EQ(first[i], serial[i]) << "t = " << times[i];
      ASSERT_EQ(second[i], serial[i]) << "t = " << times[i];
    }
  }
}

// Integrators call A(t) millions of times through the compiled expressions; every call must
// give the hand values (its speed is benchmarks/monodromy_benchmark's BM_SceneExpressionA, not
// a unit test's business).
TEST(SceneFile, RepeatedEvaluationMatchesHandValues) {
  const PeriodicSystem sys = ParseSceneYaml(kColaneri, "scene.yaml").Build();
  MatrixXd a(2, 2);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const double t = 1e-3 * i;
    sys.EvalA(t, a);
    worst = std::max(worst, (a - ColaneriA(10, t)).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst, 1e-13);
}

// ---------------------------------------------------------------------------------------------
// Scene parameters and lookup.

TEST(Scene, ResolveUnknownParameterListsTheKnownOnes) {
  const Scene scene = LoadScene("mathieu");
  EXPECT_EQ(ThrownMessage<InputError>([&] {
              scene.Resolve({{"x", "1"}});
            }),
            "unknown parameter 'x' for scene 'mathieu' (parameters: a, q, c)");
}

TEST(Scene, ResolveRejectsBadValues) {
  const Scene scene = LoadScene("mathieu");
  for (const char* bad : {"foo", "1 +", "1/0", "sqrt(-1)"}) {
    const std::string message = ThrownMessage<InputError>([&] { scene.Resolve({{"q", bad}}); });
    EXPECT_NE(message.find("parameter 'q'"), std::string::npos) << bad << ": " << message;
  }
  const ParameterMap p = scene.Resolve({{"q", "pi/4"}, {"a", "2"}});
  EXPECT_EQ(p.at("q"), pi / 4);
  EXPECT_EQ(p.at("a"), 2);
  EXPECT_EQ(p.at("c"), 0.02);  // default
}

TEST(Scene, SplitAssignment) {
  EXPECT_EQ(SplitAssignment("k=12"), (std::pair<std::string, std::string>{"k", "12"}));
  EXPECT_EQ(SplitAssignment(" a = 2*pi "), (std::pair<std::string, std::string>{"a", "2*pi"}));
  EXPECT_THROW(SplitAssignment("k12"), InputError);
  EXPECT_THROW(SplitAssignment("=1"), InputError);
}

TEST(Scene, LoadSceneByNameOrPath) {
  EXPECT_EQ(LoadScene("jeffcott").source, "built-in");
  const std::string path = ScenesDir() + "/colaneri.yaml";
  EXPECT_EQ(LoadScene(path).source, path);
  // Later scenes (rotor, flap, tower-rotor, ...) are appended to the list.
  const std::string message = ThrownMessage<InputError>([] { LoadScene("nosuch"); });
  EXPECT_EQ(message.rfind("unknown scene 'nosuch': not a built-in (mathieu, meissner, jeffcott", 0),
            0u)
      << message;
  EXPECT_NE(message.find(") and no such file"), std::string::npos) << message;
}

TEST(Scene, BuiltinsInOrderWithDescriptions) {
  const auto& scenes = BuiltinScenes();
  ASSERT_GE(scenes.size(), 3u);  // the first three in this order; others are appended
  EXPECT_EQ(scenes[0].name, "mathieu");
  EXPECT_EQ(scenes[1].name, "meissner");
  EXPECT_EQ(scenes[2].name, "jeffcott");
  for (const Scene& s : scenes) {
    EXPECT_FALSE(s.description.empty());
    for (const SceneParameter& p : s.parameters) EXPECT_FALSE(p.description.empty()) << p.name;
  }
}

TEST(Scene, BuiltinParametersAreValidated) {
  const Scene jeffcott = LoadScene("jeffcott");
  EXPECT_NE(ThrownMessage<InputError>([&] {
              jeffcott.Build({{"m", "0"}});
            }).find("'m'"),
            std::string::npos);
  EXPECT_NE(ThrownMessage<InputError>([&] {
              jeffcott.Build({{"Omega", "-1"}});
            }).find("'Omega'"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Built-in scenes against their closed forms, and the shipped scene files against the built-ins.

TEST(Builtin, MathieuFourierFormMatchesClosedForm) {
  const PeriodicSystem sys = LoadScene("mathieu").Build({{"a", "1.5"}, {"q", "0.7"}});
  ASSERT_EQ(sys.form(), PeriodicSystem::Form::kFourier);
  EXPECT_EQ(sys.period(), pi);
  EXPECT_EQ(sys.fourier_A()->max_harmonic(), 1);
  for (double t : {0.0, 0.3, 1.0, 2.0, 3.0}) {
    // y'' + c y' + (a − 2q cos 2t) y = u  ⇒  A = [[0, 1], [−a + 2q cos 2t, −c]].
    const MatrixXd a = (MatrixXd(2, 2) << 0, 1, -1.5 + 1.4 * std::cos(2 * t), -0.02).finished();
    EXPECT_LT((sys.A(t) - a).norm(), 1e-14) << "t = " << t;
  }
  EXPECT_EQ(sys.labels().states, (std::vector<std::string>{"y", "y_dot"}));
}

TEST(Builtin, MeissnerMatchesClosedForm) {
  const PeriodicSystem sys = LoadScene("meissner").Build();
  EXPECT_EQ(sys.breakpoints(), (std::vector<double>{pi / 2, 3 * pi / 2}));
  // a + b sign(cos t) with a = 1, b = 0.3.
  EXPECT_EQ(sys.A(0.1)(1, 0), -1.3);
  EXPECT_EQ(sys.A(2.0)(1, 0), -0.7);
  EXPECT_EQ(sys.A(5.0)(1, 0), -1.3);
}

TEST(Builtin, JeffcottFourierFormMatchesRotatedStiffness) {
  const double m = 2, k1 = 1, k2 = 3, c = 0.1, omega = 0.8;
  const PeriodicSystem sys =
      LoadScene("jeffcott")
          .Build({{"m", "2"}, {"k1", "1"}, {"k2", "3"}, {"c", "0.1"}, {"Omega", "0.8"}});
  ASSERT_EQ(sys.form(), PeriodicSystem::Form::kFourier);
  EXPECT_DOUBLE_EQ(sys.period(), pi / omega);
  EXPECT_EQ(sys.rotor_speed(), omega);
  for (double t : {0.0, 0.4, 1.1, 2.5, 3.9}) {
    // K(t) = R(Ωt) diag(k1, k2) R(Ωt)ᵀ, A = [[0, I], [−K/m, −(c/m) I]].
    const Eigen::Matrix2d r = Eigen::Rotation2Dd(omega * t).toRotationMatrix();
    const Eigen::Matrix2d k = r * Eigen::Vector2d(k1, k2).asDiagonal() * r.transpose();
    MatrixXd a = MatrixXd::Zero(4, 4);
    a.topRightCorner(2, 2).setIdentity();
    a.bottomLeftCorner(2, 2) = -k / m;
    a.bottomRightCorner(2, 2) = -c / m * Eigen::Matrix2d::Identity();
    EXPECT_LT((sys.A(t) - a).norm(), 1e-14) << "t = " << t;
  }
  MatrixXd b = MatrixXd::Zero(4, 2);
  b.bottomRows(2) = Eigen::Matrix2d::Identity() / m;
  EXPECT_EQ(sys.B(0.5), b);
}

TEST(Builtin, ShippedSceneFilesMatchBuiltins) {
  for (const char* name : {"mathieu", "meissner", "jeffcott"}) {
    const Scene file = LoadSceneFile(ScenesDir() + "/" + name + ".yaml");
    const Scene builtin = LoadScene(name);
    ASSERT_EQ(file.parameters.size(), builtin.parameters.size()) << name;
    for (size_t i = 0; i < file.parameters.size(); ++i) {
      EXPECT_EQ(file.parameters[i].name, builtin.parameters[i].name) << name;
      EXPECT_EQ(file.parameters[i].value, builtin.parameters[i].value) << name;
    }
    const PeriodicSystem f = file.Build(), b = builtin.Build();
    EXPECT_DOUBLE_EQ(f.period(), b.period()) << name;
    EXPECT_EQ(f.breakpoints().size(), b.breakpoints().size()) << name;
    EXPECT_EQ(f.labels().states, b.labels().states) << name;
    EXPECT_EQ(f.labels().inputs, b.labels().inputs) << name;
    EXPECT_EQ(f.labels().outputs, b.labels().outputs) << name;
    EXPECT_EQ(f.rotor_speed(), b.rotor_speed()) << name;
    for (int i = 0; i < 7; ++i) {
      const double t = b.period() * (i + 0.37) / 7;  // off the breakpoints
      EXPECT_LT((f.A(t) - b.A(t)).norm(), 1e-14) << name << " t = " << t;
      EXPECT_LT((f.B(t) - b.B(t)).norm(), 1e-14) << name << " t = " << t;
      EXPECT_LT((f.C(t) - b.C(t)).norm(), 1e-14) << name << " t = " << t;
    }
  }
}

TEST(Builtin, ShippedColaneriFileMatchesTheExample) {
  const PeriodicSystem file = LoadSceneFile(ScenesDir() + "/colaneri.yaml").Build({{"k", "7"}});
  for (double t : {0.0, 1.0, 2.0, 5.0}) EXPECT_EQ(file.A(t), ColaneriA(7, t));
}

}  // namespace
}  // namespace ltp
