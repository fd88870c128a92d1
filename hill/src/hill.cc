// Hill analysis: coefficients → Hill matrix → eigenpairs → physical selection → error
// estimates (N vs N+Δ, a-priori bound, Koopman–Hill cross-check) → result.
#include "ltp/hill/hill.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "hill_internal.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/floquet/detail/rigid_body.h"
#include "ltp/hill/hill_solver_choice.h"
#include "ltp/integrate/detail/condition_number.h"

namespace ltp {
namespace {

// Condition numbers κ_k of the Floquet exponents as eigenvalues, from the mode matrix Ξ(0)
// (columns: the selected eigenvectors summed over their blocks, normalised): κ_k is the norm
// of row k of Ξ(0)⁻¹, as in the monodromy route; in display order, and at least 1.
std::vector<double> EigenvalueConditions(Eigen::MatrixXcd xi0, const std::vector<int>& order) {
  std::vector<double> kappa(order.size(), 1.0);
  if (xi0.cols() != xi0.rows() || xi0.cols() == 0) return kappa;
  for (Eigen::Index k = 0; k < xi0.cols(); ++k) {
    const double norm = xi0.col(k).norm();
    if (norm > 0) xi0.col(k) /= norm;
  }
  const Eigen::FullPivLU<Eigen::MatrixXcd> lu(xi0);
  if (!lu.isInvertible()) {
    kappa.assign(order.size(), std::numeric_limits<double>::infinity());
    return kappa;
  }
  const Eigen::MatrixXcd inverse = lu.inverse();
  for (size_t j = 0; j < order.size(); ++j) kappa[j] = std::max(1.0, inverse.row(order[j]).norm());
  return kappa;
}

using cd = std::complex<double>;
using hill_internal::Eigenpairs;
constexpr double kPi = std::numbers::pi;

// How far the frozen eigenvalues of A(t) move over the period (1/s; 16 samples, the largest
// Hausdorff distance between the eigenvalue sets of two samples): a solution's local growth and
// frequency wander that far, so its Fourier content spans about that many rad/s, and a
// truncation with N·Ωp below it cannot represent it yet — whatever N vs N+Δ says (Mathieu
// q = 1e5: frozen eigenvalues between ±447 and ±447j, N = 200 gave ±21.7 with a change of
// 1.9 1/s against the true ±170). Measured between samples, not against the eigenvalues of the
// averaged A_0: a rotating frame x = R(θ(t)) z of z' = diag(±120) z has frozen eigenvalues
// near ±120 at every t, far from A_0's −0.25 ± j, yet its modes hold a few harmonics only.
double FrozenEigenvalueSpread(const FourierMatrix& A, double omega) {
  const int n = A.rows();
  if (n == 0) return 0;
  constexpr int kSamples = 16;
  std::vector<Eigen::VectorXcd> sets;
  for (int s = 0; s < kSamples; ++s) {
    const double t = (s + 0.5) / kSamples * 2 * kPi / omega;
    const Eigen::MatrixXd frozen = A.Evaluate(t, omega);
    sets.push_back(Eigen::EigenSolver<Eigen::MatrixXd>(frozen, false).eigenvalues());
  }
  auto directed = [](const Eigen::VectorXcd& from, const Eigen::VectorXcd& to) {
    double d = 0;
    for (Eigen::Index i = 0; i < from.size(); ++i)
      d = std::max(d, (to.array() - from(i)).abs().minCoeff());
    return d;
  };
  double spread = 0;
  for (int a = 0; a < kSamples; ++a)
    for (int b = a + 1; b < kSamples; ++b)
      spread = std::max({spread, directed(sets[a], sets[b]), directed(sets[b], sets[a])});
  return spread;
}

// The mode of a selected Hill eigenvalue μ: its multiplier's logarithm and branch. `tie`: the
// selection found μ and μ ± jΩp equally centred, so a multiplier with arg ρ within round-off of
// ±π is the negative real one, reported with arg ρ = +π as (−π, π] says.
FloquetMode MakeMode(cd mu, double T, double omega, bool tie) {
  double arg = std::remainder(mu.imag() * T, 2 * kPi);
  if (arg <= -kPi || (tie && arg < -kPi * (1 - 1e-8))) arg += 2 * kPi;
  const int branch = static_cast<int>(std::lround((mu.imag() - arg / T) / omega));
  return MakeFloquetMode(cd(mu.real() * T, arg), branch, T);
}

// Eigenpairs with the requested solver; the structured one falls back to dense when it misses
// exponents and the dense matrix fits.
Eigenpairs Solve(const FourierMatrix& A, double omega, int N, const HillOptions& o,
                 const std::vector<cd>& shifts, HillSolver& solver_used,
                 std::vector<Diagnostic>& diagnostics) {
  if (o.solver == HillSolver::kDense) {
    hill_internal::CheckDenseMemory(A.rows(), N, o.max_dense_bytes);
    solver_used = HillSolver::kDense;
    Eigenpairs p = hill_internal::SolveDense(A, omega, N);
    diagnostics.insert(diagnostics.end(), p.notes.begin(), p.notes.end());
    return p;
  }
  solver_used = HillSolver::kStructured;
  Eigenpairs p = hill_internal::SolveStructured(A, omega, N, shifts);
  diagnostics.insert(diagnostics.end(), p.notes.begin(), p.notes.end());
  return p;
}

HillResult AnalyzeFixed(const FourierMatrix& A, const FourierFit* fit, double T, int N,
                        const HillOptions& o);

// AnalyzeFixed's steps, in order.

// Eigenpairs by the requested solver and the n physical ones among them; the structured solver
// falls back to the dense one when it found too few and the dense matrix fits.
struct Solved {
  Eigenpairs pairs;
  hill_internal::Selection sel;
};
Solved SolveAndSelect(const FourierMatrix& A, double omega, int N, const HillOptions& o,
                      HillResult& r) {
  const int n = A.rows();
  std::vector<cd> shifts = o.expected;
  if (shifts.empty()) {
    const Eigen::VectorXcd e = Eigen::ComplexEigenSolver<Eigen::MatrixXcd>(A[0]).eigenvalues();
    shifts.assign(e.data(), e.data() + e.size());
  }
  Eigenpairs pairs = Solve(A, omega, N, o, shifts, r.solver, r.diagnostics);
  hill_internal::Selection sel;
  if (pairs.ok)
    sel = hill_internal::SelectPhysical(pairs, n, N, omega, o.selection, o.ambiguity_threshold);
  if (o.solver == HillSolver::kStructured && o.structured_fallback &&
      static_cast<int>(sel.chosen.size()) < n) {
    const double bytes = std::pow((2.0 * N + 1) * n, 2) * sizeof(cd);
    if (bytes <= o.max_dense_bytes) {
      r.diagnostics.push_back({DiagnosticCode::kHillSolverFellBack, Severity::kNote,
                               "structured solver found " + std::to_string(sel.chosen.size()) +
                                   " of " + std::to_string(n) + " exponents; fell back to dense"});
      HillOptions dense = o;
      dense.solver = HillSolver::kDense;
      pairs = Solve(A, omega, N, dense, shifts, r.solver, r.diagnostics);
      r.dense_fallback = true;
      if (pairs.ok)
        sel = hill_internal::SelectPhysical(pairs, n, N, omega, o.selection, o.ambiguity_threshold);
    }
  }
  r.diagnostics.insert(r.diagnostics.end(), sel.diagnostics.begin(), sel.diagnostics.end());
  r.eigenvalues = pairs.values;
  return {std::move(pairs), std::move(sel)};
}

// The selected modes in the monodromy route's order, with their eigen-residuals, and a note
// when the eigenvectors reach the truncation edge. Returns the eigenvalue condition numbers in
// that order.
std::vector<double> CollectModes(const FourierMatrix& A, double omega, double T, int N,
                                 const Solved& solved, double norm_h, HillResult& r) {
  const int n = A.rows();
  // Modes, sorted as AnalyzeFloquet sorts them: |frequency|, positive first, then Re λ.
  std::vector<FloquetMode> modes;
  std::vector<HillModeInfo> infos;
  std::vector<Eigen::VectorXcd> vectors;
  Eigen::MatrixXcd xi0 =
      Eigen::MatrixXcd::Zero(n, static_cast<Eigen::Index>(solved.sel.chosen.size()));
  for (size_t k = 0; k < solved.sel.chosen.size(); ++k) {
    const int i = solved.sel.chosen[k];
    const Eigen::VectorXcd x = solved.pairs.vectors.col(i);
    for (int v = 0; v <= 2 * N; ++v) xi0.col(k) += x.segment(static_cast<Eigen::Index>(v) * n, n);
    HillModeInfo info = solved.sel.info[k];
    // A tie between λ and its neighbour λ ± jΩp (centroid ±1/2: the strip edge of a negative
    // real multiplier) is one exponent; report the member with the larger Im λ, as the
    // monodromy route does, so both routes print +Ωp/2 for a 2:1 parametric resonance.
    cd value = solved.pairs.values[i];
    int shift = 0;  // blocks: member λ + jΩp is centred one block up
    if (info.ambiguous && info.centroid > 0 && N > 0) {
      value += cd(0, omega);
      info.centroid -= 1;
      shift = 1;
    }
    Eigen::VectorXcd v = x / x.norm();  // the eigenvector of the reported value
    if (shift == 1) {  // λ + jΩp's vector: block v is block v + 1 of λ's (block N + 1 is beyond)
      v.head(v.size() - n) = v.tail(v.size() - n).eval();
      v.tail(n).setZero();
      v /= v.norm();
    }
    vectors.push_back(std::move(v));
    FloquetMode m = MakeMode(value, T, omega, info.ambiguous);
    const std::vector<double> e = hill_internal::BlockEnergies(x, n, N);
    m.central_weight = e[N + shift];
    m.branch_margin = 0.5 - std::min(0.5, std::abs(info.centroid));
    info.residual =
        (hill_internal::HillMultiply(A, omega, N, x) - solved.pairs.values[i] * x).norm() /
        (norm_h * x.norm());
    m.eigvec_residual = info.residual;
    modes.push_back(m);
    infos.push_back(info);
  }
  const std::vector<int> order = ModeDisplayOrder(modes);  // the monodromy route's order
  r.mode_shapes.resize(n, static_cast<Eigen::Index>(order.size()));
  r.eigenvectors.resize(static_cast<Eigen::Index>(2 * N + 1) * n,
                        static_cast<Eigen::Index>(order.size()));
  for (size_t j = 0; j < order.size(); ++j) {
    r.modes.push_back(modes[order[j]]);
    r.info.push_back(infos[order[j]]);
    r.mode_shapes.col(static_cast<Eigen::Index>(j)) = xi0.col(order[j]);
    r.eigenvectors.col(static_cast<Eigen::Index>(j)) = vectors[order[j]];
  }
  r.ok = static_cast<int>(r.modes.size()) == n;
  if (!r.ok)
    r.failure = "found " + std::to_string(r.modes.size()) + " of " + std::to_string(n) +
                " Floquet exponents among the Hill eigenvalues";
  r.max_real_exponent = internal::MaxRealExponent(r.modes);

  double worst_tail = 0;
  for (const HillModeInfo& i : r.info) worst_tail = std::max(worst_tail, i.tail_weight);
  if (worst_tail > 1e-8) {
    std::ostringstream s;
    s << "eigenvectors reach the truncation edge (tail weight " << worst_tail
      << " on blocks ±N): raise N";
    r.diagnostics.push_back(
        {DiagnosticCode::kEigenvectorsAtTruncationEdge, Severity::kWarning, s.str()});
  }

  return EigenvalueConditions(xi0, order);
}

std::vector<cd> ExponentsOf(const HillResult& r) {
  std::vector<cd> v;
  for (const FloquetMode& m : r.modes) v.push_back(m.exponent);
  return v;
}

// The factor that turns the change e(N) − e(N+Δ) into a bound on e(N), for the slowest
// convergence the coefficients of A allow. Algebraic decay e(N) ∝ N^−p: the change is only
// 1 − (N/(N+Δ))^p of e(N) (30 % short for Meissner's p = 3 at Δ = N/2); the p = 1 factor
// (N+Δ)/Δ covers every p >= 1. Exponential decay ||A_w|| ∝ e^{−b|w|}: the exponents converge
// at least like e^{−bN} (the measured rate is about 2b), so the change is at least
// 1 − e^{−bΔ} of e(N) — a factor that matters only for slow decay (Poisson kernel r = 0.9:
// b = 0.105, 1.23 at Δ = 16, where the bare change fell 4 % short). A finite series converges
// faster than any exponential: factor 1.
double TruncationTailFactor(const HillDecay& decay, int N, int delta) {
  if (delta <= 0) return 1;
  if (decay.kind == FourierDecay::kAlgebraic) return double(N + delta) / delta;
  if (decay.kind == FourierDecay::kExponential && decay.rate > 0)
    return 1 / -std::expm1(-decay.rate * delta);
  return 1;
}

// Selected modes whose reported exponent at N + Δ lies whole multiples of Ωp away from the one
// at N. A Floquet exponent's eigenvector is centred on block 0 at every N, so its branch stays
// put (one step is allowed at a tie λ / λ ± jΩp). Eigenvalues of the truncation edge have
// eigenvectors pinned to blocks ±N and Im λ ≈ ±NΩp, so they move with N, while modulo jΩp they
// do not change at all: N vs N + Δ alone would call them converged (the reducible system
// x = R(θ(t)) z with exponents ±120 at N = 16: a spurious pair at −0.25 ± 15.9j, change 6e-14).
int CountMovingBranches(const HillResult& r, const HillResult& r2, double omega) {
  const std::vector<cd> a = ExponentsOf(r), b = ExponentsOf(r2);
  const std::vector<int> match = MatchExponentIndices(a, b, omega);
  int moved = 0;
  for (size_t k = 0; k < match.size(); ++k) {
    if (match[k] < 0) continue;
    const long jumps = std::lround((a[k].imag() - b[match[k]].imag()) / omega);
    const bool tie = r.info[k].ambiguous || r2.info[match[k]].ambiguous;
    moved += std::abs(jumps) > (tie ? 1 : 0);
  }
  return moved;
}

// The truncation estimate: the same analysis at N + Δ, and at N + 2Δ before the asymptotic
// regime. Returns whether that third solve measured the convergence rate.
bool EstimateTruncation(const FourierMatrix& A, const FourierFit* fit, double T, int N,
                        const HillOptions& o, HillResult& r) {
  const double omega = 2 * kPi / T;
  // Truncation estimate: the same analysis at N + Δ (shifts from this solve).
  bool rate_checked = false;  // a third solve measured the convergence rate
  if (o.delta_harmonics >= 0 && r.ok) {
    r.delta_harmonics = o.delta_harmonics > 0 ? o.delta_harmonics : std::max(2, (N + 1) / 2);
    HillOptions o2 = o;
    o2.delta_harmonics = -1;
    o2.koopman_check = false;
    o2.expected.clear();
    for (const FloquetMode& m : r.modes) o2.expected.push_back(m.exponent);
    try {
      const HillResult r2 = AnalyzeFixed(A, fit, T, N + r.delta_harmonics, o2);
      const std::vector<cd> a = ExponentsOf(r), b = ExponentsOf(r2);
      const std::vector<double> d = MatchExponents(a, b, omega);
      double change = 0;
      for (size_t k = 0; k < d.size(); ++k) {
        r.info[k].truncation_change = d[k];
        change = std::max(change, d[k]);
      }
      // The change e(N) − e(N+Δ) is only part of e(N): scale it by the slowest convergence
      // the coefficients of A allow (docs/hill-method.md, "Truncation estimate").
      const double factor = TruncationTailFactor(r.decay, N, r.delta_harmonics);
      change *= factor;
      for (auto& i : r.info)
        if (i.truncation_change) *i.truncation_change *= factor;
      // Modes whose reported branch moves with N are not Floquet exponents (below).
      if (const int moved = CountMovingBranches(r, r2, omega); moved > 0) {
        std::ostringstream s;
        s << moved << " selected eigenvalue" << (moved > 1 ? "s move" : " moves")
          << " with the truncation (Im λ shifts by whole multiples of Ωp from N = " << N
          << " to N + Δ = " << N + r.delta_harmonics
          << "): eigenvalues of the truncation edge, not Floquet exponents; no error bound "
             "(raise N, or use the monodromy route)";
        r.diagnostics.push_back(
            {DiagnosticCode::kBranchesMoveWithTruncation, Severity::kFailure, s.str()});
        change = std::numeric_limits<double>::infinity();
        r.ok = false;
        r.failure = s.str();
      }
      r.truncation_estimate = change;
      // Pre-asymptotic (eigenvectors at the truncation edge, and a change above 1e-6 of the
      // largest exponent or a large edge weight): one more solve at N + 2Δ gives the ratio q of
      // successive changes. Geometric convergence then bounds the error by change/(1 − q); no
      // shrinking (q ≥ 0.9) means no bound at all. (At N = 1 on tower-rotor the change was 0.47 of
      // the error.)
      double tail = 0, scale = 1;
      for (const HillModeInfo& i : r.info) tail = std::max(tail, i.tail_weight);
      for (const FloquetMode& m : r.modes) scale = std::max(scale, std::abs(m.exponent));
      // A tail above 1e-3 is the truncation edge whatever the size of the change (stiff.yaml,
      // structured solver at N = 16: tail 0.025, change 2.45e-9 for an error of 2.62e-9).
      if (std::isfinite(change) && tail > 1e-8 && (change > 1e-6 * scale || tail > 1e-3)) {
        rate_checked = true;
        o2.expected.clear();
        for (const FloquetMode& m : r2.modes) o2.expected.push_back(m.exponent);
        const HillResult r3 = AnalyzeFixed(A, fit, T, N + 2 * r.delta_harmonics, o2);
        double next = 0;
        for (double x : MatchExponents(b, ExponentsOf(r3), omega)) next = std::max(next, x);
        const double q = change > 0 ? next / change : 0;
        change = q < 0.5   ? 2 * change
                 : q < 0.9 ? change / (1 - q)
                           : std::numeric_limits<double>::infinity();
        if (q >= 0.9)
          r.diagnostics.push_back(
              {DiagnosticCode::kTruncationNotConverged, Severity::kWarning,
               "truncation not converging: the change from N + Δ to N + 2Δ is " +
                   std::to_string(q) + " of the one from N to N + Δ (raise N)"});
      }
      r.truncation_estimate = change;
    } catch (const ResourceError&) {
      r.delta_harmonics = 0;
      r.diagnostics.push_back(
          {DiagnosticCode::kTruncationLimited, Severity::kWarning,
           "N + Δ estimate skipped: the larger truncation does not fit in memory"});
    }
  }

  return rate_checked;
}

void CheckResolution(const FourierMatrix& A, double omega, int N, bool rate_checked,
                     HillResult& r) {
  // Resolution: below N·Ωp ≈ the frozen-eigenvalue spread the truncation may not have started
  // to converge, and a small N vs N+Δ change alone proves nothing. (A third solve that measured
  // geometric convergence is evidence: stiff.yaml's exponents converge at N = 16 although its
  // frozen eigenvalues swing by ±100.)
  if (!rate_checked && r.truncation_estimate && std::isfinite(*r.truncation_estimate)) {
    const double spread = FrozenEigenvalueSpread(A, omega);
    if (N * omega < spread) {
      std::ostringstream s;
      s << "N·Ωp = " << N * omega << " 1/s is below the spread of the frozen eigenvalues of A(t) ("
        << spread << " 1/s): the truncation cannot resolve the solutions yet, so the N vs N+Δ "
        << "change is no error bound (raise N to at least " << std::ceil(spread / omega) << ")";
      r.diagnostics.push_back({DiagnosticCode::kTruncationUnresolved, Severity::kWarning, s.str()});
      r.truncation_estimate = std::numeric_limits<double>::infinity();
    }
  }
}

// Returns Koopman–Hill's own exponent error bound (infinite when the check did not run).
double KoopmanHillCheck(const FourierMatrix& A, double omega, double T, int N, const HillOptions& o,
                        double norm_h, HillResult& r) {
  // Koopman–Hill cross-check and the a-priori bound (which needs its eigenvectors).
  r.apriori_phi_bound = KoopmanHillBound(r.decay, N, T);
  double kh_own = std::numeric_limits<double>::infinity();  // KH's own exponent error bound
  if (o.koopman_check && r.ok && r.matrix_size <= o.koopman_max_size) {
    const Eigen::MatrixXcd phi = KoopmanHillTransition(A, omega, N, T);
    if (!phi.allFinite()) {  // Eigen's eigensolver reads past its arrays on inf/NaN input
      r.apriori_phi_bound = std::numeric_limits<double>::infinity();
      r.diagnostics.push_back(
          {DiagnosticCode::kKoopmanHillSkipped, Severity::kNote,
           "Koopman–Hill check skipped: its transition matrix overflows (multipliers beyond "
           "the range of doubles); no a-priori exponent bound"});
      return kh_own;
    }
    // The bound holds in exact arithmetic; the computed expm adds round-off ~ eps ||H T|| ||Φ||.
    r.apriori_phi_bound +=
        16 * std::numeric_limits<double>::epsilon() * (2 * N + 1) * std::max(1.0, phi.stableNorm());
    // Finite entries near the top of the double range (multipliers e^{691}) still overflow
    // inside the eigensolver, which then reads past its arrays (AddressSanitizer): solve for
    // Φ/s, s its largest entry, and add log s back.
    const double s = phi.cwiseAbs().maxCoeff();
    Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(s > 0 ? Eigen::MatrixXcd(phi / s) : phi);
    std::vector<cd> kh;
    for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k) {
      const cd log_rho = std::log(es.eigenvalues()(k)) + (s > 0 ? std::log(s) : 0.0);
      r.koopman_log_multipliers.push_back(log_rho);
      kh.push_back(log_rho / T);
    }
    std::vector<cd> hill;
    for (const FloquetMode& m : r.modes) hill.push_back(m.exponent);
    double gap = 0;
    for (double d : MatchExponents(hill, kh, omega)) gap = std::max(gap, d);
    r.koopman_discrepancy = gap;
    // Bauer–Fike: |Δρ| <= κ(V) ||ΔΦ||; |Δ log ρ| <= −log(1 − |Δρ|/|ρ|).
    Eigen::MatrixXcd V = es.eigenvectors();
    for (Eigen::Index k = 0; k < V.cols(); ++k) V.col(k).normalize();
    const double kappa = internal::ConditionNumber(V);
    double worst = 0;
    for (const FloquetMode& m : r.modes) {
      const double delta = kappa * r.apriori_phi_bound / std::exp(m.exponent.real() * T);
      worst = std::max(
          worst, delta < 1 ? -std::log1p(-delta) / T : std::numeric_limits<double>::infinity());
    }
    kh_own = worst;
    // Plus the round-off floor of the eigenvalue solve (backward error ~ eps ||H_N||).
    r.apriori_bound = worst + gap + 4 * std::numeric_limits<double>::epsilon() * norm_h;
  } else if (o.koopman_check && r.ok) {
    r.diagnostics.push_back(
        {DiagnosticCode::kKoopmanHillSkipped, Severity::kNote,
         "Koopman–Hill check skipped (Hill matrix larger than koopman_max_size = " +
             std::to_string(o.koopman_max_size) + "); no a-priori exponent bound"});
  }
  return kh_own;
}

// The error estimate from the truncation change, the Koopman–Hill gap, the Liouville deficit
// and the round-off floor; the verdict from it.
void FinishEstimate(const FourierMatrix& A, const std::vector<double>& kappa, double norm_h,
                    double kh_own, HillResult& r) {
  const int n = A.rows();
  // The error estimate: the N vs N+Δ change (no convergence evidence without it: the
  // Koopman–Hill gap then stands in).
  std::optional<double> estimate =
      r.truncation_estimate ? r.truncation_estimate : r.koopman_discrepancy;
  // The Koopman–Hill projection converges more slowly than Hill's eigenvalues, so its gap
  // mostly measures itself (3.6e-5 on Mathieu at N = 4 where Hill is at 4e-13). Beyond its own
  // a-priori bound, though, it means the selection picked a wrong eigenvalue.
  if (r.koopman_discrepancy &&
      *r.koopman_discrepancy > kh_own + r.truncation_estimate.value_or(0.0)) {
    estimate = std::max(estimate.value_or(0.0), *r.koopman_discrepancy);
    r.diagnostics.push_back({DiagnosticCode::kKoopmanHillDisagrees, Severity::kWarning,
                             "Koopman–Hill disagrees with the selected exponents beyond its own "
                             "truncation bound: the selection may have picked a wrong eigenvalue"});
  }
  // Liouville: Σ Re λ_k = (1/T) ∫ tr A = Re tr A_0 for the true exponents, whatever the
  // truncation. A selection that picked spurious eigenvalues (or missed a mode, as on stiff
  // systems whose exponents differ by far more than Ωp) breaks it even when N vs N+Δ agree.
  // The usual culprit is one missed (or spurious) exponent, which then carries the whole
  // deficit, so the estimate is never below it (|deficit|/n would be a strict lower bound
  // only; the dense solver's stiff.yaml result missed +150 with a change of 896 against an
  // error of 1045 and a deficit of 1126).
  if (r.ok && estimate) {
    double sum = 0, scale = 1;
    for (const FloquetMode& m : r.modes) {
      sum += m.exponent.real();
      scale = std::max(scale, std::abs(m.exponent));
    }
    const double trace = A[0].trace().real();
    const double deficit = std::abs(sum - trace);
    if (deficit > n * std::max(*estimate, 1e-9 * scale)) {
      std::ostringstream s;
      s << "Liouville check failed: Σ Re λ = " << sum << " 1/s but the mean of tr A(t) is " << trace
        << " 1/s, so the selected eigenvalues are not all Floquet exponents (raise N, or use the "
           "monodromy route); no error bound";
      r.diagnostics.push_back({DiagnosticCode::kLiouvilleCheckFailed, Severity::kFailure, s.str()});
      r.failure = s.str();
      // Errors of the other exponents can cancel part of the deficit (dense stiff.yaml: deficit
      // 973, error 1018), so a failed check leaves no finite bound, and the result is not ok.
      estimate = std::numeric_limits<double>::infinity();
      r.ok = false;
    }
    // One wrong exponent carries the deficit, less what the other n − 1 errors (each within the
    // estimate) cancel of it: deficit + (n − 1)·estimate bounds its error (dense stiff.yaml at
    // N = 12: deficit 879, error 903, where the deficit alone fell 3 % short).
    if (deficit > *estimate) estimate = deficit + (n - 1) * *estimate;
  }
  // Round-off: the eigen-residual ||H x − λ x|| / ||x|| of each selected pair is an a-posteriori
  // bound for a well-conditioned eigenvalue, and it is local (far blocks of x are negligible,
  // so it does not grow with N·Ωp as eps·||H_N|| would); 4× for the residual's own round-off.
  // The residual bounds the eigenvalue's error only when it is well conditioned; a non-normal
  // problem (stiff.yaml's triangular A) moves it by κ times as much, a defective one by about
  // the square root of the backward error (as in the monodromy route's floor).
  double floor = 0;
  for (size_t k = 0; k < r.info.size(); ++k) {
    const double backward = 4 * r.info[k].residual * norm_h;
    const double kappa_k = k < kappa.size() ? kappa[k] : 1.0;
    floor = std::max(
        floor, std::min(kappa_k * backward, 2 * std::sqrt(backward * norm_h)) +
                   2 * std::numeric_limits<double>::epsilon() * std::abs(r.modes[k].exponent));
  }
  if (!r.modes.empty())
    r.error_estimate = estimate ? *estimate + floor : std::numeric_limits<double>::infinity();
  // The verdict needs max Re λ beyond the error estimate (as the monodromy route reports it).
  // The verdict is set once the rigid-body modes are known (AnalyzeHill).
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, r.error_estimate);
  r.stable = r.verdict == StabilityVerdict::kStable;
}

