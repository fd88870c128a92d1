#pragma once
// Whether A(t), given as a function, is periodic with the period it was given: every analysis
// assumes A(t + T) = A(t), and the routes that run over several periods (forced response,
// simulation) evaluate it beyond T. A callable written for one period (a ramp in t) or a
// period that does not match the coefficients (6.2832 for cos t) would otherwise be analysed as
// something else, without a word.
#include <optional>
#include <string>

#include "ltp/core/periodic_system.h"

namespace ltp {

/// nullopt when A(t + T) equals A(t) to 1e-9 of max ‖A‖ at seven points of the period at
/// golden-ratio fractions (away from breakpoints), or when A(t) is a Fourier series or samples
/// (periodic by construction); otherwise one sentence naming t and the difference.
std::optional<std::string> NonPeriodicCoefficients(const PeriodicSystem& system);

}  // namespace ltp
