// Automatic method choice from the work–precision study (see method_choice.h). The thresholds
// are the study's crossovers; the reasons quote what it measured.
#include "ltp/floquet/method_choice.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ltp {
namespace {

constexpr int kTraitSamples = 16;
// T·max||A||_∞ above this: an explicit method spends most of its steps on stability (study:
// stiff.yaml, 5027, rkf78 needed 0.14 s for 1e-10 where Magnus needed 4 ms).
constexpr double kStiffnessLimit = 500;
// Small systems: one matrix product per RK stage is cheaper than an n×n expm per Magnus step.
constexpr int kSmallStates = 4;
// Hill: the structured solver's N-linear cost wins from N = max(n, 12) (study crossovers).
constexpr int kStructuredFromHarmonics = 12;

std::string Format(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// Is A(t) the same at three interior points of every piece between breakpoints?
bool ConstantBetweenBreakpoints(const PeriodicSystem& system) {
  if (system.form() == PeriodicSystem::Form::kPiecewiseConstant) return true;
  if (const FourierMatrix* fa = system.fourier_A()) return fa->max_harmonic() == 0;
  std::vector<double> edges = {0.0};
  for (double b : system.breakpoints())
    if (b > 0 && b < system.period()) edges.push_back(b);
  edges.push_back(system.period());
  const int n = system.states();
  Eigen::MatrixXd first(n, n), other(n, n);
  for (size_t p = 0; p + 1 < edges.size(); ++p) {
    const double a = edges[p], b = edges[p + 1];
    system.EvalA(a + 0.25 * (b - a), first);
    const double scale = std::max(1.0, first.lpNorm<Eigen::Infinity>());
    for (double f : {0.5, 0.75}) {
      system.EvalA(a + f * (b - a), other);
      if ((other - first).lpNorm<Eigen::Infinity>() > 1e-15 * scale) return false;
    }
  }
  return true;
}

}  // namespace

SystemTraits MeasureSystemTraits(const PeriodicSystem& system) {
  SystemTraits t;
  t.states = system.states();
  const double T = system.period();
  for (double b : system.breakpoints())
    if (b > 0 && b < T) t.has_jumps = true;
  if (t.states == 0) return t;
  t.constant_pieces = ConstantBetweenBreakpoints(system);
  Eigen::MatrixXd a(t.states, t.states), mean = Eigen::MatrixXd::Zero(t.states, t.states);
  double norm = 0;
  for (int s = 0; s < kTraitSamples; ++s) {
    system.EvalA((s + 0.5) * T / kTraitSamples, a);
    norm = std::max(norm, a.lpNorm<Eigen::Infinity>());
    mean += a / kTraitSamples;
  }
  t.stiffness = T * norm;
  Eigen::MatrixXcd a0 = mean.cast<std::complex<double>>();
  if (const FourierMatrix* fa = system.fourier_A()) a0 = (*fa)[0];
  const Eigen::VectorXcd eig = a0.eigenvalues();
  double re = 0;
  for (Eigen::Index i = 0; i < eig.size(); ++i) re = std::max(re, std::abs(eig(i).real()));
  t.hill_stiffness = re / system.omega();
  return t;
}

IntegratorChoice ChooseIntegrator(const SystemTraits& t, double rel_tol) {
  (void)rel_tol;  // the study's winners did not change with the tolerance (1e-6 … 1e-10)
  IntegratorChoice c;
  if (t.constant_pieces) {
    c.type = IntegratorType::kExpm;
    c.reason = "A(t) is constant between its breakpoints, so a product of matrix exponentials is "
               "exact (study: Meissner at round-off with any step count)";
  } else if (t.stiffness > kStiffnessLimit) {
    c.type = IntegratorType::kMagnus6;
    c.reason = "stiff: T·max‖A(t)‖ = " + Format(t.stiffness) +
               " > 500, so explicit steps are bound by stability; Magnus has no such limit "
               "(study: stiff.yaml, rkf78 35× slower at 1e-10)";
  } else if (t.states > kSmallStates) {
    c.type = IntegratorType::kMagnus6;
    c.reason = "n = " + std::to_string(t.states) +
               " > 4: one n×n exponential per Magnus-6 step beats 13 matrix products per "
               "Runge–Kutta step (study: cheapest on rotor, n = 8, and tower-rotor, n = 22)";
  } else {
    c.type = IntegratorType::kBulirschStoer;
    c.reason = "small smooth system (n = " + std::to_string(t.states) +
               "): Bulirsch–Stoer extrapolation was the cheapest at every accuracy on Mathieu "
               "(study: 1.3–1.5× faster than rkf78, the runner-up)";
  }
  return c;
}

IntegratorChoice ChooseIntegrator(const PeriodicSystem& system, double rel_tol) {
  return ChooseIntegrator(MeasureSystemTraits(system), rel_tol);
}

IntegratorOptions ResolveIntegrator(const PeriodicSystem& system, IntegratorOptions options,
                                    std::string* reason) {
  if (reason) reason->clear();
  if (options.type != IntegratorType::kAuto) return options;
  const IntegratorChoice c = ChooseIntegrator(system, options.rel_tol);
  options.type = c.type;
  if (reason) *reason = c.reason;
  return options;
}

HillSolverChoice ChooseHillSolver(const SystemTraits& t, int harmonics) {
  HillSolverChoice c;
  if (t.hill_stiffness > 10) {
    c.solver = HillSolver::kStructured;
    c.reason = "exponents far from their jΩp copies (max|Re eig A_0| = " + Format(t.hill_stiffness) +
               " Ωp > 10 Ωp): shift-invert around A_0's eigenvalues (study: the dense selection "
               "missed stiff.yaml's +150 exponent at every N)";
  } else if (harmonics >= std::max(t.states, kStructuredFromHarmonics)) {
    c.solver = HillSolver::kStructured;
    c.reason = "N = " + std::to_string(harmonics) + " >= max(n, 12): the banded shift-invert solver "
               "costs ~N, dense ~N³ (study: 1.2–7× faster from N = 12 on Mathieu and rotor)";
  } else {
    c.solver = HillSolver::kDense;
    c.reason = "N = " + std::to_string(harmonics) + " < max(n = " + std::to_string(t.states) +
               ", 12): one dense eigensolve beats n shift-invert runs (study: Mathieu below N = 12, "
               "tower-rotor, n = 22, dense 2–4× faster up to N = 16)";
  }
  return c;
}

}  // namespace ltp
