#include "ltp/core/text.h"

#include <cctype>
#include <map>

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

std::vector<std::string> CollapseRepeatedLines(const std::vector<std::string>& lines, int keep) {
  std::map<std::string, size_t> count;
  for (const std::string& l : lines) ++count[NumberShape(l)];
  std::map<std::string, size_t> seen;
  std::vector<std::string> out;
  for (const std::string& l : lines) {
    const std::string key = NumberShape(l);
    const size_t k = ++seen[key];
    if (k <= static_cast<size_t>(keep) || count[key] <= static_cast<size_t>(keep) + 1) {
      out.push_back(l);
    } else if (k == static_cast<size_t>(keep) + 1) {
      out.push_back("… and " + std::to_string(count[key] - keep) + " more like the above");
    }
  }
  return out;
}

}  // namespace ltp
