// One route of the partial-FRF sweep behind one small interface: set up once (the factory),
// evaluate a frequency, report what it did. ComputePartialFrf runs the primary route on every
// frequency and the check routes on every check_every-th, and compares them; a new route is
// one new file with a solver class and one line in MakeRouteSolver (pfrf_route.cc).
#pragma once

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/htf/pfrf.h"

namespace ltp::internal {

/// H_z of the swept channel at one frequency, z = min_order … max_order, with the route's
/// own error there: `measured` is checked at the point itself (the HTF's truncation change)
/// and is the primary's estimate; `assumed` follows from the route's tolerance and is added
/// when the route checks another (a check is only as good as the checker).
struct RoutePoint {
  std::vector<std::complex<double>> values;
  double measured_error = 0;
  double assumed_error = 0;
  bool ok = false;
};

class PfrfRouteSolver {
 public:
  virtual ~PfrfRouteSolver() = default;
  /// Called once before the points run, with how many there will be (a route may spend
  /// set-up work that pays over that many).
  virtual void Prepare(int /*points*/) {}
  virtual RoutePoint Evaluate(double omega) = 0;
  /// Whether Evaluate may run on several threads at once.
  virtual bool concurrent() const { return false; }
  /// After the points ran: the route's diagnostics (and its entries in the result).
  virtual std::vector<Diagnostic> Finish(const std::vector<RoutePoint>& points) = 0;
};

/// Sets route `route` up for the sweep in `options` (PfrfRoute::kAuto is not a route). May
/// build what several routes share into `result` (the modal model) and record route facts
/// there (the HTF truncation, the settling time).
std::unique_ptr<PfrfRouteSolver> MakeRouteSolver(PfrfRoute route, const PeriodicSystem& system,
                                                 const PfrfOptions& options, PfrfResult& result);

// The routes (one file each).
std::unique_ptr<PfrfRouteSolver> MakeModalRoute(const PeriodicSystem& system,
                                                const PfrfOptions& options, PfrfResult& result);
std::unique_ptr<PfrfRouteSolver> MakeHtfRoute(const PeriodicSystem& system,
                                              const PfrfOptions& options, PfrfResult& result);
std::unique_ptr<PfrfRouteSolver> MakeForcedResponseRoute(PfrfRoute route,
                                                         const PeriodicSystem& system,
                                                         const PfrfOptions& options,
                                                         PfrfResult& result);

/// max |v| over the finite entries (the scale of a point's response).
double LargestFinite(const std::vector<std::complex<double>>& values);

}  // namespace ltp::internal
