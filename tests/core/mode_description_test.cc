// Mode descriptions: participation shares and multiblade families against shapes whose split
// is known by construction (a pure collective, a pure cyclic pattern, hand-computed mixtures),
// and against the kinetic energy of an undamped second-order system's modes from Eigen's
// symmetric generalized eigensolver (an independent route); the shares do not change with
// the states' units.
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

// With the left vector conj(v) the participation of state i is |v_i|²: the shares of the
// hand-made shapes below are their entries' squared magnitudes (and, per multiblade harmonic,
// the squared DFT coefficients over the blades, divided by B).
ModeDescription Describe(const SystemLabels& l, const Eigen::VectorXcd& v,
                         const ModeDescriptionOptions& options = {}) {
  return DescribeMode(l, v, v.conjugate(), options);
}

TEST(ModeDescription, CollectiveAndCyclicBladePatterns) {
  const SystemLabels l = ThreeBladeRotor();
  const ModeDescription collective = Describe(l, Shape({1, 1, 1}, 10));
  ASSERT_FALSE(collective.families.empty());
  EXPECT_EQ(collective.families[0].name, "zeta collective");
  EXPECT_NEAR(collective.families[0].share, 1, 1e-14);
  EXPECT_EQ(collective.text, "zeta collective 100%");
  // Blade b lags by 2π(b−1)/3: multiblade harmonic 1, a cyclic pattern.
  const cd w = std::polar(1.0, 2 * std::numbers::pi / 3);
  const ModeDescription cyclic = Describe(l, Shape({1, w, w * w}, 10));
  EXPECT_EQ(cyclic.families[0].name, "zeta cyclic");
  EXPECT_NEAR(cyclic.families[0].share, 1, 1e-14);
}

TEST(ModeDescription, SharesOfAMixtureWithRatesInTheirDisplacementsFamilies) {
  const SystemLabels l = ThreeBladeRotor();
  const cd w = std::polar(1.0, 2 * std::numbers::pi / 3);
  // Blade participation 3 (cyclic), support x 1, and the rates (entries 5..9) the same again:
  // 75 % and 25 %, with no family of its own for a rate.
  Eigen::VectorXcd v = Shape({1, w, w * w, 1, 0}, 10);
  v.tail(5) = v.head(5);
  const ModeDescription d = Describe(l, v);
  ASSERT_EQ(d.families.size(), 4u);  // zeta collective, cyclic; x; y
  EXPECT_EQ(d.families[0].name, "zeta cyclic");
  EXPECT_NEAR(d.families[0].share, 0.75, 1e-14);
  EXPECT_EQ(d.families[1].name, "x");
  EXPECT_NEAR(d.families[1].share, 0.25, 1e-14);
  EXPECT_EQ(d.text, "zeta cyclic 75%, x 25%");
  double total = 0;
  for (const auto& f : d.families) {
    total += f.share;
    EXPECT_EQ(f.name.find("_dot"), std::string::npos) << f.name;
  }
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
  const ModeDescription cantilever = Describe(l, Shape({1, 1, 0, 0, 0, 0}, 6));
  EXPECT_EQ(cantilever.text, "cantilever_bend_z1 50%, cantilever_bend_z2 50%");
  const ModeDescription d = Describe(l, Shape({0, 0, 1, -1, 0.5, 0.5}, 6));
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
  const ModeDescription d = Describe(l, Shape({1, 1, 1, 0}, 4));
  EXPECT_EQ(d.families[0].name, "ED 1st flapwise bending-mode DOF of blade, m collective");
  // OpenFAST's rates ("First time derivative of ..., m/s") join their displacements.
  SystemLabels rates = l;
  for (int i = 0; i < 4; ++i) {
    std::string name = l.states[static_cast<size_t>(i)];
    name.insert(3, "First time derivative of ");
    rates.states.push_back(name.substr(0, name.size() - 1) + "m/s");
  }
  rates.blade_states = {0, 1, 2, 4, 5, 6};
  const ModeDescription both = Describe(rates, Shape({1, 1, 1, 1, 2, 2, 2, 2}, 8));
  ASSERT_EQ(both.families.size(), 3u);  // blade collective and cyclic; tower
  EXPECT_EQ(both.families[0].name, "ED 1st flapwise bending-mode DOF of blade, m collective");
  EXPECT_NEAR(both.families[0].share, 15.0 / 20, 1e-14);
  EXPECT_EQ(both.families[1].name, "ED 1st tower fore-aft bending mode DOF, m");
  EXPECT_NEAR(both.families[1].share, 5.0 / 20, 1e-14);
  // With 4 blades claimed, the three blade states are not a complete family: named singly.
  l.blades = 4;
  const ModeDescription single = Describe(l, Shape({1, 0, 0, 0}, 4));
  EXPECT_EQ(single.families[0].name, l.states[0]);
  EXPECT_NEAR(single.families[0].share, 1, 1e-15);
}

