// Mode descriptions: energy shares and multiblade families against shapes whose split is
// known by construction (a pure collective, a pure cyclic pattern, hand-computed mixtures).
#include "ltp/core/mode_description.h"

#include <gtest/gtest.h>

#include <complex>
#include <numbers>

#include "ltp/core/error.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

SystemLabels ThreeBladeRotor() {
  SystemLabels l;
  l.states = {"zeta1",     "zeta2",     "zeta3",     "x",     "y",
              "zeta1_dot", "zeta2_dot", "zeta3_dot", "x_dot", "y_dot"};
  l.blades = 3;
  l.blade_states = {0, 1, 2};
  return l;
}

Eigen::VectorXcd Shape(std::initializer_list<cd> head, int n) {
  Eigen::VectorXcd v = Eigen::VectorXcd::Zero(n);
  int i = 0;
  for (cd x : head) v(i++) = x;
  return v;
}

TEST(ModeDescription, CollectiveAndCyclicBladePatterns) {
  const SystemLabels l = ThreeBladeRotor();
  const ModeDescription collective = DescribeModeShape(l, Shape({1, 1, 1}, 10));
  ASSERT_FALSE(collective.families.empty());
  EXPECT_EQ(collective.families[0].name, "zeta collective");
  EXPECT_NEAR(collective.families[0].share, 1, 1e-14);
  EXPECT_EQ(collective.text, "zeta collective 100%");
  // Blade b lags by 2π(b−1)/3: multiblade harmonic 1, a cyclic pattern.
  const cd w = std::polar(1.0, 2 * std::numbers::pi / 3);
  const ModeDescription cyclic = DescribeModeShape(l, Shape({1, w, w * w}, 10));
  EXPECT_EQ(cyclic.families[0].name, "zeta cyclic");
  EXPECT_NEAR(cyclic.families[0].share, 1, 1e-14);
}

TEST(ModeDescription, SharesOfAMixtureAndRatesLeftOut) {
  const SystemLabels l = ThreeBladeRotor();
  const cd w = std::polar(1.0, 2 * std::numbers::pi / 3);
  // Blade energy 3 (cyclic), support x energy 1: 75 % and 25 %. The rates (entries 5..9) are
  // large but are not displacement states.
  Eigen::VectorXcd v = Shape({1, w, w * w, 1, 0}, 10);
  v.tail(5).setConstant(50);
  const ModeDescription d = DescribeModeShape(l, v);
  ASSERT_GE(d.families.size(), 2u);
  EXPECT_EQ(d.families[0].name, "zeta cyclic");
  EXPECT_NEAR(d.families[0].share, 0.75, 1e-14);
  EXPECT_EQ(d.families[1].name, "x");
  EXPECT_NEAR(d.families[1].share, 0.25, 1e-14);
  EXPECT_EQ(d.text, "zeta cyclic 75%, x 25%");
  double total = 0;
  for (const auto& f : d.families) total += f.share;
  EXPECT_NEAR(total, 1, 1e-14);
}

TEST(ModeDescription, TwoBladesHaveADifferentialAndNamesKeepTheirOtherNumbers) {
  SystemLabels l;
  l.states = {"cantilever_bend_z1", "cantilever_bend_z2", "blade1_flap1",
              "blade2_flap1",       "blade1_flap2",       "blade2_flap2"};
  l.blades = 2;
  l.blade_states = {2, 3, 4, 5};
  // The blade number follows "blade"; flap1/flap2 stay apart, and the cantilever's modes 1
  // and 2 are not blades although their labels are numbered like them.
  const ModeDescription cantilever = DescribeModeShape(l, Shape({1, 1, 0, 0, 0, 0}, 6));
  EXPECT_EQ(cantilever.text, "cantilever_bend_z1 50%, cantilever_bend_z2 50%");
  const ModeDescription d = DescribeModeShape(l, Shape({0, 0, 1, -1, 0.5, 0.5}, 6));
  ASSERT_GE(d.families.size(), 2u);
  EXPECT_EQ(d.families[0].name, "blade_flap1 differential");
  EXPECT_NEAR(d.families[0].share, 2 / 2.5, 1e-14);
  EXPECT_EQ(d.families[1].name, "blade_flap2 collective");
  EXPECT_NEAR(d.families[1].share, 0.5 / 2.5, 1e-14);
}

TEST(ModeDescription, OpenFastStyleLabelsAndIncompleteFamilies) {
  SystemLabels l;
  for (int b = 1; b <= 3; ++b)
    l.states.push_back("ED 1st flapwise bending-mode DOF of blade " + std::to_string(b) + ", m");
  l.states.push_back("ED 1st tower fore-aft bending mode DOF, m");
  l.blades = 3;
  l.blade_states = {0, 1, 2};
  const ModeDescription d = DescribeModeShape(l, Shape({1, 1, 1, 0}, 4));
  EXPECT_EQ(d.families[0].name, "ED 1st flapwise bending-mode DOF of blade, m collective");
  // With 4 blades claimed, the three blade states are not a complete family: named singly.
  l.blades = 4;
  const ModeDescription single = DescribeModeShape(l, Shape({1, 0, 0, 0}, 4));
  EXPECT_EQ(single.families[0].name, l.states[0]);
  EXPECT_NEAR(single.families[0].share, 1, 1e-15);
}

TEST(ModeDescription, UnlabelledZeroAndMismatchedShapes) {
  const ModeDescription d = DescribeModeShape(SystemLabels{}, Shape({0, 2}, 2));
  EXPECT_EQ(d.text, "x2 100%");
  EXPECT_TRUE(DescribeModeShape(SystemLabels{}, Eigen::VectorXcd::Zero(3)).text.empty());
  EXPECT_THROW(DescribeModeShape(ThreeBladeRotor(), Eigen::VectorXcd::Ones(4)), InputError);
  ModeDescriptionOptions bad;
  bad.max_families = 0;
  EXPECT_THROW(DescribeModeShape(SystemLabels{}, Eigen::VectorXcd::Ones(2), bad), InputError);
}

}  // namespace
}  // namespace ltp
