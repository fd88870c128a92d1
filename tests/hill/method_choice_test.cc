// Automatic method choice (integrator and Hill solver `auto`): what it picks on the kinds of
// system the work–precision study covered, and that the analyses it drives are accurate
// against closed forms (Meissner's monodromy, the triangular stiff scene, a Lyapunov-reducible
// stiff system) and say which method they used and why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "ltp/hill/hill.h"
#include "ltp/hill/hill_solver_choice.h"
#include "ltp/integrate/integrator_choice.h"
#include "ltp/models/rotor.h"
#include "ltp/models/scene.h"
#include "ltp/models/scene_input.h"
#include "support/isotropic_rotor_lin.h"
#include "support/rotor_lin.h"
#include "support/systems.h"

namespace ltp {
namespace {

using cd = std::complex<double>;
using test::kPi;

// Largest distance of the modes' exponents to `exact`, matched one-to-one modulo Ωp (a missed
// exponent cannot hide behind another mode's nearest value); +inf when the counts differ.
double MatchedDistance(const std::vector<FloquetMode>& modes, const std::vector<cd>& exact,
                       double omega) {
  EXPECT_EQ(modes.size(), exact.size());
  std::vector<cd> got;
  for (const FloquetMode& m : modes) got.push_back(m.exponent);
  return MaxExponentMismatch(got, exact, omega);
}

PeriodicSystem StiffYaml() {
  return LoadScene(test::SourceDir() + "/tests/data/stiff.yaml").Build({});
}

TEST(MethodChoice, PicksTheStudysWinnerPerKindOfSystem) {
  // Rules from the study (docs/benchmarks.md): smooth → bs; constant between jumps → expm (exact);
  // stiff (fast real decay or growth) → magnus6; a Fourier series of two states → taylor, of
  // four (the Jeffcott rotor) → bs again.
  EXPECT_EQ(ChooseIntegrator(test::Mathieu(1.5, 0.5, 0.05), 1e-10).type, IntegratorType::kTaylor);
  const PeriodicSystem jeffcott = LoadScene("jeffcott").Build({});
  ASSERT_NE(jeffcott.fourier_A(), nullptr);
  EXPECT_EQ(ChooseIntegrator(jeffcott, 1e-10).type, IntegratorType::kBulirschStoer);
  EXPECT_EQ(ChooseIntegrator(test::Meissner(2, 0.5, 0.05), 1e-10).type, IntegratorType::kExpm);
  RotorParameters rotor;
  rotor.blades = 2;
  EXPECT_EQ(ChooseIntegrator(BuildRotorSystem(rotor), 1e-10).type, IntegratorType::kBulirschStoer);
  // Fast oscillation is not stiffness here: tower-rotor's modes reach 4777 rad/s, lightly damped.
  const SystemTraits tower = MeasureSystemTraits(LoadScene("tower-rotor").Build({}));
  EXPECT_LT(tower.stiffness, 500);
  EXPECT_EQ(ChooseIntegrator(tower, 1e-10).type, IntegratorType::kBulirschStoer);
  const SystemTraits stiff = MeasureSystemTraits(StiffYaml());
  EXPECT_GT(stiff.stiffness, 500);  // triangular: eig A(t) = diagonal, |−800 + 100 cos t|·2π ≥ 4398
  EXPECT_EQ(ChooseIntegrator(stiff, 1e-10).type, IntegratorType::kMagnus6);
  // Jumps between non-constant pieces are not "constant pieces".
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out << 0, 1, -(1 + (std::cos(t) > 0 ? 0.3 : -0.3) * std::sin(t)), -0.1;
  };
  const PeriodicSystem jumpy =
      PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f, {kPi / 2, 3 * kPi / 2});
  const SystemTraits t = MeasureSystemTraits(jumpy);
  EXPECT_TRUE(t.has_jumps);
  EXPECT_FALSE(t.constant_pieces);
  EXPECT_EQ(ChooseIntegrator(t, 1e-10).type, IntegratorType::kBulirschStoer);
}

