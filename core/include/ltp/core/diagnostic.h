#pragma once
// What a result says about itself: one Diagnostic per event, with a code that programs test
// and branch on and a sentence that people read. Code reads codes; no code parses the text.
#include <string>
#include <string_view>
#include <vector>

namespace ltp {

/// How much an event matters to the one who reads the result.
enum class Severity {
  kNote,     ///< how the result was made (a choice, a summary); nothing to act on
  kWarning,  ///< the result stands, but part of it is weaker than usual; read the text
  kFailure,  ///< the result (or the part the text names) is not usable
};

/// One value per kind of event the library reports, for the whole library. The text beside it
/// gives the numbers; the kind never changes with them.
enum class DiagnosticCode {
  // Integration of a period and its segment grid (ltp::integrate).
  kSegmentIntegrationFailed,  ///< a segment's state transition failed
  kSegmentRefinementStopped,  ///< the grid hit its segment limit with a badly conditioned factor

  // Floquet analysis: set-up and automatic choices.
  kWorkEstimate,           ///< the work estimate announced before a long analysis
  kStatesBalanced,         ///< states rescaled by powers of two for the integration
  kIntegratorChosen,       ///< integrator auto → which one, and why
  kSegmentsChosen,         ///< segments auto → K, and why
  kMultipliersRegrouped,   ///< periodic Schur failed; it ran again on factors paired up
  kMultipliersSingleShot,  ///< periodic Schur failed; eigenvalues of the formed product
  kMultipliersFailed,      ///< no eigenvalues of the monodromy at all
  kErrorEstimateFallback,  ///< the error estimate used another method than asked
  kErrorEstimateFailed,    ///< the error estimate's own computation failed: error unknown

  // Floquet analysis: modes and branches.
  kModesNotComputed,          ///< no mode shapes asked for: principal branch
  kModeSamplesPropagated,     ///< mode samples integrated within segments
  kModesUnderResolved,        ///< mode shapes' Fourier energy reaches the upper half
  kModeShapeFailed,           ///< one mode's periodic shape could not be computed
  kNoModeShapes,              ///< no periodic mode shape could be computed
  kModeMatrixIllConditioned,  ///< the mode matrix Ξ is (near-)singular
  kBranchOnStripEdge,         ///< negative real multiplier: exponent on the strip edge
  kBranchAmbiguous,           ///< a mode's branch (or Hill's pick) ties between harmonics
  kRigidBodyMode,             ///< a free rotation's exponent, left out of the verdict

  // Checks and the verdict.
  kLiouvilleCheckFailed,  ///< Σ Re λ does not match ∫ tr A: some exponents are wrong
  kStabilityMarginal,     ///< stability undecided: max Re λ within its error
  kVerdictPerModeBand,    ///< the verdict used each exponent's own estimate
  kModelErrorIncluded,    ///< a sampled model's own error is part of the estimate

  // Floquet analysis of the modes below a cut-off.
  kModesBelowSummary,    ///< what the reduced analysis kept and measured
  kAllModesBelowCutoff,  ///< nothing to leave out: the full analysis ran
  kNoModesBelowCutoff,   ///< no mode below the cut-off
  kCutoffsDisagree,      ///< the analyses at the two cut-offs failed or disagree

  // Hill's method.
  kFourierFitted,                 ///< A(t) fitted by FFT (how many harmonics, decay)
  kFourierFitNotConverged,        ///< the coefficients' fit did not converge: its error counted
  kHillSolverChosen,              ///< Hill solver auto → which one, and why
  kHillSolverFellBack,            ///< the structured solver fell back to the dense one
  kHillFallbackTooCostly,         ///< the dense fallback was skipped: beyond the work limit
  kHillSolverFailed,              ///< the eigenvalue solver itself failed
  kRitzPairsUnconverged,          ///< structured solver: Ritz pairs left out
  kExponentFamiliesMissing,       ///< fewer exponent families than states were found
  kSelectionRuleFailed,           ///< chosen eigenvalues that fail the selection rule
  kEigenvectorsAtTruncationEdge,  ///< eigenvectors reach blocks ±N: raise N
  kBranchesMoveWithTruncation,    ///< selected eigenvalues move with N: not exponents
  kTruncationNotConverged,        ///< a truncation still changes the result at its limit
  kTruncationLimited,             ///< a larger truncation was not tried (memory, limit)
  kTruncationUnresolved,          ///< N·Ωp below the frozen eigenvalues' spread
  kKoopmanHillSkipped,            ///< the Koopman–Hill check did not run
  kKoopmanHillDisagrees,          ///< Koopman–Hill disagrees beyond its bound
  kHarmonicsChosen,               ///< harmonics auto met its tolerance at N
  kToleranceNotReached,           ///< harmonics auto stopped short of its tolerance
  kConvergenceRateUnknown,        ///< a truncation study could fit no convergence rate
  kDiscontinuousCoefficients,     ///< A(t) jumps: algebraic convergence expected

