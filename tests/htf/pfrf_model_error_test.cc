// The sampling error of a `.lin` model in a partial-FRF sweep's estimate
// (ltp/htf/pfrf_model_error.h). References: rotating-frame files generated from an isotropic
// rotor (tests/support/isotropic_rotor_lin.h) whose blade-coordinate A(ψ) holds harmonics 0 and
// ±1 only and whose inputs and outputs are constant there, so in multi-blade coordinates the
// model holds harmonics 0 and ±3 at most: nine or more azimuths determine it exactly.
#include "ltp/htf/pfrf_model_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ltp/models/scene_input.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"
#include "support/isotropic_rotor_lin.h"

namespace ltp {
namespace {

LoadedScene Load(int azimuths, double gravity, const std::string& name) {
  auto model = test::MakeIsotropicRotorLin(2, 2, test::EvenAzimuths(azimuths), 1.0, 5, gravity);
  test::AddBladeChannels(model);
  return LoadSceneInput({test::WriteLinDirectory(model.files, ::testing::TempDir() + name)});
}

PfrfOptions Sweep(int output) {
  PfrfOptions o;
  for (double f = 0.05; f < 0.7; f += 0.05) o.frequencies_hz.push_back(f);
  o.min_order = -1;
  o.max_order = 1;
  o.output = output;
  return o;
}

double Peak(const PfrfResult& r) {
  return *std::max_element(r.order_max.begin(), r.order_max.end());
}

TEST(PfrfModelError, EstimateCoversTheSamplingErrorOfAGravityRotor) {
  // With a 1P gravity term three azimuths fold the multi-blade model's ±3 harmonics onto a
  // constant: the default sweep's routes agree with one another on a model that is off. The
  // reference is the same rotor linearised at 9 azimuths (exact; 9 and 12 agree, checked here).
  const double gravity = 0.4;
  for (int output : {0, 1}) {
    const PfrfOptions o = Sweep(output);
    const PfrfResult ref = ComputePartialFrf(Load(9, gravity, "pfrf-grav9").system, o);
    const PfrfResult check = ComputePartialFrf(Load(12, gravity, "pfrf-grav12").system, o);
    ASSERT_TRUE(ref.ok && check.ok);
    const LoadedScene l3 = Load(3, gravity, "pfrf-grav3");
    ASSERT_EQ(l3.model_alternatives.size(), 2u);  // hold ↔ trig, MBC ↔ blade coordinates
    PfrfResult r = ComputePartialFrf(l3.system, o);
    ASSERT_TRUE(r.ok);
    const double routes_only_s = r.elapsed_s;
    const std::vector<std::vector<double>> routes_only = r.error_estimate;
    IncludeModelError(l3.model_alternatives, o, r);
    ASSERT_TRUE(r.model_error.has_value());
    EXPECT_GT(r.elapsed_s, routes_only_s);  // the whole call's time
    double worst_error = 0, worst_uncovered = 0;
    for (size_t i = 0; i < r.values.size(); ++i)
      for (size_t z = 0; z < r.values[i].size(); ++z) {
        const double reference_uncertainty =
            std::abs(ref.values[i][z] - check.values[i][z]) + ref.error_estimate[i][z];
        ASSERT_LT(reference_uncertainty, 1e-7 * Peak(ref));
        const double error = std::abs(r.values[i][z] - ref.values[i][z]);
        worst_error = std::max(worst_error, error);
        worst_uncovered = std::max(worst_uncovered, error - routes_only[i][z]);
        EXPECT_GE(r.error_estimate[i][z] + reference_uncertainty, error)
            << "output " << output << ", f = " << r.frequencies_hz[i] << " Hz, z = " << z - 1;
      }
    // The case is one the routes alone cannot see: their estimate falls far short.
    EXPECT_GT(worst_uncovered, 1e-3 * Peak(ref)) << "output " << output;
    EXPECT_GT(worst_error, 1e-3 * Peak(ref));
    // The exponents' verdict carries the term too.
    EXPECT_TRUE(r.floquet.model_error.has_value());
  }
}

TEST(PfrfModelError, OneAzimuthKeepsTheOtherModelsStatesAndComparesItsChannels) {
  // One azimuth: the blade-coordinate model is constant, and the comparison keeps its states
  // (its exponents A's eigenvalues, no periodic integration) and carries only its inputs and
  // outputs into multi-blade channels. Its transfer functions must be those of the same model
  // with the states carried over too (a Lyapunov transformation changes no input–output map):
  // the reference built here as the comparison did before.
  const std::string dir = [] {
    auto model = test::MakeIsotropicRotorLin(2, 2, test::EvenAzimuths(1), 1.0, 5, 0.4);
    test::AddBladeChannels(model);
    return test::WriteLinDirectory(model.files, ::testing::TempDir() + "pfrf-one");
  }();
  const LoadedScene l = LoadSceneInput({dir});
  ASSERT_EQ(l.model_alternatives.size(), 2u);
  const PeriodicSystem& kept = l.model_alternatives[1];
  ASSERT_NE(kept.fourier_A(), nullptr);
  EXPECT_EQ(kept.fourier_A()->max_harmonic(), 0);
  const LinOperatingPoint op = ReadLinOperatingPoint({dir});
  ParameterMap blade = l.parameters;
  blade.at("mbc") = 0;
  const PeriodicSystem carried = TransformedMultiBlade(l.scene.build(blade), op, Mbc3(op), true);
  ASSERT_GT(carried.fourier_A()->max_harmonic(), 0);  // the states carried over: periodic
  for (int output : {0, 1}) {
    const PfrfOptions o = Sweep(output);
    const PfrfResult a = ComputePartialFrf(kept, o), b = ComputePartialFrf(carried, o);
    ASSERT_TRUE(a.ok && b.ok);
    for (size_t i = 0; i < a.values.size(); ++i)
      for (size_t z = 0; z < a.values[i].size(); ++z)
        EXPECT_NEAR(std::abs(a.values[i][z] - b.values[i][z]), 0,
                    a.error_estimate[i][z] + b.error_estimate[i][z] + 1e-9 * Peak(b))
            << "output " << output << ", f = " << a.frequencies_hz[i] << " Hz, z = " << z - 1;
  }
}

TEST(PfrfModelError, ExactSamplesLeaveTheEstimateSmall) {
  // Without gravity the rotor is time-invariant in multi-blade coordinates: every model of its
  // three samples is exact there, and the held and blade-coordinate models agree with it up to
  // their own accuracy — the term must not swamp the sweep.
  const PfrfOptions o = Sweep(0);
  const LoadedScene l = Load(3, 0.0, "pfrf-exact3");
  PfrfResult r = ComputePartialFrf(l.system, o);
  IncludeModelError(l.model_alternatives, o, r);
  ASSERT_TRUE(r.model_error.has_value());
  EXPECT_LT(*r.model_error, 1e-6 * Peak(r));
}

TEST(PfrfModelError, NothingHappensForAnUnsampledSystem) {
  const PfrfOptions o = Sweep(0);
  const LoadedScene l = Load(3, 0.0, "pfrf-none");
  PfrfResult r = ComputePartialFrf(l.system, o);
  const auto before = r.error_estimate;
  IncludeModelError({}, o, r);
  EXPECT_FALSE(r.model_error.has_value());
  EXPECT_EQ(r.error_estimate, before);
}

}  // namespace
}  // namespace ltp
