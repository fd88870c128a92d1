// The rotor (ground resonance) and flap scenes, multi-blade coordinates and sampled scene files.
#include "ltp/models/rotor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include "ltp/core/error.h"
#include "ltp/models/rotor_mbc.h"
#include "ltp/models/scene.h"
#include "support/compare.h"

namespace ltp {
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;
using test::CompareMatrices;

std::string ScenesDir() {
  if (const char* dir = std::getenv("LTP_SOURCE_DIR")) return std::string(dir) + "/scenes";
  return (std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "scenes")
      .string();
}

RotorParameters Anisotropic(int blades) {
  RotorParameters r;  // the scene defaults: M_x != M_y, c_x != c_y
  r.blades = blades;
  r.stiffness_y = 3.5;  // and k_x != k_y
  r.lag_stiffness = 0.05;
  return r;
}

// The first-order A(t) straight from the second-order matrices.
MatrixXd DirectA(const RotorParameters& r, double t) {
  const RotorMatrices m = RotorSecondOrderMatrices(r, t);
  const int q = static_cast<int>(m.M.rows());
  MatrixXd a = MatrixXd::Zero(2 * q, 2 * q);
  a.topRightCorner(q, q).setIdentity();
  a.bottomLeftCorner(q, q) = -m.M.lu().solve(m.K);
  a.bottomRightCorner(q, q) = -m.M.lu().solve(m.D);
  return a;
}

TEST(Rotor, MassSymmetricAndDampingIsMassRatePlusGyroscopic) {
  // Lagrange's equations with a time-dependent kinetic energy give D = dM/dt + G with G skew
  // when there is no dissipation (derivation in rotor.h).
  RotorParameters r = Anisotropic(3);
  r.lag_damping = r.damping_x = r.damping_y = 0;
  const double t = 0.7, h = 1e-6;
  const RotorMatrices m = RotorSecondOrderMatrices(r, t);
  EXPECT_TRUE(CompareMatrices(m.M, m.M.transpose(), 0));
  const MatrixXd m_dot =
      (RotorSecondOrderMatrices(r, t + h).M - RotorSecondOrderMatrices(r, t - h).M) / (2 * h);
  const MatrixXd g = m.D - m_dot;
  EXPECT_TRUE(CompareMatrices(g, -g.transpose(), 1e-8));
}

TEST(Rotor, FourierFormEqualsSecondOrderMatrices) {
  for (int blades : {3, 4, 5}) {
    RotorParameters r = Anisotropic(blades);
    r.mistune_k = 1.3;
    r.mistune_c = 0.0;
    const PeriodicSystem s = BuildRotorSystem(r);
    ASSERT_EQ(s.form(), PeriodicSystem::Form::kFourier);
    EXPECT_LE(s.fourier_A()->max_harmonic(), 3);  // M⁻¹: 2Ω, K and D: Ω
    EXPECT_DOUBLE_EQ(s.period(), 2 * pi / r.omega);
    for (double t : {0.0, 0.31, 1.7, 4.4})
      EXPECT_TRUE(CompareMatrices(s.A(t), DirectA(r, t), 1e-13)) << "N = " << blades;
  }
  const PeriodicSystem two = BuildRotorSystem(Anisotropic(2));
  EXPECT_EQ(two.form(), PeriodicSystem::Form::kFunction);
  EXPECT_TRUE(CompareMatrices(two.A(0.9), DirectA(Anisotropic(2), 0.9), 1e-13));
  EXPECT_EQ(two.labels().states.front(), "zeta1");
  EXPECT_EQ(two.labels().outputs, (std::vector<std::string>{"x", "y"}));
}

TEST(Rotor, IdenticalBladesRepeatAfterOneNthUpToRelabelling) {
  // P A(t + T/N) P⁻¹ = A(t) (rotor.h); a mistuned blade breaks it.
  for (int blades : {2, 3, 4}) {
    RotorParameters r = Anisotropic(blades);
    const PeriodicSystem s = BuildRotorSystem(r);
    const MatrixXd p = RotorBladeShift(blades);
    const double tau = s.period() / blades;
    for (double t : {0.2, 2.9})
      EXPECT_TRUE(CompareMatrices(p * s.A(t + tau) * p.transpose(), s.A(t), 1e-12));
    r.mistune_k = 0.5;
    const PeriodicSystem m = BuildRotorSystem(r);
    EXPECT_FALSE(CompareMatrices(p * m.A(0.2 + tau) * p.transpose(), m.A(0.2), 1e-6));
  }
}

TEST(Rotor, RejectsBadParameters) {
  const Scene& scene = LoadScene("rotor");
  EXPECT_THROW(scene.Build({{"blades", "2.5"}}), InputError);
  EXPECT_THROW(scene.Build({{"blades", "1"}}), InputError);
  EXPECT_THROW(scene.Build({{"Omega", "0"}}), InputError);
  EXPECT_THROW(scene.Build({{"C_zeta", "-1"}}), InputError);
  // M_x must exceed (N/2) S_b²/I_b = 2 · 0.27² = 0.1458 for N = 4.
  try {
    scene.Build({{"Mx", "0.1"}});
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'Mx'"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(scene.Build({{"Mx", "0.15"}}));
}

TEST(Rotor, ScenesAreRegisteredWithDescribedParameters) {
  for (const char* name : {"rotor", "flap"}) {
    const Scene& scene = LoadScene(name);
    EXPECT_EQ(scene.source, "built-in");
    EXPECT_FALSE(scene.description.empty());
    for (const SceneParameter& p : scene.parameters)
      EXPECT_FALSE(p.description.empty()) << name << "." << p.name;
    EXPECT_NO_THROW(scene.Build());
  }
  const PeriodicSystem rotor = LoadScene("rotor").Build({{"blades", "3"}});
  EXPECT_EQ(rotor.states(), 10);
  EXPECT_EQ(rotor.inputs(), 2);
  EXPECT_EQ(rotor.outputs(), 2);
  ASSERT_TRUE(rotor.rotor_speed().has_value());
}

TEST(Flap, FourierFormEqualsTheFlapEquation) {
  // Johnson's flap equation (flap_scene.cc), evaluated directly.
  const double gamma = 12, mu = 0.8, nu = 1.1, w = 1.3;
  const PeriodicSystem s =
      LoadScene("flap").Build({{"gamma", "12"}, {"mu", "0.8"}, {"nu", "1.1"}, {"Omega", "1.3"}});
  ASSERT_EQ(s.form(), PeriodicSystem::Form::kFourier);
  for (double t : {0.0, 0.4, 2.2, 3.9}) {
    const double psi = w * t;
    MatrixXd a(2, 2);
    a << 0, 1,
        -w * w *
            (nu * nu + gamma / 8 * (4.0 / 3 * mu * std::cos(psi) + mu * mu * std::sin(2 * psi))),
        -w * gamma / 8 * (1 + 4.0 / 3 * mu * std::sin(psi));
    EXPECT_TRUE(CompareMatrices(s.A(t), a, 1e-14));
  }
  EXPECT_DOUBLE_EQ(s.period(), 2 * pi / w);
}

TEST(Mbc, TransformIsInvertibleAndMatchesItsDerivatives) {
  for (int n : {3, 4, 5, 6}) {
    const MatrixXd t = MbcTransform(n, 0.4);
    EXPECT_GT(t.fullPivLu().rank(), n - 1);
    const double h = 1e-5;
    const MatrixXd d1 = (MbcTransform(n, 0.4 + h) - MbcTransform(n, 0.4 - h)) / (2 * h);
    EXPECT_TRUE(CompareMatrices(MbcTransform(n, 0.4, 1), d1, 1e-8));
    const MatrixXd d2 = (MbcTransform(n, 0.4 + h, 1) - MbcTransform(n, 0.4 - h, 1)) / (2 * h);
    EXPECT_TRUE(CompareMatrices(MbcTransform(n, 0.4, 2), d2, 1e-8));
    EXPECT_EQ(static_cast<int>(MbcCoordinateNames(n).size()), n);
  }
  EXPECT_THROW(MbcTransform(2, 0), InputError);
}

TEST(Mbc, ConstantCoefficientsOnAnAnisotropicSupport) {
  for (int n : {3, 4, 5, 6}) {
    const MbcRotorSystem s = RotorInMultiBladeCoordinates(Anisotropic(n));
    EXPECT_LT(s.constancy_defect, 1e-13) << "N = " << n;
    EXPECT_EQ(static_cast<int>(s.eigenvalues.size()), 2 * (n + 2));
    EXPECT_EQ(s.coordinates.back(), "y");
  }
}

// Number of entries of `values` within tol of `target`.
int CountNear(const std::vector<std::complex<double>>& values, std::complex<double> target,
              double tol) {
  int count = 0;
  for (const auto& v : values) count += std::abs(v - target) <= tol ? 1 : 0;
  return count;
}

TEST(Mbc, IsolatedBladeModesHaveTheClosedForm) {
  // Collective and differential never move the hub (Σ sin ψ_i = Σ (−1)^i sin ψ_i = 0 for
  // N >= 3 ... N >= 4 even): λ = −C/2I ± j√(K'/I − (C/2I)²), K' = K_ζ + e S_b Ω². Higher
  // cyclics n >= 2 are the same blade seen from the fixed frame: λ ± jnΩ.
  for (int n : {3, 4, 5, 6}) {
    const RotorParameters r = Anisotropic(n);
    const std::complex<double> lambda = IsolatedBladeLagExponent(r);
    const double k_eff = r.lag_stiffness + r.hinge_offset * r.first_moment * r.omega * r.omega;
    const double decay = r.lag_damping / (2 * r.inertia);
    EXPECT_NEAR(lambda.real(), -decay, 1e-15);
    EXPECT_NEAR(lambda.imag(), std::sqrt(k_eff / r.inertia - decay * decay), 1e-15);
    const MbcRotorSystem s = RotorInMultiBladeCoordinates(r);
    const int isolated = n % 2 == 0 ? 2 : 1;  // collective (+ differential)
    EXPECT_EQ(CountNear(s.eigenvalues, lambda, 1e-12), isolated) << "N = " << n;
    EXPECT_EQ(CountNear(s.eigenvalues, std::conj(lambda), 1e-12), isolated) << "N = " << n;
    for (int h = 2; h <= (n - 1) / 2; ++h)
      EXPECT_EQ(CountNear(s.eigenvalues, lambda + std::complex<double>(0, h * r.omega), 1e-12), 1)
          << "N = " << n << ", cyclic " << h;
  }
}

TEST(Mbc, RefusesTwoBladesAndMistunedBlades) {
  const RotorParameters two = Anisotropic(2);
  ASSERT_TRUE(MbcNotApplicable(two).has_value());
  EXPECT_THROW(RotorInMultiBladeCoordinates(two), InputError);
  RotorParameters mistuned = Anisotropic(4);
  mistuned.mistune_c = 0;
  const auto reason = MbcNotApplicable(mistuned);
  ASSERT_TRUE(reason.has_value());
  EXPECT_NE(reason->find("mistuned"), std::string::npos) << *reason;
  EXPECT_NE(reason->find("anisotropic"), std::string::npos) << *reason;
  EXPECT_THROW(RotorInMultiBladeCoordinates(mistuned), InputError);
  EXPECT_FALSE(MbcNotApplicable(Anisotropic(3)).has_value());
}

// --- sampled scene files ---------------------------------------------------------------

const char* kSampledHeader = R"yaml(name: s
period: 2
parameters: {k: 3}
)yaml";

TEST(SampledScene, ConstantInterpolationHoldsEachSample) {
  const std::string text = std::string(kSampledHeader) + R"yaml(sampled:
  times: [0, 0.5, 1.2]
  interpolation: constant
  A: [[[0, 1], [-k, 0]], [[0, 1], [-1, 0]], [[0, 2], ["-k/2", 0]]]
  B: [[0], [1]]
  C: [[1, 0]]
)yaml";
  const PeriodicSystem s = ParseSceneYaml(text, "s.yaml").Build();
  ASSERT_EQ(s.form(), PeriodicSystem::Form::kPiecewiseConstant);
  EXPECT_EQ(s.sample_times(), (std::vector<double>{0, 0.5, 1.2}));
  EXPECT_DOUBLE_EQ(s.A(0.3)(1, 0), -3);
  EXPECT_DOUBLE_EQ(s.A(0.7)(1, 0), -1);
  EXPECT_DOUBLE_EQ(s.A(1.9)(0, 1), 2);
  EXPECT_DOUBLE_EQ(s.B(1.9)(1, 0), 1);
  const PeriodicSystem t = ParseSceneYaml(text, "s.yaml").Build({{"k", "5"}});
  EXPECT_DOUBLE_EQ(t.A(1.9)(1, 0), -2.5);
}

