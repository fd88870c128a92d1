#pragma once
// Small text helpers shared by the readers of scenes, sweeps and OpenFAST files.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ltp {

/// `s` without leading and trailing blanks (space, tab, CR, LF).
std::string Trim(std::string_view s);

/// `s` cut at every `separator`: n separators give n + 1 parts, empty ones included ("a,,b," →
/// "a", "", "b", ""; "" → ""). The one splitter of the readers and option parsers.
std::vector<std::string> SplitAt(std::string_view s, char separator);

/// Where `text` stops being UTF-8 (RFC 3629: no overlong forms, surrogates or code points
/// beyond U+10FFFF), as "not valid UTF-8 text (byte 0x.. on line .. at offset ..); `rule`"
/// (the line when `text` has several), or empty when it is valid. Names read from files end up in
/// JSON and on terminals: a stray byte is refused by the reader with its line, not by the JSON
/// writer after the work.
std::optional<std::string> NotUtf8(std::string_view text, std::string_view rule);

/// `line` with every number replaced by '#': lines that differ only in their numbers share it.
std::string NumberShape(std::string_view line);

/// An OpenFAST-style label without its trailing unit: "ED 1st tower ... DOF, m" → "ED 1st tower
/// ... DOF" (the part after the last ", " when it is short and has no blank); else unchanged.
std::string WithoutUnit(const std::string& label);

}  // namespace ltp
