// What a user names as the system (built-in, YAML file, .lin files) with --set style
// assignments: the one loader of the CLI and the Python module.
#include "ltp/models/scene_input.h"

#include <gtest/gtest.h>

#include "ltp/core/error.h"

namespace ltp {
namespace {

TEST(SceneInput, BuiltinWithAssignments) {
  const LoadedScene l = LoadSceneInput({"mathieu"}, {"a=2", "q=pi/4"});
  EXPECT_EQ(l.scene.name, "mathieu");
  EXPECT_EQ(l.parameters.at("a"), 2);
  EXPECT_DOUBLE_EQ(l.parameters.at("q"), 0.7853981633974483);
  EXPECT_EQ(l.system.states(), 2);
  EXPECT_TRUE(l.diagnostics.empty());
}

TEST(SceneInput, RefusesWhatItCannotLoad) {
  EXPECT_THROW(LoadSceneInput({"no-such-scene"}), InputError);
  EXPECT_THROW(LoadSceneInput({"mathieu"}, {"a"}), InputError);     // no '='
  EXPECT_THROW(LoadSceneInput({"mathieu"}, {"zz=1"}), InputError);  // not a parameter
  EXPECT_THROW(LoadSceneInput({"mathieu", "extra"}), InputError);   // several: .lin only
  EXPECT_THROW(LoadSceneInput({}), InputError);
}

}  // namespace
}  // namespace ltp
