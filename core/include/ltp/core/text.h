#pragma once
// Small text helpers shared by the readers of scenes, sweeps and OpenFAST files.
#include <string>
#include <string_view>
#include <vector>

namespace ltp {

/// `s` without leading and trailing blanks (space, tab, CR, LF).
std::string Trim(std::string_view s);

/// `line` with every number replaced by '#': lines that differ only in their numbers share it.
std::string NumberShape(std::string_view line);

/// Diagnostics said once: lines that differ only in their numbers (one per segment, step or
/// point of a failing run) are kept up to `keep` times; the rest of each such group becomes one
/// line "… and N more like the above". Order of first appearance is kept. A failing run used
/// to return 19 945 lines of the same sentence.
std::vector<std::string> CollapseRepeatedLines(const std::vector<std::string>& lines, int keep = 3);

}  // namespace ltp