// One Hill analysis at fixed period and N (no period doubling).
HillResult AnalyzeFixed(const FourierMatrix& A, const FourierFit* fit, double T, int N,
                        const HillOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const double omega = 2 * kPi / T;
  HillResult r;
  r.states = A.rows();
  r.harmonics = N;
  r.matrix_size = (2 * N + 1) * A.rows();
  r.period = T;
  r.selection = o.selection;
  r.selection_rule = std::string(ToString(r.selection));
  const Solved solved = SolveAndSelect(A, omega, N, o, r);
  if (!solved.pairs.ok) {
    r.failure = solved.pairs.notes.empty() ? "the eigenvalues of the Hill matrix were not found"
                                           : solved.pairs.notes.front().text;
    r.elapsed_s = SecondsSince(start);
    return r;
  }
  const double norm_h = hill_internal::HillNormEstimate(A, omega, N);
  const std::vector<double> kappa = CollectModes(A, omega, T, N, solved, norm_h, r);
  r.decay = FitHillDecay(A, fit, N, T);  // also tells the truncation estimate the decay kind
  const bool rate_checked = EstimateTruncation(A, fit, T, N, o, r);
  CheckResolution(A, omega, N, rate_checked, r);
  const double kh_own = KoopmanHillCheck(A, omega, T, N, o, norm_h, r);
  FinishEstimate(A, kappa, norm_h, kh_own, r);
  r.elapsed_s = SecondsSince(start);
  return r;
}

