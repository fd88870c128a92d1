// The truncated HTF (HtfSolver) as a sweep route: truncation N chosen at three probe
// frequencies, then at every point the solve at N and at N + Δ, whose change is the point's
// measured error; for many points both Hill matrices are reduced to Hessenberg form first.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "pfrf_route.h"

namespace ltp::internal {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

class HtfRoute : public PfrfRouteSolver {
 public:
  HtfRoute(const PeriodicSystem& system, const PfrfOptions& options, PfrfResult& result)
      : options_(options), result_(result), solver_(system, options.htf) {
    const std::vector<double>& f = options.frequencies_hz;
    std::vector<double> probes;
    for (size_t q = 0; q < 3; ++q) probes.push_back(kTwoPi * f[(f.size() - 1) * q / 2]);
    result_.htf_harmonics = solver_.ChooseTruncation(options.min_order, options.max_order, probes);
  }

  void Prepare(int points) override {
    const int N = solver_.harmonics();
    reduced_ = solver_.PrepareSweep(points, {N, N + solver_.delta()});
  }

  RoutePoint Evaluate(double omega) override {
    const int zmin = options_.min_order, zmax = options_.max_order;
    RoutePoint p;
    p.values = Channel(solver_.Evaluate(omega, zmin, zmax));
    const std::vector<std::complex<double>> wider =
        Channel(solver_.Evaluate(omega, zmin, zmax, solver_.harmonics() + solver_.delta()));
    double change = 0;
    for (size_t z = 0; z < p.values.size(); ++z)
      change = std::max(change, std::abs(p.values[z] - wider[z]));
    p.measured_error = change;
    p.ok = std::isfinite(change);
    return p;
  }
  bool concurrent() const override { return true; }  // each frequency an independent solve
  std::vector<Diagnostic> Finish(const std::vector<RoutePoint>& points) override {
    std::vector<Diagnostic> d = solver_.diagnostics();
    double worst = 0;
    for (const RoutePoint& p : points) worst = std::max(worst, p.measured_error);
    result_.htf_truncation_change = worst;
    std::ostringstream s;
    s << "htf: truncation N = " << solver_.harmonics() << " (A has "
      << solver_.coefficient_harmonics() << " harmonics; "
      << (reduced_ ? "Hill matrices reduced once to Hessenberg form, a Hessenberg solve per point"
                   : "banded solve per point")
      << "), check against N + " << solver_.delta() << ": max change " << worst;
    d.push_back({DiagnosticCode::kRouteSummary, Severity::kNote, s.str()});
    return d;
  }

 private:
  std::vector<std::complex<double>> Channel(const PartialFrfs& h) const {
    std::vector<std::complex<double>> v(h.size());
    for (size_t z = 0; z < h.size(); ++z) v[z] = h[z](options_.output, options_.input);
    return v;
  }

  const PfrfOptions& options_;
  PfrfResult& result_;
  HtfSolver solver_;
  bool reduced_ = false;
};

}  // namespace

std::unique_ptr<PfrfRouteSolver> MakeHtfRoute(const PeriodicSystem& system,
                                              const PfrfOptions& options, PfrfResult& result) {
  return std::make_unique<HtfRoute>(system, options, result);
}

}  // namespace ltp::internal
