// Floquet analysis of the rotor scenes against independent references: multi-blade
// coordinates (a constant-coefficient route), the closed-form lag exponent of an isolated
// blade, energy conservation, the 1/N-revolution monodromy, the flapping instability, and the
// sampled scene files against the built-in Mathieu oscillator.
#include "ltp/studies/rotor_floquet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/floquet/floquet.h"
#include "ltp/models/rotor.h"
#include "ltp/models/rotor_mbc.h"
#include "ltp/models/scene.h"
#include "support/compare.h"

namespace ltp {
namespace {

using cd = std::complex<double>;

FloquetOptions Tight() {
  FloquetOptions o;
  o.integrator.rel_tol = 1e-12;
  return o;
}

// Scene defaults with an anisotropic support in mass, damping and stiffness, and a lag spring.
RotorParameters Anisotropic(int blades, double omega) {
  RotorParameters r;
  r.blades = blades;
  r.omega = omega;
  r.stiffness_y = 3.5;
  r.lag_stiffness = 0.05;
  return r;
}

std::vector<cd> Exponents(const FloquetResult& r) {
  std::vector<cd> e;
  for (const FloquetMode& m : r.modes) e.push_back(m.exponent);
  return e;
}

double MaxReal(const std::vector<cd>& values) {
  double m = -1e300;
  for (const cd& v : values) m = std::max(m, v.real());
  return m;
}

// Exponents compared as sets modulo j·modulus (to `tol` in 1/s): map λ to log ρ = λ·2π/modulus,
// whose argument the comparison wraps.
void ExpectExponentsEqualModulo(const std::vector<cd>& actual, const std::vector<cd>& expected,
                                double modulus, double tol) {
  const double scale = 2 * std::numbers::pi / modulus;
  std::vector<cd> a, e;
  for (const cd& x : actual) a.push_back(x * scale);
  for (const cd& x : expected) e.push_back(x * scale);
  test::ExpectLogEigenvaluesNear(a, e, tol * scale);
}

// Number of exponents equal to `target` modulo j·modulus within tol.
int CountModulo(const std::vector<cd>& values, cd target, double modulus, double tol) {
  int n = 0;
  for (const cd& v : values) n += ExponentDistance(v, target, modulus) <= tol ? 1 : 0;
  return n;
}

TEST(RotorFloquet, UndampedRotorConservesEnergy) {
  // No lag or support damping: a Hamiltonian (gyroscopic) periodic system, so a stable rotor
  // has all its exponents on the imaginary axis. Ω = 0.4 and 2.2 are outside the undamped
  // ground-resonance (coalescence) region of these parameters.
  for (int blades : {2, 3, 4}) {
    for (double omega : {0.4, 2.2}) {
      RotorParameters r = Anisotropic(blades, omega);
      r.lag_damping = r.damping_x = r.damping_y = 0;
      const FloquetResult f = AnalyzeFloquet(BuildRotorSystem(r), Tight());
      ASSERT_TRUE(f.ok) << f.BriefReport();
      for (const FloquetMode& m : f.modes)
        EXPECT_LT(std::abs(m.exponent.real()), 1e-10)
            << "N = " << blades << ", Omega = " << omega << ": " << m.exponent;
      EXPECT_LT(std::abs(f.liouville_residual.value()), 1e-10);
    }
  }
}

TEST(RotorFloquet, ExponentsEqualMbcEigenvaluesModuloOmega) {
  // p(t) = T(t) q(t) with T 2π/Ω-periodic, so an MBC eigenvalue s is a Floquet exponent mod jΩ.
  for (int blades : {3, 4}) {
    for (double omega : {0.9, 1.4}) {
      const RotorParameters r = Anisotropic(blades, omega);
      const FloquetResult f = AnalyzeFloquet(BuildRotorSystem(r), Tight());
      ASSERT_TRUE(f.ok) << f.BriefReport();
      const MbcRotorSystem mbc = RotorInMultiBladeCoordinates(r);
      SCOPED_TRACE("N = " + std::to_string(blades) + ", Omega = " + std::to_string(omega));
      ExpectExponentsEqualModulo(Exponents(f), mbc.eigenvalues, omega, 1e-9);
      EXPECT_NEAR(f.max_real_exponent, MaxReal(mbc.eigenvalues), 1e-9);
    }
  }
}

TEST(RotorFloquet, SectorIntegrationEqualsFullRevolution) {
  // Φ(T, 0) = (P Φ(T/N, 0))^N (rotor.h) against the full-revolution integration.
  for (int blades : {2, 3, 4}) {
    const RotorParameters r = Anisotropic(blades, 1.1);
    const FloquetResult full = AnalyzeFloquet(BuildRotorSystem(r), Tight());
    const SectorFloquetResult sector = RotorSectorFloquet(r, Tight().integrator);
    ASSERT_TRUE(full.ok && sector.ok) << sector.message;
    SCOPED_TRACE("N = " + std::to_string(blades));
    EXPECT_LT(sector.symmetry_defect, 1e-12);
    EXPECT_DOUBLE_EQ(sector.sector_time, full.period / blades);
    EXPECT_TRUE(test::CompareMatrices(sector.monodromy, full.monodromy, 1e-9));
    std::vector<cd> full_logs;
    for (const FloquetMode& m : full.modes) full_logs.push_back(m.log_multiplier);
    test::ExpectLogEigenvaluesNear(sector.log_multipliers, full_logs, 1e-9);
    ExpectExponentsEqualModulo(sector.exponents, Exponents(full), r.omega, 1e-9);
    EXPECT_NEAR(sector.max_real_exponent, full.max_real_exponent, 1e-9);
  }
}

TEST(RotorFloquet, SectorExponentsAreMbcEigenvaluesModuloNOmega) {
  // For odd N, P T(τ) = T(0) for the MBC transform, so the sector map G has eigenvalues
  // e^{sτ}: the sector exponents equal the MBC eigenvalues modulo jNΩ (finer than jΩ). (For
  // even N the differential coordinate changes sign over τ: μ = −e^{sτ}, a shift by jNΩ/2.)
  for (int blades : {3, 5}) {
    const RotorParameters r = Anisotropic(blades, 0.9);
    const SectorFloquetResult sector = RotorSectorFloquet(r, Tight().integrator);
    ASSERT_TRUE(sector.ok);
    ExpectExponentsEqualModulo(sector.exponents, RotorInMultiBladeCoordinates(r).eigenvalues,
                               blades * r.omega, 1e-9);
  }
}

TEST(RotorFloquet, SectorIntegrationNeedsIdenticalBlades) {
  RotorParameters r = Anisotropic(3, 1.0);
  r.mistune_k = 1.2;
  EXPECT_THROW(RotorSectorFloquet(r), InputError);
  // A relabelling that is not the rotor's symmetry is refused, not silently used.
  const RotorParameters tuned = Anisotropic(3, 1.0);
  const Eigen::MatrixXd backwards = RotorBladeShift(3).transpose();
  EXPECT_THROW(CyclicFloquet(BuildRotorSystem(tuned), 3, backwards), InputError);
}

TEST(RotorFloquet, CollectiveLagModeHasTheClosedForm) {
  // The collective ζ_0 never moves the hub (Σ sin ψ_i = Σ cos ψ_i = 0 for N >= 2), so
  // λ = −C/2I ± j√(K'/I − (C/2I)²), K' = K_ζ + e S_b Ω², is an exact exponent (mod jΩ) for any
  // support — including N = 2 on an anisotropic support, where MBC does not apply. For N = 4
  // the differential is isolated too (multiplicity 2).
  for (int blades : {2, 3, 4}) {
    const RotorParameters r = Anisotropic(blades, 1.2);
    const FloquetResult f = AnalyzeFloquet(BuildRotorSystem(r), Tight());
    ASSERT_TRUE(f.ok);
    const cd lambda = IsolatedBladeLagExponent(r);
    const int expected = blades == 4 ? 2 : 1;
    EXPECT_EQ(CountModulo(Exponents(f), lambda, r.omega, 1e-9), expected) << "N = " << blades;
    EXPECT_EQ(CountModulo(Exponents(f), std::conj(lambda), r.omega, 1e-9), expected)
        << "N = " << blades;
  }
}

TEST(RotorFloquet, StiffSupportGivesEveryBladeItsOwnLagExponent) {
  // On a (nearly) rigid support the blades decouple: blade 1, with K_ζ and C_ζ scaled by
  // mistune_k = 2 and mistune_c = 0.5, has its own closed-form exponent, the other blades the
  // tuned one. The hub coupling shifts them by O(S_b² Ω²/(I_b k)): measured 2.1e-4 at
  // k = 1e3 and 2.1e-5 at k = 1e4 (this code).
  RotorParameters r = Anisotropic(4, 1.0);
  r.stiffness_x = r.stiffness_y = 1e3;
  r.mistune_k = 2;
  r.mistune_c = 0.5;
  const FloquetResult f = AnalyzeFloquet(BuildRotorSystem(r), Tight());
  ASSERT_TRUE(f.ok);
  RotorParameters blade1 = r;
  blade1.lag_stiffness *= 2;
  blade1.lag_damping *= 0.5;
  EXPECT_GE(CountModulo(Exponents(f), IsolatedBladeLagExponent(blade1), r.omega, 5e-4), 1);
  EXPECT_GE(CountModulo(Exponents(f), IsolatedBladeLagExponent(r), r.omega, 5e-4), 1);
  EXPECT_NE(IsolatedBladeLagExponent(blade1), IsolatedBladeLagExponent(r));
}

TEST(RotorFloquet, TwoBladesOnAnAnisotropicSupport) {
  const Scene& scene = LoadScene("rotor");
  const std::vector<std::pair<std::string, std::string>> set = {{"blades", "2"}, {"Omega", "0.9"}};
  const FloquetResult f = AnalyzeFloquet(scene.Build(set), Tight());
  ASSERT_TRUE(f.ok) << f.BriefReport();
  EXPECT_EQ(f.states, 8);
  EXPECT_TRUE(std::isfinite(f.max_real_exponent));
  EXPECT_THROW(RotorInMultiBladeCoordinates(RotorParametersFrom(scene.Resolve(set))), InputError);
}

// max Re of the MBC eigenvalues at rotor speed Ω.
double MbcMaxReal(RotorParameters r, double omega) {
  r.omega = omega;
  return MaxReal(RotorInMultiBladeCoordinates(r).eigenvalues);
}

// Root of f in [lo, hi] (f(lo), f(hi) of opposite signs), to `tol`.
double Bisect(const std::function<double(double)>& f, double lo, double hi, double tol) {
  const bool lo_negative = f(lo) < 0;
  EXPECT_NE(lo_negative, f(hi) < 0) << "no sign change in [" << lo << ", " << hi << "]";
  while (hi - lo > tol) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) < 0) == lo_negative ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(RotorFloquet, GroundResonanceBandsAroundTheColemanCoincidences) {
  // Light damping (C_ζ = 0.05, c_x = 0.3, c_y = 0.15; otherwise the scene defaults, N = 4).
  // Ground resonance: the regressive lag mode, at Ω(1 − ν_ζ) in the fixed frame
  // (ν_ζ = √(e S_b/I_b) per rev here, K_ζ = 0), meets a support mode ω_x = √(k_x/M_x) or
  // ω_y = √(k_y/M_y) (Coleman & Feingold 1958). Bands measured here by bisection on the MBC
  // eigenvalues (no literature value for this parameter set): Ω ≈ 0.7219–0.9740 and
  // 1.0959–1.7259 rad/s; each contains its coincidence speed ω/(1 − ν_ζ) = 0.869, 1.365.
  RotorParameters r;
  r.lag_damping = 0.05;
  r.damping_x = 0.3;
  r.damping_y = 0.15;
  const double nu = std::sqrt(r.hinge_offset * r.first_moment / r.inertia);
  const double coincidence_x = std::sqrt(r.stiffness_x / r.mass_x) / (1 - nu);
  const double coincidence_y = std::sqrt(r.stiffness_y / r.mass_y) / (1 - nu);
  auto growth = [&](double omega) { return MbcMaxReal(r, omega); };
  const double edges[4] = {Bisect(growth, 0.70, 0.75, 1e-6), Bisect(growth, 0.95, 1.00, 1e-6),
                           Bisect(growth, 1.05, 1.15, 1e-6), Bisect(growth, 1.70, 1.75, 1e-6)};
  EXPECT_NEAR(edges[0], 0.7219, 2e-3);
  EXPECT_NEAR(edges[1], 0.9740, 2e-3);
  EXPECT_NEAR(edges[2], 1.0959, 2e-3);
  EXPECT_NEAR(edges[3], 1.7259, 2e-3);
  EXPECT_LT(edges[0], coincidence_x);
  EXPECT_GT(edges[1], coincidence_x);
  EXPECT_LT(edges[2], coincidence_y);
  EXPECT_GT(edges[3], coincidence_y);
  // The Floquet route sees the same: unstable inside the bands, stable between and above.
  for (double omega : {0.85, 1.03, 1.4, 2.0}) {
    r.omega = omega;
    const FloquetResult f = AnalyzeFloquet(BuildRotorSystem(r), Tight());
    EXPECT_NEAR(f.max_real_exponent, MbcMaxReal(r, omega), 1e-9) << "Omega = " << omega;
    EXPECT_EQ(f.stable, omega == 1.03 || omega == 2.0) << "Omega = " << omega;
  }
}

TEST(RotorFloquet, OneInoperativeDamperOpensABandOnlyFloquetSees) {
  // Scene defaults (N = 4): the tuned rotor is stable at all speeds (MBC sweep 0.2–2.5 rad/s),
  // but with blade 1's damper inoperative (mistune_c = 0; the case Hammond (1974) used Floquet
  // theory for) an unstable band opens around the y coincidence. Measured here: lower edge
  // Ω ≈ 1.1400 rad/s, max Re λ ≈ 0.0205 1/s at Ω = 1.4, upper edge near 1.76.
  RotorParameters r;
  r.mistune_c = 0;
  auto growth = [&](double omega) {
    RotorParameters s = r;
    s.omega = omega;
    FloquetOptions o = Tight();
    o.compute_modes = false;
    o.estimate_error = false;
    return AnalyzeFloquet(BuildRotorSystem(s), o).max_real_exponent;
  };
  const double lower = Bisect(growth, 1.10, 1.15, 1e-4);
  EXPECT_NEAR(lower, 1.1400, 1e-3);
  EXPECT_NEAR(growth(1.4), 0.0205, 5e-4);
  EXPECT_LT(growth(1.0), 0);
  RotorParameters tuned;
  for (double omega = 0.2; omega <= 2.5; omega += 0.05) EXPECT_LT(MbcMaxReal(tuned, omega), 0);
  EXPECT_THROW(RotorInMultiBladeCoordinates(r), InputError);
}

// --- flap ------------------------------------------------------------------------------------

FloquetResult Flap(double gamma, double mu, double nu = 1.0) {
  const Scene& scene = LoadScene("flap");
  return AnalyzeFloquet(scene.Build({{"gamma", std::to_string(gamma)},
                                     {"mu", std::to_string(mu)},
                                     {"nu", std::to_string(nu)}}),
                        Tight());
}

TEST(FlapFloquet, InstabilityIsARealMultiplierCrossingPlusOne) {
  // det Φ = exp(−γπ/4) (Liouville: tr A = −γ/8 per unit ψ), so while the multipliers are a
  // complex pair both have Re λ = −γ/16 exactly; instability needs a real multiplier leaving
  // the unit circle. For γ = 12, ν = 1 (this model: uniform inflow, no reverse flow) the
  // crossing is at ρ = +1, μ* ≈ 1.4119 (measured here by bisection). Peters & Hohenemser
  // (1971) discuss the same flapping instability at high advance ratio, with reverse flow
  // included; their boundary is not reproduced here.
  const double gamma = 12;
  const FloquetResult low = Flap(gamma, 0.1);
  for (const FloquetMode& m : low.modes) EXPECT_NEAR(m.exponent.real(), -gamma / 16, 1e-10);
  const double mu_star =
      Bisect([&](double mu) { return Flap(gamma, mu).max_real_exponent; }, 1.40, 1.45, 1e-7);
  EXPECT_NEAR(mu_star, 1.4119, 2e-3);
  const FloquetResult at = Flap(gamma, mu_star);
  const Eigen::VectorXcd rho = at.monodromy.eigenvalues();
  const Eigen::Index k = rho.cwiseAbs().maxCoeff() == std::abs(rho(0)) ? 0 : 1;
  EXPECT_NEAR(rho(k).real(), 1.0, 1e-5);
  EXPECT_EQ(rho(k).imag(), 0.0);
  EXPECT_FALSE(Flap(gamma, mu_star + 0.01).stable);
  EXPECT_TRUE(Flap(gamma, mu_star - 0.01).stable);
}

std::string ScenesDir() {
  if (const char* dir = std::getenv("LTP_SOURCE_DIR")) return std::string(dir) + "/scenes";
  return (std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "scenes")
      .string();
}

TEST(FlapFloquet, ShippedFileEqualsBuiltin) {
  const std::vector<std::pair<std::string, std::string>> set = {{"gamma", "12"}, {"mu", "1.2"}};
  const FloquetResult file =
      AnalyzeFloquet(LoadScene(ScenesDir() + "/flap.yaml").Build(set), Tight());
  const FloquetResult builtin = AnalyzeFloquet(LoadScene("flap").Build(set), Tight());
  ASSERT_TRUE(file.ok && builtin.ok);
  test::ExpectLogEigenvaluesNear(Exponents(file), Exponents(builtin), 1e-9);
}

// --- sampled scene files -----------------------------------------------------------------------

TEST(SampledFloquet, FourierInterpolationOfMathieuSamplesIsExact) {
  // A(t) of the Mathieu oscillator has harmonic 1 (of Ωp = 2) only, so the DFT of 8 samples
  // recovers it exactly: same exponents as the built-in `mathieu`.
  const std::string path = ScenesDir() + "/sampled-mathieu.yaml";
  for (const char* q : {"0.2", "0.6"}) {
    const FloquetResult sampled = AnalyzeFloquet(LoadScene(path).Build({{"q", q}}), Tight());
    const FloquetResult exact = AnalyzeFloquet(LoadScene("mathieu").Build({{"q", q}}), Tight());
    ASSERT_TRUE(sampled.ok && exact.ok);
    test::ExpectLogEigenvaluesNear(Exponents(sampled), Exponents(exact), 1e-10);
  }
}

}  // namespace
}  // namespace ltp
