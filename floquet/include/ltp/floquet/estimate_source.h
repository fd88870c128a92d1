#pragma once
// How an analysis's error estimate was made, in words, for the commands' result lines and the
// options' help: the one place that says which integrator carries what
// (docs/local-error-estimate.md).
#include <string_view>

#include "ltp/floquet/floquet.h"

namespace ltp {

/// How `method` (as resolved: kRefinedRun or kLocalErrors) estimated the exponents' error with
/// `integrator`, and where the reported numbers come from: one sentence without a final stop.
std::string_view EstimateSource(ErrorEstimateMethod method, IntegratorType integrator);

/// The same in a few words for a table row ("from its order-p product"); empty for the refined
/// run, the default that needs no saying.
std::string_view EstimateSourceBrief(ErrorEstimateMethod method, IntegratorType integrator);

/// What `local-errors` carries with each integrator that can, for the help of the estimate
/// option (CLI --estimate, Python `estimate=`).
inline constexpr std::string_view kLocalErrorSources =
    "Bulirsch–Stoer's steps' local errors carried to the exponents; Taylor series' order-p "
    "product beside the reported order p + 4; the Magnus methods' pass at half the steps beside "
    "the reported one";

}  // namespace ltp
