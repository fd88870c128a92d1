// An OpenFAST operating point as a scene: the shipped NREL 5 MW files
// (tests/data/openfast/README.md) built as held samples and as a trigonometric interpolation,
// compared with the files' own A.
#include "ltp/models/lin_scene.h"

#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <vector>

#include "ltp/core/error.h"
#include "support/rotor_lin.h"

namespace ltp {
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;
using test::FiveMwDir;

TEST(LinScene, SceneOverTheFiles) {
  const LinOperatingPoint op = ReadLinOperatingPoint({FiveMwDir()});
  const Scene scene = MakeLinScene(op);
  EXPECT_EQ(scene.name, "openfast: Main.1.lin, Main.12.lin, Main.24.lin");
  // Defaults: trigonometric interpolation in multi-blade coordinates (3 blades: MBC applies;
  // docs/sampled-models.md); the files' own matrices are the hold in their coordinates.
  const ParameterMap defaults = scene.Resolve({});
  EXPECT_EQ(defaults.at("trig"), 1);
  EXPECT_EQ(defaults.at("mbc"), 1);
  EXPECT_EQ(scene.Build().form(), PeriodicSystem::Form::kFourier);
  const PeriodicSystem hold = scene.Build({{"trig", "0"}, {"mbc", "0"}});
  EXPECT_EQ(hold.states(), 20);
  EXPECT_DOUBLE_EQ(hold.period(), 2 * pi / 0.9425);
  ASSERT_TRUE(hold.rotor_speed().has_value());
  // At each sample azimuth the system is that file's A (Main.12.lin at ψ = 1.9224).
  EXPECT_EQ(hold.A(1.9224 / 0.9425), ReadLinFile(FiveMwDir() + "/Main.12.lin").A);
  const PeriodicSystem trig = scene.Build({{"trig", "1"}, {"mbc", "0"}});
  EXPECT_EQ(trig.form(), PeriodicSystem::Form::kFourier);
  const MatrixXd a24 = ReadLinFile(FiveMwDir() + "/Main.24.lin").A;
  EXPECT_LT((trig.A(4.0147 / 0.9425) - a24).norm(), 1e-13 * a24.norm());
  EXPECT_THROW(scene.Build({{"trig", "2"}}), InputError);
  const std::vector<Diagnostic> notes = LinCaveats(op);
  ASSERT_FALSE(notes.empty());
  EXPECT_EQ(notes[0].code, DiagnosticCode::kAzimuthSamplesResolve);
  EXPECT_EQ(notes[0].severity, Severity::kNote);
  EXPECT_NE(notes[0].text.find("3 azimuths hold only harmonics 0 and ±1"), std::string::npos)
      << notes[0].text;
  // The 5 MW files have blade states (rotating frame) and the generator azimuth.
  EXPECT_TRUE(HasCode(notes, DiagnosticCode::kExponentsModuloRotorSpeed));
  EXPECT_TRUE(HasCode(notes, DiagnosticCode::kRigidBodyMode));
}

}  // namespace
}  // namespace ltp