// An unconverged FFT fit (a discontinuous A(t): coefficients ~1/w, aliased by O(w/S²) and
// worse) perturbs every exponent whatever N — on a sawtooth at N = 256 by 1e-9, ten times the
// truncation error. The same analysis on a fit with half the samples changes the exponents by
// at least the error of the full fit (the aliasing error falls at least like 1/S); that change
// is added to the estimate (docs/hill-method.md).
void FitErrorEstimate(const PeriodicSystem& system, const HillOptions& options,
                      const FourierFit& fit, HillResult& r) {
  FourierFitOptions coarse_options = options.fourier;
  coarse_options.max_samples = fit.samples / 2;
  auto f = [&system](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalA(t, out); };
  const FourierFit coarse =
      FitFourier(f, system.states(), system.states(), system.period(), coarse_options);
  HillOptions o = options;
  o.delta_harmonics = -1;
  o.koopman_check = false;
  o.expected.clear();
  std::vector<cd> fine;
  for (const FloquetMode& m : r.modes) {
    fine.push_back(m.exponent);
    o.expected.push_back(m.exponent);
  }
  const HillResult c = AnalyzeFixed(coarse.series, &coarse, r.period, r.harmonics, o);
  std::vector<cd> other;
  for (const FloquetMode& m : c.modes) other.push_back(m.exponent);
  r.fourier_fit_error = std::numeric_limits<double>::infinity();
  if (other.size() == fine.size()) {
    r.fourier_fit_error = 0;
    for (double d : MatchExponents(fine, other, 2 * kPi / r.period))
      r.fourier_fit_error = std::max(r.fourier_fit_error, d);
  }
  if (r.error_estimate) *r.error_estimate += r.fourier_fit_error;
  std::ostringstream s;
  s << "Fourier fit of A(t) not converged: its error moves the exponents by about "
    << r.fourier_fit_error << " 1/s whatever N (" << fit.samples << " vs " << coarse.samples
    << " samples); included in the error estimate";
  r.diagnostics.push_back({DiagnosticCode::kFourierFitNotConverged, Severity::kWarning, s.str()});
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, r.error_estimate);
  r.stable = r.verdict == StabilityVerdict::kStable;
}

}  // namespace