TEST(SampledScene, FourierInterpolationPassesThroughTheSamples) {
  // Azimuths 0, 90, 180, 270 deg of the period 2: t = 0, 0.5, 1, 1.5. K = 4 is even, so the
  // Nyquist harmonic is split (scene_file.cc); the interpolant still hits every sample.
  const std::string text = std::string(kSampledHeader) + R"yaml(sampled:
  azimuths_deg: [0, 90, 180, 270]
  interpolation: fourier
  A: [[[1]], [[2]], [[-1]], ["k"]]
)yaml";
  // A sample written as a row (["k"]) instead of a matrix ([["k"]]) is an error.
  EXPECT_THROW(ParseSceneYaml(text, "s.yaml"), SceneError);
  const std::string good = std::string(kSampledHeader) + R"yaml(sampled:
  azimuths_deg: [0, 90, 180, 270]
  interpolation: fourier
  A: [[[1]], [[2]], [[-1]], [["k"]]]
)yaml";
  const PeriodicSystem s = ParseSceneYaml(good, "s.yaml").Build();
  ASSERT_EQ(s.form(), PeriodicSystem::Form::kFourier);
  const double values[] = {1, 2, -1, 3};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(s.A(0.5 * k)(0, 0), values[k], 1e-14);
  EXPECT_NEAR(s.A(0.25)(0, 0), s.fourier_A()->Evaluate(0.25, pi)(0, 0), 1e-15);
}

