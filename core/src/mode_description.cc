#include "ltp/core/mode_description.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <numbers>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/core/multiblade.h"
#include "ltp/core/text.h"

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

// For each state, the index of the displacement whose rate it is, else its own index (see
// the header: "s_dot" beside "s"; "First time derivative of s, m/s" beside "s, m").
std::vector<int> CoordinateOf(const SystemLabels& labels, int n) {
  std::map<std::string, int> index, index_without_unit;
  for (int i = 0; i < n; ++i) {
    index.emplace(StateName(labels, i), i);
    index_without_unit.emplace(WithoutUnit(StateName(labels, i)), i);
  }
  static const std::string kDerivative = "First time derivative of ";
  std::vector<int> coordinate(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    coordinate[static_cast<size_t>(i)] = i;
    const std::string name = StateName(labels, i);
    if (name.size() > 4 && name.ends_with("_dot")) {
      const auto it = index.find(name.substr(0, name.size() - 4));
      if (it != index.end()) coordinate[static_cast<size_t>(i)] = it->second;
    } else if (const auto at = name.find(kDerivative); at != std::string::npos) {
      std::string base = name;
      base.erase(at, kDerivative.size());
      const auto it = index_without_unit.find(WithoutUnit(base));
      if (it != index_without_unit.end() && it->second != i)
        coordinate[static_cast<size_t>(i)] = it->second;
    }
  }
  return coordinate;
}

// Participation of a blade family per multiblade harmonic k = 0..B−1: the DFT over the blade
// index of the right vector's entries and the inverse DFT of the left's, so the harmonics'
// participations add up to the family's Σ_b v_b w_b.
std::vector<std::complex<double>> MultibladeParticipation(
    const std::vector<std::complex<double>>& v, const std::vector<std::complex<double>>& w) {
  const int B = static_cast<int>(v.size());
  std::vector<std::complex<double>> p(static_cast<size_t>(B), 0);
  for (int k = 0; k < B; ++k) {
    std::complex<double> vk = 0, wk = 0;
    for (int b = 0; b < B; ++b) {
      const std::complex<double> e = std::polar(1.0, -2 * std::numbers::pi * k * b / B);
      vk += v[static_cast<size_t>(b)] * e;
      wk += w[static_cast<size_t>(b)] * std::conj(e);
    }
    p[static_cast<size_t>(k)] = vk * wk / static_cast<double>(B);
  }
  return p;
}

std::string MultibladePart(int k, int B) {
  const int harmonic = std::min(k, B - k);
  if (harmonic == 0) return "collective";
  if (B % 2 == 0 && 2 * harmonic == B) return "differential";
  if (harmonic == 1) return "cyclic";
  return "cyclic " + std::to_string(harmonic);
}

// Blade families: the label with its blade number replaced by '#' → state index per blade
// (complete families only; key_of names each member's family, empty for the others).
struct BladeFamilies {
  std::map<std::string, std::vector<int>> members;
  std::vector<std::string> key_of;
};

BladeFamilies FindBladeFamilies(const SystemLabels& labels, const std::vector<int>& coordinate) {
  const int n = static_cast<int>(coordinate.size());
  BladeFamilies f;
  f.key_of.resize(static_cast<size_t>(n));
  const int B = labels.blades;
  if (B < 2) return f;
  std::vector<char> blade_state(static_cast<size_t>(n), 0);
  for (int i : labels.blade_states)
    if (i >= 0 && i < n) blade_state[static_cast<size_t>(i)] = 1;
  for (int i = 0; i < n; ++i) {
    // A rate is a blade state when its displacement is.
    if (!blade_state[static_cast<size_t>(i)] &&
        !blade_state[static_cast<size_t>(coordinate[static_cast<size_t>(i)])])
      continue;
    const BladeNumber b = FindBladeNumber(StateName(labels, i));
    if (b.blade < 1 || b.blade > B) continue;
    auto& members = f.members[b.key];
    members.resize(static_cast<size_t>(B), -1);
    if (members[static_cast<size_t>(b.blade - 1)] >= 0) continue;  // twice: not a family
    members[static_cast<size_t>(b.blade - 1)] = i;
    f.key_of[static_cast<size_t>(i)] = b.key;
  }
  for (auto it = f.members.begin(); it != f.members.end();) {
    const bool complete = std::count(it->second.begin(), it->second.end(), -1) == 0;
    if (!complete)
      for (int i : it->second)
        if (i >= 0) f.key_of[static_cast<size_t>(i)].clear();
    it = complete ? std::next(it) : f.members.erase(it);
  }
  return f;
}

