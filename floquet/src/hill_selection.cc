// Which n of the Hill eigenvalues are the physical exponents: one member of each jΩp-shift
// family, chosen by where its eigenvector's energy sits over the harmonic blocks.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "hill_internal.h"

namespace ltp::hill_internal {
namespace {

struct Candidate {
  cd value;
  std::vector<double> energy;  // per block, sums to 1
  double centroid = 0;
  double score = 0;  // smaller is better
  bool passes = false;
};

// Score under the rule (smaller = better) and whether the candidate passes the rule's test.
void Score(Candidate& c, int N, double omega, HillSelectionRule rule) {
  const std::vector<double>& e = c.energy;
  switch (rule) {
    case HillSelectionRule::kCentroid:
      c.score = std::abs(c.centroid);
      c.passes = c.score < 0.5;
      break;
    case HillSelectionRule::kCentralWeight:
      c.score = 1 - e[N];
      c.passes = *std::max_element(e.begin(), e.end()) <= e[N];
      break;
    case HillSelectionRule::kStrip:
      c.score = std::abs(c.value.imag()) / omega;
      c.passes = c.score <= 0.5;
      break;
  }
}

// The score the runner-up of c's family would have, from c's own energy distribution: member
// λ + jkΩp has the distribution shifted by k blocks (exact for N → ∞).
double TranslatedRunnerUpScore(const Candidate& c, int N, double omega, HillSelectionRule rule) {
  switch (rule) {
    case HillSelectionRule::kCentroid:
      return 1 - std::abs(c.centroid);
    case HillSelectionRule::kCentralWeight: {
      double best = 0;
      for (int k = -N; k <= N; ++k)
        if (k != 0) best = std::max(best, c.energy[k + N]);
      return 1 - best;
    }
    case HillSelectionRule::kStrip:
    default:
      return 1 - std::abs(c.value.imag()) / omega;
  }
}

}  // namespace

Selection SelectPhysical(const Eigenpairs& pairs, int n, int harmonics, double omega,
                         HillSelectionRule rule, double ambiguity_threshold) {
  const int N = harmonics;
  const int count = static_cast<int>(pairs.values.size());
  const int states = n;
  const int block = count > 0 ? static_cast<int>(pairs.vectors.rows()) / (2 * N + 1) : n;
  std::vector<Candidate> cands(count);
  double scale = omega;
  for (int i = 0; i < count; ++i) {
    Candidate& c = cands[i];
    c.value = pairs.values[i];
    c.energy = BlockEnergies(pairs.vectors.col(i), block, N);
    for (int v = -N; v <= N; ++v) c.centroid += v * c.energy[v + N];
    Score(c, N, omega, rule);
    if (std::isfinite(std::abs(c.value))) scale = std::max(scale, std::abs(c.value.real()));
  }
  // Members of one family differ by jkΩp; the tolerance covers the (larger) truncation error
  // of shifted members, which are effectively truncated closer to their edge.
  const double family_tol = 1e-6 * scale;
  auto same_family = [&](int i, int j) {
    const cd d = cands[i].value - cands[j].value;
    return std::abs(d.real()) <= family_tol &&
           std::abs(std::remainder(d.imag(), omega)) <= family_tol;
  };

  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return cands[a].score < cands[b].score; });

  // A further member at the same eigenvalue is a genuine multiple exponent only if it adds a
  // direction: a solver can return one eigenpair several times (shift-invert runs from
  // nearby shifts) or several combinations of one double eigenvector pair. Values split by more
  // than round-off (a defective pair, split by ~√eps) count as distinct.
  auto adds_direction = [&](int i, const std::vector<int>& members) {
    const double round_off = 1e-10 * scale;
    Eigen::MatrixXcd basis(pairs.vectors.rows(), 0);
    for (int j : members) {
      if (std::abs(cands[i].value - cands[j].value) > round_off) continue;
      basis.conservativeResize(Eigen::NoChange, basis.cols() + 1);
      basis.col(basis.cols() - 1) = pairs.vectors.col(j).normalized();
    }
    if (basis.cols() == 0) return true;
    const Eigen::VectorXcd x = pairs.vectors.col(i).normalized();
    const Eigen::MatrixXcd q = Eigen::HouseholderQR<Eigen::MatrixXcd>(basis).householderQ() *
                               Eigen::MatrixXcd::Identity(basis.rows(), basis.cols());
    return (x - q * (q.adjoint() * x)).norm() > 1e-3;
  };

  // Greedy: best score first; a family accepts further members only at the same eigenvalue
  // (a genuine multiple exponent), every other member is a runner-up.
  Selection sel;
  std::vector<int> family_of(count, -1);   // index into `families`
  std::vector<std::vector<int>> families;  // chosen members
  std::vector<double> runner_up;           // best runner-up score per family
  for (int i : order) {
    int f = -1;
    for (size_t g = 0; g < families.size() && f < 0; ++g)
      if (same_family(i, families[g][0])) f = static_cast<int>(g);
    if (f >= 0) {
      const int first = families[f][0];
      const bool same_value = std::abs(cands[i].value - cands[first].value) <= family_tol;
      if (same_value && !adds_direction(i, families[f])) {
        family_of[i] = f;  // a repeat of a chosen pair: neither a member nor a runner-up
        continue;
      }
      if (same_value && static_cast<int>(sel.chosen.size()) < states) {
        families[f].push_back(i);
        sel.chosen.push_back(i);
      } else if (runner_up[f] < 0) {
        runner_up[f] = cands[i].score;
      }
      family_of[i] = f;
      continue;
    }
    if (static_cast<int>(sel.chosen.size()) >= states) continue;
    family_of[i] = static_cast<int>(families.size());
    families.push_back({i});
    runner_up.push_back(-1);
    sel.chosen.push_back(i);
  }

  for (int i : sel.chosen) {
    const Candidate& c = cands[i];
    HillModeInfo info;
    info.centroid = c.centroid;
    info.tail_weight = c.energy.front() + (N > 0 ? c.energy.back() : 0);
    info.passed = c.passes;
    const double translated = TranslatedRunnerUpScore(c, N, omega, rule);
    const double r = runner_up[family_of[i]];
    const double runner = r >= 0 ? std::min(r, translated) : translated;
    info.selection_margin = std::max(0.0, runner - c.score);
    info.ambiguous = info.selection_margin < ambiguity_threshold;
    sel.passed += c.passes || info.ambiguous;  // ties are reported separately below
    sel.info.push_back(info);
  }

  if (static_cast<int>(sel.chosen.size()) < states) {
    std::ostringstream s;
    s << "only " << sel.chosen.size() << " of " << states
      << " exponent families were found among the Hill eigenvalues";
    sel.diagnostics.push_back(s.str());
  }
  if (sel.passed < static_cast<int>(sel.chosen.size())) {
    std::ostringstream s;
    s << "only " << sel.passed << " of " << states << " chosen eigenvalues pass the "
      << ToString(rule) << " rule";
    if (rule == HillSelectionRule::kCentroid) s << " (|energy centroid| < 1/2)";
    if (rule == HillSelectionRule::kCentralWeight) s << " (block 0 the heaviest)";
    if (rule == HillSelectionRule::kStrip) s << " (|Im λ| <= Ωp/2)";
    s << "; the others are the best-scoring members of their family: raise N";
    sel.diagnostics.push_back(s.str());
  }
  // Ties said once, with their count (a rotor at 3 azimuths has dozens).
  std::vector<double> ties;
  double smallest_margin = 1;
  for (size_t k = 0; k < sel.chosen.size(); ++k)
    if (sel.info[k].ambiguous) {
      ties.push_back(cands[sel.chosen[k]].value.real());
      smallest_margin = std::min(smallest_margin, sel.info[k].selection_margin);
    }
  if (!ties.empty()) {
    std::ostringstream s;
    s << ties.size() << (ties.size() == 1 ? " exponent (Re λ = " : " exponents (Re λ = ");
    for (size_t k = 0; k < std::min<size_t>(ties.size(), 4); ++k) s << (k ? ", " : "") << ties[k];
    if (ties.size() > 4) s << ", …";
    s << (ties.size() == 1 ? ") has its eigenvector" : ") have their eigenvectors")
      << " centred between two harmonic blocks (margin down to " << smallest_margin << " < "
      << ambiguity_threshold
      << "): a tie between λ and λ ± jΩp, which are the same exponent modulo jΩp (a negative "
         "real multiplier puts it on the strip edge Im λ = ±Ωp/2); the one with the larger "
         "Im λ is reported";
    sel.diagnostics.push_back(s.str());
  }
  return sel;
}

}  // namespace ltp::hill_internal
