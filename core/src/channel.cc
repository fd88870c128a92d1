#include "ltp/core/channel.h"

#include "ltp/core/error.h"

namespace ltp {

int ResolveChannel(const std::string& text, const std::vector<std::string>& names, int count,
                   const std::string& option, const std::string& what) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == text) return static_cast<int>(i);
  bool digits = !text.empty();
  for (char c : text) digits = digits && c >= '0' && c <= '9';
  if (digits && text.size() < 8) {
    const int i = std::stoi(text);
    if (i < count) return i;
  }
  std::string valid;
  for (int i = 0; i < count; ++i)
    valid += (i ? ", " : "") + std::to_string(i) +
             (i < static_cast<int>(names.size()) && !names[i].empty() ? " (" + names[i] + ")" : "");
  throw InputError(option + " '" + text + "' is not one of the system's " + what +
                   "s: " + (count ? valid : std::string("none")));
}

}  // namespace ltp
