#include "ltp/htf/identify.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <unsupported/Eigen/FFT>

#include "ltp/core/error.h"

namespace ltp {

namespace {

using cd = std::complex<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kBiasRatio = 10;
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

void CheckData(const TimeData& data, const IdentifyOptions& options) {
  options.Validate();
  data.Validate();
  if (options.input >= data.records[0].inputs.cols())
    throw InputError("input " + std::to_string(options.input) + " is not in the data (" +
                     std::to_string(data.records[0].inputs.cols()) + " inputs)");
  if (options.output >= data.records[0].outputs.cols())
    throw InputError("output " + std::to_string(options.output) + " is not in the data (" +
                     std::to_string(data.records[0].outputs.cols()) + " outputs)");
}

// Bin k of a record starting at t0, relative to absolute time (the system's phase): the bin is
// the coefficient on e^{j2πk(t − t0)/L}, so it carries e^{−j2πk t0/L}. k < 0: the mirror bin.
cd AbsoluteBin(const std::vector<cd>& c, long k, double t0, double L) {
  const long N = static_cast<long>(c.size());
  const long bin = ((k % N) + N) % N;
  return c[static_cast<size_t>(bin)] * std::polar(1.0, -kTwoPi * static_cast<double>(k) * t0 / L);
}

// One broadband estimate: H_z at an excited bin, with what its bound and report need.
struct LineEstimate {
  cd h{std::numeric_limits<double>::quiet_NaN(), 0};
  double variance_factor = std::numeric_limits<double>::infinity();  // [(MᴴM)⁻¹]_jj
  double condition = std::numeric_limits<double>::infinity();
  double quality = std::numeric_limits<double>::quiet_NaN();
  double line_variance = std::numeric_limits<double>::quiet_NaN();  // |residual|² / (R − q)
};

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
  const auto absolute = [&](const std::vector<cd>& c, long k) { return AbsoluteBin(c, k, t0, L); };
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
  CheckData(data, options);
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

IdentifyResult IdentifyBroadband(const TimeData& data, const IdentifyOptions& options) {
  CheckData(data, options);
  const TimeRecord& first = data.records.front();
  const long N = static_cast<long>(first.time.size());
  const double dt = (first.time.back() - first.time.front()) / static_cast<double>(N - 1);
  const double L = N * dt;
  bool whole = false;
  const long P = WholeNumber(L / data.period, &whole);
  if (!whole || P < 1)
    throw InputError("the records are " + MessageNumber(L / data.period, 8) +
                     " periods long; identification needs whole periods");
  const long R = static_cast<long>(data.records.size());
  std::vector<std::vector<cd>> u(R), y(R);
  std::vector<double> t0(R);
  for (long r = 0; r < R; ++r) {
    const TimeRecord& rec = data.records[r];
    const std::string where = "record " + std::to_string(r + 1);
    if (rec.excitation_hz != 0)
      throw InputError(where + " is a step-sine record (" + MessageNumber(rec.excitation_hz, 8) +
                       " Hz): identify it with the step-sine method");
    const double dtr = (rec.time.back() - rec.time.front()) / static_cast<double>(N - 1);
    if (static_cast<long>(rec.time.size()) != N || std::abs(dtr - dt) > 1e-9 * dt)
      throw InputError(where +
                       " differs from record 1 in length or sampling: broadband "
                       "identification combines records of one length and rate");
    u[r] = Spectrum(rec.inputs.col(options.input));
    y[r] = Spectrum(rec.outputs.col(options.output));
    t0[r] = rec.time.front();
  }
  // The excited bins: where record 1's input has energy; every record must excite the same.
  std::set<long> excited;
  for (long r = 0; r < R; ++r) {
    double top = 0;
    for (long k = 1; 2 * k < N; ++k) top = std::max(top, std::abs(u[r][k]));
    std::set<long> here;
    for (long k = 1; 2 * k < N; ++k)
      if (std::abs(u[r][k]) > 1e-6 * top) here.insert(k);
    if (r == 0) excited = here;
    if (here.empty() || here != excited)
      throw InputError("record " + std::to_string(r + 1) +
                       (here.empty() ? ": the input is not excited"
                                     : " excites other frequencies than record 1: broadband "
                                       "identification needs one set of frequencies"));
  }
  for (long k : excited)
    for (int z : {options.min_order, options.max_order})
      if (2 * std::abs(k + z * P) >= N)
        throw InputError("the line of order " + std::to_string(z) + " of " +
                         MessageNumber(k / L, 8) +
                         " Hz lies above the Nyquist frequency: sample faster or ask for "
                         "fewer orders");
  // Per response line (bin b): the unknowns H_z at the excited b − zP, solved across records.
  std::map<std::pair<long, int>, LineEstimate> found;
  double rss = 0;
  long dof = 0, lines = 0, under = 0, missing = 0;
  for (long b = 1; 2 * b < N; ++b) {
    std::vector<std::pair<int, long>> unknowns;  // (z, excitation bin; < 0: mirror)
    for (int z = options.min_order; z <= options.max_order; ++z) {
      const long k = b - z * P;
      if (k != 0 && excited.count(std::abs(k))) unknowns.emplace_back(z, k);
    }
    if (unknowns.empty()) continue;
    ++lines;
    const long q = static_cast<long>(unknowns.size());
    Eigen::MatrixXcd M(R, q);
    Eigen::VectorXcd Y(R);
    for (long r = 0; r < R; ++r) {
      Y(r) = AbsoluteBin(y[r], b, t0[r], L);
      for (long j = 0; j < q; ++j) {
        const long k = unknowns[j].second;
        const cd uk = AbsoluteBin(u[r], std::abs(k), t0[r], L);
        M(r, j) = k > 0 ? uk : std::conj(uk);
      }
    }
    Eigen::JacobiSVD<Eigen::MatrixXcd> svd(M, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& sv = svd.singularValues();
    LineEstimate e;
    if (R < q || !(sv(q - 1) > 1e-12 * sv(0))) {
      ++under;
      missing = std::max(missing, q - R);
    } else {
      const Eigen::VectorXcd x = svd.solve(Y);
      const double res = (Y - M * x).squaredNorm();
      rss += res;
      dof += R - q;
      e.condition = sv(0) / sv(q - 1);
      if (R > q && Y.squaredNorm() > 0) e.quality = 1 - res / Y.squaredNorm();
      if (R > q) e.line_variance = res / static_cast<double>(R - q);
      for (long j = 0; j < q; ++j) {
        LineEstimate ej = e;
        ej.variance_factor = 0;
        for (long i = 0; i < q; ++i)
          ej.variance_factor += std::norm(svd.matrixV()(j, i)) / (sv(i) * sv(i));
        const auto [z, k] = unknowns[j];
        ej.h = k > 0 ? x(j) : std::conj(x(j));
        // A mirrored unknown is H_z(−f) = conj H_{−z}(f) of the real system.
        const std::pair<long, int> key = k > 0 ? std::make_pair(k, z) : std::make_pair(-k, -z);
        auto [it, inserted] = found.emplace(key, ej);
        if (!inserted && ej.variance_factor < it->second.variance_factor) it->second = ej;
      }
      continue;
    }
    for (const auto& [z, k] : unknowns) {
      const std::pair<long, int> key = k > 0 ? std::make_pair(k, z) : std::make_pair(-k, -z);
      found.emplace(key, e);
    }
  }
  IdentifyResult r;
  r.min_order = options.min_order;
  r.max_order = options.max_order;
  const double sigma2 = dof > 0 ? rss / static_cast<double>(dof) : kNaN;
  // A line whose residual is far above the pooled noise is fed by something the regression
  // lacks — orders outside the requested range, nonlinearity — a bias, not noise: its bounds
  // use its own residual (under white noise a ratio of 10 has probability < 1e-4 already at
  // R − q = 2) and the lines are reported.
  std::set<std::pair<long, int>> biased;
  for (auto& [key, e] : found)
    if (e.line_variance > kBiasRatio * sigma2) biased.insert(key);
  for (long k : excited) {
    IdentifiedFrequency f;
    f.excitation_hz = static_cast<double>(k) / L;
    f.noise = std::sqrt(sigma2 * static_cast<double>(N));
    for (int z = options.min_order; z <= options.max_order; ++z) {
      const auto it = found.find({k, z});
      const LineEstimate e = it != found.end() ? it->second : LineEstimate{};
      f.h.push_back(e.h);
      const double variance = biased.count({k, z}) ? e.line_variance : sigma2;
      f.bound.push_back(dof > 0 && std::isfinite(e.variance_factor)
                            ? kBoundFactor * std::sqrt(variance * e.variance_factor)
                            : std::numeric_limits<double>::infinity());
      f.condition.push_back(e.condition);
      f.quality.push_back(e.quality);
    }
    r.frequencies.push_back(std::move(f));
  }
  if (under > 0)
    r.diagnostics.push_back(std::to_string(under) + " of " + std::to_string(lines) +
                            " response lines are under-determined (more unknown H_z than the " +
                            std::to_string(R) + " records give equations): record at least " +
                            std::to_string(missing) +
                            " more records with new phases; their H_z are left out (NaN)");
  if (!biased.empty())
    r.diagnostics.push_back(
        std::to_string(biased.size()) + " estimates come from response lines whose residual is " +
        "over " + MessageNumber(kBiasRatio, 3) + "× the pooled noise: orders outside " +
        std::to_string(options.min_order) + ".." + std::to_string(options.max_order) +
        " (or nonlinearity) feed them; their bounds use their own residual — widen --orders");
  if (dof == 0)
    r.diagnostics.push_back(
        "no response line has more records than unknowns: the noise cannot be estimated and "
        "the bounds are unknown (∞); record more records than orders");
  return r;
}

}  // namespace ltp
