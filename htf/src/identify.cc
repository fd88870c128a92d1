#include "ltp/htf/identify.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <unsupported/Eigen/FFT>

#include "angle_interpolation.h"
#include "broadband_on_angle.h"
#include "line_fit.h"
#include "ltp/core/error.h"

namespace ltp {

namespace {

using cd = std::complex<double>;
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kBiasRatio = 10;
using internal::kBoundFactor;

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

// One line of a record's fit: what it is and its frequency (rad/s, at the mean speed).
struct Line {
  double omega_factor = 0;  // multiple of ω
  int order = 0;            // multiple of θ
  double frequency = 0;     // |ν| = |kω + zΩ̄|
};

// The lines a record is fitted with: the requested orders first, then what else a rig's
// response holds — further orders, the synchronous orders m·Ωp (unbalance), 2ω and 3ω and
// their orders (nonlinearity) — each only below 0.9 × Nyquist and 1.5 bins from every line already
// taken, so the extra lines keep energy out of the noise estimate without making a requested line
// undetermined.
std::vector<Line> LinesToFit(double omega, double speed, double nyquist, double bin,
                             const IdentifyOptions& o) {
  std::vector<Line> lines;
  for (int z = o.min_order; z <= o.max_order; ++z)
    lines.push_back({1, z, std::abs(omega + z * speed)});
  const auto consider = [&](double k, int z) {
    const double f = std::abs(k * omega + z * speed);
    if (f > 0.9 * nyquist || f < 1.5 * bin) return;
    for (const Line& l : lines)
      if (std::abs(f - l.frequency) < 1.5 * bin) return;
    lines.push_back({k, z, f});
  };
  for (int m = 1; m <= 10; ++m) consider(0, m);
  for (int extra = 1; extra <= 8; ++extra) {
    consider(1, o.max_order + extra);
    consider(1, o.min_order - extra);
  }
  // A nonlinearity's harmonics are modulated by the system too: kω + zθ.
  for (double k : {2.0, 3.0})
    for (int z = 0; std::abs(z) <= std::max(-o.min_order, o.max_order); z = z > 0 ? -z : 1 - z)
      consider(k, z);
  return lines;
}

Eigen::MatrixXd LinePhases(const std::vector<Line>& lines, const std::vector<double>& time,
                           const std::vector<double>& theta, double omega) {
  Eigen::MatrixXd phases(static_cast<Eigen::Index>(time.size()),
                         static_cast<Eigen::Index>(lines.size()));
  for (size_t l = 0; l < lines.size(); ++l)
    for (size_t n = 0; n < time.size(); ++n)
      phases(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(l)) =
          lines[l].omega_factor * omega * time[n] + lines[l].order * theta[n];
  return phases;
}

// Samples in runs of ≥ 3 equal values at the channel's extreme: a clipped signal.
long ClippedRuns(const Eigen::VectorXd& x) {
  long runs = 0;
  for (const double extreme : {x.maxCoeff(), x.minCoeff()}) {
    long length = 0;
    for (Eigen::Index i = 0; i <= x.size(); ++i) {
      if (i < x.size() && x(i) == extreme) {
        ++length;
        continue;
      }
      if (length >= 3) ++runs;
      length = 0;
    }
  }
  return runs;
}

// The input's phase in each quarter of the record against the whole record's sine: dropped
// samples whose times were written as if none were lost, or a drifting shaker, move it.
// Returns the largest move (rad) that exceeds 6 standard deviations of the quarters' phases.
double InputPhaseMove(const std::vector<double>& time, const Eigen::VectorXd& u, double omega) {
  const long n = static_cast<long>(time.size()), q = n / 4;
  if (q < 16) return 0;
  std::vector<std::complex<double>> amplitude;
  std::vector<double> sd;
  for (long k = 0; k < 4; ++k) {
    const std::vector<double> t(time.begin() + k * q, time.begin() + (k + 1) * q);
    Eigen::MatrixXd phase(q, 1);
    for (long i = 0; i < q; ++i) phase(i, 0) = omega * t[static_cast<size_t>(i)];
    const internal::LineFit f = internal::FitLines(u.segment(k * q, q), phase);
    amplitude.push_back(f.amplitude[0]);
    sd.push_back(std::sqrt(f.variance[0]) / std::max(std::abs(f.amplitude[0]), 1e-300));
  }
  double move = 0;
  for (long k = 1; k < 4; ++k) {
    const double d = std::abs(std::arg(amplitude[k] / amplitude[0]));
    if (d > 6 * std::hypot(sd[k], sd[0]) && d > 1e-6) move = std::max(move, d);
  }
  return move;
}

// What a record's data say about themselves, one line each where something is wrong.
void RecordNotes(const TimeRecord& rec, const IdentifyOptions& o, double omega, double dt,
                 const std::string& where, std::vector<Diagnostic>& notes) {
  long gaps = 0, first = 0;
  for (size_t i = 1; i < rec.time.size(); ++i)
    if (rec.time[i] - rec.time[i - 1] > 1.5 * dt && gaps++ == 0) first = static_cast<long>(i);
  if (gaps > 0)
    notes.push_back({DiagnosticCode::kRecordGaps, Severity::kWarning,
                     where + ": " + std::to_string(gaps) + " gap(s) in t, the first at sample " +
                         std::to_string(first + 1) +
                         " (t = " + MessageNumber(rec.time[static_cast<size_t>(first)], 10) +
                         " s); the fit uses the times as written"});
  for (const auto& [channel, name] :
       {std::pair{rec.inputs.col(o.input), "input"}, {rec.outputs.col(o.output), "output"}}) {
    const Eigen::VectorXd x = channel;
    if (const long runs = ClippedRuns(x); runs >= 2)
      notes.push_back({DiagnosticCode::kRecordClipped, Severity::kWarning,
                       where + ": the " + name + " sits at its extreme value in " +
                           std::to_string(runs) +
                           " runs of 3 or more samples: clipped? A clipped record biases H_z"});
  }
  if (const double move = InputPhaseMove(rec.time, rec.inputs.col(o.input), omega); move > 0)
    notes.push_back({DiagnosticCode::kInputPhaseMoves, Severity::kWarning,
                     where + ": the input's phase moves by " +
                         MessageNumber(move * 180 / std::numbers::pi, 3) +
                         "° within the record: samples dropped while the times went on, or the "
                         "shaker's frequency drifts — H_z is biased by as much"});
}

// Lines beyond the requested ones that stand out of the noise, over all records (said once).
struct ExtraLines {
  std::set<int> synchronous;  // orders m of the lines m·θ
  long harmonic_records = 0;  // records with a response at 2ω or 3ω
  double speed_change = 0;    // largest relative change of dθ/dt within a record
  long off_speed = 0;         // records without a measured angle whose lines sit off 2π/T
  double largest_offset = 0;  // relative
  long moved = 0;             // records whose input's frequency is not the written one
  double largest_move = 0;    // Hz
};

// How much dθ/dt changes over a record, relative to its mean: θ(t) fitted by a quadratic
// a + b s + c s² (s = t − mid), the change 2cL against b.
double SpeedChange(const std::vector<double>& time, const std::vector<double>& theta) {
  const Eigen::Index n = static_cast<Eigen::Index>(time.size());
  if (n < 3) return 0;
  const double mid = 0.5 * (time.front() + time.back()), L = time.back() - time.front();
  Eigen::MatrixXd X(n, 3);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = (time[static_cast<size_t>(i)] - mid) / L;
    X.row(i) << 1, s, s * s;
    y(i) = theta[static_cast<size_t>(i)];
  }
  const Eigen::Vector3d c = X.colPivHouseholderQr().solve(y);
  return std::abs(2 * c(2) / c(1));
}

// The record's excitation: its frequency measured from the input (from the written one, or
// the input's strongest line), and the input's amplitude there, by least squares on
// ω(t − input_delay). @throws InputError when the input is not one sine at that frequency.
struct RecordExcitation {
  internal::FittedRate rate;  // ω (rad/s) and its standard error
  cd U;                       // the input's complex amplitude of e^{jωt}
  double variance = 0;        // of U, from the input's residual (0: none)
};

RecordExcitation ExcitationOf(const TimeRecord& rec, const Eigen::VectorXd& u,
                              const IdentifyOptions& o, const std::string& where) {
  RecordExcitation e;
  const bool written = rec.excitation_hz > 0;
  e.rate = internal::FitSineFrequency(
      rec.time, u, written ? kTwoPi * rec.excitation_hz : internal::StrongestLine(rec.time, u));
  Eigen::MatrixXd excitation(static_cast<Eigen::Index>(rec.time.size()), 1);
  for (size_t n = 0; n < rec.time.size(); ++n)
    excitation(static_cast<Eigen::Index>(n), 0) = e.rate.rate * (rec.time[n] - o.input_delay);
  const internal::LineFit in = internal::FitLines(u, excitation);
  e.U = in.amplitude[0];
  e.variance = std::isfinite(in.variance[0]) ? in.variance[0] : 0;
  if (!(std::abs(e.U) > 1e-12 * u.cwiseAbs().maxCoeff()))
    throw InputError(where + ": input " + std::to_string(o.input) + " is not excited at " +
                     MessageNumber(rec.excitation_hz, 8) + " Hz");
  // One sine per record: a multisine or noise input has most of its power elsewhere.
  const double centred = (u.array() - u.mean()).matrix().squaredNorm();
  const double sine_power = 2 * std::norm(e.U) * static_cast<double>(u.size());
  if (sine_power < 0.5 * centred)
    throw InputError(where + ": the input is not one sine (" +
                     MessageNumber(100 * (1 - sine_power / centred), 3) +
                     " % of its power lies off its strongest line): step-sine identification "
                     "needs one frequency per record (broadband records: --method broadband)");
  return e;
}

// H_z = Y_z / U from the output's fit, each with its 95 % bound: output noise through Y_z,
// input noise through U (first order; independent); without a measured angle, the written
// times' error moves zθ by up to |z|·Ωp·time_error.
void FillEstimates(const internal::LineFit& fit, const RecordExcitation& e, const TimeRecord& rec,
                   const IdentifyOptions& o, double speed, IdentifiedFrequency& out) {
  for (int z = o.min_order; z <= o.max_order; ++z) {
    const size_t l = static_cast<size_t>(z - o.min_order);
    const cd h = fit.amplitude[l] / e.U;
    out.separable = out.separable && fit.determined[l];
    out.h.push_back(h);
    const double variance = (fit.variance[l] + std::norm(h) * e.variance) / std::norm(e.U);
    const double clock = rec.angle.empty() ? std::abs(z * speed) * rec.time_error * std::abs(h) : 0;
    out.bound.push_back(fit.dof > 0 && std::isfinite(variance)
                            ? kBoundFactor * std::sqrt(variance) + clock
                            : std::numeric_limits<double>::infinity());
  }
}

// What the record shows beyond the requested lines, tallied for the notes said once: the
// extra lines that stand out (synchronous orders, harmonics of ω), the speed's change, lines
// off 2π/T without a measured angle, a written frequency other than the input's.
void TallyExtraLines(const TimeRecord& rec, const IdentifyOptions& o, const Eigen::VectorXd& y,
                     const std::vector<Line>& lines, const internal::LineFit& fit,
                     const RecordExcitation& e, const std::vector<double>& theta, double speed,
                     ExtraLines& extra) {
  const double omega = e.rate.rate, L = rec.time.back() - rec.time.front();
  const size_t requested = static_cast<size_t>(o.max_order - o.min_order + 1);
  double largest = 0;
  for (size_t l = 0; l < requested; ++l)
    if (fit.determined[l]) largest = std::max(largest, std::abs(fit.amplitude[l]));
  bool harmonic = false;
  for (size_t l = requested; l < lines.size(); ++l) {
    const double a = std::abs(fit.amplitude[l]);
    if (!(a * a > 36 * fit.variance[l] && a > 1e-6 * largest)) continue;
    if (lines[l].omega_factor == 0) extra.synchronous.insert(lines[l].order);
    harmonic = harmonic || lines[l].omega_factor > 1;
  }
  extra.harmonic_records += harmonic;
  extra.speed_change = std::max(extra.speed_change, SpeedChange(rec.time, theta));
  if (rec.angle.empty() && (o.min_order != 0 || o.max_order != 0)) {
    // Without a measured angle, the data themselves say at which speed their lines sit.
    Eigen::MatrixXd base(static_cast<Eigen::Index>(rec.time.size()), o.max_order - o.min_order + 1);
    std::vector<double> orders;
    for (int z = o.min_order; z <= o.max_order; ++z) {
      orders.push_back(z);
      for (size_t n = 0; n < rec.time.size(); ++n)
        base(static_cast<Eigen::Index>(n), z - o.min_order) = omega * rec.time[n];
    }
    const internal::FittedRate fitted = internal::FitLineRate(rec.time, y, base, orders, speed);
    const double offset = std::abs(fitted.rate / speed - 1);
    if (offset > 1e-6 && std::abs(fitted.rate - speed) > 6 * fitted.standard_error) {
      ++extra.off_speed;
      extra.largest_offset = std::max(extra.largest_offset, offset);
    }
  }
  // The written frequency is off when the input's own is further from it than its noise
  // allows (six standard errors) and than the digits a log keeps.
  const double move = rec.excitation_hz > 0 ? std::abs(omega / kTwoPi - rec.excitation_hz) : 0.0;
  const double uncertainty =
      std::isfinite(e.rate.standard_error) ? 6 * e.rate.standard_error / kTwoPi : 1e-3 / L;
  if (move > std::max(1e-9 * rec.excitation_hz, uncertainty)) {
    ++extra.moved;
    extra.largest_move = std::max(extra.largest_move, move);
  }
}

IdentifiedFrequency IdentifyRecord(const TimeRecord& rec, double T, const IdentifyOptions& o,
                                   size_t index, std::vector<Diagnostic>& diagnostics,
                                   ExtraLines& extra) {
  const std::string where = "record " + std::to_string(index + 1);
  const double dt = SamplingStep(rec);
  const double L = rec.time.back() - rec.time.front();
  const double nyquist = std::numbers::pi / dt, bin = kTwoPi / L;
  std::vector<double> theta = rec.angle;  // the system's phase: measured, or the model's
  if (theta.empty())
    for (double t : rec.time) theta.push_back(kTwoPi * t / T);
  const double speed = (theta.back() - theta.front()) / L;
  if (!(speed * L >= kTwoPi * (1 - 1e-9)))
    throw InputError(where + ": " + MessageNumber(speed * L / kTwoPi, 6) +
                     " periods long; the orders need at least one period to be told apart");
  const Eigen::VectorXd u = rec.inputs.col(o.input), y = rec.outputs.col(o.output);
  const RecordExcitation e = ExcitationOf(rec, u, o, where);
  const double omega = e.rate.rate;
  // The lines' phases are taken on absolute time: beyond ~1e12 rad a double keeps no digit of
  // them (times written as epoch seconds at kHz would do that).
  const double latest = std::max(std::abs(rec.time.front()), std::abs(rec.time.back()));
  if (!(std::max(omega, std::abs(speed)) * latest < 1e12))
    throw InputError(where + ": times up to " + MessageNumber(latest, 6) + " s at " +
                     MessageNumber(omega / kTwoPi, 6) +
                     " Hz leave the phase ωt no correct digit; give times from the start of "
                     "the test (the model's phase must then be referenced to that start)");
  for (int z : {o.min_order, o.max_order})
    if (std::abs(omega + z * speed) >= nyquist * (1 - 1e-9))
      throw InputError(where + ": the line of order " + std::to_string(z) +
                       " lies above the Nyquist frequency: sample faster or ask for fewer orders");
  if (!rec.angle.empty())
    for (const double delay : {o.input_delay, o.output_delay})
      if (std::abs(delay) > 0.05 * L)
        throw InputError(where + ": a delay of " + MessageNumber(delay, 3) +
                         " s is over 5 % of the record: the measured angle is not extrapolated "
                         "that far; trim the records to the span both channels cover");
  const std::vector<Line> lines = LinesToFit(omega, speed, nyquist, bin, o);
  const internal::DelayedClock out_clock =
      internal::Delayed(rec.time, theta, !rec.angle.empty(), T, o.output_delay);
  const internal::LineFit fit =
      internal::FitLines(y, LinePhases(lines, out_clock.time, out_clock.theta, omega));
  IdentifiedFrequency out;
  out.excitation_hz = omega / kTwoPi;
  out.speed = speed;
  out.noise = std::sqrt(fit.noise_variance);
  FillEstimates(fit, e, rec, o, speed, out);
  if (fit.dof == 0)
    diagnostics.push_back({DiagnosticCode::kNoNoiseEstimate, Severity::kWarning,
                           where + ": as many lines as samples: the noise (and the bounds) cannot "
                                   "be estimated; record longer"});
  if (!out.separable) {
    const double halves = 2 * omega / speed;
    diagnostics.push_back(
        {DiagnosticCode::kLinesNotSeparable, Severity::kWarning,
         where + ": " + MessageNumber(out.excitation_hz, 8) + " Hz" +
             (std::abs(halves - std::round(halves)) < 1e-6
                  ? " is a multiple of Ωp/2: H_z and the mirror of another order share each line, "
                    "one record cannot separate them"
                  : ": two of its response lines coincide; those H_z are left out (NaN)")});
  }
  TallyExtraLines(rec, o, y, lines, fit, e, theta, speed, extra);
  RecordNotes(rec, o, omega, dt, where, diagnostics);
  return out;
}

}  // namespace

