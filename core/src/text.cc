#include "ltp/core/text.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace ltp {

std::string Trim(std::string_view s) {
  // The characters std::isspace calls blank, so a trimmed line is empty exactly when a
  // whitespace tokenizer finds no token in it.
  constexpr std::string_view kBlanks = " \t\r\n\v\f";
  const auto first = s.find_first_not_of(kBlanks);
  if (first == std::string_view::npos) return "";
  const auto last = s.find_last_not_of(kBlanks);
  return std::string(s.substr(first, last - first + 1));
}

std::vector<std::string> SplitAt(std::string_view s, char separator) {
  std::vector<std::string> parts;
  for (size_t start = 0;;) {
    const size_t at = s.find(separator, start);
    parts.emplace_back(s.substr(start, at == std::string_view::npos ? s.npos : at - start));
    if (at == std::string_view::npos) return parts;
    start = at + 1;
  }
}

namespace {

// Byte offset of the first byte that breaks UTF-8, or npos.
size_t InvalidUtf8At(std::string_view text) {
  const auto* b = reinterpret_cast<const unsigned char*>(text.data());
  const size_t n = text.size();
  for (size_t i = 0; i < n;) {
    const unsigned char c = b[i];
    const int extra = c < 0x80           ? 0
                      : (c >> 5) == 0x6  ? 1
                      : (c >> 4) == 0xE  ? 2
                      : (c >> 3) == 0x1E ? 3
                                         : -1;
    if (extra < 0 || (extra == 1 && c < 0xC2) || i + extra >= n + (extra == 0 ? 1 : 0)) return i;
    for (int k = 1; k <= extra; ++k)
      if (i + k >= n || (b[i + k] & 0xC0) != 0x80) return i;
    // Well-formed sequences only (RFC 3629): no overlong 3- and 4-byte forms, no UTF-16
    // surrogates U+D800…DFFF (ED A0…BF), nothing above U+10FFFF (F4 90… and F5…).
    if (extra == 2 && ((c == 0xE0 && b[i + 1] < 0xA0) || (c == 0xED && b[i + 1] >= 0xA0))) return i;
    if (extra == 3 &&
        ((c == 0xF0 && b[i + 1] < 0x90) || (c == 0xF4 && b[i + 1] >= 0x90) || c > 0xF4))
      return i;
    i += extra + 1;
  }
  return std::string::npos;
}

}  // namespace

std::string NumberShape(std::string_view line) {
  std::string key;
  for (size_t i = 0; i < line.size();) {
    if (std::isdigit(static_cast<unsigned char>(line[i]))) {
      while (i < line.size() && (std::isdigit(static_cast<unsigned char>(line[i])) ||
                                 line[i] == '.' || line[i] == 'e' || line[i] == 'E' ||
                                 ((line[i] == '-' || line[i] == '+') && i > 0 &&
                                  (line[i - 1] == 'e' || line[i - 1] == 'E'))))
        ++i;
      key += '#';
    } else {
      key += line[i++];
    }
  }
  return key;
}

std::optional<std::string> NotUtf8(std::string_view text, std::string_view rule) {
  const size_t at = InvalidUtf8At(text);
  if (at == std::string::npos) return std::nullopt;
  const auto before = text.substr(0, at);
  std::ostringstream s;
  s << "not valid UTF-8 text (byte 0x" << std::hex
    << static_cast<int>(static_cast<unsigned char>(text[at])) << std::dec;
  if (text.find('\n') != std::string_view::npos)
    s << " on line " << 1 + std::count(before.begin(), before.end(), '\n');
  s << " at offset " << at << "); " << rule;
  return s.str();
}

std::string WithoutUnit(const std::string& label) {
  const auto comma = label.rfind(", ");
  if (comma == std::string::npos) return label;
  const std::string unit = label.substr(comma + 2);
  if (unit.empty() || unit.size() > 10 || unit.find(' ') != std::string::npos) return label;
  return label.substr(0, comma);
}

}  // namespace ltp
