#pragma once
// The error of a model built from samples, in a Floquet result's error estimate.
//
// A system built from K azimuth samples (OpenFAST linearisations) is exact only at the
// samples; in between it is an interpolation. The integration estimate says how well the
// exponents of that interpolated system were computed, not how far they are from the exponents
// of the system the samples came from. The same samples interpolated another way (nearest-
// sample hold ↔ trigonometric polynomial) give a second model; how far its exponents are from
// the analysed one's is the model error term, added to the estimate before the verdict
// (docs/sampled-models.md states the rule and what it cannot see).
#include <complex>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"

namespace ltp {

/// Analyses each of `alternatives` (multipliers only, on `r`'s grid; the exact kExpm integrator
/// when piecewise constant); each exponent's sampling error e_k is its largest distance to its
/// match in any of them (modulo jΩp; +inf when an analysis failed). Sets r.model_error =
/// max_k e_k, adds it to r.error_estimate (to 0 when no estimate was asked for) and
/// reclassifies the verdict: every Re λ_k ± (integration estimate + e_k) below or above 0;
/// each mode's own estimate gets its e_k; the time and evaluations these analyses took are added
/// to r.elapsed_s and r.rhs_evals (what the whole call cost). Nothing happens for an empty list.
/// @throws InputError when an alternative has another size or period than `r`.
void IncludeModelError(const std::vector<PeriodicSystem>& alternatives,
                       const FloquetOptions& options, FloquetResult& r);

/// The same when the alternatives were analysed already (a caller that needed them anyway,
/// e.g. the partial-FRF sweep of each other model): `analysed[i]` is AnalyzeFloquet of the i-th
/// alternative (modes or multipliers only); their time and evaluations are the caller's to add.
/// @throws InputError when an analysis has another size or period than `r`.
void IncludeModelError(const std::vector<FloquetResult>& analysed, FloquetResult& r);

/// Each exponent's sampling error against `alternatives` (see above), analysed by the monodromy
/// route (multipliers only, `options`, from `grid_segments` segments when > 0); for a route
/// whose exponents come from elsewhere (Hill's: ltp/hill/hill_model_error.h).
struct SamplingErrors {
  std::vector<double> per_exponent;  ///< e_k, in the order of `exponents`
  long evaluations = 0;              ///< what the alternatives' analyses cost
};
SamplingErrors SamplingErrorsAgainst(const std::vector<PeriodicSystem>& alternatives, int states,
                                     double period, const FloquetOptions& options,
                                     const std::vector<std::complex<double>>& exponents,
                                     int grid_segments = 0);

/// The band on max Re λ that a verdict uses when exponent k carries its own error own[k]
/// besides the common `integration` estimate: the largest distance from `max_real` to
/// max_k (Re λ_k ± (integration + own[k])) over the modes not `skip`ped (rigid-body ones);
/// `fallback` when no mode counts or a bound is not finite. Fast-decaying modes that two models
/// place far apart (−50 vs −53 1/s) then leave a clear verdict clear.
double PerExponentBand(const std::vector<double>& real_parts, const std::vector<double>& own,
                       const std::vector<bool>& skip, double integration, double max_real,
                       double fallback);

/// The same over modes: each with its own FloquetMode::error_estimate (`fallback` for a mode
/// without one), rigid-body modes skipped.
double PerModeBand(const std::vector<FloquetMode>& modes, double max_real, double fallback);

}  // namespace ltp
