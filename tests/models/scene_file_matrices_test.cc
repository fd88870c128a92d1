// Scene files whose second_order matrices come from Matrix Market files: the Jeffcott rotor of
// scenes/jeffcott.yaml written as files (constant parts, the cos/sin harmonic of its rotating
// asymmetry, a parameter factor) gives the same A(t), B(t), C(t) as the expression scene
// evaluated by muParser, as an exact Fourier-form system; bad combinations are refused with
// the entry that is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "ltp/core/error.h"
#include "ltp/models/scene.h"

namespace ltp {
namespace {

// A directory of its own with the files `files` (name, text) and scene.yaml = `scene`.
std::string SceneWithFiles(const std::string& dir_name,
                           const std::vector<std::pair<std::string, std::string>>& files,
                           const std::string& scene) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / dir_name;
  std::filesystem::create_directories(dir);
  for (const auto& [name, text] : files) std::ofstream(dir / name) << text;
  std::ofstream(dir / "scene.yaml") << scene;
  return (dir / "scene.yaml").string();
}

// K(t) = (k1+k2)/2 I + (k1−k2)/2 [[cos 2Ωt, sin 2Ωt], [sin 2Ωt, −cos 2Ωt]] with k1 = 1,
// k2 = 1.5: K0 = 1.25 I, the cos part −0.25 diag(1, −1), the sin part −0.25 [[0, 1], [1, 0]]
// (period π/Ω, so 2Ωt is harmonic 1). Damping c·I with c a parameter factor.
const std::vector<std::pair<std::string, std::string>> kJeffcottFiles = {
    {"M.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2 2 1\n"},
    {"I.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1\n2 2 1\n"},
    {"K0.mtx", "%%MatrixMarket matrix array real symmetric\n2 2\n1.25\n0\n1.25\n"},
    {"Kc.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 -0.25\n2 2 0.25\n"},
    {"Ks.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n2 1 -0.25\n"},
};

const char* kJeffcottScene = R"(
period: pi/Omega
rotor_speed: Omega
parameters: {c: 0.05, Omega: 1.1}
states: [x, y, x_dot, y_dot]
second_order:
  M: {file: M.mtx}
  D: {file: I.mtx, factor: c}
  K:
    file: K0.mtx
    harmonics:
      - {order: 1, cos: Kc.mtx, sin: Ks.mtx}
  F: [[1, 0], [0, 1]]
  outputs:
    displacement: [[1, 0], [0, 1]]
)";

TEST(SceneFileMatrices, JeffcottFromFilesEqualsTheExpressionScene) {
  const Scene files = LoadSceneFile(SceneWithFiles("jeffcott", kJeffcottFiles, kJeffcottScene));
  const std::string source_dir =
      std::getenv("LTP_SOURCE_DIR") ? std::getenv("LTP_SOURCE_DIR") : ".";
  const Scene expressions = LoadSceneFile(source_dir + "/scenes/jeffcott.yaml");
  for (const char* omega : {"1.1", "0.7"}) {
    const PeriodicSystem a = files.Build({{"Omega", omega}, {"c", "0.05"}});
    const PeriodicSystem b = expressions.Build({{"Omega", omega}, {"c", "0.05"}});
    EXPECT_EQ(a.form(), PeriodicSystem::Form::kFourier);
    EXPECT_DOUBLE_EQ(a.period(), b.period());
    EXPECT_EQ(a.labels().states, b.labels().states);
    for (double s : {0.0, 0.13, 0.5, 0.77}) {
      const double t = s * a.period();
      EXPECT_LE((a.A(t) - b.A(t)).cwiseAbs().maxCoeff(), 1e-15) << "t = " << t;
      EXPECT_LE((a.B(t) - b.B(t)).cwiseAbs().maxCoeff(), 1e-15);
      EXPECT_LE((a.C(t) - b.C(t)).cwiseAbs().maxCoeff(), 1e-15);
    }
  }
}

TEST(SceneFileMatrices, WhatCannotBeCombinedIsRefusedWithItsEntry) {
  struct Bad {
    const char* name;
    std::string from, to, says;
  };
  for (const Bad& b : std::vector<Bad>{
           {"t_beside_files", "F: [[1, 0], [0, 1]]", "F: [[\"cos(t)\", 0], [0, 1]]",
            "F depends on t beside matrices from files"},
           {"size", "D: {file: I.mtx, factor: c}", "D: {file: Kc3.mtx}", "must be 2x2"},
           {"missing", "D: {file: I.mtx, factor: c}", "D: {file: nothing.mtx}",
            "second_order.D.file: "},
           {"no_file", "D: {file: I.mtx, factor: c}", "D: {factor: c}",
            "gives neither file nor harmonics"},
           {"order", "order: 1,", "order: -1,", "expected an integer 1..999"},
           {"key", "D: {file: I.mtx, factor: c}", "D: {file: I.mtx, scale: c}", "unknown key"},
           {"bad_file", "D: {file: I.mtx, factor: c}", "D: {file: Bad.mtx}",
            "Bad.mtx:3: entry (3, 1) is outside"},
       }) {
    SCOPED_TRACE(b.name);
    std::string scene = kJeffcottScene;
    const auto at = scene.find(b.from);
    ASSERT_NE(at, std::string::npos);
    scene.replace(at, b.from.size(), b.to);
    auto files = kJeffcottFiles;
    files.push_back(
        {"Kc3.mtx", "%%MatrixMarket matrix array real general\n3 3\n1\n0\n0\n0\n1\n0\n0\n0\n1\n"});
    files.push_back({"Bad.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1\n"});
    try {
      LoadSceneFile(SceneWithFiles(std::string("bad_") + b.name, files, scene));
      ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(b.says), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("scene.yaml:"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace ltp
