#pragma once
// The stability-only route of maps: the multipliers of Φ(T, 0) formed in one integration,
// without the segment grid and periodic Schur form of AnalyzeFloquet (a quarter of a map
// point's cost).
#include <complex>
#include <optional>
#include <vector>

#include "ltp/core/periodic_system.h"
#include "ltp/integrate/integrator.h"

namespace ltp {

/// Log multipliers from Φ(T, 0) formed in one integration — over half a period when the
/// system is time-reversible (docs/time-reversal.md) — and the eigenvalues of the n×n product
/// (for two states with an exact trace integral, from trace and Liouville's determinant). The
/// largest multiplier keeps its relative accuracy in the formed product however small the
/// others are. nullopt when the integration fails or the product over- or underflows.
std::optional<std::vector<std::complex<double>>> FormedLogMultipliers(
    const PeriodicSystem& system, const IntegratorOptions& integrator);

/// Whether FormedLogMultipliers forms Φ(T) from half a period: the system is time-reversible
/// (docs/time-reversal.md).
bool FormsMonodromyFromHalfPeriod(const PeriodicSystem& system);

}  // namespace ltp
