#pragma once
// The sampling error of a model built from azimuth samples, in a partial-FRF sweep's estimate.
//
// A `.lin` model is an interpolation between the azimuths OpenFAST linearised at; the routes of
// a sweep check one another on that interpolated system and know nothing of the samples. The
// same samples interpolated the other way (held ↔ trigonometric) or built in the other
// coordinates (multi-blade ↔ the files') give other models; how far their H_z are from the
// analysed one's is the model error, added to each value's estimate as the Floquet analysis adds
// it to the exponents' (docs/sampled-models.md).
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/htf/pfrf.h"

namespace ltp {

/// Sweeps each of `alternatives` at r's frequencies, orders and channel (route auto without
/// check points: the modal route unless it reports itself unreliable) and adds |H_alt − H| to
/// each value's estimate; r.model_error is the largest difference, r.floquet gets its own model
/// error (IncludeModelError), time is added to r.elapsed_s. An alternative whose sweep fails makes
/// every estimate infinite. Nothing happens for an empty list. @throws InputError when an
/// alternative has another size, channel count or period.
void IncludeModelError(const std::vector<PeriodicSystem>& alternatives, const PfrfOptions& options,
                       PfrfResult& r);

}  // namespace ltp
