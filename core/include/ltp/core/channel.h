#pragma once
// Input and output channels chosen by index or by name, as `ltp pfrf --input` and Python's
// `input=` take them.
#include <string>
#include <vector>

namespace ltp {

/// The channel `text` names: an index from 0, or a name among `names` (names win over
/// indices). `option` is how the caller spells the argument in the message ("--input",
/// "input"); `what` is "input" or "output".
/// @throws InputError naming the valid choices.
int ResolveChannel(const std::string& text, const std::vector<std::string>& names, int count,
                   const std::string& option, const std::string& what);

}  // namespace ltp
