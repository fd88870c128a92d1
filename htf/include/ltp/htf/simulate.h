#pragma once
// Simulated tests: the response of a periodic system to u_i(t) = a cos(2π f t) on one input,
// one record per frequency (step-sine), or to a multisine of many frequencies at once, several
// records with random phases (broadband); started from rest, recorded after the transient has
// decayed over a whole number of periods, with optional white output noise. The data an
// experimentalist would measure on a rig, for `ltp identify` (identify.h) and for checking it.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "ltp/core/diagnostic.h"
#include "ltp/core/periodic_system.h"
#include "ltp/htf/time_data.h"

namespace ltp {

struct SimulateOptions {
  int input = 0;                       ///< the excited input
  std::vector<double> frequencies_hz;  ///< one record per frequency (> 0)
  double amplitude = 1;
  /// Recorded length per record, in periods T. Frequencies are moved to the nearest multiple
  /// of 1/(periods·T) (the record then holds whole cycles of every response line: no leakage)
  /// that is not a multiple of fp/2 (where one record cannot separate the orders), and the
  /// move is reported.
  int periods = 20;
  int samples_per_period = 64;
  /// The transient is integrated for ln(cond Ξ / settle_tol) / |max Re λ|, rounded up to whole
  /// periods, before recording (the system must be asymptotically stable).
  double settle_tol = 1e-10;
  /// A transient longer than this many periods is refused before any work (a lightly damped
  /// system: slowest exponent −2e-4 1/s on a period of π takes 34 000 periods per record).
  double max_settle_periods = 100000;
  /// Output noise: white Gaussian, per output, with rms = rms(clean output) · 10^(−snr_db/20);
  /// +inf = none. Each record draws from its own stream of the seed (seeds K and K + 1 share
  /// no record's noise).
  double noise_snr_db = std::numeric_limits<double>::infinity();
  /// Noise on the recorded input (the measurement's, not the force's), as noise_snr_db.
  double input_noise_snr_db = std::numeric_limits<double>::infinity();
  std::uint64_t seed = 1;
  /// A rig's rotor: the system's phase runs at (1 + speed_offset) × its own speed,
  /// and rises by a further speed_ramp over each record (relative); A(t), B, C, D are taken at
  /// that phase — the coefficients' own dependence on the speed (gyroscopic terms) is not
  /// changed. tacho: an auxiliary channel "tacho" with one flat-top pulse per period whose
  /// edge rises through mid-level at phase 0 (`ltp identify --tacho tacho`).
  double speed_offset = 0, speed_ramp = 0;
  bool tacho = false;
  /// A cubic spring between output 0 and the excited input: the input's force is
  /// u(t) − cubic_stiffness · y0³, y0 = (C x)_0 — collocated when output 0 is the displacement
  /// where the force acts. 0: the linear system. For planning how large an excitation stays
  /// linear (`ltp identify` names a response at 2ω or 3ω). Hardening only (≥ 0): a softening
  /// spring lets the response escape.
  double cubic_stiffness = 0;
  /// RKF78 tolerance; absolute: rel_tol · 1e-3 · the largest state in a pilot over the first
  /// period (the states' own scale, whatever their units).
  double rel_tol = 1e-10;
  /// Multisine (SimulateMultisine): realisations to record, each exciting every frequency at
  /// once with its own random phases (seed + record); ≥ the number of orders to identify.
  int records = 10;
  /// Multisine: Rayleigh-distributed line amplitudes (rms `amplitude`) instead of equal ones —
  /// band-limited Gaussian noise that repeats with the record, so no line leaks (noise:F0:F1).
  bool random_amplitudes = false;
  /// @throws InputError naming the field and the violated constraint.
  void Validate() const;
};

struct SimulationResult {
  TimeData data;
  double settle_time = 0;               ///< s, integrated before each record
  double max_real_exponent = 0;         ///< of the system (1/s)
  std::vector<Diagnostic> diagnostics;  ///< e.g. frequencies moved to the record's grid
};

/// @throws InputError for bad options, an input the system does not have, an unstable or
/// marginal system (no steady state), or a sampling rate that aliases a response line the
/// records must resolve.
SimulationResult SimulateStepSine(const PeriodicSystem& system, const SimulateOptions& options);

/// Broadband (multisine) tests: `records` realisations of
///   u(t) = (amplitude / √K) Σ_k cos(2π f_k t + φ_{r,k}),  φ uniform random (seed + r),
/// every f_k of frequencies_hz moved to the record grid as for step-sine; the records are
/// marked excitation_hz = 0 (broadband). For IdentifyBroadband (identify.h).
/// @throws InputError as SimulateStepSine.
SimulationResult SimulateMultisine(const PeriodicSystem& system, const SimulateOptions& options);

}  // namespace ltp