  // Partial FRFs, the HTF operator, its norms and zeros.
  kRoutesChosen,             ///< route auto → primary and checks, and why
  kRouteFailed,              ///< a route failed at some frequencies
  kRoutesDisagree,           ///< two routes disagree beyond their estimates
  kRoutesCompared,           ///< how far a check route agreed (a summary)
  kModalUnreliable,          ///< the modal model is not to be trusted
  kModalSamplesFailed,       ///< refining the modal model's mode samples failed
  kModalSpectrumUnresolved,  ///< CΞ and Ξ⁻¹B not resolved by the modal model's samples
  kFloquetFailed,            ///< the Floquet analysis a step needed failed
  kSystemUnstable,           ///< the response is not reached from rest
  kResonance,                ///< excitation on a Floquet exponent: H_z unbounded there
  kForcedResponseFailed,     ///< the forced-response integration failed
  kShootingSingular,         ///< I − Φ e^{−jωT} singular: excitation on a Floquet line
  kNoSteadyState,            ///< the transient does not decay in the allowed periods
  kSettlingTime,             ///< the time route's settling time (a summary)
  kRouteSummary,             ///< a route's truncation or sampling and its own check
  kCheckRouteUnavailable,    ///< no second route to check with: the value is unchecked
  kNormInfinite,             ///< the norm is infinite (unstable, or a feedthrough)
  kNormUnresolved,           ///< a norm route resolves the value only coarsely
  kNormNotComputed,          ///< the norm could not be computed
  kNonFiniteValues,          ///< a route gave non-finite values
  kZerosSummary,             ///< the zeros' pencil: sizes and counts
  kZerosUnpaired,            ///< zeros at N with no partner at N + Δ

  // Simulation and identification from time data.
  kFrequencyMovedToGrid,      ///< excitation frequencies moved to the record's grid
  kFrequenciesMerged,         ///< requested frequencies fell on one grid frequency
  kRecordGaps,                ///< gaps in a record's time axis
  kRecordClipped,             ///< a channel sits at its extreme value: clipped?
  kInputPhaseMoves,           ///< the input's phase drifts over a record
  kNoNoiseEstimate,           ///< as many unknowns as samples: no noise, no bounds
  kLinesNotSeparable,         ///< one record cannot separate the orders' lines
  kSynchronousResponse,       ///< synchronous lines fitted as their own
  kNonlinearResponse,         ///< harmonics above the noise: not linear at this amplitude
  kSpeedOffModel,             ///< the measured speed differs from the model's 2π/T
  kExcitationFrequencyMoved,  ///< records excite at another frequency than the file says
  kSpeedChanges,              ///< the speed changes within the records
  kLinesUnderDetermined,      ///< H_z not determined by these records (NaN)
  kResidualBias,              ///< residuals above the pooled noise: orders outside the fit
  kBroadbandFit,              ///< the broadband fit on the measured angle (a summary)

  // Campbell diagrams.
  kLineLost,                ///< a tracked line ends before the sweep does
  kOverdampedLinesLeftOut,  ///< lines damped above the limit left out
  kLineLockedToHarmonic,    ///< a line follows a per-rev harmonic: no crossing
  kTrackingAmbiguous,       ///< mode tracking ambiguous at some points

  // OpenFAST linearisations and MBC3.
  kMbcNotTransformed,          ///< B or C not transformed to multi-blade coordinates
  kMbcEigenFailed,             ///< the eigenvalue solver failed on the averaged matrix
  kNoRotatingStates,           ///< no rotating-frame states: the transform is the identity
  kMultiBladeCoordinates,      ///< the operating point was moved to multi-blade coordinates
  kAzimuthsUneven,             ///< the azimuths are unevenly spaced
  kRotorSpeedsDiffer,          ///< the files' rotor speeds differ
  kMatrixDropped,              ///< a matrix missing in some files was dropped from all
  kOperatingSpeedDiffers,      ///< a file's azimuth rate differs from its header's rotor speed
  kAzimuthSamplesResolve,      ///< which harmonics of A(ψ) the K azimuth samples determine
  kTooFewAzimuths,             ///< too few azimuths to average the periodic part for MBC3
  kExponentsModuloRotorSpeed,  ///< exponents seen through rotating-frame states may be ±1P off
  kBranchesMatched,            ///< each sampled-model exponent shown on its reference's branch
  kDistanceToMbc,              ///< how far the Floquet exponents are from the MBC3 eigenvalues

  // Campbell diagrams: what the filters left out.
  kLinesAboveBandLeftOut,  ///< lines above the band of interest left out
  kModulesLeftOut,         ///< modes carried mostly by excluded modules' states left out

  kCount  ///< not a code: how many there are (new codes go above it)
};

/// Every DiagnosticCode, in declaration order (for tests and tables).
const std::vector<DiagnosticCode>& AllDiagnosticCodes();

/// A stable snake_case name for `code` ("liouville_check_failed"), as Python shows it.
std::string_view CodeName(DiagnosticCode code);

/// One event a result reports: its kind, how much it matters and the sentence for people.
struct Diagnostic {
  DiagnosticCode code;
  Severity severity = Severity::kNote;
  std::string text;
};

/// Whether any of `diagnostics` has `code`.
bool HasCode(const std::vector<Diagnostic>& diagnostics, DiagnosticCode code);

/// The sentences of `diagnostics`, in order (what the CLI and Python print).
std::vector<std::string> Texts(const std::vector<Diagnostic>& diagnostics);

/// Diagnostics said once: those of one code whose texts differ only in their numbers (one per
/// segment, step or point of a failing run; NumberShape) are kept up to `keep` times; the rest
/// of each such group becomes one "… and N more like the above" with the group's code and
/// severity. Order of first appearance is kept. A failing run used to return 19 945 lines of
/// the same sentence.
std::vector<Diagnostic> CollapseRepeated(const std::vector<Diagnostic>& diagnostics, int keep = 3);

}  // namespace ltp