void IdentifyOptions::Validate() const {
  const OptionCheck check("IdentifyOptions");
  if (input < 0) check.Fail("input", input, ">= 0");
  if (output < 0) check.Fail("output", output, ">= 0");
  for (const auto& [delay, name] :
       {std::pair{input_delay, "input_delay"}, {output_delay, "output_delay"}})
    if (!std::isfinite(delay)) check.Fail(name, delay, "finite");
  if (min_order > max_order || max_order - min_order > 200)
    check.Fail("min_order..max_order", std::to_string(min_order) + ".." + std::to_string(max_order),
               "min_order <= max_order, at most 201 orders");
}

IdentifyResult IdentifyStepSine(const TimeData& data, const IdentifyOptions& options) {
  CheckData(data, options);
  IdentifyResult r;
  r.min_order = options.min_order;
  r.max_order = options.max_order;
  ExtraLines extra;
  for (size_t i = 0; i < data.records.size(); ++i)
    r.frequencies.push_back(
        IdentifyRecord(data.records[i], data.period, options, i, r.diagnostics, extra));
  if (!extra.synchronous.empty()) {
    std::string orders;
    for (int m : extra.synchronous)
      orders += (orders.empty() ? "" : ", ") + std::to_string(m) + "×";
    r.diagnostics.push_back({DiagnosticCode::kSynchronousResponse, Severity::kNote,
                             "synchronous response at " + orders +
                                 " the system's frequency 1/T (unbalance, misalignment): fitted as "
                                 "lines of their own and kept out of the noise and the bounds"});
  }
  if (extra.harmonic_records > 0)
    r.diagnostics.push_back(
        {DiagnosticCode::kNonlinearResponse, Severity::kWarning,
         std::to_string(extra.harmonic_records) + " of " + std::to_string(data.records.size()) +
             " records respond at 2 or 3 times the excitation frequency above the "
             "noise: the system is not linear at this amplitude (or the output "
             "clips); H_z is its linear part at best and the bounds do not cover "
             "what the nonlinearity changes — excite less"});
  if (extra.off_speed > 0)
    r.diagnostics.push_back(
        {DiagnosticCode::kSpeedOffModel, Severity::kWarning,
         "in " + std::to_string(extra.off_speed) + " of " + std::to_string(data.records.size()) +
             " records the response's lines sit at a speed up to " +
             MessageNumber(100 * extra.largest_offset, 3) +
             " % off 2π/T (fitted from the data): the rotor did not turn at the model's speed, and "
             "H_z (z ≠ 0) is biased by the phase it gained — measure its angle (a tacho or an "
             "encoder channel) or give the period it turned at"});
  if (extra.moved > 0)
    r.diagnostics.push_back(
        {DiagnosticCode::kExcitationFrequencyMoved, Severity::kNote,
         std::to_string(extra.moved) + " of " + std::to_string(data.records.size()) +
             " records excite at another frequency than the file says (by up to " +
             MessageNumber(extra.largest_move, 3) +
             " Hz): each input's own frequency is used and reported"});
  if (extra.speed_change > 1e-3)
    r.diagnostics.push_back({DiagnosticCode::kSpeedChanges, Severity::kNote,
                             "the speed changes by up to " +
                                 MessageNumber(100 * extra.speed_change, 2) +
                                 " % within a record: H_z moves with it, and each estimate is the "
                                 "average over its record's speeds"});
  double offset = 0;
  for (const IdentifiedFrequency& f : r.frequencies)
    offset = std::max(offset, std::abs(f.speed * data.period / (2 * std::numbers::pi) - 1));
  if (offset > 1e-6)
    r.diagnostics.push_back({DiagnosticCode::kSpeedOffModel, Severity::kNote,
                             "the measured speed differs from the model's 2π/T by up to " +
                                 MessageNumber(100 * offset, 3) +
                                 " %: H_z is the rig's at its own speed (each record's in "
                                 "`speed`); compare with the model at that speed"});
  std::stable_sort(r.frequencies.begin(), r.frequencies.end(),
                   [](const auto& a, const auto& b) { return a.excitation_hz < b.excitation_hz; });
  return r;
}

