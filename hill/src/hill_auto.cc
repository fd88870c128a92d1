#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/hill/hill.h"

namespace ltp {

HillResult AnalyzeHillAuto(const PeriodicSystem& system, HillOptions options, double tol,
                           int max_harmonics) {
  if (!(tol > 0)) throw InputError("AnalyzeHillAuto: tol must be > 0");
  const auto start_time = std::chrono::steady_clock::now();
  // Time reported is the whole call: every truncation tried, not only the last.
  auto finish = [&](HillResult r, bool met, const std::string& why) {
    r.tolerance_met = met;
    r.diagnostics.push_back(
        {met ? DiagnosticCode::kHarmonicsChosen : DiagnosticCode::kToleranceNotReached,
         met ? Severity::kNote : Severity::kWarning, why});
    r.elapsed_s = SecondsSince(start_time);
    return r;
  };
  options.harmonics = std::clamp(options.harmonics, 1, std::max(1, max_harmonics));
  if (options.delta_harmonics < 0) options.delta_harmonics = 0;  // the estimate drives the loop
  HillResult best;
  const int start = options.harmonics;
  int previous_n = 0;
  double previous_change = -1;
  for (;;) {
    // HillSolver::kAuto is resolved per N by AnalyzeHill (the study's crossover rule).
    // The Koopman–Hill cross-check needs a dense expm of the whole Hill matrix (O(size³)); in
    // the automatic loop keep it to sizes where it costs well under a second.
    options.koopman_max_size = std::min(options.koopman_max_size, 600);
    HillResult r;
    try {
      r = AnalyzeHill(system, options);
    } catch (const ResourceError& e) {
      if (best.modes.empty()) throw;
      return finish(
          std::move(best), false,
          std::string("automatic truncation stopped short of the tolerance: ") + e.what());
    }
    double scale = 1;
    for (const auto& m : r.modes) scale = std::max(scale, std::abs(m.exponent));
    const double goal = tol * scale;
    const double change = r.truncation_estimate.value_or(-1.0);  // -1: not computed
    const bool converged = r.ok && change >= 0 && change <= goal && r.fourier_fit_error <= goal;
    best = std::move(r);
    std::ostringstream s;
    if (converged) {
      s << "harmonics auto → N = " << best.harmonics << ": the N vs N+Δ change " << change
        << " 1/s met the tolerance " << tol << " × max(1, max|λ|)"
        << (best.harmonics > start ? " (N doubled from " + std::to_string(start) + ")" : "");
      return finish(std::move(best), true, s.str());
    }
    // Once the truncation error is below the error of the fitted coefficients of A, raising N
    // cannot help.
    if (best.ok && best.fourier_fit_error > goal && change >= 0 &&
        change <= best.fourier_fit_error) {
      s << "automatic truncation stopped at N = " << best.harmonics << ": the Fourier fit of A(t) "
        << "limits every exponent to about " << best.fourier_fit_error
        << " 1/s, above the tolerance " << goal << ", and the N vs N+Δ change " << change
        << " 1/s is already below that (A(t) is "
        << "discontinuous; the monodromy route has no such limit)";
      return finish(std::move(best), false, s.str());
    }
    if (best.harmonics >= max_harmonics) break;
    // Doubling N shrinks the change of a converging truncation at least 2× (algebraic p >= 1,
    // far more for smooth A): a change that did not is round-off — near a double multiplier an
    // ill-conditioned exponent stalls at ~1e-13 — and larger N only costs time.
    if (best.ok && previous_change > 0 && std::isfinite(change) && change > 0.5 * previous_change) {
      s << "automatic truncation stopped at N = " << best.harmonics << ": the N vs N+Δ change "
        << change << " 1/s no longer shrinks as N doubles (it was " << previous_change
        << "): it is at round-off (near a double multiplier) or converging too slowly to reach "
        << "the tolerance " << goal << "; the estimate above is the error at this N";
      return finish(std::move(best), false, s.str());
    }
    // Slow convergence: at the rate seen between the last two truncations, would the tolerance
    // be met below max_harmonics? If not, stop now rather than spend minutes. The law follows
    // the coefficients of A: a power of N when they decay algebraically (discontinuous A),
    // geometric in N otherwise (extrapolating a geometric decay as a power law predicted
    // N ≈ 6000 for the Poisson kernel r = 0.9, which N = 96 resolves to 1e-14).
    if (best.ok && previous_change > 0 && change > 0 && std::isfinite(change) &&
        change < previous_change) {
      const bool algebraic = best.decay.kind == FourierDecay::kAlgebraic;
      const double shrink = std::log(previous_change / change);
      const double rate = algebraic ? shrink / std::log(double(best.harmonics) / previous_n)
                                    : shrink / (best.harmonics - previous_n);
      const double needed = algebraic ? best.harmonics * std::pow(change / goal, 1 / rate)
                                      : best.harmonics + std::log(change / goal) / rate;
      if (rate > 0 && needed > 2.0 * max_harmonics) {
        s << "automatic truncation stopped at N = " << best.harmonics << ": the N vs N+Δ change "
          << change << " 1/s falls like "
          << (algebraic ? "N^-" + MessageNumber(rate, 3) : "e^{-" + MessageNumber(rate, 3) + " N}")
          << ", so the tolerance " << goal << " needs N ≈ " << std::ceil(needed) << " (limit "
          << max_harmonics << "); the estimate above is the error at this N";
        return finish(std::move(best), false, s.str());
      }
    }
    previous_n = best.ok && std::isfinite(change) ? best.harmonics : 0;
    previous_change = best.ok && std::isfinite(change) ? change : -1;
    options.harmonics = std::min(2 * options.harmonics, max_harmonics);
  }
  std::ostringstream s;
  s << "automatic truncation: N = " << best.harmonics << " (the limit) did not reach the tolerance "
    << tol;
  if (best.truncation_estimate) s << " (N vs N+Δ change " << *best.truncation_estimate << ")";
  return finish(std::move(best), false, s.str());
}

double HillAutoTolerance(double rel_tol) { return std::max(rel_tol, 1e-12); }

HillResult AnalyzeHillToTolerance(const PeriodicSystem& system, HillOptions options,
                                  double rel_tol) {
  options.harmonics = kHillAutoStartHarmonics;
  return AnalyzeHillAuto(system, options, HillAutoTolerance(rel_tol));
}

}  // namespace ltp
