#pragma once
// Small text helpers shared by the readers of scenes, sweeps and OpenFAST files.
#include <string>
#include <string_view>

namespace ltp {

/// `s` without leading and trailing blanks (space, tab, CR, LF).
std::string Trim(std::string_view s);

}  // namespace ltp