TEST(SampledScene, ShippedMathieuSamplesGiveTheMathieuSeries) {
  // scenes/sampled-mathieu.yaml: 8 samples of A(t) = [[0, 1], [−(a − 2q cos 2t), −c]]; the DFT
  // returns A_0 = [[0, 1], [−a, −c]], A_{±1}(1, 0) = q exactly (harmonic 1 of Ωp = 2), and
  // nothing else. B and C are constant; there is no D.
  const std::string path = ScenesDir() + "/sampled-mathieu.yaml";
  const PeriodicSystem s = LoadScene(path).Build({{"q", "0.3"}});
  ASSERT_EQ(s.form(), PeriodicSystem::Form::kFourier);
  EXPECT_DOUBLE_EQ(s.period(), pi);
  const FourierMatrix& a = *s.fourier_A();
  EXPECT_NEAR(a.coefficient(0).real()(1, 0), -1, 1e-15);
  EXPECT_NEAR(std::abs(a.coefficient(1)(1, 0) - 0.3), 0, 1e-15);
  for (int w = 2; w <= a.max_harmonic(); ++w) EXPECT_LT(a.coefficient(w).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(s.B(0.4)(1, 0), 1);
  EXPECT_DOUBLE_EQ(s.C(0.4)(0, 0), 1);
  EXPECT_DOUBLE_EQ(s.D(0.4)(0, 0), 0);
  EXPECT_EQ(s.labels().states, (std::vector<std::string>{"y", "y_dot"}));
}

TEST(SampledScene, ErrorsNameFileLineAndEntry) {
  struct Case {
    const char* body;
    const char* message;
  };
  const Case cases[] = {
      {"sampled:\n  times: [0, 1]\n  interpolation: linear\n  A: [[[1]], [[2]]]\n",
       "s.yaml:6: sampled.interpolation: must be 'constant'"},
      {"sampled:\n  times: [0, 1]\n  interpolation: constant\n  A: [[[1]]]\n",
       "s.yaml:7: sampled.A: expected 2 matrices"},
      {"sampled:\n  times: [0, 0.5]\n  interpolation: fourier\n  A: [[[1]], [[2]]]\n",
       "s.yaml:5: sampled.times[1]: fourier interpolation needs equally spaced samples"},
      {"sampled:\n  times: [0, 3]\n  interpolation: constant\n  A: [[[1]], [[2]]]\n",
       "s.yaml:5: sampled.times[1]: 3 is outside [0, 2)"},
      {"sampled:\n  times: [0, 1]\n  interpolation: constant\n  A: [[[1]], [[2, 3]]]\n",
       "s.yaml:7: sampled.A: is 1x2 but must be 1x1"},
      {"sampled:\n  times: [0, 1]\n  interpolation: constant\n  A: [[[1]], [[2]]]\n"
       "  B: [[[1]]]\n",
       "s.yaml:8: sampled.B: expected 2 matrices"},
  };
  for (const Case& c : cases) {
    try {
      ParseSceneYaml(std::string(kSampledHeader) + c.body, "s.yaml");
      ADD_FAILURE() << "no error for:\n" << c.body;
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.message, 0), 0u)
          << "got: " << e.what() << "\nwant prefix: " << c.message;
    }
  }
}

}  // namespace
}  // namespace ltp