std::string_view ToString(std::optional<HillConvergence> convergence) {
  if (!convergence) return "";
  return *convergence == HillConvergence::kExponential ? "exponential" : "algebraic";
}

std::string_view ToString(HillSolver solver) {
  switch (solver) {
    case HillSolver::kDense:
      return "dense";
    case HillSolver::kStructured:
      return "structured";
    case HillSolver::kAuto:
      return "auto";
  }
  return "?";
}

std::optional<HillSolver> ParseHillSolver(std::string_view name) {
  if (name == "dense") return HillSolver::kDense;
  if (name == "structured") return HillSolver::kStructured;
  if (name == "auto") return HillSolver::kAuto;
  return std::nullopt;
}

std::string_view ToString(HillSelectionRule rule) {
  switch (rule) {
    case HillSelectionRule::kCentroid:
      return "centroid";
    case HillSelectionRule::kCentralWeight:
      return "central-weight";
    case HillSelectionRule::kStrip:
      return "strip";
  }
  return "?";
}

std::optional<HillSelectionRule> ParseHillSelectionRule(std::string_view name) {
  if (name == "centroid") return HillSelectionRule::kCentroid;
  if (name == "central-weight") return HillSelectionRule::kCentralWeight;
  if (name == "strip") return HillSelectionRule::kStrip;
  return std::nullopt;
}

