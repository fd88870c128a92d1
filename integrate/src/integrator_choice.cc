// Automatic integrator choice from the work–precision study (see integrator_choice.h). The
// thresholds are the study's crossovers; the reasons quote what it measured.
#include "ltp/integrate/integrator_choice.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

#include "integrator_internal.h"
#include "ltp/core/error.h"
#include "ltp/integrate/detail/modal_basis.h"
#include "ltp/integrate/detail/state_balancing.h"

namespace ltp {
namespace {

// Samples of A(t) for the traits: stiff systems are stiff over most of the period, so a few
// suffice, and each costs an evaluation plus an n×n eig (on the rotor scene 16 samples cost as
// much as the whole Bulirsch–Stoer analysis they chose).
constexpr int kTraitSamples = 4;
// T·max|Re eig A(t)| above this: the fast decay (or growth) bounds an explicit method's steps
// while Magnus follows it exactly (study: stiff.yaml 5027 and stiff-coupled, Magnus 6 the
// cheapest integrator at every accuracy). Fast *oscillation* (tower-rotor's undamped modes at
// 4777 rad/s) is not counted: there Bulirsch–Stoer was faster in the full analysis.
constexpr double kStiffnessLimit = 500;
// Where Taylor series steps beat Bulirsch–Stoer (TaylorSeriesPay): up to 2 states, and from 8 on
// for series of at most 8 harmonics (measured to H = 8; between 3 and 7 states the two cost the
// same within ±20 %).
constexpr int kTaylorSmallStates = 2;
constexpr int kTaylorLargeStates = 8;
constexpr int kTaylorMaxHarmonics = 8;

// Fast oscillation around a mean that A(t) leaves by less than the tolerance: Magnus 6 steps are
// exact for the mean Ā, so a few reach the tolerance where an explicit method resolves every
// oscillation (an OpenFAST model of a nearly isotropic rotor in multi-blade coordinates, modes at
// 600 × 1P, 64–124 states: 20–30× cheaper than Bulirsch–Stoer). Not for a larger periodic part:
// Magnus's error terms then carry powers of h·ρ(Ā) (order reduction), and on the same model's
// blade-coordinate twin (periodic part 0.2 % of ρ) it took 3.4× Bulirsch–Stoer's time (5.7 s, 1.7
// s) (docs/model-sizes.md).
constexpr double kFastOscillation = 200;
// MeasureSystemTraits weighs Magnus–Filon at the loosest tolerance anyone asks for, so that the
// eigenbasis is known whenever a choice at a tighter one could want it.
constexpr double kLoosestFilonTolerance = 1e-3;

// Is A(t) the same at five interior points of every piece between breakpoints? The points sit
// at fractions k·φ mod 1 of the piece (φ the golden ratio): no two differ by a simple fraction,
// so an A(t) that repeats every T/4 or T/12 is not mistaken for a constant (it was, sampled at
// T/4, T/2, 3T/4: Vinograd's system over 2π became a product of exponentials, 40 s and a wrong
// verdict). A sample that is not finite makes the piece not constant.
bool ConstantBetweenBreakpoints(const PeriodicSystem& system) {
  if (system.form() == PeriodicSystem::Form::kPiecewiseConstant) return true;
  if (const FourierMatrix* fa = system.fourier_A()) return fa->max_harmonic() == 0;
  std::vector<double> edges = {0.0};
  for (double b : system.breakpoints())
    if (b > 0 && b < system.period()) edges.push_back(b);
  edges.push_back(system.period());
  const int n = system.states();
  constexpr double kGolden = 0.6180339887498949;
  Eigen::MatrixXd first(n, n), other(n, n);
  for (size_t p = 0; p + 1 < edges.size(); ++p) {
    const double a = edges[p], b = edges[p + 1];
    system.EvalA(a + kGolden * (b - a), first);
    if (!first.allFinite()) return false;
    const double scale = std::max(1.0, first.lpNorm<Eigen::Infinity>());
    for (int k = 2; k <= 5; ++k) {
      const double f = k * kGolden - std::floor(k * kGolden);
      system.EvalA(a + f * (b - a), other);
      if (!other.allFinite() || !((other - first).lpNorm<Eigen::Infinity>() <= 1e-15 * scale))
        return false;
    }
  }
  return true;
}

// The traits part of MagnusFilonPays: all but the eigenbasis.
bool FilonStepsPay(const SystemTraits& traits, double rel_tol) {
  return traits.fourier_form && traits.oscillation > kFastOscillation &&
         MagnusFilonSteps(traits, rel_tol) < traits.oscillation / 4;
}

}  // namespace

SystemTraits MeasureSystemTraits(const PeriodicSystem& system) {
  SystemTraits t;
  t.states = system.states();
  if (const auto shape = internal::ShapeOfSeries(system)) {
    t.fourier_form = true;
    t.harmonics = shape->harmonics;
    t.series_products_per_order = shape->ProductsPerOrder();
  }
  const double T = system.period();
  for (double b : system.breakpoints())
    if (b > 0 && b < T) t.has_jumps = true;
  if (t.states == 0) return t;
  t.constant_pieces = ConstantBetweenBreakpoints(system);
  Eigen::MatrixXd a(t.states, t.states), mean = Eigen::MatrixXd::Zero(t.states, t.states);
  double rate = 0;
  const int samples = kTraitSamples;
  std::vector<Eigen::MatrixXd> sampled;  // kept for the periodic part below
  for (int s = 0; s < samples; ++s) {
    system.EvalA((s + 0.5) * T / samples, a);
    sampled.push_back(a);
    mean += a / samples;
    // Eigen's eigensolvers read past their arrays on NaN input (AddressSanitizer): a sample
    // that is not finite says nothing of the rates anyway.
    if (!a.allFinite()) continue;
    if (const std::optional<Eigen::VectorXcd> eig = internal::RealEigenvalues(a))
      for (Eigen::Index i = 0; i < eig->size(); ++i)
        rate = std::max(rate, std::abs((*eig)(i).real()));
  }
  t.stiffness = T * rate;
  Eigen::MatrixXcd a0 = mean.cast<std::complex<double>>();
  if (const FourierMatrix* fa = system.fourier_A()) a0 = (*fa)[0];
  const Eigen::VectorXcd eig =
      !a0.allFinite()       ? Eigen::VectorXcd::Zero(0)
      : a0.imag().isZero(0) ? internal::RealEigenvalues(a0.real()).value_or(Eigen::VectorXcd())
                            : Eigen::VectorXcd(a0.eigenvalues());
  double re = 0, radius = 0;
  for (Eigen::Index i = 0; i < eig.size(); ++i) {
    re = std::max(re, std::abs(eig(i).real()));
    radius = std::max(radius, std::abs(eig(i)));
  }
  t.hill_stiffness = re / system.omega();
  t.oscillation = T * radius;
  if (eig.size() > 0) t.decay_spread = T * (eig.real().maxCoeff() - eig.real().minCoeff());
  const Eigen::VectorXd scale = internal::BalancingScales(internal::MagnitudeOfA(system));
  if (const FourierMatrix* fa = system.fourier_A()) {
    double sum = 0;
    for (int w = -fa->max_harmonic(); w <= fa->max_harmonic(); ++w)
      if (w != 0) sum += internal::BalancedNorm((*fa)[w], scale);
    t.variation = T * sum;
  } else {
    for (const Eigen::MatrixXd& x : sampled)
      t.variation =
          std::max(t.variation, T * internal::BalancedNorm(Eigen::MatrixXd(x - mean), scale));
  }
  // The eigenbasis costs an eigen-decomposition with vectors: looked for only when it could
  // decide.
  t.mean_eigenbasis = FilonStepsPay(t, kLoosestFilonTolerance) &&
                      internal::MagnusFilonIntegrator(system).unsuitable().empty();
  return t;
}

IntegratorChoice ChooseIntegrator(const SystemTraits& t, double rel_tol) {
  IntegratorChoice c;
  if (t.constant_pieces) {
    c.type = IntegratorType::kExpm;
    c.reason =
        "A(t) is constant between its breakpoints, so a product of matrix exponentials is "
        "exact (study: Meissner at round-off with any step count)";
  } else if (t.stiffness > kStiffnessLimit) {
    c.type = IntegratorType::kMagnus6;
    c.reason = "stiff: T·max|Re eig A(t)| = " + MessageNumber(t.stiffness, 3) +
               " > 500, so explicit steps are bound by stability; Magnus 6 follows the fast "
               "decay exactly (study: the cheapest integrator on stiff.yaml and stiff-coupled)";
  } else if (MagnusOverTheMeanPays(t, rel_tol)) {
    c.type = IntegratorType::kMagnus6;
    c.reason = "fast oscillation (T·ρ(Ā) = " + MessageNumber(t.oscillation, 3) +
               ") around a mean A(t) leaves by less than the tolerance (T·max‖A(t) − Ā‖ = " +
               MessageNumber(t.variation, 3) +
               ", balanced): Magnus 6 steps are exact for the mean, so a few suffice where an "
               "explicit method resolves every oscillation (docs/model-sizes.md)";
  } else if (MagnusFilonPays(t, rel_tol)) {
    c.type = IntegratorType::kMagnusFilon;
    c.reason =
        "fast modes (T·ρ(Ā) = " + MessageNumber(t.oscillation, 3) +
        ") around a small periodic part (T·max‖A(t) − Ā‖ = " + MessageNumber(t.variation, 3) +
        ", balanced): Magnus–Filon steps follow the periodic part only, where an "
        "explicit method resolves every oscillation (docs/magnus-filon.md)";
  } else if (TaylorSeriesPay(t)) {
    c.type = IntegratorType::kTaylor;
    c.reason = "A(t) is a Fourier series of " + std::to_string(t.states) + " states and " +
               std::to_string(t.harmonics) + (t.harmonics == 1 ? " harmonic" : " harmonics") +
               ": Taylor series steps from its exact derivatives were the cheapest (study: "
               "1.35–1.9× cheaper than Bulirsch–Stoer on Mathieu, 1.6–3.7× from 8 states on)";
  } else {
    c.type = IntegratorType::kBulirschStoer;
    c.reason = "smooth, not stiff (T·max|Re eig A(t)| = " + MessageNumber(t.stiffness, 3) +
               "): Bulirsch–Stoer extrapolation was the cheapest adaptive integrator at tight "
               "tolerances on Mathieu, rotor and tower-rotor (study)";
  }
  return c;
}

bool TaylorSeriesPay(const SystemTraits& traits) {
  return traits.fourier_form && traits.harmonics <= kTaylorMaxHarmonics &&
         (traits.states <= kTaylorSmallStates || traits.states >= kTaylorLargeStates);
}

bool MagnusOverTheMeanPays(const SystemTraits& traits, double rel_tol) {
  return traits.oscillation > kFastOscillation && traits.variation <= rel_tol * traits.oscillation;
}

double MagnusFilonSteps(const SystemTraits& traits, double rel_tol) {
  return std::max(
      {8.0, 100 * traits.variation * std::pow(1e-10 / rel_tol, 0.25), traits.decay_spread / 2});
}

bool MagnusFilonPays(const SystemTraits& traits, double rel_tol) {
  return FilonStepsPay(traits, rel_tol) && traits.mean_eigenbasis;
}

IntegratorChoice ChooseIntegrator(const PeriodicSystem& system, double rel_tol) {
  return ChooseIntegrator(MeasureSystemTraits(system), rel_tol);
}

IntegratorOptions ResolveIntegrator(const PeriodicSystem& system, IntegratorOptions options,
                                    std::string* reason, const SystemTraits* measured) {
  if (reason) reason->clear();
  if (options.type == IntegratorType::kTaylor && system.RealSeriesA(nullptr) == nullptr)
    throw InputError(
        "integrator 'taylor' needs A(t) as a Fourier series (a Fourier-form scene or system); "
        "this system's A(t) is not one: use bs, rkf78 or auto");
  if (options.type == IntegratorType::kMagnusFilon && system.fourier_A() == nullptr)
    throw InputError(
        "integrator 'magnus-filon' needs A(t) as a Fourier series (a Fourier-form scene or "
        "system); this system's A(t) is not one: use bs, rkf78 or auto");
  if (options.type != IntegratorType::kAuto) return options;
  const IntegratorChoice c = measured ? ChooseIntegrator(*measured, options.rel_tol)
                                      : ChooseIntegrator(system, options.rel_tol);
  options.type = c.type;
  if (reason) *reason = c.reason;
  return options;
}

}  // namespace ltp
