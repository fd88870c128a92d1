// The forced-response routes (ForcedResponseSolver) as sweep routes: shooting (the exact
// periodic steady state, no truncation of A) and time (simulation from rest past the settling
// time, then projection), for cross-checks where no truncation may be trusted.
#include <limits>
#include <sstream>

#include "pfrf_route.h"

namespace ltp::internal {

namespace {

class ForcedResponseRoute : public PfrfRouteSolver {
 public:
  ForcedResponseRoute(PfrfRoute route, const PeriodicSystem& system, const PfrfOptions& options,
                      PfrfResult& result)
      : route_(route), options_(options), solver_(system, options.shooting) {
    if (route_ != PfrfRoute::kTime) return;
    result.settle_time = result.floquet.ok ? ForcedResponseSolver::SettlingTime(
                                                 result.floquet, options.shooting.settle_tol)
                                           : std::numeric_limits<double>::infinity();
    settle_ = *result.settle_time;
    std::ostringstream s;
    s << "time: settling time " << settle_ << " s = ln(cond Ξ / " << options.shooting.settle_tol
      << ") / |max Re λ| (slowest Floquet exponent " << result.floquet.max_real_exponent
      << " 1/s), then " << options.shooting.record_periods << " periods projected";
    setup_diagnostics_.push_back({DiagnosticCode::kSettlingTime, Severity::kNote, s.str()});
  }

  RoutePoint Evaluate(double omega) override {
    const int zmin = options_.min_order, zmax = options_.max_order;
    RoutePoint p;
    const PartialFrfs h = route_ == PfrfRoute::kShooting
                              ? solver_.Shooting(omega, zmin, zmax, &p.ok)
                              : solver_.TimeSimulation(omega, zmin, zmax, settle_, &p.ok);
    p.values.resize(h.size());
    for (size_t z = 0; z < h.size(); ++z) p.values[z] = h[z](options_.output, options_.input);
    // Errors spread over all orders: a tiny H_z is not known better than the tolerance
    // relative to the largest response at this frequency.
    const double tol =
        route_ == PfrfRoute::kShooting ? options_.shooting.rel_tol : options_.shooting.settle_tol;
    p.assumed_error = tol * LargestFinite(p.values);
    return p;
  }
  std::vector<Diagnostic> Finish(const std::vector<RoutePoint>&) override {
    std::vector<Diagnostic> d = setup_diagnostics_;
    const std::string name(ToString(route_));
    std::ostringstream s;
    s << name << ": " << solver_.samples() << " samples per period, RKF78 rel tol "
      << options_.shooting.rel_tol << "; response spectrum upper-half amplitude "
      << solver_.sample_tail()
      << (solver_.sample_tail() > options_.shooting.sample_tol
              ? " (NOT resolved: raise max_samples)"
              : "");
    d.push_back({DiagnosticCode::kRouteSummary,
                 solver_.sample_tail() > options_.shooting.sample_tol ? Severity::kWarning
                                                                      : Severity::kNote,
                 s.str()});
    // The solver serves this route only: everything it noticed is this route's.
    for (const auto& m : solver_.diagnostics()) d.push_back(m);
    return d;
  }

 private:
  PfrfRoute route_;
  const PfrfOptions& options_;
  ForcedResponseSolver solver_;
  double settle_ = 0;
  std::vector<Diagnostic> setup_diagnostics_;
};

}  // namespace

std::unique_ptr<PfrfRouteSolver> MakeForcedResponseRoute(PfrfRoute route,
                                                         const PeriodicSystem& system,
                                                         const PfrfOptions& options,
                                                         PfrfResult& result) {
  return std::make_unique<ForcedResponseRoute>(route, system, options, result);
}

}  // namespace ltp::internal