void HillOptions::Validate() const {
  const OptionCheck check("HillOptions");
  if (harmonics < 0) check.Fail("harmonics", harmonics, "harmonics >= 0");
  if (!(ambiguity_threshold >= 0 && ambiguity_threshold < 1))
    check.Fail("ambiguity_threshold", ambiguity_threshold, "0 <= ambiguity_threshold < 1");
  if (delta_harmonics < -1)
    check.Fail("delta_harmonics", delta_harmonics, ">= -1 (0 = automatic, -1 = off)");
  if (koopman_max_size < 0)
    check.Fail("koopman_max_size", koopman_max_size, "koopman_max_size >= 0");
  if (!(max_dense_bytes > 0) || !std::isfinite(max_dense_bytes))
    check.Fail("max_dense_bytes", max_dense_bytes, "finite and > 0");
  if (!(max_work_seconds >= 0)) check.Fail("max_work_seconds", max_work_seconds, ">= 0");
  if (!(announce_work_seconds >= 0))
    check.Fail("announce_work_seconds", announce_work_seconds, ">= 0");
  for (const auto& e : expected)
    if (!std::isfinite(e.real()) || !std::isfinite(e.imag()))
      check.Fail("expected", e.real() + e.imag(), "every expected exponent finite");
}

namespace {

// Rows of the Hill matrices at N and, for the estimate, at N + Δ (0 when Δ is off).
std::pair<double, double> HillRows(int n, int N, const HillOptions& o) {
  const int delta = o.delta_harmonics < 0   ? -1
                    : o.delta_harmonics > 0 ? o.delta_harmonics
                                            : std::max(2, (N + 1) / 2);
  return {static_cast<double>(n) * (2.0 * N + 1),
          delta < 0 ? 0.0 : static_cast<double>(n) * (2.0 * (N + delta) + 1)};
}

// Dense: the eigen-solves at N and N + Δ and the Koopman–Hill expm cost about 4 complex
// products per size³ (calibrated on Mathieu, m = 402…1602: 1.3–78 s).
WorkEstimate DenseHillWork(int n, int N, const HillOptions& o, double seconds_per_cube) {
  const auto [m, m2] = HillRows(n, N, o);
  const bool koopman = o.koopman_check && m <= o.koopman_max_size;
  constexpr double kProductsPerCube = 4;
  WorkEstimate w;
  w.evaluations = m * m * m * (koopman ? 3 : 1) + m2 * m2 * m2;
  w.seconds_per_evaluation = kProductsPerCube * seconds_per_cube;
  w.fewest_evaluations = w.evaluations / 3;
  std::ostringstream basis;
  basis << "dense Hill eigen-solves of size " << static_cast<long>(m) << (m2 > 0 ? " and " : "")
        << (m2 > 0 ? std::to_string(static_cast<long>(m2)) : std::string()) << " ("
        << (koopman ? "with" : "without") << " the Koopman–Hill expm), ~" << kProductsPerCube
        << " complex products per size³";
  w.basis = basis.str();
  return w;
}

// Structured: one banded shift-invert Arnoldi run per state, each linear in the rows. Measured
// (Mathieu n = 2, N = 1e4 and 1e5; tower-rotor n = 22, N = 200 and 600: 2 s, 29 s, 64 s, 194 s)
// against the timed product: 9e3 product-cubes per row·n² over both truncations. The rotor
// (n = 12, N = 1000: 8.4 s) costs a sixth of that, so the fewest count is a tenth.
WorkEstimate StructuredHillWork(int n, int N, const HillOptions& o, double seconds_per_cube) {
  const auto [m, m2] = HillRows(n, N, o);
  constexpr double kCubesPerRowAndState2 = 9e3;
  WorkEstimate w;
  w.evaluations = (m + m2) * n * n;
  w.seconds_per_evaluation = kCubesPerRowAndState2 * seconds_per_cube;
  w.fewest_evaluations = w.evaluations / 10;
  std::ostringstream basis;
  basis << "structured (banded shift-invert) Hill solves of " << static_cast<long>(m)
        << (m2 > 0 ? " and " + std::to_string(static_cast<long>(m2)) : std::string())
        << " rows, one per state (" << n << "), ~" << kCubesPerRowAndState2
        << " product-cubes per row·n²";
  w.basis = basis.str();
  return w;
}

void WeighTheWork(int n, int N, const HillOptions& o, std::vector<Diagnostic>& notes) {
  const bool dense = o.solver == HillSolver::kDense;
  if (dense) hill_internal::CheckDenseMemory(n, N, o.max_dense_bytes);  // memory first
  // Well under a second anywhere below these sizes; nothing to weigh when neither limit is on
  // (a convergence study weighs itself as a whole and runs its solves so: no timed product
  // per truncation).
  if (n * (2.0 * N + 1) < (dense ? 300 : 2000)) return;
  if (o.max_work_seconds <= 0 && !(o.announce_work_seconds < HUGE_VAL)) return;
  hill_internal::WeighHillWork(
      hill_internal::HillWork(n, N, o, hill_internal::ComplexProductSecondsPerCube()),
      "Hill's method at N = " + std::to_string(N), o,
      dense ? "use the structured solver or fewer harmonics"
            : "fewer harmonics (--harmonics auto stops where the estimate is met)",
      notes);
}

}  // namespace