TEST(MethodChoice, AutoIsNotAConcreteIntegrator) {
  const auto all = AllIntegrators();
  EXPECT_EQ(std::count(all.begin(), all.end(), IntegratorType::kAuto), 0);
  EXPECT_EQ(ParseIntegratorType("auto"), IntegratorType::kAuto);
  EXPECT_EQ(ParseHillSolver("auto"), HillSolver::kAuto);
}

TEST(MethodChoice, AutoMonodromyOnMeissnerIsExactAndSaysWhy) {
  // Closed form: Φ = E₊(π/2) E₋(π) E₊(π/2) (tests/support/systems.h).
  const PeriodicSystem s = test::Meissner(2, 0.5, 0.05);
  const Eigen::Matrix2d phi = test::MeissnerMonodromy(2, 0.5, 0.05);
  std::vector<cd> exact;
  for (int k = 0; k < 2; ++k) exact.push_back(std::log(cd(phi.eigenvalues()(k))) / s.period());
  FloquetOptions o;
  o.integrator.type = IntegratorType::kAuto;
  const FloquetResult r = AnalyzeFloquet(s, o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.integrator, IntegratorType::kExpm);
  EXPECT_TRUE(HasCode(r.diagnostics, DiagnosticCode::kIntegratorChosen));
  const double err = MatchedDistance(r.modes, exact, s.omega());
  EXPECT_LT(err, 1e-13);
  EXPECT_GE(r.error_estimate.value(), err);
}

TEST(MethodChoice, AutoMonodromyIsTheChosenIntegratorsRun) {
  // Same integrator, same options: the auto run must be the explicit run, bit for bit.
  const PeriodicSystem s = test::Mathieu(1.5, 0.5, 0.05);
  FloquetOptions o;
  o.integrator.type = IntegratorType::kAuto;
  const FloquetResult a = AnalyzeFloquet(s, o);
  o.integrator.type = IntegratorType::kTaylor;
  const FloquetResult b = AnalyzeFloquet(s, o);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_EQ(a.integrator, IntegratorType::kTaylor);
  ASSERT_EQ(a.modes.size(), b.modes.size());
  for (size_t k = 0; k < a.modes.size(); ++k) EXPECT_EQ(a.modes[k].exponent, b.modes[k].exponent);
  EXPECT_EQ(a.error_estimate.value(), b.error_estimate.value());
}

TEST(MethodChoice, AutoOnAStiffNonTriangularSystemMeetsTheClosedForm) {
  // Lyapunov-reducible, exponents exactly diag(Λ) (tests/support/systems.h): stiff like
  // stiff.yaml (ρ = e^{−5027} and e^{942}) but fully coupled, so Magnus is not exact by
  // structure here and has to earn its accuracy.
  const PeriodicSystem s = test::Reducible4(Eigen::Vector4d(-800, 150, -3, -0.5));
  EXPECT_EQ(ChooseIntegrator(s, 1e-10).type, IntegratorType::kMagnus6);
  FloquetOptions o;
  o.integrator.type = IntegratorType::kAuto;
  const FloquetResult r = AnalyzeFloquet(s, o);
  ASSERT_TRUE(r.ok) << r.BriefReport();
  EXPECT_EQ(r.integrator, IntegratorType::kMagnus6);
  const double err = MatchedDistance(r.modes, {-800.0, 150.0, -3.0, -0.5}, s.omega());
  EXPECT_LT(err, 1e-8 * 800);
  EXPECT_GE(r.error_estimate.value(), err);
}

