#include <algorithm>
#include <cmath>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/floquet/hill.h"

namespace ltp {

HillResult AnalyzeHillAuto(const PeriodicSystem& system, HillOptions options, double tol,
                           int max_harmonics) {
  if (!(tol > 0)) throw InputError("AnalyzeHillAuto: tol must be > 0");
  options.harmonics = std::clamp(options.harmonics, 1, std::max(1, max_harmonics));
  if (options.delta_harmonics < 0) options.delta_harmonics = 0;  // the estimate drives the loop
  HillResult best;
  const int start = options.harmonics;
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
      best.diagnostics.push_back(std::string("automatic truncation stopped: ") + e.what());
      return best;
    }
    double scale = 1;
    for (const auto& m : r.modes) scale = std::max(scale, std::abs(m.exponent));
    const bool converged = r.ok && r.truncation_estimate >= 0 && r.truncation_estimate <= tol * scale;
    best = std::move(r);
    if (converged) {
      std::ostringstream s;
      s << "harmonics auto → N = " << best.harmonics << ": the N vs N+Δ change "
        << best.truncation_estimate << " 1/s met the tolerance " << tol << " × max(1, max|λ|)"
        << (best.harmonics > start ? " (N doubled from " + std::to_string(start) + ")" : "");
      best.diagnostics.push_back(s.str());
      return best;
    }
    if (options.harmonics >= max_harmonics) break;
    options.harmonics = std::min(2 * options.harmonics, max_harmonics);
  }
  std::ostringstream s;
  s << "automatic truncation: N = " << best.harmonics << " did not reach the tolerance " << tol
    << " (N vs N+Δ change " << best.truncation_estimate << ")";
  best.diagnostics.push_back(s.str());
  return best;
}

}  // namespace ltp