TEST(ModeDescription, UnlabelledZeroAndMismatchedShapes) {
  const ModeDescription d = Describe(SystemLabels{}, Shape({0, 2}, 2));
  EXPECT_EQ(d.text, "x2 100%");
  EXPECT_TRUE(Describe(SystemLabels{}, Eigen::VectorXcd::Zero(3)).text.empty());
  EXPECT_THROW(Describe(ThreeBladeRotor(), Eigen::VectorXcd::Ones(4)), InputError);
  EXPECT_THROW(DescribeMode(SystemLabels{}, Eigen::VectorXcd::Ones(2), Eigen::VectorXcd::Ones(3)),
               InputError);
  EXPECT_TRUE(LeftEigenvectors(Eigen::MatrixXcd::Ones(2, 3)).size() == 0);
  EXPECT_TRUE(DescribeModeShapes(SystemLabels{}, Eigen::MatrixXcd::Zero(2, 2))[0].empty());
  ModeDescriptionOptions bad;
  bad.max_families = 0;
  EXPECT_THROW(Describe(SystemLabels{}, Eigen::VectorXcd::Ones(2), bad), InputError);
}

// M q'' + K q = 0 with a consistent-mass-like coupled M (a beam element's pattern) and K in
// mixed units (DOF 1 a translation in m, DOF 2 a slope in rad whose entries are 10³ apart):
// each mode's shares equal φ_i(Mφ)_i / φᵀMφ, its kinetic-energy split, from the symmetric
// generalized eigenproblem Kφ = ω²Mφ solved on its own.
struct SecondOrderExample {
  Eigen::MatrixXd m{{2.0, 0.1, 0.0}, {0.1, 0.01, 0.002}, {0.0, 0.002, 1.5}};
  Eigen::MatrixXd k{{5.0e3, 40.0, -1.0e3}, {40.0, 3.0, 0.0}, {-1.0e3, 0.0, 2.0e3}};
  Eigen::MatrixXd A() const {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(6, 6);
    a.topRightCorner(3, 3).setIdentity();
    a.bottomLeftCorner(3, 3) = -m.ldlt().solve(k);
    return a;
  }
  SystemLabels labels() const {
    SystemLabels l;
    l.states = {"v", "theta", "w", "v_dot", "theta_dot", "w_dot"};
    return l;
  }
};

TEST(ModeDescription, SecondOrderSharesAreKineticEnergyShares) {
  const SecondOrderExample e;
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(e.A());
  const Eigen::MatrixXcd right = eig.eigenvectors();
  const Eigen::MatrixXcd left = LeftEigenvectors(right);
  ASSERT_EQ(left.rows(), 6);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(e.k, e.m);
  for (int k = 0; k < 6; ++k) {
    const double omega = std::abs(eig.eigenvalues()(k).imag());
    int j = 0;  // the undamped mode with this frequency
    (modes.eigenvalues().cwiseSqrt().array() - omega).abs().minCoeff(&j);
    const Eigen::VectorXd phi = modes.eigenvectors().col(j);
    const Eigen::VectorXd kinetic = phi.cwiseProduct(e.m * phi) / phi.dot(e.m * phi);
    const ModeDescription d = DescribeMode(e.labels(), right.col(k), left.row(k).transpose(),
                                           {.min_share = 0, .max_families = 3});
    ASSERT_EQ(d.families.size(), 3u);
    double absolute_total = kinetic.cwiseAbs().sum();  // a consistent mass may give one < 0
    for (const auto& f : d.families) {
      const int i = f.name == "v" ? 0 : f.name == "theta" ? 1 : 2;
      EXPECT_NEAR(f.share, std::abs(kinetic(i)) / absolute_total, 1e-10)
          << "mode " << k << " " << f.name;
    }
  }
}

TEST(ModeDescription, SharesDoNotDependOnTheStatesUnits) {
  const SecondOrderExample e;
  // The slope in mrad: state 2 (and its rate) scaled by 1000, A → S A S⁻¹.
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(6);
  scale(1) = scale(4) = 1000;
  const Eigen::MatrixXd scaled = scale.asDiagonal() * e.A() * scale.cwiseInverse().asDiagonal();
  const Eigen::EigenSolver<Eigen::MatrixXd> a(e.A()), b(scaled);
  const ModeDescriptionOptions all{.min_share = 0, .max_families = 3};
  const std::vector<std::string> in_rad = DescribeModeShapes(e.labels(), a.eigenvectors(), all);
  const std::vector<std::string> in_mrad = DescribeModeShapes(e.labels(), b.eigenvectors(), all);
  for (int k = 0; k < 6; ++k) {
    int j = 0;  // b's mode with a's eigenvalue
    (b.eigenvalues().array() - a.eigenvalues()(k)).abs().minCoeff(&j);
    EXPECT_EQ(in_rad[static_cast<size_t>(k)], in_mrad[static_cast<size_t>(j)]) << "mode " << k;
    EXPECT_FALSE(in_rad[static_cast<size_t>(k)].empty());
  }
}

}  // namespace
}  // namespace ltp