namespace hill_internal {

double ComplexProductSecondsPerCube() {
  constexpr int k = 128;
  const Eigen::MatrixXcd a = Eigen::MatrixXcd::Random(k, k);
  Eigen::MatrixXcd c(k, k);
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < 3; ++r) {  // the fastest of three
    const auto start = std::chrono::steady_clock::now();
    c.noalias() = a * a;
    best = std::min(best, SecondsSince(start));
  }
  return best / (static_cast<double>(k) * k * k);
}

WorkEstimate HillWork(int n, int N, const HillOptions& o, double seconds_per_cube) {
  return o.solver == HillSolver::kDense ? DenseHillWork(n, N, o, seconds_per_cube)
                                        : StructuredHillWork(n, N, o, seconds_per_cube);
}

void WeighHillWork(const WorkEstimate& w, const std::string& job, const HillOptions& o,
                   const char* advice, std::vector<Diagnostic>& notes) {
  if (o.max_work_seconds > 0 && w.fewest_seconds() > o.max_work_seconds) {
    std::ostringstream s;
    s.precision(3);
    s << job << " would take at least " << w.fewest_seconds() << " CPU s (about " << w.seconds()
      << " s; " << w.basis << "), beyond HillOptions::max_work_seconds = " << o.max_work_seconds
      << " (ltp: --max-work); " << advice;
    throw InputError(s.str());
  }
  if (w.seconds() > o.announce_work_seconds) {
    std::ostringstream s;
    s.precision(2);
    s << "work estimate before the analysis: about " << w.seconds() << " CPU s (" << w.basis << ")";
    notes.push_back({DiagnosticCode::kWorkEstimate, Severity::kNote, s.str()});
    if (o.on_long_work) o.on_long_work(w);
  }
}

}  // namespace hill_internal