namespace {

// The bins a set of broadband records excites, told from the noise a measured input carries:
// the input's power per bin averaged over the records, sorted, cut at its largest drop (a
// multisine's or a band's lines stand above the noise floor by the SNR). Power below 1e-20 of
// the strongest bin is round-off (noise-free records: only the lines are above it). A largest
// drop under 20 dB separates nothing: then every bin above round-off counts.
std::set<long> ExcitedBins(const std::vector<std::vector<cd>>& u, long N) {
  const long R = static_cast<long>(u.size());
  std::vector<std::pair<double, long>> power;  // (mean |U_k|², k)
  for (long k = 1; 2 * k < N; ++k) {
    double p = 0;
    for (long r = 0; r < R; ++r) p += std::norm(u[r][k]) / static_cast<double>(R);
    power.emplace_back(p, k);
  }
  std::sort(power.begin(), power.end(), std::greater<>());
  if (power.empty() || !(power.front().first > 0))
    throw InputError("record 1: the input is not excited");
  // Below 1e-20 of the strongest line's power is round-off, not noise: it ends the search.
  const double silent = 1e-20 * power.front().first;
  size_t cut = 0, audible = 0;
  while (audible < power.size() && power[audible].first > silent) ++audible;
  double drop = 1;
  for (size_t i = 0; i + 1 < audible; ++i)
    if (power[i].first / power[i + 1].first > drop)
      drop = power[i].first / power[i + 1].first, cut = i + 1;
  if (drop < 100) cut = audible;  // no floor below the lines: every audible bin is excited
  std::set<long> excited;
  for (size_t i = 0; i < cut; ++i) excited.insert(power[i].second);
  // A record of another design: a line no other record has. (A record may excite a line
  // weakly — noise excitation has Rayleigh amplitudes — and only contributes less there.)
  const double weakest = power[cut - 1].first;
  for (long r = 0; r < R; ++r)
    for (long k = 1; 2 * k < N; ++k)
      if (!excited.count(k) && std::norm(u[r][k]) > 0.1 * weakest)
        throw InputError("record " + std::to_string(r + 1) + " excites " +
                         MessageNumber(static_cast<double>(k) / static_cast<double>(N), 6) +
                         " of the sampling rate, which the others do not: broadband "
                         "identification needs one set of frequencies");
  return excited;
}

// Broadband records on a measured angle: the excited lines' frequencies and the input's
// amplitudes there (absolute time, its delay undone), then one fit over all records.
IdentifyResult OnMeasuredAngle(const TimeData& data, const IdentifyOptions& o,
                               const std::set<long>& excited, const std::vector<std::vector<cd>>& u,
                               const std::vector<double>& t0, double L) {
  const TimeRecord& first = data.records.front();
  const double nyquist = std::numbers::pi * static_cast<double>(first.time.size() - 1) /
                         (first.time.back() - first.time.front());
  double fastest = 0;  // the largest dθ/dt between samples of any record
  for (const TimeRecord& rec : data.records)
    for (size_t i = 1; i < rec.time.size(); ++i)
      fastest = std::max(
          fastest, std::abs(rec.angle[i] - rec.angle[i - 1]) / (rec.time[i] - rec.time[i - 1]));
  std::vector<double> omegas;
  Eigen::MatrixXcd amplitudes(static_cast<Eigen::Index>(u.size()),
                              static_cast<Eigen::Index>(excited.size()));
  for (const long k : excited) {
    const double omega = kTwoPi * static_cast<double>(k) / L;
    for (const int z : {o.min_order, o.max_order})
      if (std::abs(omega + z * fastest) >= nyquist)
        throw InputError("the line of order " + std::to_string(z) + " of " +
                         MessageNumber(omega / kTwoPi, 8) +
                         " Hz reaches the Nyquist frequency at the records' fastest speed: "
                         "sample faster or ask for fewer orders");
    for (size_t r = 0; r < u.size(); ++r)
      amplitudes(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(omegas.size())) =
          AbsoluteBin(u[r], k, t0[r], L) * std::polar(1.0, omega * o.input_delay);
    omegas.push_back(omega);
  }
  // The input's noise per bin, from the bins it does not excite (DC left out).
  double noise = 0;
  long bins = 0;
  for (const std::vector<cd>& c : u)
    for (size_t k = 1; 2 * k < c.size(); ++k)
      if (!excited.count(static_cast<long>(k))) noise += std::norm(c[k]), ++bins;
  IdentifyResult r = internal::IdentifyBroadbandOnAngle(data, o, omegas, amplitudes,
                                                        bins > 0 ? noise / bins : 0.0);
  double offset = 0;
  for (const IdentifiedFrequency& f : r.frequencies)
    offset = std::max(offset, std::abs(f.speed * data.period / kTwoPi - 1));
  if (offset > 1e-6)
    r.diagnostics.push_back({DiagnosticCode::kSpeedOffModel, Severity::kNote,
                             "the measured speed differs from the model's 2π/T by " +
                                 MessageNumber(100 * offset, 3) +
                                 " %: H_z is the rig's at its own speed; compare with the model at "
                                 "that speed"});
  double change = 0;
  for (const TimeRecord& rec : data.records)
    change = std::max(change, SpeedChange(rec.time, rec.angle));
  if (change > 1e-3)
    r.diagnostics.push_back({DiagnosticCode::kSpeedChanges, Severity::kNote,
                             "the speed changes by up to " + MessageNumber(100 * change, 2) +
                                 " % within a record: H_z moves with it, and each estimate is the "
                                 "average over the records' speeds"});
  return r;
}

// The records' spectra on their common grid (one length and rate, every record broadband, all
// on a measured angle or none), absolute time, and what the records share.
struct BroadbandSpectra {
  long N = 0, P = 0;  // samples per record; periods per record (model's speed)
  double L = 0;       // record length (s)
  bool measured = false;
  std::vector<std::vector<cd>> u, y;
  std::vector<double> t0;
  double time_error = 0;
};

BroadbandSpectra SpectraOf(const TimeData& data, const IdentifyOptions& options) {
  BroadbandSpectra s;
  s.measured = !data.records.front().angle.empty();
  for (size_t r = 0; r < data.records.size(); ++r) {
    const std::string where = "record " + std::to_string(r + 1);
    RequireUniformSampling(data.records[r], where);  // the DFT needs the grid
    if (data.records[r].angle.empty() == s.measured)
      throw InputError(where + (s.measured ? " has no measured angle, record 1 has one"
                                           : " has a measured angle, record 1 has none"));
  }
  const TimeRecord& first = data.records.front();
  s.N = static_cast<long>(first.time.size());
  const double dt = (first.time.back() - first.time.front()) / static_cast<double>(s.N - 1);
  s.L = s.N * dt;
  bool whole = false;
  s.P = WholeNumber(s.L / data.period, &whole);
  // At the model's speed the response lines sit on bins when the records are whole periods;
  // on a measured angle they do not anyway (broadband_on_angle.h).
  if (!s.measured && (!whole || s.P < 1))
    throw InputError("the records are " + MessageNumber(s.L / data.period, 8) +
                     " periods long; identification needs whole periods (or a measured "
                     "angle: --tacho/--angle)");
  for (size_t r = 0; r < data.records.size(); ++r) {
    const TimeRecord& rec = data.records[r];
    const std::string where = "record " + std::to_string(r + 1);
    if (rec.excitation_hz != 0)
      throw InputError(where + " is a step-sine record (" + MessageNumber(rec.excitation_hz, 8) +
                       " Hz): identify it with the step-sine method");
    const double dtr = (rec.time.back() - rec.time.front()) / static_cast<double>(s.N - 1);
    if (static_cast<long>(rec.time.size()) != s.N || std::abs(dtr - dt) > 1e-9 * dt)
      throw InputError(where +
                       " differs from record 1 in length or sampling: broadband "
                       "identification combines records of one length and rate");
    s.u.push_back(Spectrum(rec.inputs.col(options.input)));
    s.y.push_back(Spectrum(rec.outputs.col(options.output)));
    s.t0.push_back(rec.time.front());
    s.time_error = std::max(s.time_error, rec.time_error);
  }
  return s;
}

// Every response line's least-squares problem across the records, and the pooled residual.
struct LineSolutions {
  std::map<std::pair<long, int>, LineEstimate> found;  // (excited bin, z)
  double rss = 0;
  long dof = 0, lines = 0, under = 0, missing = 0;
};

// One response line (bin b): the unknowns H_z at the excited b − zP, solved across records.
void SolveResponseLine(const BroadbandSpectra& s, const std::set<long>& excited,
                       const IdentifyOptions& o, long b, LineSolutions& out) {
  // A channel sampled `delay` late: its bin k carries e^{−j2πk·delay/L}; undone here.
  const auto undelayed = [&](const std::vector<cd>& c, long k, double t, double delay) {
    return AbsoluteBin(c, k, t, s.L) *
           std::polar(1.0, kTwoPi * static_cast<double>(k) * delay / s.L);
  };
  std::vector<std::pair<int, long>> unknowns;  // (z, excitation bin; < 0: mirror)
  for (int z = o.min_order; z <= o.max_order; ++z) {
    const long k = b - z * s.P;
    if (k != 0 && excited.count(std::abs(k))) unknowns.emplace_back(z, k);
  }
  if (unknowns.empty()) return;
  ++out.lines;
  const long R = static_cast<long>(s.u.size()), q = static_cast<long>(unknowns.size());
  Eigen::MatrixXcd M(R, q);
  Eigen::VectorXcd Y(R);
  for (long r = 0; r < R; ++r) {
    Y(r) = undelayed(s.y[r], b, s.t0[r], o.output_delay);
    for (long j = 0; j < q; ++j) {
      const long k = unknowns[j].second;
      const cd uk = undelayed(s.u[r], std::abs(k), s.t0[r], o.input_delay);
      M(r, j) = k > 0 ? uk : std::conj(uk);
    }
  }
  // A mirrored unknown is H_z(−f) = conj H_{−z}(f) of the real system.
  const auto key = [](int z, long k) {
    return k > 0 ? std::make_pair(k, z) : std::make_pair(-k, -z);
  };
  Eigen::JacobiSVD<Eigen::MatrixXcd> svd(M, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  LineEstimate e;
  if (R < q || !(sv(q - 1) > 1e-12 * sv(0))) {
    ++out.under;
    out.missing = std::max(out.missing, q - R);
    for (const auto& [z, k] : unknowns) out.found.emplace(key(z, k), e);
    return;
  }
  const Eigen::VectorXcd x = svd.solve(Y);
  const double res = (Y - M * x).squaredNorm();
  out.rss += res;
  out.dof += R - q;
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
    auto [it, inserted] = out.found.emplace(key(z, k), ej);
    if (!inserted && ej.variance_factor < it->second.variance_factor) it->second = ej;
  }
}

// The estimates per excited frequency from the lines' solutions, with their bounds and notes.
IdentifyResult BroadbandEstimates(const TimeData& data, const IdentifyOptions& o,
                                  const BroadbandSpectra& s, const std::set<long>& excited,
                                  const LineSolutions& solved) {
  IdentifyResult r;
  r.min_order = o.min_order;
  r.max_order = o.max_order;
  const double sigma2 = solved.dof > 0 ? solved.rss / static_cast<double>(solved.dof) : kNaN;
  // A line whose residual is far above the pooled noise is fed by something the regression
  // lacks — orders outside the requested range, nonlinearity — a bias, not noise: its bounds
  // use its own residual (under white noise a ratio of 10 has probability < 1e-4 already at
  // R − q = 2) and the lines are reported.
  std::set<std::pair<long, int>> biased;
  for (const auto& [key, e] : solved.found)
    if (e.line_variance > kBiasRatio * sigma2) biased.insert(key);
  for (long k : excited) {
    IdentifiedFrequency f;
    f.excitation_hz = static_cast<double>(k) / s.L;
    f.noise = std::sqrt(sigma2 * static_cast<double>(s.N));
    for (int z = o.min_order; z <= o.max_order; ++z) {
      const auto it = solved.found.find({k, z});
      const LineEstimate e = it != solved.found.end() ? it->second : LineEstimate{};
      f.h.push_back(e.h);
      const double variance = biased.count({k, z}) ? e.line_variance : sigma2;
      const double clock = std::abs(z * kTwoPi / data.period) * s.time_error * std::abs(e.h);
      f.bound.push_back(solved.dof > 0 && std::isfinite(e.variance_factor)
                            ? kBoundFactor * std::sqrt(variance * e.variance_factor) + clock
                            : std::numeric_limits<double>::infinity());
      f.condition.push_back(e.condition);
      f.quality.push_back(e.quality);
    }
    r.frequencies.push_back(std::move(f));
  }
  if (solved.under > 0)
    r.diagnostics.push_back(
        {DiagnosticCode::kLinesUnderDetermined, Severity::kWarning,
         std::to_string(solved.under) + " of " + std::to_string(solved.lines) +
             " response lines are under-determined (more unknown H_z than the " +
             std::to_string(s.u.size()) + " records give equations): record at " + "least " +
             std::to_string(solved.missing) +
             " more records with new phases; their H_z are left out (NaN)"});
  if (!biased.empty())
    r.diagnostics.push_back(
        {DiagnosticCode::kResidualBias, Severity::kWarning,
         std::to_string(biased.size()) + " estimates come from response lines whose residual is " +
             "over " + MessageNumber(kBiasRatio, 3) + "× the pooled noise: orders outside " +
             std::to_string(o.min_order) + ".." + std::to_string(o.max_order) +
             " (or nonlinearity) feed them; their bounds use their own residual — widen --orders"});
  if (solved.dof == 0)
    r.diagnostics.push_back(
        {DiagnosticCode::kNoNoiseEstimate, Severity::kWarning,
         "no response line has more records than unknowns: the noise cannot be estimated and "
         "the bounds are unknown (∞); record more records than orders"});
  return r;
}

}  // namespace

IdentifyResult IdentifyBroadband(const TimeData& data, const IdentifyOptions& options) {
  CheckData(data, options);
  const BroadbandSpectra s = SpectraOf(data, options);
  const std::set<long> excited = ExcitedBins(s.u, s.N);
  if (s.measured) return OnMeasuredAngle(data, options, excited, s.u, s.t0, s.L);
  for (long k : excited)
    for (int z : {options.min_order, options.max_order})
      if (2 * std::abs(k + z * s.P) >= s.N)
        throw InputError("the line of order " + std::to_string(z) + " of " +
                         MessageNumber(k / s.L, 8) +
                         " Hz lies above the Nyquist frequency: sample faster or ask for "
                         "fewer orders");
  LineSolutions solved;
  for (long b = 1; 2 * b < s.N; ++b) SolveResponseLine(s, excited, options, b, solved);
  return BroadbandEstimates(data, options, s, excited, solved);
}

}  // namespace ltp
