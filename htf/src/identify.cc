#include "ltp/htf/identify.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <unsupported/Eigen/FFT>

#include "ltp/core/error.h"

namespace ltp {

namespace {

using cd = std::complex<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;
const double kBoundFactor =
    std::sqrt(std::log(20.0));  // P(|circular Gaussian| > r) = e^{−r²/σ²} = 5 %

// Nearest integer to x, with *ok = x is one to 1e-6 (and small enough to count samples).
long WholeNumber(double x, bool* ok) {
  const double r = std::round(x);
  *ok = std::abs(r) < 1e12 && std::abs(x - r) <= 1e-6 * std::max(1.0, std::abs(x));
  return *ok ? static_cast<long>(r) : 0;
}

// DFT of a real column: c_k = (1/N) Σ_n y_n e^{−j2πkn/N}, k = 0..N−1.
std::vector<cd> Spectrum(const Eigen::VectorXd& y) {
  Eigen::FFT<double> fft;
  std::vector<double> in(y.data(), y.data() + y.size());
  std::vector<cd> out;
  fft.fwd(out, in);
  for (cd& c : out) c /= static_cast<double>(y.size());
  return out;
}

IdentifiedFrequency IdentifyRecord(const TimeRecord& rec, double T, const IdentifyOptions& o,
                                   size_t index, std::vector<std::string>& diagnostics) {
  const std::string where = "record " + std::to_string(index + 1);
  const long N = static_cast<long>(rec.time.size());
  const double dt = (rec.time.back() - rec.time.front()) / static_cast<double>(N - 1);
  const double L = N * dt;
  bool whole = false;
  const long P = WholeNumber(L / T, &whole);  // periods in the record
  if (!whole || P < 1)
    throw InputError(where + ": " + MessageNumber(L / T, 8) +
                     " periods long; identification needs whole periods");
  const long kf = WholeNumber(rec.excitation_hz * L, &whole);
  if (!whole || kf < 1)
    throw InputError(
        where + ": excitation " + MessageNumber(rec.excitation_hz, 8) + " Hz makes " +
        MessageNumber(rec.excitation_hz * L, 8) +
        " cycles; identification needs whole cycles (ltp simulate places the frequencies so)");
  if (P > N || kf >= N)
    throw InputError(where + ": " + std::to_string(N) + " samples cannot resolve the excitation (" +
                     std::to_string(kf) + " cycles in " + std::to_string(P) +
                     " periods): sample faster");
  for (int z : {o.min_order, o.max_order})
    if (2 * std::abs(kf + z * P) >= N)
      throw InputError(
          where + ": the line of order " + std::to_string(z) +
          " lies above the Nyquist frequency: " + "sample faster or ask for fewer orders");
  const double t0 = rec.time.front();
  // Bin k of a record starting at t0 is the coefficient on e^{j2πk(t − t0)/L}: relative to
  // absolute time (the system's phase) it carries e^{−j2πk t0/L}.
  const auto absolute = [&](const std::vector<cd>& c, long k) {
    const long bin = ((k % N) + N) % N;
    return c[static_cast<size_t>(bin)] * std::polar(1.0, -kTwoPi * static_cast<double>(k) * t0 / L);
  };
  const std::vector<cd> u = Spectrum(rec.inputs.col(o.input));
  const std::vector<cd> y = Spectrum(rec.outputs.col(o.output));
  const cd U = absolute(u, kf);
  if (!(std::abs(U) > 1e-12 * rec.inputs.col(o.input).cwiseAbs().maxCoeff()))
    throw InputError(where + ": input " + std::to_string(o.input) + " is not excited at " +
                     MessageNumber(rec.excitation_hz, 8) + " Hz");
  // Noise power: the bins 1..N/2−1 off every response line ±kf + mP.
  double power = 0;
  long count = 0;
  for (long k = 1; 2 * k < N; ++k) {
    const long a = ((k - kf) % P + P) % P, b = ((k + kf) % P + P) % P;
    if (a == 0 || b == 0) continue;
    power += std::norm(y[static_cast<size_t>(k)]);
    ++count;
  }
  IdentifiedFrequency out;
  out.excitation_hz = rec.excitation_hz;
  const double sigma = count > 0 ? std::sqrt(power / static_cast<double>(count)) : 0.0;
  out.noise = sigma * std::sqrt(static_cast<double>(N));  // rms of white noise: E|c_k|² = rms² / N
  out.separable = (2 * kf) % P != 0;
  if (count == 0)
    diagnostics.push_back(where +
                          ": no bin is free of response lines: the noise (and the bounds) cannot "
                          "be estimated; record more periods");
  if (!out.separable)
    diagnostics.push_back(where + ": " + MessageNumber(rec.excitation_hz, 8) +
                          " Hz is a multiple of Ωp/2: H_z and the mirror of another "
                          "order share each line, one record cannot separate them");
  for (int z = o.min_order; z <= o.max_order; ++z) {
    const cd h = absolute(y, kf + z * P) / U;
    out.h.push_back(out.separable ? h : cd(std::numeric_limits<double>::quiet_NaN(), 0));
    out.bound.push_back(count > 0 ? kBoundFactor * sigma / std::abs(U)
                                  : std::numeric_limits<double>::infinity());
  }
  return out;
}

}  // namespace

void IdentifyOptions::Validate() const {
  if (input < 0)
    throw InputError("IdentifyOptions::input = " + std::to_string(input) +
                     ". Violated constraint: >= 0");
  if (output < 0)
    throw InputError("IdentifyOptions::output = " + std::to_string(output) +
                     ". Violated constraint: >= 0");
  if (min_order > max_order || max_order - min_order > 200)
    throw InputError("IdentifyOptions::orders " + std::to_string(min_order) + ".." +
                     std::to_string(max_order) +
                     ". Violated constraint: min_order <= max_order, at most 201 orders");
}

IdentifyResult IdentifyStepSine(const TimeData& data, const IdentifyOptions& options) {
  options.Validate();
  data.Validate();
  if (options.input >= data.records[0].inputs.cols())
    throw InputError("input " + std::to_string(options.input) + " is not in the data (" +
                     std::to_string(data.records[0].inputs.cols()) + " inputs)");
  if (options.output >= data.records[0].outputs.cols())
    throw InputError("output " + std::to_string(options.output) + " is not in the data (" +
                     std::to_string(data.records[0].outputs.cols()) + " outputs)");
  IdentifyResult r;
  r.min_order = options.min_order;
  r.max_order = options.max_order;
  for (size_t i = 0; i < data.records.size(); ++i)
    r.frequencies.push_back(
        IdentifyRecord(data.records[i], data.period, options, i, r.diagnostics));
  std::stable_sort(r.frequencies.begin(), r.frequencies.end(),
                   [](const auto& a, const auto& b) { return a.excitation_hz < b.excitation_hz; });
  return r;
}

}  // namespace ltp
