#pragma once
// The Campbell diagram of `ltp chart` (1-D sweeps) as text, JSON and the crossing CSV.
#include <CLI/CLI.hpp>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "ltp/studies/campbell.h"

namespace ltp::cli {

/// {"lines": [...], "crossings": [...], "weakly_damped": [...], "per_rev": [...], "diagnostics"}.
nlohmann::json CampbellJson(const CampbellDiagram& d);

/// The mode lines with their names and the crossing table; `axis` names the swept parameter.
void PrintCampbell(std::ostream& out, const CampbellDiagram& d, const std::string& axis);

/// One row per crossing: mode, description, n, parameter, its error, rotor speed, frequency,
/// Re λ, damping ratio. @throws InputError when the file cannot be written.
void WriteCrossingsCsv(const std::string& path, const CampbellDiagram& d, const std::string& axis);

/// --per-rev and --weak-damping, bound to `options` (defaults shown from it), for `ltp chart`
/// and `ltp campbell`; CampbellOptions::Validate checks them once parsed.
void AddCampbellArgs(CLI::App* cmd, CampbellOptions& options);

/// "out/c.csv" → "out/c-crossings.csv".
std::string CrossingsCsvPath(const std::string& csv);

}  // namespace ltp::cli
