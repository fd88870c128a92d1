#pragma once
// Frequency and order ranges written as text, as `ltp pfrf --freq 0:450:0.6 --orders -4:4`
// and Python's `freq="0:450:0.6", orders="-4:4"` take them: one parser, so both get the same
// grid to the last bit.
#include <string>
#include <utility>
#include <vector>

namespace ltp {

/// "F0:F1:DF" (Hz) → F0 + i·DF for i = 0, 1, ... while <= F1 (within a rounding error); equal
/// ends: the one frequency. `option` is how the caller spells the argument in messages.
/// @throws InputError (not three finite numbers, F1 < F0, DF <= 0, over a million points).
std::vector<double> ParseFrequencyRange(const std::string& text, const std::string& option);

/// Comma-separated items, each one frequency "F" or a range "F0:F1:DF" (as above), in the order
/// given: "0.2", "0.1,0.25,0.4", "0:1:0.1,1.5". @throws InputError (an empty item, a bad number or
/// range, over a million points in all).
std::vector<double> ParseFrequencyList(const std::string& text, const std::string& option);

/// "F0:F1" (Hz) → (F0, F1) with 0 <= F0 < F1. @throws InputError.
std::pair<double, double> ParseFrequencyBand(const std::string& text, const std::string& option);

/// "ZMIN:ZMAX" or "Z" → (min, max), |z| <= 1000. @throws InputError.
std::pair<int, int> ParseOrderRange(const std::string& text, const std::string& option);

}  // namespace ltp
