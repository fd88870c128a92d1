// ‖G‖₂ of a periodic system by two routes (docs/htf-operator.md, "H2"):
//   modal     with H_z(s) = Σ_u Ĉ_{z−u} ((s + juΩp)I − Λ)⁻¹ B̂_u, Parseval over the whole
//             frequency axis in closed form:
//               ‖G‖₂² = Σ_d Σ_{k,l} [Gc(d)]_{lk} [Gb(d)]_{kl} / (−λ_k − conj(λ_l) + jdΩp),
//             Gc(d) = Σ_v Ĉ_{v+d}ᴴ Ĉ_v, Gb(d) = Σ_u B̂_u B̂_{u−d}ᴴ;
//   Lyapunov  the periodic solution of P' = AP + PAᵀ + BBᵀ from one state transition of the
//             linear system [vec P; J; 1] (n² + 2 states, J' = tr(C P Cᵀ)): its fixed point
//             P(T) = P(0) is one linear solve, ‖G‖₂² = J(T)/T. No Fourier truncation.
#include <cmath>
#include <limits>
#include <sstream>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/htf/harmonic_transfer_function.h"

namespace ltp {

namespace {
using cd = std::complex<double>;

double ModalH2Squared(const ModalModel& model) {
  const int V = model.harmonics, n = model.states;
  cd total = 0;
  for (int d = -2 * V; d <= 2 * V; ++d) {
    Eigen::MatrixXcd gc = Eigen::MatrixXcd::Zero(n, n), gb = Eigen::MatrixXcd::Zero(n, n);
    for (int v = std::max(-V, -V - d); v <= std::min(V, V - d); ++v)
      gc.noalias() += model.c_hat[v + d + V].adjoint() * model.c_hat[v + V];
    for (int u = std::max(-V, -V + d); u <= std::min(V, V + d); ++u)
      gb.noalias() += model.b_hat[u + V] * model.b_hat[u - d + V].adjoint();
    for (int l = 0; l < n; ++l)
      for (int k = 0; k < n; ++k)
        total += gc(l, k) * gb(k, l) /
                 (-model.exponents[k] - std::conj(model.exponents[l]) + cd(0, d * model.omega_p));
  }
  return total.real();
}

struct LyapunovRun {
  bool ok = false;
  double squared = 0;
  /// What the tolerance allows in `squared`: the integration holds P to about rel_tol · max|P|
  /// (error control relative to the largest entries), so a norm carried by P's small entries
  /// (an output far from the input) is not resolved below rel_tol · max|P| · max‖C‖_F².
  double floor = 0;
  std::string message;
};

LyapunovRun LyapunovH2Squared(const PeriodicSystem& augmented, int n, double period, double rel_tol,
                              double output_scale) {
  IntegratorOptions io;
  io.rel_tol = rel_tol;
  io.abs_tol = rel_tol * 1e-3;
  const TransitionResult psi = StateTransition(augmented, 0, period, io);
  LyapunovRun run;
  if (!psi.ok) {
    run.message = psi.message;
    return run;
  }
  const int nn = n * n, j = nn, one = nn + 1;
  const Eigen::MatrixXd fixed = Eigen::MatrixXd::Identity(nn, nn) - psi.phi.topLeftCorner(nn, nn);
  const Eigen::VectorXd p0 = fixed.colPivHouseholderQr().solve(psi.phi.col(one).head(nn));
  run.squared = (psi.phi.row(j).head(nn).dot(p0) + psi.phi(j, one)) / period;
  run.floor = rel_tol * p0.cwiseAbs().maxCoeff() * output_scale;
  run.ok = std::isfinite(run.squared);
  if (!run.ok) run.message = "the periodic Lyapunov solution is not finite";
  return run;
}

// max_t ‖C(t)‖_F², on 64 samples of the period.
double OutputScale(const PeriodicSystem& system) {
  double scale = 0;
  for (int s = 0; s < 64; ++s)
    scale = std::max(scale, system.C(s * system.period() / 64).squaredNorm());
  return scale;
}

// The error in ‖G‖₂ that an error `squared` in ‖G‖₂² allows around the value v.
double RootError(double squared, double v) {
  return v > 0 ? std::min(squared / (2 * v), std::sqrt(squared)) : std::sqrt(squared);
}

// The Lyapunov route at two tolerances (their difference and the tolerance's floor are its
// estimate), compared with the modal value. The value is the route with the smaller estimate;
// the disagreement beyond the other route's estimate is added to it.
H2Norm CompareWithLyapunov(const PeriodicSystem& system, H2Norm r, double modal_error,
                           const NormOptions& options) {
  const PeriodicSystem augmented = internal::LyapunovSystem(system);
  const int n = system.states();
  const double tol = std::max(options.rel_tol * 1e-2, 1e-13), scale = OutputScale(system);
  const LyapunovRun coarse = LyapunovH2Squared(augmented, n, system.period(), 100 * tol, scale);
  const LyapunovRun fine = LyapunovH2Squared(augmented, n, system.period(), tol, scale);
  if (!coarse.ok || !fine.ok) {
    r.failure = "H2: the Lyapunov route failed: " + (fine.ok ? coarse.message : fine.message);
    return r;
  }
  const double value = std::sqrt(std::max(0.0, fine.squared));
  const double own =
      RootError(std::abs(fine.squared - coarse.squared) + fine.floor, value) + 1e-14 * value;
  r.lyapunov_value = value;
  const bool lyapunov_better = own < modal_error;
  r.value = lyapunov_better ? value : r.modal_value;
  const double disagreement = std::abs(value - r.modal_value);
  const double chosen = lyapunov_better ? own : modal_error,
               other = lyapunov_better ? modal_error : own;
  r.error_estimate = std::max(chosen, disagreement - other) + 1e-15 * r.value;
  if (own > 1e-3 * value)
    r.diagnostics.push_back({DiagnosticCode::kNormUnresolved, Severity::kWarning,
                             "H2: the Lyapunov route resolves this norm only to " +
                                 MessageNumber(own / std::max(value, 1e-300), 2) +
                                 " (relative; an output carried by P's small entries): the modal "
                                 "value is checked only that far"});
  const double allowed = 10 * (own + modal_error) + options.rel_tol * value;
  r.ok = disagreement <= allowed;
  if (!r.ok) {
    std::ostringstream s;
    s << "H2: the modal (" << r.modal_value << ") and Lyapunov (" << value
      << ") routes disagree by " << disagreement << ", more than their estimates allow (" << allowed
      << ")";
    r.failure = s.str();
    r.diagnostics.push_back({DiagnosticCode::kRoutesDisagree, Severity::kFailure, s.str()});
  }
  return r;
}

// −Re λ of the least damped mode (the modal value's sensitivity to the exponents).
double SlowestDecay(const std::vector<cd>& exponents) {
  double slowest = std::numeric_limits<double>::infinity();
  for (const cd& l : exponents) slowest = std::min(slowest, -l.real());
  return slowest;
}

}  // namespace

namespace internal {

PeriodicSystem LyapunovSystem(const PeriodicSystem& system) {
  const int n = system.states();
  PeriodicSystem::Functions f;
  f.A = [system, n](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const Eigen::MatrixXd a = system.A(t), b = system.B(t), c = system.C(t);
    const Eigen::MatrixXd bbt = b * b.transpose(), ctc = c.transpose() * c;
    out.setZero();
    // Row i + jn of vec(AP + PAᵀ): Σ_k A_ik P_kj + Σ_k A_jk P_ik.
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n; ++k) {
          out(i + j * n, k + j * n) += a(i, k);
          out(i + j * n, i + k * n) += a(j, k);
        }
        out(i + j * n, n * n + 1) = bbt(i, j);
        out(n * n, i + j * n) = ctc(j, i);  // tr(C P Cᵀ) = Σ (CᵀC)_ji P_ij
      }
  };
  return PeriodicSystem::FromFunctions(system.period(), n * n + 2, 0, 0, std::move(f),
                                       system.breakpoints());
}

}  // namespace internal

