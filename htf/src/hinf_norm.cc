// ‖G‖∞ of a periodic system by two routes (docs/htf-operator.md, "H∞"):
//   search       σmax of the operator's section −K…K at s = jω over a grid of one fundamental
//                interval and every mode's frequency, the best candidates refined by Brent's
//                method, K doubled until the peak stops growing. Each value is a lower bound
//                of the norm (a section is a compression of the operator).
//   Hamiltonian  γ > ‖G‖∞ exactly when the periodic Hamiltonian system of the bounded-real test
//                (internal::HamiltonianSystem) has no Floquet exponent on the imaginary axis;
//                bisection on γ from a bracket around the search's value, each test one
//                Floquet analysis of 2n states with its per-exponent error estimate. No Fourier
//                truncation.
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <sstream>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/htf/harmonic_transfer_function.h"
#include "ltp/integrate/threads.h"

namespace ltp {

namespace {
using cd = std::complex<double>;

double LargestSingularValue(const Eigen::MatrixXcd& m) {
  if (m.size() == 0) return 0;
  if (!m.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  return Eigen::BDCSVD<Eigen::MatrixXcd>(m).singularValues()(0);
}

struct Peak {
  double omega = 0, value = 0;
};

// Brent's method on −σ over [w0 − half, w0 + half] (not below 0), the interval moved and
// searched again while the maximum sits at its edge (the peak lies beyond it).
template <class Sigma>
Peak ClimbToPeak(Sigma sigma, double w0, double half, int* points) {
  Peak best;
  for (int moves = 0; moves < 20; ++moves) {
    const double lo = std::max(0.0, w0 - half), hi = w0 + half;
    std::uintmax_t iterations = 200;
    const auto found = boost::math::tools::brent_find_minima([&](double w) { return -sigma(w); },
                                                             lo, hi, 52, iterations);
    *points += static_cast<int>(iterations);
    if (!(-found.second > best.value)) break;
    best = {found.first, -found.second};
    const double edge = 1e-6 * half;
    if (found.first - lo > edge && hi - found.first > edge) break;
    if (found.first - lo <= edge && lo == 0.0) break;
    w0 = found.first;
  }
  return best;
}

// The frequency search at section K: the grid and the modes' frequencies, then Brent on the
// best few candidates, each within its neighbourhood.
Peak SearchSection(const HarmonicTransferFunction& htf, OperatorRoute route, int K,
                   const NormOptions& options, int* points) {
  const double wp = htf.system().omega();
  std::vector<double> omegas;
  for (int i = 0; i < options.grid_points; ++i)
    omegas.push_back(0.5 * wp * i / (options.grid_points - 1));
  for (const FloquetMode& m : htf.floquet().modes) omegas.push_back(std::abs(m.exponent.imag()));
  const int count = static_cast<int>(omegas.size());
  std::vector<double> values(count);
  auto sigma = [&](double w) { return LargestSingularValue(htf.Section(cd(0, w), K, route)); };
#pragma omp parallel for schedule(dynamic) num_threads(ThreadsFor(options.threads))
  for (int i = 0; i < count; ++i) values[i] = sigma(omegas[i]);
  *points += count;
  std::vector<int> order(count);
  for (int i = 0; i < count; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values[a] > values[b]; });
  Peak best;
  const double spacing = 0.5 * wp / (options.grid_points - 1);
  for (int c = 0; c < std::min(count, 6); ++c) {
    const double w0 = omegas[order[c]];
    if (values[order[c]] > best.value) best = {w0, values[order[c]]};
    // A mode's peak lies within a few |Re λ| of its frequency; a grid point's within a spacing.
    double half = spacing;
    for (const FloquetMode& m : htf.floquet().modes)
      if (std::abs(std::abs(m.exponent.imag()) - w0) < 1e-12 * wp)
        half = std::clamp(2 * std::abs(m.exponent.real()), spacing, 0.25 * wp);
    const Peak found = ClimbToPeak(sigma, w0, half, points);
    if (found.value > best.value) best = found;
  }
  return best;
}

}  // namespace

namespace internal {

PeriodicSystem HamiltonianSystem(const PeriodicSystem& system, double gamma) {
  const int n = system.states(), m = system.inputs();
  PeriodicSystem::Functions f;
  f.A = [system, gamma, n, m](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const Eigen::MatrixXd a = system.A(t), b = system.B(t), c = system.C(t), d = system.D(t);
    const Eigen::MatrixXd r = gamma * gamma * Eigen::MatrixXd::Identity(m, m) - d.transpose() * d;
    const Eigen::LLT<Eigen::MatrixXd> llt(r);
    const Eigen::MatrixXd ri_dt_c = llt.solve(d.transpose() * c);  // R⁻¹DᵀC
    const Eigen::MatrixXd ri_bt = llt.solve(b.transpose());        // R⁻¹Bᵀ
    const Eigen::MatrixXd a_hat = a + b * ri_dt_c;
    out.topLeftCorner(n, n) = a_hat;
    out.topRightCorner(n, n) = b * ri_bt;
    out.bottomLeftCorner(n, n) =
        -(c.transpose() * c + c.transpose() * d * llt.solve(d.transpose() * c));
    out.bottomRightCorner(n, n) = -a_hat.transpose();
  };
  return PeriodicSystem::FromFunctions(system.period(), 2 * n, 0, 0, std::move(f),
                                       system.breakpoints());
}

}  // namespace internal

namespace {

// Whether the Hamiltonian system at γ has an exponent on the imaginary axis (within 100× its
// own error estimate, or 1e-10 of the exponents' scale): then γ <= ‖G‖∞.
std::optional<bool> HasAxisExponent(const PeriodicSystem& system, double gamma,
                                    const NormOptions& options, std::string* failure) {
  FloquetOptions fo;
  fo.compute_modes = false;
  fo.integrator.rel_tol = options.hamiltonian_rel_tol;
  fo.integrator.abs_tol = options.hamiltonian_rel_tol * 1e-3;
  const FloquetResult r = AnalyzeFloquet(internal::HamiltonianSystem(system, gamma), fo);
  if (!r.ok) {
    *failure = "the Hamiltonian system's Floquet analysis failed at γ = " + std::to_string(gamma) +
               ": " + r.failure;
    return std::nullopt;
  }
  for (const FloquetMode& m : r.modes) {
    const double own = m.error_estimate.value_or(r.error_estimate.value_or(0.0));
    const double scale = std::abs(m.exponent) + system.omega();
    if (std::abs(m.exponent.real()) <= 100 * own + 1e-10 * scale) return true;
  }
  return false;
}

// The search with the section doubled from K = 4 until the peak grows by less than rel_tol.
void SearchFrequencies(const HarmonicTransferFunction& htf, const NormOptions& options,
                       HinfNorm& r) {
  const OperatorRoute route = htf.modal() ? OperatorRoute::kModal : OperatorRoute::kHill;
  int K = std::min(4, options.max_section_harmonics);
  Peak peak = SearchSection(htf, route, K, options, &r.search_points);
  for (bool converged = false; !converged;) {
    if (K >= options.max_section_harmonics) {
      r.diagnostics.push_back({DiagnosticCode::kTruncationLimited, Severity::kWarning,
                               "H∞ search: the section reached max_section_harmonics = " +
                                   std::to_string(K) + " before the peak stopped growing"});
      break;
    }
    const int next = std::min(2 * K, options.max_section_harmonics);
    const double grown = LargestSingularValue(htf.Section(cd(0, peak.omega), next, route));
    ++r.search_points;
    converged = grown - peak.value <= options.rel_tol * grown;
    K = next;
    if (converged)
      peak.value = std::max(peak.value, grown);
    else
      peak = SearchSection(htf, route, K, options, &r.search_points);
  }
  r.search_value = peak.value;
  r.peak_omega = peak.omega;
  r.section_harmonics = K;
}

// Bisection on γ between a level with axis exponents (lo) and one without (hi), starting
// 100 × rel_tol (at least 1e-6) either side of the search's value, widening geometrically
// where that is wrong.
HinfNorm BisectHamiltonian(const PeriodicSystem& system, HinfNorm r, const NormOptions& options) {
  const double found = r.search_value, floor = internal::MaxFeedthrough(system);
  if (!(found > 0) || !std::isfinite(found)) {
    r.failure = "H∞ search found no positive gain (" + std::to_string(found) + ")";
    return r;
  }
  std::string failure;
  auto fail = [&r](std::string why) {
    r.failure = std::move(why);
    return r;
  };
  auto axis = [&](double gamma) {
    ++r.hamiltonian_analyses;
    return HasAxisExponent(system, gamma, options, &failure);
  };
  // The search is usually right to rel_tol: a bracket 100× wider costs ~7 bisections.
  const double kStep = std::max(1e-6, 100 * options.rel_tol);
  double lo = found * (1 - kStep), hi = found * (1 + kStep);
  for (int i = 1;; ++i) {  // lo: axis exponents (or the feedthrough's floor)
    if (lo <= floor * (1 + 1e-12)) {
      lo = floor;
      break;
    }
    const auto a = axis(lo);
    if (!a) return fail(failure);
    if (*a) break;
    hi = lo;
    lo = std::max(floor, found * (1 - kStep * std::pow(4.0, i)));
  }
  for (int i = 1;; ++i) {  // hi: none
    const auto a = axis(hi);
    if (!a) return fail(failure);
    if (!*a) break;
    lo = hi;
    hi = found * (1 + kStep * std::pow(4.0, i));
    if (i > 40) return fail("H∞: no level without axis exponents below " + std::to_string(hi));
  }
  for (int i = 0; hi - lo > 0.25 * options.rel_tol * hi && i < options.max_bisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    const auto a = axis(mid);
    if (!a) return fail(failure);
    (*a ? lo : hi) = mid;
  }
  r.lower = lo;
  r.upper = hi;
  r.value = 0.5 * (lo + hi);
  const double disagreement = std::abs(found - r.value);
  r.error_estimate = 0.5 * (hi - lo) + disagreement;
  r.ok = disagreement <= 10 * options.rel_tol * r.value + (hi - lo);
  if (!r.ok) {
    std::ostringstream s;
    s << "H∞: the frequency search (" << found << ") and the Hamiltonian bisection ([" << lo << ", "
      << hi << "]) disagree";
    r.failure = s.str();
  }
  return r;
}

}  // namespace

HinfNorm HarmonicTransferFunction::Hinf(const NormOptions& options) const {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  HinfNorm r;
  auto finish = [&](HinfNorm out) -> HinfNorm {
    out.elapsed_s = SecondsSince(start);
    if (!out.ok && out.failure.empty()) out.failure = "H∞ norm not computed";
    if (!out.ok)
      out.diagnostics.push_back(
          {DiagnosticCode::kNormNotComputed, Severity::kFailure, out.failure});
    return out;
  };
  if (!floquet_.ok) {
    r.failure = "the Floquet decomposition failed: " + floquet_.failure;
    return finish(r);
  }
  if (floquet_.verdict == StabilityVerdict::kUnstable) {
    r.ok = true;
    r.value = r.lower = r.upper = std::numeric_limits<double>::infinity();
    r.diagnostics.push_back({DiagnosticCode::kNormInfinite, Severity::kNote,
                             "the system is unstable: its H∞ norm is infinite"});
    return finish(r);
  }
  if (floquet_.verdict != StabilityVerdict::kStable) {
    r.failure = "stability undecided (" + std::string(ToString(floquet_.verdict)) +
                "): the H∞ norm is finite only for a stable system";
    return finish(r);
  }
  SearchFrequencies(*this, options, r);
  return finish(BisectHamiltonian(system_, std::move(r), options));
}

}  // namespace ltp
