#include "broadband_on_angle.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "angle_interpolation.h"
#include "line_fit.h"
#include "ltp/core/error.h"

namespace ltp::internal {

namespace {

// Per record and line, the change of the model that a unit error of U_rk makes (real, then
// imaginary part), with the estimates in it: 2 Re(δU Σ_z H_z e^{jφ_kz}) on the record's rows.
std::vector<RowPerturbation> InputErrorChanges(const TimeData& data, const LineFit& fit,
                                               const Eigen::MatrixXd& phases, long K, long Z) {
  std::vector<RowPerturbation> changes;
  Eigen::Index row = 0;
  for (const TimeRecord& rec : data.records) {
    const Eigen::Index n = static_cast<Eigen::Index>(rec.time.size());
    for (long k = 0; k < K; ++k) {
      Eigen::VectorXcd g = Eigen::VectorXcd::Zero(n);
      for (long z = 0; z < Z; ++z) {
        const std::complex<double> h = fit.amplitude[static_cast<size_t>(k * Z + z)];
        if (!std::isfinite(std::abs(h))) continue;
        for (Eigen::Index i = 0; i < n; ++i)
          g(i) += h * std::polar(1.0, phases(row + i, k * Z + z));
      }
      changes.push_back({row, 2 * g.real()});
      changes.push_back({row, -2 * g.imag()});
    }
    row += n;
  }
  return changes;
}

}  // namespace

IdentifyResult IdentifyBroadbandOnAngle(const TimeData& data, const IdentifyOptions& o,
                                        const std::vector<double>& omegas,
                                        const Eigen::MatrixXcd& input_amplitudes,
                                        double input_bin_variance) {
  const long K = static_cast<long>(omegas.size()), Z = o.max_order - o.min_order + 1;
  long rows = 0;
  for (const TimeRecord& rec : data.records) rows += static_cast<long>(rec.time.size());
  // The design matrix and its SVD factors: three copies of rows × (1 + 2KZ) doubles.
  const double cells = static_cast<double>(rows) * static_cast<double>(1 + 2 * K * Z);
  if (cells > 2.5e7)
    throw InputError(
        "broadband identification on a measured angle fits every line and order "
        "of all records at once: " +
        std::to_string(K) + " lines × " + std::to_string(Z) + " orders × " + std::to_string(rows) +
        " samples is " + MessageNumber(cells, 3) +
        " matrix entries, over 2.5e7 — fewer lines, orders or samples, or "
        "step-sine records");
  Eigen::VectorXd y(rows);
  Eigen::MatrixXd phases(rows, K * Z);
  Eigen::MatrixXcd gains(rows, K * Z);
  double turned = 0, elapsed = 0;
  long row = 0;
  for (size_t r = 0; r < data.records.size(); ++r) {
    const TimeRecord& rec = data.records[r];
    const DelayedClock clock = Delayed(rec.time, rec.angle, true, data.period, o.output_delay);
    turned += rec.angle.back() - rec.angle.front();
    elapsed += rec.time.back() - rec.time.front();
    for (size_t n = 0; n < rec.time.size(); ++n, ++row) {
      y(row) = rec.outputs(static_cast<Eigen::Index>(n), o.output);
      for (long k = 0; k < K; ++k)
        for (long z = 0; z < Z; ++z) {
          phases(row, k * Z + z) = omegas[static_cast<size_t>(k)] * clock.time[n] +
                                   static_cast<double>(z + o.min_order) * clock.theta[n];
          gains(row, k * Z + z) = input_amplitudes(static_cast<Eigen::Index>(r), k);
        }
    }
  }
  const LineBasis basis(phases, gains);
  const LineFit fit = basis.Fit(y);
  // The input's noise, through the same factored fit.
  const std::vector<std::vector<std::complex<double>>> responses =
      input_bin_variance > 0 ? basis.Response(InputErrorChanges(data, fit, phases, K, Z))
                             : std::vector<std::vector<std::complex<double>>>{};
  IdentifyResult result;
  result.min_order = o.min_order;
  result.max_order = o.max_order;
  long undetermined = 0;
  for (long k = 0; k < K; ++k) {
    IdentifiedFrequency f;
    f.excitation_hz = omegas[static_cast<size_t>(k)] / (2 * std::numbers::pi);
    f.speed = turned / elapsed;
    f.noise = std::sqrt(fit.noise_variance);
    for (long z = 0; z < Z; ++z) {
      const size_t l = static_cast<size_t>(k * Z + z);
      f.h.push_back(fit.amplitude[l]);
      f.separable = f.separable && fit.determined[l];
      undetermined += !fit.determined[l];
      double variance = fit.variance[l];  // output noise; then the input's, each δU's share
      for (const auto& response : responses)
        variance += input_bin_variance / 2 * std::norm(response[l]);
      f.bound.push_back(fit.determined[l] && fit.dof > 0 ? kBoundFactor * std::sqrt(variance)
                                                         : std::numeric_limits<double>::infinity());
    }
    result.frequencies.push_back(std::move(f));
  }
  result.diagnostics.push_back(
      {DiagnosticCode::kBroadbandFit, Severity::kNote,
       "broadband on the measured angle: one least-squares fit of " + std::to_string(K * Z) +
           " H_z over the " + std::to_string(data.records.size()) + " records (mean speed " +
           MessageNumber(turned / elapsed, 7) +
           " rad/s; 2π/T = " + MessageNumber(2 * std::numbers::pi / data.period, 7) + ")"});
  if (undetermined > 0)
    result.diagnostics.push_back({DiagnosticCode::kLinesUnderDetermined, Severity::kWarning,
                                  std::to_string(undetermined) +
                                      " H_z are not determined by these records (their lines "
                                      "coincide in every record): record more records with new "
                                      "phases; they are left out (NaN)"});
  if (fit.dof == 0)
    result.diagnostics.push_back({DiagnosticCode::kNoNoiseEstimate, Severity::kWarning,
                                  "as many unknowns as samples: the bounds are unknown (∞)"});
  return result;
}

}  // namespace ltp::internal
