#pragma once
// Automatic integrator choice (`--integrator auto`): the rules the work–precision study found
// (docs/benchmarks.md, "Work–precision study"; scripts/work-precision), applied to traits of
// the system that cost a few evaluations of A(t) to measure. Every choice carries the reason,
// which the analyses put in their diagnostics.
#include <string>

#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"

namespace ltp {

/// What the choice looked at.
struct SystemTraits {
  int states = 0;
  /// A(t) is constant between its breakpoints (piecewise-constant form, or sampled at five
  /// interior points of every piece, at no simple fractions of it, and found equal and finite):
  /// products of matrix exponentials are exact.
  bool constant_pieces = false;
  bool has_jumps = false;  ///< breakpoints inside the period
  /// T · max_t max|Re eig A(t)| over 4 samples: how many e-folds of decay (or growth) an
  /// explicit method has to follow per period with steps bound by stability, not accuracy.
  double stiffness = 0;
  /// max |Re eig(A_0)| / Ωp of the averaged system (Hill: exponents far from their jΩp copies).
  double hill_stiffness = 0;
  /// A(t) is a Fourier series (its derivatives are exact: Taylor series steps are possible).
  bool fourier_form = false;
  /// Its highest harmonic H (Fourier form only).
  int harmonics = 0;
  /// Products of n × n matrices per order of a Taylor-series step (Fourier form only): 1 + 2H;
  /// (1 + 2H)/2 for a second-order system; (1 + H)/2 with constant damping.
  double series_products_per_order = 0;
  /// T · ρ(Ā), Ā the period mean of A(t): about 2π × the fast oscillations (or e-folds) per
  /// period that an explicit method must resolve step by step.
  double oscillation = 0;
  /// T · max_t ‖A(t) − Ā‖ in diagonally balanced coordinates (Frobenius; for a Fourier series
  /// the bound Σ_{w≠0} ‖A_w‖): how far the periodic part alone moves the solution per period.
  /// Magnus steps are exact for Ā, so only this part sets their number.
  double variation = 0;
  /// T · (max Re λ − min Re λ) over the eigenvalues λ of Ā: Magnus–Filon keeps h times this
  /// spread below 2, so it sets its fewest steps.
  double decay_spread = 0;
  /// Ā has an eigenbasis of condition ≤ 1e7 (measured only for a Fourier series whose other
  /// traits make Magnus–Filon worth weighing): the interaction picture applies.
  bool mean_eigenbasis = false;
};
SystemTraits MeasureSystemTraits(const PeriodicSystem& system);

/// Taylor series steps are the cheapest integrator: A(t) a Fourier series of at most 8
/// harmonics, and at most 2 or at least 8 states. Study (whole analyses at 1e-10, random
/// first- and second-order Fourier systems, docs/taylor-integrator.md): Taylor / Bulirsch–Stoer
/// time 0.27–0.62 from n = 8 on at H = 1…8; 0.8–1.2 at n = 4 (no gain there); Mathieu (n = 2)
/// 1.35–1.9× cheaper at every tolerance.
bool TaylorSeriesPay(const SystemTraits& traits);

/// Magnus 6 steps over the mean pay: fast oscillation (T·ρ(Ā) > 200) around a mean that A(t)
/// leaves by less than the tolerance (variation ≤ rel_tol · oscillation), so steps exact for Ā
/// reach the tolerance in a few where an explicit method resolves every oscillation.
bool MagnusOverTheMeanPays(const SystemTraits& traits, double rel_tol);

/// Magnus–Filon steps pay: fast oscillation (T·ρ(Ā) > 200) around a periodic part whose own
/// steps, about 100 · variation · (1e-10/rel_tol)^{1/4} per period (and T·spread/2), stay below
/// T·ρ(Ā)/4 — an explicit method spends about 100 evaluations per radian of the fastest mode,
/// a Magnus–Filon step about 20 products (docs/magnus-filon.md) — and Ā has an eigenbasis.
bool MagnusFilonPays(const SystemTraits& traits, double rel_tol);
/// The Magnus–Filon steps per period that rule expects (typical, within a few times).
double MagnusFilonSteps(const SystemTraits& traits, double rel_tol);
/// Real n×n products of arithmetic in one Magnus–Filon step (its exponential and one product).
inline constexpr double kMagnusFilonProductsPerStep = 20;

struct IntegratorChoice {
  IntegratorType type = IntegratorType::kRkf78;
  std::string reason;  ///< one sentence: the trait and the study result behind the choice
};

/// The integrator the study found cheapest for systems like this one at this tolerance:
/// constant pieces → expm (exact); stiff (T·max|Re eig A| > 500) → magnus6 (no stability
/// limit); fast modes over a small periodic part → magnus6 (MagnusOverTheMeanPays) or
/// magnus-filon (MagnusFilonPays); a Fourier series of ≤ 2 states → taylor (TaylorSeriesPay);
/// else Bulirsch–Stoer.
IntegratorChoice ChooseIntegrator(const PeriodicSystem& system, double rel_tol);
IntegratorChoice ChooseIntegrator(const SystemTraits& traits, double rel_tol);

/// `options` with IntegratorType::kAuto replaced by the choice (unchanged otherwise);
/// `reason` (if given) receives the choice's reason, or stays empty. Throws InputError for
/// kTaylor on a system whose A(t) is not a Fourier series.
/// `measured`: the system's traits when the caller has them (else measured here, for kAuto).
IntegratorOptions ResolveIntegrator(const PeriodicSystem& system, IntegratorOptions options,
                                    std::string* reason = nullptr,
                                    const SystemTraits* measured = nullptr);

}  // namespace ltp