// Participation summed per family name, in order of first appearance.
class FamilySums {
 public:
  void Add(const std::string& name, std::complex<double> p) {
    const auto [it, added] = index_.emplace(name, sums_.size());
    if (added) sums_.push_back({name, 0});
    sums_[it->second].second += p;
  }
  const std::vector<std::pair<std::string, std::complex<double>>>& sums() const { return sums_; }

 private:
  std::map<std::string, size_t> index_;
  std::vector<std::pair<std::string, std::complex<double>>> sums_;
};

}  // namespace

void ModeDescriptionOptions::Validate() const {
  const OptionCheck check("ModeDescriptionOptions");
  if (!(min_share >= 0 && min_share <= 1)) check.Fail("min_share", min_share, "in [0, 1]");
  if (max_families < 1) check.Fail("max_families", max_families, ">= 1");
}

ModeDescription DescribeMode(const SystemLabels& labels, const Eigen::VectorXcd& right,
                             const Eigen::VectorXcd& left, const ModeDescriptionOptions& options) {
  options.Validate();
  const int n = static_cast<int>(right.size());
  if (left.size() != right.size())
    throw InputError("mode description: right eigenvector has " + std::to_string(n) +
                     " entries, left " + std::to_string(left.size()));
  if (!labels.states.empty() && static_cast<int>(labels.states.size()) != n)
    throw InputError("mode shape has " + std::to_string(n) + " entries for " +
                     std::to_string(labels.states.size()) + " labelled states");
  const std::vector<int> coordinate = CoordinateOf(labels, n);
  const BladeFamilies blade = FindBladeFamilies(labels, coordinate);
  FamilySums sums;
  for (int i = 0; i < n; ++i)
    if (blade.key_of[static_cast<size_t>(i)].empty())
      sums.Add(StateName(labels, coordinate[static_cast<size_t>(i)]), right(i) * left(i));
  for (const auto& [key, members] : blade.members) {
    // A rate family is named after its displacements' family.
    const std::string& displacement_key =
        blade.key_of[static_cast<size_t>(coordinate[static_cast<size_t>(members[0])])];
    const std::string name = FamilyName(displacement_key.empty() ? key : displacement_key);
    std::vector<std::complex<double>> v, w;
    for (int i : members) {
      v.push_back(right(i));
      w.push_back(left(i));
    }
    const std::vector<std::complex<double>> p = MultibladeParticipation(v, w);
    const int B = static_cast<int>(members.size());
    for (int k = 0; k < B; ++k)
      sums.Add(name + " " + MultibladePart(k, B), p[static_cast<size_t>(k)]);
  }
  ModeDescription d;
  double total = 0;
  for (const auto& [name, p] : sums.sums()) total += std::abs(p);
  if (!(total > 0) || !std::isfinite(total)) return d;
  for (const auto& [name, p] : sums.sums()) d.families.push_back({name, std::abs(p) / total});
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

std::vector<std::string> DescribeModes(const SystemLabels& labels, const Eigen::MatrixXcd& right,
                                       const Eigen::MatrixXcd& left,
                                       const ModeDescriptionOptions& options) {
  std::vector<std::string> out(static_cast<size_t>(right.cols()));
  if ((!labels.states.empty() && static_cast<Eigen::Index>(labels.states.size()) != right.rows()) ||
      left.rows() != right.cols() || left.cols() != right.rows())
    return out;
  for (Eigen::Index k = 0; k < right.cols(); ++k)
    out[static_cast<size_t>(k)] =
        DescribeMode(labels, right.col(k), left.row(k).transpose(), options).text;
  return out;
}

Eigen::MatrixXcd LeftEigenvectors(const Eigen::MatrixXcd& right) {
  if (right.rows() != right.cols() || right.size() == 0) return {};
  Eigen::MatrixXcd left = right.partialPivLu().inverse();
  if (!left.allFinite()) return {};
  return left;
}

std::vector<std::string> DescribeModeShapes(const SystemLabels& labels,
                                            const Eigen::MatrixXcd& shapes,
                                            const ModeDescriptionOptions& options) {
  return DescribeModes(labels, shapes, LeftEigenvectors(shapes), options);
}

}  // namespace ltp