TEST(MethodChoice, MagnusCrossesTheFastModesOfARotorConstantInMultiBladeCoordinates) {
  // An isotropic rotor sampled at 3 azimuths (tests/support/isotropic_rotor_lin.h), its modes
  // at up to 600 × 1P as a BeamDyn blade's at 10 rpm: constant in multi-blade coordinates, so
  // Magnus steps are exact there and a few reach the tolerance, where Bulirsch–Stoer resolves
  // every oscillation. Exact exponents: eig(A_MBC) modulo jΩ.
  const double omega = 4.0 / 600;
  const auto model = test::MakeIsotropicRotorLin(4, 2, test::EvenAzimuths(3), omega);
  const std::string dir = test::WriteLinDirectory(model.files, ::testing::TempDir() + "fast-iso");
  const PeriodicSystem mbc = LoadSceneInput({dir}, {}).system;
  const SystemTraits traits = MeasureSystemTraits(mbc);
  EXPECT_GT(traits.oscillation, 200);
  EXPECT_LT(traits.variation, 1e-10 * traits.oscillation);
  FloquetOptions o;
  const FloquetResult r = AnalyzeFloquet(mbc, o);
  ASSERT_TRUE(r.ok) << r.BriefReport();
  EXPECT_EQ(r.integrator, IntegratorType::kMagnus6);
  const double err = MatchedDistance(r.modes, model.exponents, omega);
  EXPECT_LT(err, 1e-10);
  EXPECT_GE(r.error_estimate.value(), err);
  o.integrator.type = IntegratorType::kBulirschStoer;
  const FloquetResult bs = AnalyzeFloquet(mbc, o);
  ASSERT_TRUE(bs.ok);
  EXPECT_LT(MatchedDistance(bs.modes, model.exponents, omega), bs.error_estimate.value());
  EXPECT_LT(10 * r.rhs_evals, bs.rhs_evals);  // work, not time: A(t) evaluations
  // The same samples in blade coordinates vary by a large share of the fast frequencies:
  // Magnus's error terms then grow with h·ρ(Ā), and an explicit method stays the choice —
  // Taylor series for the fitted series of one harmonic and 28 states.
  const PeriodicSystem blade = LoadSceneInput({dir}, {"mbc=0"}).system;
  const SystemTraits rotating = MeasureSystemTraits(blade);
  EXPECT_GT(rotating.variation, 0.01 * rotating.oscillation);
  EXPECT_EQ(rotating.states, 28);
  EXPECT_EQ(ChooseIntegrator(rotating, 1e-10).type, IntegratorType::kTaylor);
}

TEST(MethodChoice, APeriodicAWhosePeriodDividesTheSamplesIsNotConstant) {
  // Vinograd's system (exponents 2 and −13, closed form: A(t) = R(6t)·[[−1, −12], [0, −13]]·
  // R(6t)ᵀ + its rotation, period π/3) analysed over 2π: A repeats every π/6, so samples at
  // T/4, T/2, 3T/4 were equal and `auto` took it for constant — expm, 40 s, MARGINAL.
  PeriodicSystem::Functions f;
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const double c = std::cos(6 * t), s = std::sin(6 * t), s12 = std::sin(12 * t);
    out << -1 - 9 * c * c + 6 * s12, 12 * c * c + 4.5 * s12, -12 * s * s + 4.5 * s12,
        -1 - 9 * s * s - 6 * s12;
  };
  const PeriodicSystem vinograd = PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f);
  EXPECT_FALSE(MeasureSystemTraits(vinograd).constant_pieces);
  FloquetOptions o;
  const FloquetResult r = AnalyzeFloquet(vinograd, o);
  ASSERT_TRUE(r.ok) << r.BriefReport();
  EXPECT_NE(r.integrator, IntegratorType::kExpm);
  const double err = MatchedDistance(r.modes, {2.0, -13.0}, vinograd.omega());
  EXPECT_LE(err, r.error_estimate.value());
  EXPECT_EQ(r.verdict, StabilityVerdict::kUnstable);
  // A(t) of period π/2 over 2π, and one that is not finite in the middle of the period.
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out << 0, 1, -1 + 0.8 * std::cos(4 * t), -0.02;
  };
  EXPECT_FALSE(
      MeasureSystemTraits(PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f)).constant_pieces);
  f.A = [](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out << 0, 1, std::abs(t - kPi) < 1.5 ? std::nan("") : -1.0, 0;
  };
  EXPECT_FALSE(
      MeasureSystemTraits(PeriodicSystem::FromFunctions(2 * kPi, 2, 0, 0, f)).constant_pieces);
}

