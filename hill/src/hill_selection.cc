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

// The candidates scored under the rule, with the size the family tolerances are relative to.
struct ScoredCandidates {
  std::vector<Candidate> cands;  // parallel to the eigenpairs
  double scale = 0;              // max(Ωp, max |Re λ|)
};

ScoredCandidates ScoreCandidates(const Eigenpairs& pairs, int n, int N, double omega,
                                 HillSelectionRule rule) {
  const int count = static_cast<int>(pairs.values.size());
  const int block = count > 0 ? static_cast<int>(pairs.vectors.rows()) / (2 * N + 1) : n;
  ScoredCandidates scored;
  scored.cands.resize(count);
  scored.scale = omega;
  for (int i = 0; i < count; ++i) {
    Candidate& c = scored.cands[i];
    c.value = pairs.values[i];
    c.energy = BlockEnergies(pairs.vectors.col(i), block, N);
    for (int v = -N; v <= N; ++v) c.centroid += v * c.energy[v + N];
    Score(c, N, omega, rule);
    if (std::isfinite(std::abs(c.value)))
      scored.scale = std::max(scored.scale, std::abs(c.value.real()));
  }
  return scored;
}

// Members of one family differ by jkΩp (within family_tol).
bool SameFamily(const Candidate& a, const Candidate& b, double omega, double family_tol) {
  const cd d = a.value - b.value;
  return std::abs(d.real()) <= family_tol &&
         std::abs(std::remainder(d.imag(), omega)) <= family_tol;
}

// A further member at the same eigenvalue is a genuine multiple exponent only if it adds a
// direction: a solver can return one eigenpair several times (shift-invert runs from
// nearby shifts) or several combinations of one double eigenvector pair. Values split by more
// than round-off (a defective pair, split by ~√eps) count as distinct.
bool AddsDirection(const Eigenpairs& pairs, const ScoredCandidates& scored, int i,
                   const std::vector<int>& members) {
  const std::vector<Candidate>& cands = scored.cands;
  const double round_off = 1e-10 * scored.scale;
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
}

// The jΩp-shift families the chosen candidates head.
struct Families {
  std::vector<int> family_of;             // per candidate: index into `members`, or −1
  std::vector<std::vector<int>> members;  // chosen members of each family
  std::vector<double> runner_up;          // best runner-up score per family, −1 for none
};

// Greedy: best score first; a family accepts further members only at the same eigenvalue
// (a genuine multiple exponent), every other member is a runner-up. Fills sel->chosen.
Families ChooseFamilies(const Eigenpairs& pairs, const ScoredCandidates& scored, int states,
                        double omega, Selection* sel) {
  const std::vector<Candidate>& cands = scored.cands;
  const int count = static_cast<int>(cands.size());
  // The tolerance covers the (larger) truncation error of shifted members, which are
  // effectively truncated closer to their edge.
  const double family_tol = 1e-6 * scored.scale;
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return cands[a].score < cands[b].score; });

  Families fam;
  fam.family_of.assign(count, -1);
  for (int i : order) {
    int f = -1;
    for (size_t g = 0; g < fam.members.size() && f < 0; ++g)
      if (SameFamily(cands[i], cands[fam.members[g][0]], omega, family_tol))
        f = static_cast<int>(g);
    if (f >= 0) {
      const int first = fam.members[f][0];
      const bool same_value = std::abs(cands[i].value - cands[first].value) <= family_tol;
      if (same_value && !AddsDirection(pairs, scored, i, fam.members[f])) {
        fam.family_of[i] = f;  // a repeat of a chosen pair: neither a member nor a runner-up
        continue;
      }
      if (same_value && static_cast<int>(sel->chosen.size()) < states) {
        fam.members[f].push_back(i);
        sel->chosen.push_back(i);
      } else if (fam.runner_up[f] < 0) {
        fam.runner_up[f] = cands[i].score;
      }
      fam.family_of[i] = f;
      continue;
    }
    if (static_cast<int>(sel->chosen.size()) >= states) continue;
    fam.family_of[i] = static_cast<int>(fam.members.size());
    fam.members.push_back({i});
    fam.runner_up.push_back(-1);
    sel->chosen.push_back(i);
  }
  return fam;
}

