#include "ltp/core/error.h"

#include <charconv>
#include <sstream>

namespace ltp {

std::string MessageNumber(double x, int significant) {
  std::ostringstream s;
  s.precision(significant);
  s << x;
  return s.str();
}

void OptionCheck::Fail(std::string_view field, double value, std::string_view constraint) const {
  char text[32];  // the shortest round-trip form of a double takes at most 24
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  Fail(field, std::string_view(text, static_cast<size_t>(end - text)), constraint);
}

void OptionCheck::Fail(std::string_view field, std::string_view value,
                       std::string_view constraint) const {
  std::string message(owner_);
  message.append("::").append(field).append(" = ").append(value);
  message.append(". Violated constraint: ").append(constraint);
  throw InputError(message);
}

}  // namespace ltp