TEST(MethodChoice, HillAutoSolverOnStiffYamlFindsEveryExponent) {
  // Closed form: the period averages of the triangular diagonal, −800, 150, −3. The dense
  // selection misses +150 (study); the automatic choice goes structured and must not.
  const PeriodicSystem s = StiffYaml();
  HillOptions o;
  o.solver = HillSolver::kAuto;
  o.harmonics = 8;
  const HillResult h = AnalyzeHill(s, o);
  ASSERT_TRUE(h.ok);
  EXPECT_TRUE(HasCode(h.diagnostics, DiagnosticCode::kHillSolverChosen));
  EXPECT_EQ(h.solver, HillSolver::kStructured);
  const double err = MatchedDistance(h.modes, {-800.0, 150.0, -3.0}, s.omega());
  EXPECT_LT(err, 1e-6 * 800);
  EXPECT_GE(h.error_estimate.value(), err);
}

TEST(MethodChoice, DenseHillOnStiffYamlDoesNotUnderstateItsError) {
  // Where the dense selection does miss an exponent, the Liouville deficit (Σ Re λ against the
  // mean of tr A) must carry into the estimate, estimate ≥ true error (closed form); where the
  // check fails outright the result is not ok (its verdict is "failed", not a stability claim).
  const PeriodicSystem s = StiffYaml();
  for (int N : {4, 8, 16}) {
    HillOptions o;
    o.solver = HillSolver::kDense;
    o.harmonics = N;
    const HillResult h = AnalyzeHill(s, o);
    ASSERT_EQ(h.modes.size(), 3u) << "N = " << N;  // three exponents, one of them wrong
    // Either the estimate covers the miss (below) or the check failed and the result says so.
    if (!h.ok) {
      EXPECT_EQ(h.verdict, StabilityVerdict::kFailed) << "N = " << N;
    }
    EXPECT_NE(h.verdict, StabilityVerdict::kStable) << "N = " << N;  // the system is unstable
    const double err = MatchedDistance(h.modes, {-800.0, 150.0, -3.0}, s.omega());
    EXPECT_GT(err, 100) << "N = " << N;  // the miss this test is about
    EXPECT_GE(h.error_estimate.value(), err) << "N = " << N;
  }
}

TEST(MethodChoice, HillSolverRuleFollowsTheStudysCrossover) {
  // Crossovers measured in the study (dense vs structured CPU time at fixed N).
  SystemTraits mathieu;  // n = 2, H_A = 1: dense 1.4× faster at N = 8, structured 2× at N = 16
  mathieu.states = 2;
  EXPECT_EQ(ChooseHillSolver(mathieu, 8, 1).solver, HillSolver::kDense);
  EXPECT_EQ(ChooseHillSolver(mathieu, 16, 1).solver, HillSolver::kStructured);
  SystemTraits tower;  // n = 22, H_A = 10: dense 2× faster at N = 16, structured ahead by N = 32
  tower.states = 22;
  EXPECT_EQ(ChooseHillSolver(tower, 16, 10).solver, HillSolver::kDense);
  EXPECT_EQ(ChooseHillSolver(tower, 32, 10).solver, HillSolver::kStructured);
  SystemTraits meissner;  // n = 2, fitted H_A = 128: structured 1.4–2× faster from N = 32
  meissner.states = 2;
  EXPECT_EQ(ChooseHillSolver(meissner, 32, 128).solver, HillSolver::kStructured);
  tower.hill_stiffness = 800;  // far from the jΩp copies: structured whatever the size
  EXPECT_EQ(ChooseHillSolver(tower, 2, 10).solver, HillSolver::kStructured);
}

}  // namespace
}  // namespace ltp
