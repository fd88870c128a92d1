#pragma once
// What a Floquet analysis by the monodromy matrix will cost, estimated before it starts from
// what decides it: the radians (or e-folds) an explicit integrator must follow per period, the
// pieces a product of exponentials multiplies, the system's size, and the time one evaluation
// of A(t) and one n×n product take on this machine now (docs/model-sizes.md, "Cost before the
// work").
#include <string>

#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"
#include "ltp/integrate/integrator_choice.h"

namespace ltp {

struct WorkEstimate {
  /// Evaluations of A(t)·Φ over the whole analysis (the run, the refined run of the estimate,
  /// the mode samples): the typical count, within about 3× either way on the measured systems.
  double evaluations = 0;
  /// A count no run of this integrator goes below (a fifth of the typical count per radian of
  /// the fastest oscillation for an explicit method; one per piece for a product of exponentials).
  double fewest_evaluations = 0;
  /// Seconds per evaluation on this machine: one A(t) and one n×n product, timed now.
  double seconds_per_evaluation = 0;
  double seconds() const { return evaluations * seconds_per_evaluation; }
  double fewest_seconds() const { return fewest_evaluations * seconds_per_evaluation; }
  std::string basis;  ///< what decided the count, one sentence
};

/// One evaluation of A(t) and one n×n product on this machine now (the fastest of three).
double SecondsPerEvaluation(const PeriodicSystem& system);

/// The estimate for a system with `traits` (MeasureSystemTraits), `pieces` intervals between
/// breakpoints, analysed with `integrator` (resolved: not kAuto) from a grid of `segments`;
/// `integrator.carry_local_errors` says the estimate comes from the run's carried local errors,
/// not from a refined run (the Magnus methods then do about a third of the work).
WorkEstimate EstimateFloquetWork(const SystemTraits& traits, const IntegratorOptions& integrator,
                                 double pieces, int segments, double seconds_per_evaluation);

/// More evaluations than any integrator needs for a system with T·max‖A(t)‖ = `period_scale`
/// (which bounds T·ρ and the e-folds), `pieces` and `segments`: what decides whether an
/// analysis is small enough to skip the traits and the estimate.
double MostEvaluations(double period_scale, double pieces, int segments,
                       const IntegratorOptions& integrator);

}  // namespace ltp