namespace {

// A's Fourier coefficients as Hill's method uses them: exact for a Fourier-form system, else the
// FFT fit of A(t) (kept, with a sentence saying how it went).
struct HillCoefficients {
  FourierMatrix A;
  std::optional<FourierFit> fit;
  std::string note;  ///< empty for exact coefficients
};
HillCoefficients CoefficientsOf(const PeriodicSystem& system, const FourierFitOptions& options) {
  HillCoefficients c;
  if (const FourierMatrix* fa = system.fourier_A()) {
    c.A = *fa;
    return c;
  }
  auto f = [&system](double t, Eigen::Ref<Eigen::MatrixXd> out) { system.EvalA(t, out); };
  c.fit = FitFourier(f, system.states(), system.states(), system.period(), options);
  c.A = c.fit->series;
  std::ostringstream s;
  s << "A(t) fitted by FFT: " << c.A.max_harmonic() << " harmonics from " << c.fit->samples
    << " samples, relative tail " << c.fit->tail << ", decay " << ToString(c.fit->decay);
  if (c.fit->decay == FourierDecay::kExponential) s << " (b = " << c.fit->decay_rate << ")";
  if (c.fit->decay == FourierDecay::kAlgebraic)
    s << " (|A_w| ~ |w|^-" << c.fit->decay_rate
      << ": discontinuous A(t), expect algebraic convergence in N)";
  c.note = s.str();
  return c;
}

}  // namespace

