// The harmonic transfer function as an operator: set-up (one Floquet decomposition, the Hill
// route's truncation) and evaluation at any complex s. The norms are in hinf_norm.cc and
// h2_norm.cc.
#include "ltp/htf/harmonic_transfer_function.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ltp/core/error.h"

namespace ltp {

namespace {
using cd = std::complex<double>;

FloquetResult DecomposeForModes(const PeriodicSystem& system, FloquetOptions options) {
  options.compute_modes = true;
  return AnalyzeFloquet(system, options);
}

// Where the Hill truncation is probed: the axis at 0 and Ωp/4 and every mode's frequency.
std::vector<double> ProbeFrequencies(const FloquetResult& floquet, double omega_p) {
  std::vector<double> probes = {0.0, 0.25 * omega_p};
  for (const FloquetMode& m : floquet.modes)
    if (std::isfinite(m.exponent.imag())) probes.push_back(std::abs(m.exponent.imag()));
  std::sort(probes.begin(), probes.end());
  probes.erase(std::unique(probes.begin(), probes.end()), probes.end());
  return probes;
}

}  // namespace

std::string_view ToString(OperatorRoute route) {
  return route == OperatorRoute::kModal ? "modal" : "hill";
}

std::optional<OperatorRoute> ParseOperatorRoute(std::string_view name) {
  if (name == "modal") return OperatorRoute::kModal;
  if (name == "hill" || name == "htf") return OperatorRoute::kHill;
  return std::nullopt;
}

void HtfOperatorOptions::Validate() const {
  floquet.Validate();
  modal.Validate();
  hill.Validate();
  if (probe_orders < 0)
    OptionCheck("HtfOperatorOptions").Fail("probe_orders", probe_orders, ">= 0");
}

void NormOptions::Validate() const {
  const OptionCheck check("NormOptions");
  if (!(rel_tol > 0 && rel_tol < 0.1)) check.Fail("rel_tol", rel_tol, "in (0, 0.1)");
  if (grid_points < 2) check.Fail("grid_points", grid_points, ">= 2");
  if (max_section_harmonics < 1) check.Fail("max_section_harmonics", max_section_harmonics, ">= 1");
  if (!(hamiltonian_rel_tol > 0 && hamiltonian_rel_tol < 1e-3))
    check.Fail("hamiltonian_rel_tol", hamiltonian_rel_tol, "in (0, 1e-3)");
  if (max_bisections < 1) check.Fail("max_bisections", max_bisections, ">= 1");
  if (max_lyapunov_states < 0) check.Fail("max_lyapunov_states", max_lyapunov_states, ">= 0");
  if (threads < 0) check.Fail("threads", threads, ">= 0 (0 = all cores)");
}

HarmonicTransferFunction::HarmonicTransferFunction(const PeriodicSystem& system,
                                                   const HtfOperatorOptions& options)
    : system_(system), options_(options), hill_(system, options.hill) {
  options.Validate();
  floquet_ = DecomposeForModes(system, options.floquet);
  if (floquet_.ok) modal_ = BuildModalModel(system, floquet_, options.modal);
  const int z = options.probe_orders;
  hill_.ChooseTruncation(-z, z, ProbeFrequencies(floquet_, system.omega()));
}

PartialFrfs HarmonicTransferFunction::Partial(cd s, int min_order, int max_order,
                                              OperatorRoute route) const {
  if (max_order < min_order) throw InputError("htf operator: max_order must be >= min_order");
  if (!std::isfinite(s.real()) || !std::isfinite(s.imag()))
    throw InputError("htf operator: s must be finite");
  if (route == OperatorRoute::kHill) return hill_.EvaluateAt(s, min_order, max_order);
  if (modal_) return modal_->EvaluateAt(s, min_order, max_order);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return PartialFrfs(max_order - min_order + 1,
                     Eigen::MatrixXcd::Constant(system_.outputs(), system_.inputs(), cd(nan, 0)));
}

Eigen::MatrixXcd HarmonicTransferFunction::Section(cd s, int harmonics, OperatorRoute route) const {
  if (harmonics < 0) throw InputError("htf operator: section harmonics must be >= 0");
  const int K = harmonics, p = system_.outputs(), m = system_.inputs();
  Eigen::MatrixXcd h((2 * K + 1) * p, (2 * K + 1) * m);
  for (int u = -K; u <= K; ++u) {
    // Column block u: H_{v−u}(s + juΩp) for v = −K…K, i.e. orders −K−u … K−u.
    const PartialFrfs column = Partial(s + cd(0, u * system_.omega()), -K - u, K - u, route);
    for (int v = -K; v <= K; ++v) h.block((v + K) * p, (u + K) * m, p, m) = column[v + K];
  }
  return h;
}

bool HarmonicTransferFunction::ok() const {
  return modal_ && modal_->reliable && hill_.truncation_converged();
}

std::vector<Diagnostic> HarmonicTransferFunction::diagnostics() const {
  std::vector<Diagnostic> d = floquet_.diagnostics;
  if (modal_) d.insert(d.end(), modal_->diagnostics.begin(), modal_->diagnostics.end());
  d.insert(d.end(), hill_.diagnostics().begin(), hill_.diagnostics().end());
  return d;
}

namespace internal {

double MaxFeedthrough(const PeriodicSystem& system) {
  constexpr int kSamples = 64;
  double d = 0;
  for (int s = 0; s < kSamples; ++s) {
    const Eigen::MatrixXd ds = system.D(s * system.period() / kSamples);
    if (ds.size()) d = std::max(d, Eigen::JacobiSVD<Eigen::MatrixXd>(ds).singularValues()(0));
  }
  return d;
}

}  // namespace internal

}  // namespace ltp
