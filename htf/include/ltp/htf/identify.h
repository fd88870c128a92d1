#pragma once
// Partial FRFs from step-sine time data (the paper's eq. 47): in the steady state under
// u = a cos(ωt + φ) = U e^{jωt} + c.c., every output holds the lines ω·t + z·θ(t) with complex
// amplitudes U·H_z(ω) (and their mirrors), θ the system's phase (2πt/T at the model's speed, or
// measured on a rig: rotor_angle.h). Each record is fitted by least squares with those lines,
// ω measured from the input itself, and the lines a rig adds (further orders, the synchronous
// m·θ of an unbalance, 2ω and 3ω of a nonlinearity) so that they do not count as noise:
//   H_z(ω) = Y_z / U.
// Over whole periods and cycles at the model's speed the lines are orthogonal and this is the
// DFT bin ratio exactly; the fit needs neither (docs/rig-data.md). The residual's variance σ²
// gives each estimate its variance σ²[(XᵀX)⁻¹] through Y_z, the input's residual through U,
// and a 95 % bound sqrt(ln 20) × the standard deviation (the radius that circular Gaussian
// noise exceeds with probability 5 %). A frequency at a multiple of Ωp/2 puts H_z(ω) and the
// mirror of H_{z'}(ω) on one line: one record cannot separate them, and the estimate says so.
#include <complex>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/htf/time_data.h"

namespace ltp {

struct IdentifyOptions {
  int input = 0, output = 0;
  int min_order = -2, max_order = 2;
  /// How much later than the rotor's phase each channel's samples are taken (s): an
  /// anti-alias filter's group delay, a DAQ's channel skew. The fit takes a delayed channel's
  /// lines at t − delay (θ interpolated there), so H_z is the undelayed system's.
  double input_delay = 0, output_delay = 0;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct IdentifiedFrequency {
  double excitation_hz = 0;
  std::vector<std::complex<double>> h;  ///< H_z, z = min_order..max_order (NaN: not separable)
  std::vector<double> bound;            ///< 95 % bound on |error| of each H_z
  double noise = 0;                     ///< rms of the noise bins (output units)
  bool separable = true;                ///< false at multiples of Ωp/2 (see the header)
  double speed = 0;  ///< step-sine: the record's mean dθ/dt (rad/s; 2π/T without a measured angle)
  /// Broadband: per order, the condition number of the least-squares problem of the response
  /// line that determines H_z (∞: under-determined) and its quality 1 − |residual|²/|Y|²
  /// over the records (1: the lines explain the response; NaN: no residual to judge by).
  std::vector<double> condition, quality;
};

struct IdentifyResult {
  int min_order = 0, max_order = 0;
  std::vector<IdentifiedFrequency> frequencies;  ///< one per record, by excitation frequency
  std::vector<Diagnostic> diagnostics;
};

/// A record whose excitation_hz is 0 (not written) is excited at its input's strongest line.
/// Notes in the diagnostics: a measured input frequency other than the written one, gaps in
/// t, clipped channels, an input phase that moves within a record (dropped samples), a
/// synchronous or harmonic response, a measured speed other than 2π/T.
/// @throws InputError when the data fail TimeData::Validate, a record spans less than one
/// period, the input is not excited at the record's frequency, the sampling aliases a
/// requested line, or the options do not fit the data.
IdentifyResult IdentifyStepSine(const TimeData& data, const IdentifyOptions& options);

/// Partial FRFs from broadband records (multisine or noise, excitation_hz = 0; §4.2 of the
/// paper): every response line ν carries Σ_z H_z(ν − zΩp) U(ν − zΩp), so one record gives one
/// equation per line and the orders are separated by least squares across records whose
/// excitations differ (random phases): per line, unknowns H_z at the excited ν − zΩp (a
/// negative one is the mirror conj H_{−z}(zΩp − ν) of a real system). The noise variance is
/// pooled from the residuals of all lines (it needs more records than unknowns somewhere), and
/// gives each estimate a 95 % bound sqrt(ln 20)·sqrt(σ² [(MᴴM)⁻¹]_jj). Lines with fewer records
/// than unknowns (or a rank-deficient system) are reported, with the records still missing.
/// @throws InputError when the data fail TimeData::Validate, a record is not broadband, the
/// records differ in length, sampling or excited frequencies, or do not span whole periods.
IdentifyResult IdentifyBroadband(const TimeData& data, const IdentifyOptions& options);

}  // namespace ltp