H2Norm HarmonicTransferFunction::H2(const NormOptions& options) const {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  H2Norm r;
  auto finish = [&](H2Norm out) -> H2Norm {
    out.elapsed_s = SecondsSince(start);
    if (!out.ok && out.failure.empty()) out.failure = "H2 norm not computed";
    return out;
  };
  if (!floquet_.ok || !modal_) {
    r.failure = "the Floquet decomposition failed: " + floquet_.failure;
    return finish(r);
  }
  if (floquet_.verdict == StabilityVerdict::kUnstable || internal::MaxFeedthrough(system_) > 0) {
    r.ok = true;
    r.value = r.modal_value = std::numeric_limits<double>::infinity();
    r.diagnostics.push_back({DiagnosticCode::kNormInfinite, Severity::kNote,
                             floquet_.verdict == StabilityVerdict::kUnstable
                                 ? "the system is unstable: its H2 norm is infinite"
                                 : "the system has a direct feedthrough D(t) ≠ 0: its H2 norm is "
                                   "infinite"});
    return finish(r);
  }
  if (floquet_.verdict != StabilityVerdict::kStable) {
    r.failure = "stability undecided (" + std::string(ToString(floquet_.verdict)) +
                "): the H2 norm is finite only for a stable system";
    return finish(r);
  }
  r.modal_value = std::sqrt(std::max(0.0, ModalH2Squared(*modal_)));
  // ‖G‖₂² carries 1/(−Re λ) of every mode: an exponent error δ moves it by about δ/decay.
  const double modal_error =
      r.modal_value * (std::max(modal_->tail, 1e-13) +
                       floquet_.error_estimate.value_or(0.0) / SlowestDecay(modal_->exponents));
  if (system_.states() > options.max_lyapunov_states) {
    std::ostringstream s;
    s << "H2: the Lyapunov route was skipped (" << system_.states() << " states, more than "
      << options.max_lyapunov_states << "); the modal value is unchecked";
    r.diagnostics.push_back({DiagnosticCode::kCheckRouteUnavailable, Severity::kNote, s.str()});
    r.value = r.modal_value;
    r.error_estimate = modal_error;
    r.ok = true;
    return finish(r);
  }
  return finish(CompareWithLyapunov(system_, std::move(r), modal_error, options));
}

}  // namespace ltp
