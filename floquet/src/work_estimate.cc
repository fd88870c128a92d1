// The cost model of EstimateFloquetWork. Counts measured with `ltp floquet --json` (rhs_evals, the
// whole analysis: run, refined run, mode samples) at the default tolerance 1e-10 on
// x'' + 0.02 x' + w²(1 + 0.1 cos t) x = 0 over 2π (T·ρ = 2π w rad): w = 100 / 1000 gave
// Bulirsch–Stoer 162 / 100 evaluations per radian, rkf78 94 / 93, Magnus 6 129 / 127; the 120-state
// finite-element shaft 140 (docs/model-sizes.md).
#include "ltp/floquet/work_estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/integrate/detail/matrix_product.h"

namespace ltp {
namespace {

// Typical evaluations per radian of the fastest motion over the whole analysis at rel_tol 1e-10
// (see above), and how the count grows as the tolerance tightens: the same oscillator (w = 1000)
// took rkf78 15 / 28 / 93, Bulirsch–Stoer 35 / 53 / 100, Magnus 6 11 / 21 / 127 per radian at
// 1e-4 / 1e-6 / 1e-10, about (1/tol)^0.13.
constexpr double kTypicalPerRadian = 120;
constexpr double kTolerancePower = 0.13;
// Fewest per radian: a fifth of the typical count (at 1e-4: 4 against the 11 measured, at 1e-10:
// 24 against 93).
constexpr double kFewestFraction = 0.2;
// Start-up per segment (first steps, the step-size search) at 1e-10, scaled with the tolerance
// as the count per radian: the w = 100 runs' 128 segments.
constexpr double kPerSegment = 250;
// An adaptive integrator restarts at each breakpoint: 28–57 evaluations per piece at 1e-10
// (Mathieu cut at 10^3 / 10^4 breakpoints from a Python callable: 34 / 28; at 10^3 jumps of a
// scene's sign(sin(m t)): 57), scaled with the tolerance as the count per radian. A Python
// callable costs more per call inside the analysis than alone (its threads take turns with the
// GIL): 10^5 breakpoints are estimated at 7 s and take 16–22 s.
constexpr double kPerPiece = 45;
// One matrix exponential of a piece costs about this many n×n products (scaling and squaring
// with a degree-13 Padé approximant), and the analysis forms each piece about twice.
constexpr double kProductsPerPiece = 2 * 12;
// The Magnus methods choosing their steps with the estimate from the doubling loop's coarse pass
// instead of a refined run: 0.21–0.28 of the refined-run analysis's count (Magnus 4 on the
// oscillator above, w = 30 and 300, tol 1e-6 and 1e-8); Magnus–Filon's passes 3.5 → 2.
constexpr double kCoarsePassShare = 0.3;
constexpr double kMagnusFilonPasses = 3.5, kMagnusFilonPassesWithCoarsePass = 2;
// Magnus 6 where MagnusOverTheMeanPays (A(t) constant to the tolerance around fast modes):
// the 64-state generated rotor took 882 evaluations.
constexpr double kNearlyConstantMagnus = 1000;
// Taylor series: a step of order p = −ln tol spans about p/e² radians of the fastest motion at
// any tolerance (docs/taylor-integrator.md), about e² orders per radian in each pass; the run
// and the refined run make two (the 120-state finite-element shaft: 13 orders per radian over
// the analysis).
constexpr double kTaylorOrdersPerRadian = 15;
// CVODE's cost per right-hand side in evaluations (see EstimateFloquetWork).
constexpr double kCvodeTypicalCost = 10;
constexpr double kCvodeLeastCost = 2;

double PerRadian(double rel_tol) {
  return kTypicalPerRadian * std::pow(1e-10 / std::max(rel_tol, 1e-16), kTolerancePower);
}

// The low-order fixed-step methods on a varying A(t), where the doubling loop's steps grow as
// (1/tol)^(1/order): evaluations per radian of the fastest oscillation, measured on the
// oscillator above with rel tol 1e-6 / 1e-8 / 1e-10: Magnus 4 at w = 100 42 / 124 / 371, at
// w = 1000 24 / 86 / 227 (×9–10 per 10⁴ in tol: order 4); the exponential midpoint rule at
// w = 30 485 / – / –, w = 100 137 / 1284 / –, w = 1000 68 / 653 / – (×9.4–9.6 per 10²: order 2),
// and on the tower-rotor scene (T·ρ = 300) 930 / 7900 at 1e-6 / 1e-8 — about 7e3–8e4 at 1e-10,
// 2.5e4 within 3.5× of each. Each step also forms one exponential (about kProductsPerPiece / 2
// products), shared by its nodes.
struct LowOrderMethod {
  double per_radian_at_1e10;
  double order;
  double nodes;
};
constexpr LowOrderMethod kMagnus4Steps{400, 4, 2};
constexpr LowOrderMethod kMidpointExpSteps{25000, 2, 1};

// Evaluation-equivalents (the nodes and each step's exponential) per radian for Magnus 4 or
// the exponential midpoint rule at rel_tol.
double LowOrderPerRadian(IntegratorType type, double rel_tol) {
  const LowOrderMethod m = type == IntegratorType::kMagnus4 ? kMagnus4Steps : kMidpointExpSteps;
  return m.per_radian_at_1e10 * std::pow(1e-10 / std::max(rel_tol, 1e-16), 1 / m.order) *
         (1 + kProductsPerPiece / 2 / m.nodes);
}

}  // namespace

double SecondsPerEvaluation(const PeriodicSystem& system) {
  const int n = system.states();
  Eigen::MatrixXd a(n, n), phi = Eigen::MatrixXd::Identity(n, n), out(n, n);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const auto start = std::chrono::steady_clock::now();
    system.EvalA((k + 0.37) * system.period() / 3, a);
    internal::MultiplyInto(a, phi, out);  // the product the integrators use (BLAS for large n)
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

double MostEvaluations(double period_scale, double pieces, int segments,
                       const IntegratorOptions& integrator) {
  const double rel_tol = integrator.rel_tol;
  double per_radian = PerRadian(rel_tol);
  if (integrator.type == IntegratorType::kMagnus4 || integrator.type == IntegratorType::kExpm)
    per_radian = std::max(per_radian, LowOrderPerRadian(integrator.type, rel_tol));
  return per_radian * (period_scale + kPerSegment / kTypicalPerRadian * std::max(segments, 1)) +
         std::max(kProductsPerPiece, kPerPiece * PerRadian(rel_tol) / kTypicalPerRadian) * pieces;
}

WorkEstimate EstimateFloquetWork(const SystemTraits& traits, const IntegratorOptions& integrator,
                                 double pieces, int segments, double seconds_per_evaluation) {
  WorkEstimate w;
  w.seconds_per_evaluation = seconds_per_evaluation;
  std::ostringstream s;
  s.precision(3);
  const bool magnus =
      integrator.type == IntegratorType::kMagnus4 || integrator.type == IntegratorType::kMagnus6;
  // The estimate from the doubling loop's coarse pass: no refined run.
  const bool coarse_pass = integrator.carry_local_errors && integrator.steps_per_period == 0;
  // Magnus 6 on A(t) constant to the tolerance: a count of its own, refined run or not.
  const bool over_the_mean = integrator.type == IntegratorType::kMagnus6 &&
                             MagnusOverTheMeanPays(traits, integrator.rel_tol);
  if (magnus && integrator.steps_per_period > 0) {
    // Fixed steps: the count is the user's, the nodes per step the method's; the refined run
    // of the estimate doubles it, the mode samples add about half a pass.
    const double nodes = integrator.type == IntegratorType::kMagnus4 ? 2 : 3;
    w.fewest_evaluations = nodes * integrator.steps_per_period;
    w.evaluations = 3.5 * w.fewest_evaluations;
    s << integrator.steps_per_period << " fixed steps per period, " << nodes << " evaluations each";
  } else if (integrator.type == IntegratorType::kMagnusFilon) {
    // Products, not evaluations: the exponential and one product per step (no A(t) is
    // evaluated); the doubling loop, the refined run and the mode samples about 3.5 passes.
    const double steps = integrator.steps_per_period > 0
                             ? integrator.steps_per_period
                             : MagnusFilonSteps(traits, integrator.rel_tol);
    w.fewest_evaluations = kMagnusFilonProductsPerStep * std::max(8.0, traits.decay_spread / 2);
    w.evaluations = (coarse_pass ? kMagnusFilonPassesWithCoarsePass : kMagnusFilonPasses) *
                    kMagnusFilonProductsPerStep * steps;
    s << "about " << std::lround(steps) << " Magnus–Filon steps per period, "
      << kMagnusFilonProductsPerStep << " products each";
  } else if ((integrator.type == IntegratorType::kExpm && !traits.constant_pieces) ||
             integrator.type == IntegratorType::kMagnus4) {
    const double per_radian = LowOrderPerRadian(integrator.type, integrator.rel_tol);
    w.fewest_evaluations = kFewestFraction * per_radian * traits.oscillation;
    w.evaluations = per_radian * traits.oscillation;
    s << "T·ρ(A) = " << traits.oscillation << " radians per period, about "
      << std::lround(per_radian) << " evaluations each (a low-order method's steps at tol "
      << integrator.rel_tol << ", their exponentials counted as evaluations)";
  } else if (integrator.type == IntegratorType::kTaylor) {
    // Products, not evaluations: series_products_per_order for each order of a step.
    const double radians = std::max(traits.oscillation, traits.stiffness);
    const double per_radian =
        kTaylorOrdersPerRadian * std::max(traits.series_products_per_order, 0.5);
    w.fewest_evaluations = kFewestFraction * per_radian * radians;
    w.evaluations = per_radian * radians;
    s << "T·ρ(A) = " << radians << " radians per period to follow, about "
      << std::lround(per_radian) << " products each over the analysis (Taylor series, "
      << traits.series_products_per_order << " per order)";
  } else if (integrator.type == IntegratorType::kExpm) {
    w.fewest_evaluations = pieces;
    w.evaluations = kProductsPerPiece * pieces;
    s << pieces << " constant pieces, one matrix exponential each";
  } else if (over_the_mean) {
    w.fewest_evaluations = 1;
    w.evaluations = kNearlyConstantMagnus;
    s << "A(t) constant to the tolerance: Magnus steps exact for its mean";
  } else {
    // Explicit methods follow every radian of the fastest oscillation and every e-fold of the
    // fastest decay; Magnus follows the decay exactly but not the oscillation of a periodic part.
    const double radians = integrator.type == IntegratorType::kMagnus6
                               ? traits.oscillation
                               : std::max(traits.oscillation, traits.stiffness);
    const double per_radian = PerRadian(integrator.rel_tol);
    // Each segment and each piece starts the integrator afresh; a segment boundary at a
    // breakpoint is one start, so the larger of the two counts.
    const double restarts = pieces - 1;  // at the breakpoints inside the period
    const double starts = std::max(kPerSegment * std::max(segments, 1), kPerPiece * restarts);
    // CVODE carries Φ's n² entries as one N_Vector through its vector operations and Newton
    // iterations: on the 22-state tower-rotor scene 47–55 µs per right-hand side against
    // Bulirsch–Stoer's 4.6 µs (one evaluation's worth); counted as kCvodeTypicalCost
    // evaluations each, and at least kCvodeLeastCost (the Newton solves alone, at large n).
    const bool cvode = integrator.type == IntegratorType::kCvodeBdf ||
                       integrator.type == IntegratorType::kCvodeAdams;
    w.fewest_evaluations = (cvode ? kCvodeLeastCost : 1) * kFewestFraction * per_radian *
                           (radians + kPerPiece / kTypicalPerRadian * restarts);
    w.evaluations =
        (cvode ? kCvodeTypicalCost : 1) * per_radian * (radians + starts / kTypicalPerRadian);
    s << "T·ρ(A) = " << radians << " radians or e-folds per period to follow";
    if (restarts > 0) s << " and " << restarts << " restarts at breakpoints";
    s << ", about " << std::lround(per_radian) << " evaluations each over the analysis at tol "
      << integrator.rel_tol;
    if (cvode) s << ", CVODE's vector work " << kCvodeTypicalCost << " evaluations' worth each";
  }
  if (magnus && coarse_pass && !over_the_mean) {
    w.evaluations *= kCoarsePassShare;
    w.fewest_evaluations *= kCoarsePassShare;
    s << ", a third of it without a refined run";
  }
  w.evaluations = std::max(w.evaluations, w.fewest_evaluations);
  s << ", at " << w.seconds_per_evaluation * 1e6 << " µs per evaluation of A(t)·Φ ("
    << traits.states << " states)";
  w.basis = s.str();
  return w;
}

}  // namespace ltp