// Per chosen candidate: its centroid, tail weight, pass and margin to its family's runner-up.
void DescribeChosen(const std::vector<Candidate>& cands, const Families& fam, int N, double omega,
                    HillSelectionRule rule, double ambiguity_threshold, Selection* sel) {
  for (int i : sel->chosen) {
    const Candidate& c = cands[i];
    HillModeInfo info;
    info.centroid = c.centroid;
    info.tail_weight = c.energy.front() + (N > 0 ? c.energy.back() : 0);
    info.passed = c.passes;
    const double translated = TranslatedRunnerUpScore(c, N, omega, rule);
    const double r = fam.runner_up[fam.family_of[i]];
    const double runner = r >= 0 ? std::min(r, translated) : translated;
    info.selection_margin = std::max(0.0, runner - c.score);
    info.ambiguous = info.selection_margin < ambiguity_threshold;
    sel->passed += c.passes || info.ambiguous;  // ties are reported separately below
    sel->info.push_back(info);
  }
}

// Missing families and chosen eigenvalues that fail the rule.
void ReportShortfalls(int states, HillSelectionRule rule, Selection* sel) {
  if (static_cast<int>(sel->chosen.size()) < states) {
    std::ostringstream s;
    s << "only " << sel->chosen.size() << " of " << states
      << " exponent families were found among the Hill eigenvalues";
    sel->diagnostics.push_back(
        {DiagnosticCode::kExponentFamiliesMissing, Severity::kWarning, s.str()});
  }
  if (sel->passed < static_cast<int>(sel->chosen.size())) {
    std::ostringstream s;
    s << "only " << sel->passed << " of " << states << " chosen eigenvalues pass the "
      << ToString(rule) << " rule";
    if (rule == HillSelectionRule::kCentroid) s << " (|energy centroid| < 1/2)";
    if (rule == HillSelectionRule::kCentralWeight) s << " (block 0 the heaviest)";
    if (rule == HillSelectionRule::kStrip) s << " (|Im λ| <= Ωp/2)";
    s << "; the others are the best-scoring members of their family: raise N";
    sel->diagnostics.push_back({DiagnosticCode::kSelectionRuleFailed, Severity::kWarning, s.str()});
  }
}

// Ties said once, with their count (a rotor at 3 azimuths has dozens).
void ReportTies(const std::vector<Candidate>& cands, double ambiguity_threshold, Selection* sel) {
  std::vector<double> ties;
  double smallest_margin = 1;
  for (size_t k = 0; k < sel->chosen.size(); ++k)
    if (sel->info[k].ambiguous) {
      ties.push_back(cands[sel->chosen[k]].value.real());
      smallest_margin = std::min(smallest_margin, sel->info[k].selection_margin);
    }
  if (ties.empty()) return;
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
  sel->diagnostics.push_back({DiagnosticCode::kBranchAmbiguous, Severity::kNote, s.str()});
}

}  // namespace

Selection SelectPhysical(const Eigenpairs& pairs, int n, int harmonics, double omega,
                         HillSelectionRule rule, double ambiguity_threshold) {
  const int N = harmonics;
  const int states = n;
  const ScoredCandidates scored = ScoreCandidates(pairs, n, N, omega, rule);
  Selection sel;
  const Families fam = ChooseFamilies(pairs, scored, states, omega, &sel);
  DescribeChosen(scored.cands, fam, N, omega, rule, ambiguity_threshold, &sel);
  ReportShortfalls(states, rule, &sel);
  ReportTies(scored.cands, ambiguity_threshold, &sel);
  return sel;
}

}  // namespace ltp::hill_internal
