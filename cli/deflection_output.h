#pragma once
// --deflection-csv of `ltp floquet`: each mode's deflected structure over one period.
#include <string>

#include "ltp/studies/mode_deflection.h"

namespace ltp::cli {

/// One row per mode, sample time, body and node: mode (numbered as in the table), t, body,
/// node, the rest position and the deflected position (m). A long table: pandas' groupby or
/// ParaView's "Table To Points" per time animate it. @throws InputError if it cannot be written.
void WriteDeflectionCsv(const std::string& file, const ModeDeflections& deflections);

/// One row per mode (at most 4): the deflection at every sample time drawn over each other on
/// the structure as it stands at t = 0 (DeflectionFrame::standing), in three views
/// on one scale — along the shaft (x–z), from the side (x–y), along the cantilever (z–y) — and
/// the rest shape at t = 0 dashed.
/// @throws InputError (more than 4 modes, the file, gnuplot).
void PlotDeflection(const std::string& file, const ModeDeflections& deflections);

}  // namespace ltp::cli
