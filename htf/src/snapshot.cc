#include "ltp/htf/snapshot.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "fft_util.h"
#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/integrate/threads.h"

namespace ltp {

namespace {
using cd = std::complex<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;
}  // namespace

Eigen::MatrixXcd FrozenFrf(const LtiSystem& s, double omega) {
  const Eigen::Index n = s.A.rows();
  Eigen::MatrixXcd M = cd(0, omega) * Eigen::MatrixXcd::Identity(n, n) - s.A.cast<cd>();
  Eigen::PartialPivLU<Eigen::MatrixXcd> lu(M);
  Eigen::MatrixXcd h(s.C.rows(), s.B.cols());
  if (!(lu.rcond() > 1e-15)) {
    h.setConstant(cd(std::numeric_limits<double>::quiet_NaN(), 0));
    return h;
  }
  h = s.C.cast<cd>() * lu.solve(s.B.cast<cd>());
  if (s.D.size() == h.size()) h += s.D.cast<cd>();
  return h;
}

void SnapshotOptions::Validate() const {
  const OptionCheck check("SnapshotOptions");
  if (frequencies_hz.empty()) check.Fail("frequencies_hz", "{}", "at least one frequency");
  for (double f : frequencies_hz)
    if (!std::isfinite(f)) check.Fail("frequencies_hz", f, "finite");
  if (time.has_value() == angle_deg.has_value())
    check.Fail("time, angle_deg", time ? "both set" : "both unset", "exactly one of them set");
  if (time && !std::isfinite(*time)) check.Fail("time", *time, "finite");
  if (angle_deg && !std::isfinite(*angle_deg)) check.Fail("angle_deg", *angle_deg, "finite");
  if (input < 0) check.Fail("input", input, ">= 0");
  if (output < 0) check.Fail("output", output, ">= 0");
  if (min_order > max_order)
    check.Fail("min_order", min_order,
               "min_order <= max_order (" + std::to_string(max_order) + ")");
  if (check_points < 1) check.Fail("check_points", check_points, ">= 1");
  floquet.Validate();
  modal.Validate();
  htf.Validate();
}

namespace {

void CheckChannels(const PeriodicSystem& system, const SnapshotOptions& options) {
  if (system.inputs() < 1 || system.outputs() < 1)
    throw InputError("FRFs need at least one input and one output");
  if (options.input >= system.inputs())
    throw InputError("snapshot: input " + std::to_string(options.input) +
                     " out of range (the system has " + std::to_string(system.inputs()) + ")");
  if (options.output >= system.outputs())
    throw InputError("snapshot: output " + std::to_string(options.output) +
                     " out of range (the system has " + std::to_string(system.outputs()) + ")");
}

// Sets r.frozen, r.time and (by angle) r.angle_deg: the LTI system at the requested instant.
void Freeze(const PeriodicSystem& system, const SnapshotOptions& options, SnapshotResult& r) {
  if (options.angle_deg) {
    const double rad =
        std::fmod(*options.angle_deg, 360.0) * std::numbers::pi / 180;  // 1e308° stays finite
    r.frozen = system.SnapshotAtAngle(rad);  // throws InputError without a rotor speed
    r.angle_deg = options.angle_deg;
    r.time = std::fmod(rad, 2 * std::numbers::pi) / *system.rotor_speed();
  } else {
    r.time = *options.time;
    r.frozen = system.Snapshot(r.time);
  }
}

// Eigenvalues of the frozen A, by |Im| ascending (the positive one of a pair first).
std::vector<cd> SortedEigenvalues(const Eigen::MatrixXd& frozen_a) {
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(frozen_a.cast<cd>(), false);
  std::vector<cd> eigenvalues;
  for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k)
    eigenvalues.push_back(es.eigenvalues()(k));
  std::sort(eigenvalues.begin(), eigenvalues.end(), [](cd a, cd b) {
    return std::abs(a.imag()) != std::abs(b.imag()) ? std::abs(a.imag()) < std::abs(b.imag())
                                                    : a.imag() > b.imag();
  });
  return eigenvalues;
}

// r.summed: G(ω) = Σ_z H_z(ω − zΩp) by the modal route. Returns Σ_z |H_z(ω − zΩp)| per
// frequency, which scales the check's relative disagreement into an error of G.
std::vector<double> SumPartials(const ModalChannel& channel, double wp,
                                const SnapshotOptions& options, SnapshotResult& r) {
  const int F = static_cast<int>(options.frequencies_hz.size());
  std::vector<double> magnitude_sum(F, 0.0);
  for (int i = 0; i < F; ++i) {
    const double w = kTwoPi * options.frequencies_hz[i];
    cd g = 0;
    for (int z = options.min_order; z <= options.max_order; ++z) {
      const cd h = channel.Evaluate(w - z * wp, z, z).front();
      g += h;
      magnitude_sum[i] += std::abs(h);
    }
    r.summed.push_back(g);
  }
  return magnitude_sum;
}

// Checks the modal model by the harmonic transfer function where G needs it: at excitation
// frequencies spread over [ω0 − zmax Ωp, ω1 − zmin Ωp], every order from one solve. Sets
// r.max_summed_disagreement (relative to the largest |H_z| at each check frequency) and says
// how it was found in a diagnostic.
void CheckByHtf(const PeriodicSystem& system, const ModalChannel& channel, double wp,
                const SnapshotOptions& options, SnapshotResult& r) {
  const int zmin = options.min_order, zmax = options.max_order;
  const double e0 = kTwoPi * options.frequencies_hz.front() - zmax * wp;
  const double e1 = kTwoPi * options.frequencies_hz.back() - zmin * wp;
  const int P = options.check_points;
  std::vector<double> check(P);
  for (int q = 0; q < P; ++q) check[q] = P == 1 ? 0.5 * (e0 + e1) : e0 + (e1 - e0) * q / (P - 1);
  // The truncation is chosen at the check frequencies themselves: its own error there must
  // not pass for the modal route's.
  HtfSolver htf(system, options.htf);
  htf.ChooseTruncation(zmin, zmax, check);
  htf.PrepareSweep(P);
  std::vector<double> disagreement(P, 0.0);
#pragma omp parallel for schedule(dynamic) num_threads(ThreadsFor(0))  // independent solves
  for (int q = 0; q < P; ++q) {
    const double w = check[q];
    const PartialFrfs h = htf.Evaluate(w, zmin, zmax);
    const std::vector<cd> modal = channel.Evaluate(w, zmin, zmax);
    double largest = 0, diff = 0;
    for (int z = zmin; z <= zmax; ++z) {
      const cd reference = h[z - zmin](options.output, options.input);
      largest = std::max(largest, std::abs(reference));
      diff = std::max(diff, std::abs(reference - modal[z - zmin]));
    }
    if (largest > 0) disagreement[q] = diff / largest;
  }
  for (double d : disagreement) r.max_summed_disagreement = std::max(r.max_summed_disagreement, d);
  std::ostringstream s;
  s << "summed partials: orders " << zmin << ".." << zmax << " by the modal route, checked by "
    << "the htf route (N = " << htf.harmonics() << ") at " << P << " excitation frequencies "
    << "over the band the orders need: max disagreement " << r.max_summed_disagreement
    << " (relative to the largest |H_z| there)";
  r.diagnostics.push_back({DiagnosticCode::kRoutesCompared, Severity::kNote, s.str()});
}

// --compare: the periodic system's Floquet exponents and summed partials G with their error.
void CompareWithPeriodic(const PeriodicSystem& system, const SnapshotOptions& options,
                         SnapshotResult& r) {
  FloquetOptions fo = options.floquet;
  fo.compute_modes = true;
  const FloquetResult fl = AnalyzeFloquet(system, fo);
  for (const auto& m : fl.modes) r.floquet_exponents.push_back(m.exponent);
  if (!fl.ok) {
    r.diagnostics.push_back({DiagnosticCode::kFloquetFailed, Severity::kWarning,
                             "Floquet analysis failed: no summed partial FRFs"});
    return;
  }
  const ModalModel model = BuildModalModel(system, fl, options.modal);
  r.modal_reliable = model.reliable;
  for (const auto& d : model.diagnostics) r.diagnostics.push_back(d);
  const ModalChannel channel(model, options.output, options.input);
  const double wp = system.omega();
  const std::vector<double> magnitude_sum = SumPartials(channel, wp, options, r);
  CheckByHtf(system, channel, wp, options, r);
  // A relative disagreement δ of every H_z carries to G as δ Σ_z |H_z|.
  r.summed_error.resize(magnitude_sum.size());
  for (size_t i = 0; i < magnitude_sum.size(); ++i)
    r.summed_error[i] = r.max_summed_disagreement * magnitude_sum[i];
}

}  // namespace

SnapshotResult ComputeSnapshotFrf(const PeriodicSystem& system, const SnapshotOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  CheckChannels(system, options);
  SnapshotResult r;
  r.frequencies_hz = options.frequencies_hz;
  Freeze(system, options, r);
  r.eigenvalues = SortedEigenvalues(r.frozen.A);
  for (double f : options.frequencies_hz)
    r.snapshot.push_back(FrozenFrf(r.frozen, kTwoPi * f)(options.output, options.input));
  if (options.compare) CompareWithPeriodic(system, options, r);
  r.elapsed_s = SecondsSince(start);
  return r;
}

}  // namespace ltp
