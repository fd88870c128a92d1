#pragma once
// The error of a model built from samples in a Hill result's estimate (as
// ltp/floquet/model_error.h for the monodromy route; docs/sampled-models.md).
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/floquet/floquet.h"
#include "ltp/hill/hill.h"

namespace ltp {

/// The alternatives are analysed by the monodromy route (multipliers only, `options`), each
/// exponent's e_k is added to its band and the largest to h.error_estimate; h.model_error, the
/// verdict and the time are set as IncludeModelError does for a FloquetResult. A Hill estimate
/// of 1e-13 on a model whose samples leave 1e-5 undetermined is not an estimate.
/// @throws InputError when an alternative has another size or period than `h`.
void IncludeModelError(const std::vector<PeriodicSystem>& alternatives,
                       const FloquetOptions& options, HillResult& h);

}  // namespace ltp
