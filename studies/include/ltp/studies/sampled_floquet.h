#pragma once
// Floquet analysis of a rotor given at K azimuths (OpenFAST linearisations), beside the MBC3
// Campbell table of the same files.
//
// The K matrices are extended to the whole revolution in two ways — each sample held over the
// azimuths nearest to it (exact product of matrix exponentials) and the trigonometric
// polynomial through the samples — and each is analysed via its monodromy matrix
// (floquet.h). When MBC applies (N >= 3 blades) the samples analysed are the MBC-transformed
// ones, not averaged: T(ψ) is a Lyapunov transformation, so the exponents equal those of the
// files' rotating-frame system modulo jΩ, while the mode shapes, and hence the branch each
// exponent is reported on, are in the fixed frame. The difference from the MBC eigenvalues is
// the periodicity that azimuth averaging discards (plus sampling error); the difference
// between the two interpolations shows what the K samples do not pin down.
//
// Floquet exponents are defined modulo jΩ: each is matched to the MBC eigenvalue nearest to it
// modulo jΩ and reported on that branch.
#include <complex>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "ltp/floquet/floquet.h"
#include "ltp/openfast/linearization.h"
#include "ltp/openfast/mbc3.h"

namespace ltp {

struct SampledFloquetOptions {
  /// Options of the trigonometric route (smooth A(t): the default integrator and tolerance);
  /// the nearest-sample route uses the same options with the exact kExpm integrator. With
  /// floquet.modes_below both routes analyse the modes below it (FloquetResult::reduction),
  /// and the table lists the MBC modes with |λ| at most the cut-off.
  FloquetOptions floquet;
  /// Analyse the MBC-transformed samples when MBC applies (false: the files' coordinates).
  bool multiblade_coordinates = true;
  /// Periodic mode shapes of the nearest-sample route even when the table does not need them
  /// (with MBC it shows each exponent on its MBC eigenvalue's branch; without, the shapes find
  /// the rigid rotation and are computed anyway). 200 states: 2.6 of the route's 3.7 s.
  bool hold_mode_shapes = false;
};

/// One mode: a Floquet exponent of each route on the branch of the mode it is matched to.
struct SampledFloquetMode {
  /// Index into Mbc3Result::modes; nullopt when MBC does not apply (the modes are then those
  /// of the nearest-sample route with Im λ >= 0, on its own branch).
  std::optional<size_t> mbc_mode;
  std::complex<double> reference;   ///< the MBC eigenvalue (or the hold route's exponent)
  std::complex<double> hold, trig;  ///< exponents (1/s) of the two routes
  double difference = 0;            ///< |hold − trig| (1/s)
  double to_reference = 0;          ///< max(|hold − ref|, |trig − ref|) (MBC modes only)
  bool rigid_body = false;
};

struct SampledFloquetResult {
  bool ok = false;  ///< both routes succeeded
  /// "multi-blade coordinates" or "the files' coordinates".
  std::string coordinates;
  int samples = 0;             ///< K
  int resolved_harmonics = 0;  ///< ⌊(K−1)/2⌋: harmonics of A(ψ) the samples determine
  FloquetResult hold, trig;    ///< the two analyses in full
  std::vector<SampledFloquetMode> modes;
  /// max Re λ of each route without the rigid-body mode (1/s).
  double max_real_hold = 0, max_real_trig = 0;
  bool stable = false;  ///< verdict == kStable
  /// The trigonometric route's max Re λ against its error band: every mode's exponent
  /// ± (integration estimate + its |hold − trig|, the sampling error; docs/sampled-models.md);
  /// marginal when that band holds 0.
  StabilityVerdict verdict = StabilityVerdict::kFailed;
  double error_estimate = 0;    ///< that band on max Re λ (1/s)
  double max_difference = 0;    ///< max |hold − trig| over the modes (1/s)
  double max_to_reference = 0;  ///< max distance to the MBC eigenvalues (1/s), −1 if none
  /// Caveats (what K samples resolve, branches, the rigid body, the distance to MBC3) and a
  /// failed route (kFloquetFailed; its own diagnostics say why).
  std::vector<Diagnostic> diagnostics;
};

/// Both Floquet routes on the samples, matched to `mbc`'s modes (pass a result with
/// applicable = false to analyse the files' coordinates without MBC).
/// @throws InputError when the rotor speed is 0 (no period).
SampledFloquetResult AnalyzeSampledFloquet(const LinOperatingPoint& op, const Mbc3Result& mbc,
                                           const SampledFloquetOptions& options = {});

}  // namespace ltp
