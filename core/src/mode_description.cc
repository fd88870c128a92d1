#include "ltp/core/mode_description.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <numbers>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/core/multiblade.h"

namespace ltp {

namespace {

struct BladeNumber {
  int blade = 0;    ///< 0: none
  std::string key;  ///< the label with the blade number replaced by '#'
};

// The blade number of a label, found as for OpenFAST channels (BladeDigit).
BladeNumber FindBladeNumber(const std::string& label) {
  const auto at = BladeDigit(label);
  if (!at) return {};
  return {label[*at] - '0', label.substr(0, *at) + "#" + label.substr(*at + 1)};
}

// "blade#_flap1" → "blade_flap1", "zeta#" → "zeta", "... of blade #, m" → "... of blade, m".
std::string FamilyName(std::string key) {
  key.erase(std::remove(key.begin(), key.end(), '#'), key.end());
  const auto collapse = [&](const std::string& from, const std::string& to) {
    for (size_t at = key.find(from); at != std::string::npos; at = key.find(from, at))
      key.replace(at, from.size(), to);
  };
  collapse("__", "_");
  collapse("  ", " ");
  collapse(" ,", ",");
  collapse("_ ", " ");
  collapse(" _", " ");
  while (!key.empty() && (key.back() == '_' || key.back() == ' ')) key.pop_back();
  while (!key.empty() && (key.front() == '_' || key.front() == ' ')) key.erase(0, 1);
  return key;
}

std::string StateName(const SystemLabels& labels, int i) {
  if (i < static_cast<int>(labels.states.size())) return labels.states[static_cast<size_t>(i)];
  std::string name = "x";  // (not "x" + to_string: g++ 12 warns falsely, -Wrestrict)
  return name += std::to_string(i + 1);
}

// Indices of the displacement states (see the header).
std::vector<int> DisplacementStates(const SystemLabels& labels, int n) {
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) index[StateName(labels, i)] = i;
  std::vector<int> rate(static_cast<size_t>(n), 0);
  bool any = false;
  for (int i = 0; i < n; ++i) {
    const std::string name = StateName(labels, i);
    const bool dot =
        name.size() > 4 && name.ends_with("_dot") && index.count(name.substr(0, name.size() - 4));
    if (dot || name.find("First time derivative of ") != std::string::npos) {
      rate[static_cast<size_t>(i)] = 1;
      any = true;
    }
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (!any || !rate[static_cast<size_t>(i)]) out.push_back(i);
  return out;
}

// Energy of a blade family per multiblade harmonic k = 0..B−1 (DFT over the blade index,
// scaled so the harmonics sum to the family's energy).
std::vector<double> MultibladeEnergies(const std::vector<std::complex<double>>& v) {
  const int B = static_cast<int>(v.size());
  std::vector<double> e(static_cast<size_t>(B), 0);
  for (int k = 0; k < B; ++k) {
    std::complex<double> c = 0;
    for (int b = 0; b < B; ++b)
      c += v[static_cast<size_t>(b)] * std::polar(1.0, -2 * std::numbers::pi * k * b / B);
    e[static_cast<size_t>(k)] = std::norm(c) / B;
  }
  return e;
}

}  // namespace

void ModeDescriptionOptions::Validate() const {
  const OptionCheck check("ModeDescriptionOptions");
  if (!(min_share >= 0 && min_share <= 1)) check.Fail("min_share", min_share, "in [0, 1]");
  if (max_families < 1) check.Fail("max_families", max_families, ">= 1");
}

ModeDescription DescribeModeShape(const SystemLabels& labels, const Eigen::VectorXcd& shape,
                                  const ModeDescriptionOptions& options) {
  options.Validate();
  const int n = static_cast<int>(shape.size());
  if (!labels.states.empty() && static_cast<int>(labels.states.size()) != n)
    throw InputError("mode shape has " + std::to_string(n) + " entries for " +
                     std::to_string(labels.states.size()) + " labelled states");
  const std::vector<int> states = DisplacementStates(labels, n);
  // Blade families: key → state index per blade.
  const int B = labels.blades;
  std::map<std::string, std::vector<int>> blade_family;
  std::vector<std::string> key_of(static_cast<size_t>(n));
  if (B >= 2) {
    std::vector<char> blade_state(static_cast<size_t>(n), 0);
    for (int i : labels.blade_states)
      if (i >= 0 && i < n) blade_state[static_cast<size_t>(i)] = 1;
    for (int i : states) {
      if (!blade_state[static_cast<size_t>(i)]) continue;
      const BladeNumber b = FindBladeNumber(StateName(labels, i));
      if (b.blade < 1 || b.blade > B) continue;
      auto& members = blade_family[b.key];
      members.resize(static_cast<size_t>(B), -1);
      if (members[static_cast<size_t>(b.blade - 1)] >= 0) continue;  // twice: not a family
      members[static_cast<size_t>(b.blade - 1)] = i;
      key_of[static_cast<size_t>(i)] = b.key;
    }
    for (auto it = blade_family.begin(); it != blade_family.end();) {
      const bool complete = std::count(it->second.begin(), it->second.end(), -1) == 0;
      if (!complete)
        for (int i : it->second)
          if (i >= 0) key_of[static_cast<size_t>(i)].clear();
      it = complete ? std::next(it) : blade_family.erase(it);
    }
  }
  ModeDescription d;
  double total = 0;
  for (int i : states) total += std::norm(shape(i));
  if (!(total > 0)) return d;
  for (int i : states)
    if (key_of[static_cast<size_t>(i)].empty())
      d.families.push_back({StateName(labels, i), std::norm(shape(i)) / total});
  for (const auto& [key, members] : blade_family) {
    std::vector<std::complex<double>> v;
    for (int i : members) v.push_back(shape(i));
    const std::vector<double> e = MultibladeEnergies(v);
    const std::string name = FamilyName(key);
    std::map<std::string, double> parts;
    for (int k = 0; k < B; ++k) {
      const int harmonic = std::min(k, B - k);
      std::string part = harmonic == 0                       ? "collective"
                         : (B % 2 == 0 && 2 * harmonic == B) ? "differential"
                         : harmonic == 1                     ? "cyclic"
                                                             : "cyclic " + std::to_string(harmonic);
      parts[part] += e[static_cast<size_t>(k)];
    }
    for (const auto& [part, energy] : parts)
      d.families.push_back({name + " " + part, energy / total});
  }
  // Largest first; shares equal to 1e-9 (e.g. a circular whirl's two planes) keep state order.
  std::stable_sort(d.families.begin(), d.families.end(), [](const auto& a, const auto& b) {
    return std::llround(a.share * 1e9) > std::llround(b.share * 1e9);
  });
  std::ostringstream text;
  for (size_t k = 0; k < d.families.size() && static_cast<int>(k) < options.max_families; ++k) {
    if (k > 0 && d.families[k].share < options.min_share) break;
    text << (k ? ", " : "") << d.families[k].name << " " << std::lround(100 * d.families[k].share)
         << "%";
  }
  d.text = text.str();
  return d;
}

std::vector<std::string> DescribeModeShapes(const SystemLabels& labels,
                                            const Eigen::MatrixXcd& shapes,
                                            const ModeDescriptionOptions& options) {
  std::vector<std::string> out(static_cast<size_t>(shapes.cols()));
  if (!labels.states.empty() && static_cast<Eigen::Index>(labels.states.size()) != shapes.rows())
    return out;
  for (Eigen::Index k = 0; k < shapes.cols(); ++k)
    out[static_cast<size_t>(k)] = DescribeModeShape(labels, shapes.col(k), options).text;
  return out;
}

}  // namespace ltp
