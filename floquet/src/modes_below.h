#pragma once
// Floquet analysis of the modes below a frequency (FloquetOptions::modes_below).
#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"

namespace ltp::internal {

/// The analysis of `options.modes_below` (> 0): the system projected on the slow spectral
/// subspace of its mean (spectral_split.h) at the cut-off and at kModesBelowCheck × it, each
/// analysed in full; the numbers are the second's, each exponent's estimate its own plus its
/// change between the two, and FloquetResult::reduction says what was left out
/// (docs/model-sizes.md, "Modes below a frequency").
FloquetResult AnalyzeModesBelow(const PeriodicSystem& system, const FloquetOptions& options);

}  // namespace ltp::internal
