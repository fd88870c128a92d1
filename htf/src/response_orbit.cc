#include "ltp/htf/response_orbit.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "ltp/core/error.h"
#include "ltp/integrate/threads.h"

namespace ltp {

std::vector<ResponseOrbit> ResponseOrbits(const HarmonicTransferFunction& htf, double omega,
                                          const Eigen::VectorXcd& input, int x_output, int y_output,
                                          int min_order, int max_order, OperatorRoute route) {
  const PeriodicSystem& system = htf.system();
  if (input.size() != system.inputs())
    throw InputError("ResponseOrbits: the input has " + std::to_string(input.size()) +
                     " weights, the system " + std::to_string(system.inputs()) + " inputs");
  for (int o : {x_output, y_output})
    if (o < 0 || o >= system.outputs())
      throw InputError("ResponseOrbits: output index " + std::to_string(o) + " is out of range");
  if (!std::isfinite(omega)) throw InputError("ResponseOrbits: the frequency must be finite");
  const int spin = RotorSpin(system);
  const double omega_p = 2 * std::numbers::pi / system.period();
  const PartialFrfs H = htf.Partial(std::complex<double>(0, omega), min_order, max_order, route);
  std::vector<ResponseOrbit> out;
  for (int z = min_order; z <= max_order; ++z) {
    const Eigen::VectorXcd y = H[static_cast<size_t>(z - min_order)] * input;
    ResponseOrbit r;
    r.order = z;
    r.frequency = omega + z * omega_p;
    r.x = y(x_output);
    r.y = y(y_output);
    r.orbit = OrbitOf(r.x, r.y, r.frequency, spin);
    out.push_back(r);
  }
  return out;
}

Eigen::VectorXcd UnbalanceInput(int inputs, int fx, int fy, int spin) {
  for (int i : {fx, fy})
    if (i < 0 || i >= inputs)
      throw InputError("UnbalanceInput: input index " + std::to_string(i) + " is out of range (" +
                       std::to_string(inputs) + " inputs)");
  if (fx == fy) throw InputError("UnbalanceInput: fx and fy must be two different inputs");
  Eigen::VectorXcd u = Eigen::VectorXcd::Zero(inputs);
  u(fx) = 1;
  u(fy) = std::complex<double>(0, spin < 0 ? 1 : -1);
  return u;
}

std::string_view ToString(OrbitSense sense) {
  switch (sense) {
    case OrbitSense::kForward:
      return "FW";
    case OrbitSense::kBackward:
      return "BW";
    case OrbitSense::kStraight:
      return "line";
    case OrbitSense::kStill:
      return "still";
  }
  return "?";
}

OrbitSense SenseOf(const Orbit& orbit, double uncertainty) {
  if (orbit.forward <= uncertainty && orbit.backward <= uncertainty) return OrbitSense::kStill;
  if (orbit.forward - orbit.backward > uncertainty) return OrbitSense::kForward;
  if (orbit.backward - orbit.forward > uncertainty) return OrbitSense::kBackward;
  return OrbitSense::kStraight;
}

bool HasTilt(const Orbit& orbit, double uncertainty) {
  return orbit.forward > uncertainty && orbit.backward > uncertainty;
}

void OrbitSweepOptions::Validate() const {
  const OptionCheck check("OrbitSweepOptions");
  if (max_order < min_order)
    check.Fail("max_order", max_order, "max_order >= min_order = " + std::to_string(min_order));
  if (!(max_relative_disagreement > 0))
    check.Fail("max_relative_disagreement", max_relative_disagreement, "> 0");
  if (!(negligible >= 0 && negligible < 1)) check.Fail("negligible", negligible, "in [0, 1)");
  if (threads < 0) check.Fail("threads", threads, ">= 0");
}

namespace {

// The route of the reported values, and why.
OperatorRoute ChooseOrbitRoute(const HarmonicTransferFunction& htf,
                               const OrbitSweepOptions& options, RouteReason* reason,
                               std::string* why) {
  if (options.route) {
    *reason = RouteReason::kAsRequested;
    *why = "as requested";
    return *options.route;
  }
  if (!htf.modal()) {
    *reason = RouteReason::kNoDecomposition;
    *why = "automatic: the Floquet decomposition failed, so there is no modal model";
    return OperatorRoute::kHill;
  }
  if (!htf.modal()->reliable) {
    *reason = RouteReason::kModalUnreliable;
    *why = "automatic: the modal model reports itself unreliable";
    return OperatorRoute::kHill;
  }
  *reason = RouteReason::kModalResolved;
  *why = "automatic: one Floquet decomposition, then sums of modal terms";
  return OperatorRoute::kModal;
}

bool AllFinite(const std::vector<ResponseOrbit>& orbits) {
  return std::all_of(orbits.begin(), orbits.end(), [](const ResponseOrbit& o) {
    return std::isfinite(std::abs(o.x)) && std::isfinite(std::abs(o.y));
  });
}

// Sense of every value, and whether the routes agree well enough for `ok`.
void JudgeSweep(const OrbitSweepOptions& options, OrbitSweep& r) {
  const double floor = options.negligible * r.max_semi_major;
  r.max_relative_disagreement = r.max_semi_major > 0 ? r.max_disagreement / r.max_semi_major : 0;
  for (size_t i = 0; i < r.orbits.size(); ++i) {
    std::vector<double>& uncertainty = r.uncertainty.emplace_back();
    std::vector<OrbitSense>& sense = r.sense.emplace_back();
    for (size_t k = 0; k < r.orbits[i].size(); ++k) {
      const double estimate = r.error_estimate.empty() ? 0 : r.error_estimate[i][k];
      uncertainty.push_back(std::isnan(estimate) ? floor : std::max(estimate, floor));
      sense.push_back(SenseOf(r.orbits[i][k].orbit, uncertainty.back()));
    }
  }
  if (!r.ok) return;
  if (r.check_route && !(r.max_relative_disagreement <= options.max_relative_disagreement)) {
    r.ok = false;
    std::ostringstream s;
    s << "the " << ToString(r.route) << " and " << ToString(*r.check_route)
      << " routes disagree by " << r.max_relative_disagreement
      << " of the largest semi-major axis (limit " << options.max_relative_disagreement << ")";
    r.failure = s.str();
    r.diagnostics.push_back({DiagnosticCode::kRoutesDisagree, Severity::kFailure, r.failure});
  }
}

// The primary's values at every frequency and, with a check route, that route's too: on all
// threads (evaluation of the HTF is const and thread-safe), the first frequency alone before
// them so that invalid arguments throw outside the threads.
void EvaluateSweep(const HarmonicTransferFunction& htf, const Eigen::VectorXcd& input, int x_output,
                   int y_output, const OrbitSweepOptions& options, OrbitSweep& r,
                   std::vector<std::vector<ResponseOrbit>>& check) {
  const int count = static_cast<int>(r.omegas.size());
  r.orbits.resize(r.omegas.size());
  if (r.check_route) check.resize(r.omegas.size());
  const auto evaluate = [&](int i) {
    const double w = r.omegas[static_cast<size_t>(i)];
    r.orbits[static_cast<size_t>(i)] = ResponseOrbits(
        htf, w, input, x_output, y_output, options.min_order, options.max_order, r.route);
    if (r.check_route)
      check[static_cast<size_t>(i)] = ResponseOrbits(
          htf, w, input, x_output, y_output, options.min_order, options.max_order, *r.check_route);
  };
  evaluate(0);
#pragma omp parallel for schedule(dynamic) num_threads(ThreadsFor(options.threads))
  for (int i = 1; i < count; ++i) evaluate(i);
}

}  // namespace

OrbitSweep ResponseOrbitSweep(const HarmonicTransferFunction& htf,
                              const std::vector<double>& omegas, const Eigen::VectorXcd& input,
                              int x_output, int y_output, const OrbitSweepOptions& options) {
  options.Validate();
  if (omegas.empty()) throw InputError("ResponseOrbitSweep: no frequencies");
  for (double w : omegas)
    if (!std::isfinite(w)) throw InputError("ResponseOrbitSweep: every frequency must be finite");
  OrbitSweep r;
  r.omegas = omegas;
  r.min_order = options.min_order;
  r.max_order = options.max_order;
  r.spin = RotorSpin(htf.system());
  r.route = ChooseOrbitRoute(htf, options, &r.route_reason, &r.route_choice);
  if (options.check && r.route == OperatorRoute::kModal)
    r.check_route = OperatorRoute::kHill;
  else if (options.check && htf.modal())
    r.check_route = OperatorRoute::kModal;
  else if (options.check)
    r.diagnostics.push_back({DiagnosticCode::kCheckRouteUnavailable, Severity::kWarning,
                             "unchecked: the Floquet decomposition failed, so there is no modal "
                             "route to check the hill route with"});
  // The orbits are the input's periodic response; without asymptotic stability no rig
  // settles on it (a disturbance grows, or does not decay, beside it).
  const FloquetResult& floquet = htf.floquet();
  if (floquet.ok && floquet.verdict != StabilityVerdict::kStable)
    r.diagnostics.push_back(
        {DiagnosticCode::kSystemUnstable, Severity::kWarning,
         "the system is " + std::string(ToString(floquet.verdict)) +
             " (max Re λ = " + MessageNumber(floquet.max_real_exponent, 6) +
             " 1/s): these orbits are the input's periodic response, not a steady state a rig "
             "settles on — any disturbance " +
             (floquet.verdict == StabilityVerdict::kUnstable ? "grows" : "may not decay") +
             " beside it"});
  std::vector<std::vector<ResponseOrbit>> check;
  EvaluateSweep(htf, input, x_output, y_output, options, r, check);
  r.ok = true;
  for (size_t i = 0; i < omegas.size(); ++i) {
    const std::vector<ResponseOrbit>& primary = r.orbits[i];
    if (!AllFinite(primary) && r.ok) {
      r.ok = false;
      r.failure = "the " + std::string(ToString(r.route)) + " route gave no finite values at " +
                  std::to_string(omegas[i]) + " rad/s";
      r.diagnostics.push_back({DiagnosticCode::kNonFiniteValues, Severity::kFailure, r.failure});
    }
    for (const ResponseOrbit& o : primary)
      if (std::isfinite(o.orbit.semi_major))
        r.max_semi_major = std::max(r.max_semi_major, o.orbit.semi_major);
    if (!r.check_route) continue;
    std::vector<double>& estimate = r.error_estimate.emplace_back();
    for (size_t k = 0; k < primary.size(); ++k) {
      estimate.push_back(std::abs(primary[k].x - check[i][k].x) +
                         std::abs(primary[k].y - check[i][k].y));
      r.max_disagreement = std::max(r.max_disagreement, estimate.back());  // NaN: not taken
    }
  }
  JudgeSweep(options, r);
  return r;
}

}  // namespace ltp
