#pragma once
// What an analysis of the modes below a cut-off (FloquetOptions::modes_below) kept, checked and
// left out, as `ltp floquet` and `ltp mbc` print it and write it in JSON.
#include <nlohmann/json.hpp>
#include <optional>

#include "ltp/floquet/floquet.h"

namespace ltp::cli {

/// {"cutoff_hz", "states", "check_cutoff_hz", "check_states", "truncation_change", "tail",
/// "dropped_mean_eigenvalues", "periodic_part"}; null without a reduction.
nlohmann::json ReductionJson(const std::optional<ModalReduction>& m);

/// Two lines: what was analysed and checked, what was left out; `states` of the full system.
void PrintReduction(const ModalReduction& m, int states);

}  // namespace ltp::cli