Eigen::MatrixXcd HillMatrix(const PeriodicSystem& system, int harmonics,
                            const HillOptions& options) {
  if (harmonics < 0) throw InputError("HillMatrix: harmonics must be >= 0");
  hill_internal::CheckDenseMemory(system.states(), harmonics, options.max_dense_bytes);
  return HillMatrix(CoefficientsOf(system, options.fourier).A, system.omega(), harmonics,
                    options.max_dense_bytes);
}

HillResult AnalyzeHill(const PeriodicSystem& system, const HillOptions& requested) {
  requested.Validate();
  const auto start = std::chrono::steady_clock::now();
  const double T = system.period();
  std::vector<Diagnostic> notes;
  HillOptions options = requested;
  HillCoefficients coefficients = CoefficientsOf(system, options.fourier);
  const FourierMatrix& A = coefficients.A;
  const std::optional<FourierFit>& fit = coefficients.fit;
  const std::string& fit_note = coefficients.note;
  if (fit) notes.push_back({DiagnosticCode::kFourierFitted, Severity::kNote, fit_note});

  if (options.solver == HillSolver::kAuto) {  // needs H_A: after the fit
    const HillSolverChoice c =
        ChooseHillSolver(MeasureSystemTraits(system), options.harmonics, A.max_harmonic());
    options.solver = c.solver;
    notes.push_back({DiagnosticCode::kHillSolverChosen, Severity::kNote,
                     "solver auto → " + std::string(ToString(c.solver)) + ": " + c.reason});
  }
  WeighTheWork(A.rows(), options.harmonics, options, notes);
  HillResult r = AnalyzeFixed(A, fit ? &*fit : nullptr, T, options.harmonics, options);
  // A structured result that failed its own checks (e.g. one eigenpair of a double exponent
  // found twice and another family missed) is replaced by the dense solver's, which sees the
  // whole spectrum, when that fits.
  const double dense_bytes = std::pow((2.0 * options.harmonics + 1) * A.rows(), 2) * sizeof(cd);
  if (!r.ok && !r.modes.empty() && options.solver == HillSolver::kStructured &&
      options.structured_fallback && dense_bytes <= options.max_dense_bytes) {
    HillOptions dense = options;
    dense.solver = HillSolver::kDense;
    // The fallback only where its dense solve costs no more than the limit allows (weighed
    // here, not on every structured call: the weighing times a product).
    const bool affordable = options.max_work_seconds <= 0 ||
                            DenseHillWork(A.rows(), options.harmonics, dense,
                                          hill_internal::ComplexProductSecondsPerCube())
                                    .fewest_seconds() <= options.max_work_seconds;
    if (!affordable) {
      notes.push_back(
          {DiagnosticCode::kHillFallbackTooCostly, Severity::kWarning,
           "structured solver's exponents failed their checks; the dense solver would take longer "
           "than max_work_seconds, so the result stays as it is"});
    } else {
      WeighTheWork(A.rows(), options.harmonics, dense, notes);  // announced when long
      HillResult d = AnalyzeFixed(A, fit ? &*fit : nullptr, T, options.harmonics, dense);
      notes.push_back(
          {DiagnosticCode::kHillSolverFellBack, Severity::kWarning,
           "structured solver's exponents failed their checks (" +
               (r.diagnostics.empty() ? std::string("see below") : r.diagnostics.back().text) +
               "); replaced by the dense solver's"});
      d.dense_fallback = true;
      r = std::move(d);
    }
  }
  if (fit && !fit->converged && !r.modes.empty()) FitErrorEstimate(system, options, *fit, r);
  // The rigid rotation of a free angle (rigid_body.h): left out of max Re λ and the verdict,
  // as the monodromy route does.
  for (std::string& line : internal::FlagRigidBodyModes(system.labels(), r.mode_shapes, r.modes))
    r.diagnostics.push_back({DiagnosticCode::kRigidBodyMode, Severity::kNote, std::move(line)});
  r.max_real_exponent = internal::MaxRealExponent(r.modes);
  r.verdict = ClassifyStability(r.ok, r.max_real_exponent, r.error_estimate);
  r.stable = r.verdict == StabilityVerdict::kStable;
  r.diagnostics.insert(r.diagnostics.begin(), notes.begin(), notes.end());
  r.fourier_fit = fit_note;
  r.elapsed_s = SecondsSince(start);
  return r;
}

std::string HillResult::SolverDescription() const {
  return dense_fallback ? "structured→dense" : std::string(ToString(solver));
}

std::string HillResult::BriefReport() const {
  std::ostringstream s;
  s << "Hill N = " << harmonics << " (" << SolverDescription() << ", size " << matrix_size
    << "): max Re λ = " << max_real_exponent << " (" << ToString(verdict) << "), N vs N+"
    << delta_harmonics << ": ";
  if (truncation_estimate)
    s << *truncation_estimate;
  else
    s << "not computed";
  s << ", a-priori bound: " << apriori_bound << ", Koopman–Hill gap: ";
  if (koopman_discrepancy)
    s << *koopman_discrepancy;
  else
    s << "not computed";
  s << ", " << elapsed_s * 1e3 << " ms";
  return s.str();
}

}  // namespace ltp
