#include "ltp/core/diagnostic.h"

#include <algorithm>
#include <map>
#include <utility>

#include "ltp/core/text.h"

namespace ltp {

const std::vector<DiagnosticCode>& AllDiagnosticCodes() {
  static const std::vector<DiagnosticCode> kAll = {DiagnosticCode::kSegmentIntegrationFailed,
                                                   DiagnosticCode::kSegmentRefinementStopped,
                                                   DiagnosticCode::kWorkEstimate,
                                                   DiagnosticCode::kStatesBalanced,
                                                   DiagnosticCode::kIntegratorChosen,
                                                   DiagnosticCode::kSegmentsChosen,
                                                   DiagnosticCode::kMultipliersRegrouped,
                                                   DiagnosticCode::kMultipliersSingleShot,
                                                   DiagnosticCode::kMultipliersFailed,
                                                   DiagnosticCode::kErrorEstimateFallback,
                                                   DiagnosticCode::kErrorEstimateFailed,
                                                   DiagnosticCode::kModesNotComputed,
                                                   DiagnosticCode::kModeSamplesPropagated,
                                                   DiagnosticCode::kModesUnderResolved,
                                                   DiagnosticCode::kModeShapeFailed,
                                                   DiagnosticCode::kNoModeShapes,
                                                   DiagnosticCode::kModeMatrixIllConditioned,
                                                   DiagnosticCode::kBranchOnStripEdge,
                                                   DiagnosticCode::kBranchAmbiguous,
                                                   DiagnosticCode::kRigidBodyMode,
                                                   DiagnosticCode::kLiouvilleCheckFailed,
                                                   DiagnosticCode::kStabilityMarginal,
                                                   DiagnosticCode::kVerdictPerModeBand,
                                                   DiagnosticCode::kModelErrorIncluded,
                                                   DiagnosticCode::kModesBelowSummary,
                                                   DiagnosticCode::kAllModesBelowCutoff,
                                                   DiagnosticCode::kNoModesBelowCutoff,
                                                   DiagnosticCode::kCutoffsDisagree,
                                                   DiagnosticCode::kFourierFitted,
                                                   DiagnosticCode::kFourierFitNotConverged,
                                                   DiagnosticCode::kHillSolverChosen,
                                                   DiagnosticCode::kHillSolverFellBack,
                                                   DiagnosticCode::kHillFallbackTooCostly,
                                                   DiagnosticCode::kHillSolverFailed,
                                                   DiagnosticCode::kRitzPairsUnconverged,
                                                   DiagnosticCode::kExponentFamiliesMissing,
                                                   DiagnosticCode::kSelectionRuleFailed,
                                                   DiagnosticCode::kEigenvectorsAtTruncationEdge,
                                                   DiagnosticCode::kBranchesMoveWithTruncation,
                                                   DiagnosticCode::kTruncationNotConverged,
                                                   DiagnosticCode::kTruncationLimited,
                                                   DiagnosticCode::kTruncationUnresolved,
                                                   DiagnosticCode::kKoopmanHillSkipped,
                                                   DiagnosticCode::kKoopmanHillDisagrees,
                                                   DiagnosticCode::kHarmonicsChosen,
                                                   DiagnosticCode::kToleranceNotReached,
                                                   DiagnosticCode::kConvergenceRateUnknown,
                                                   DiagnosticCode::kDiscontinuousCoefficients,
                                                   DiagnosticCode::kRoutesChosen,
                                                   DiagnosticCode::kRouteFailed,
                                                   DiagnosticCode::kRoutesDisagree,
                                                   DiagnosticCode::kRoutesCompared,
                                                   DiagnosticCode::kModalUnreliable,
                                                   DiagnosticCode::kModalSamplesFailed,
                                                   DiagnosticCode::kModalSpectrumUnresolved,
                                                   DiagnosticCode::kFloquetFailed,
                                                   DiagnosticCode::kSystemUnstable,
                                                   DiagnosticCode::kResonance,
                                                   DiagnosticCode::kForcedResponseFailed,
                                                   DiagnosticCode::kShootingSingular,
                                                   DiagnosticCode::kNoSteadyState,
                                                   DiagnosticCode::kSettlingTime,
                                                   DiagnosticCode::kRouteSummary,
                                                   DiagnosticCode::kCheckRouteUnavailable,
                                                   DiagnosticCode::kNormInfinite,
                                                   DiagnosticCode::kNormUnresolved,
                                                   DiagnosticCode::kNormNotComputed,
                                                   DiagnosticCode::kNonFiniteValues,
                                                   DiagnosticCode::kZerosSummary,
                                                   DiagnosticCode::kZerosUnpaired,
                                                   DiagnosticCode::kFrequencyMovedToGrid,
                                                   DiagnosticCode::kFrequenciesMerged,
                                                   DiagnosticCode::kRecordGaps,
                                                   DiagnosticCode::kRecordClipped,
                                                   DiagnosticCode::kInputPhaseMoves,
                                                   DiagnosticCode::kNoNoiseEstimate,
                                                   DiagnosticCode::kLinesNotSeparable,
                                                   DiagnosticCode::kSynchronousResponse,
                                                   DiagnosticCode::kNonlinearResponse,
                                                   DiagnosticCode::kSpeedOffModel,
                                                   DiagnosticCode::kExcitationFrequencyMoved,
                                                   DiagnosticCode::kSpeedChanges,
                                                   DiagnosticCode::kLinesUnderDetermined,
                                                   DiagnosticCode::kResidualBias,
                                                   DiagnosticCode::kBroadbandFit,
                                                   DiagnosticCode::kLineLost,
                                                   DiagnosticCode::kOverdampedLinesLeftOut,
                                                   DiagnosticCode::kLineLockedToHarmonic,
                                                   DiagnosticCode::kTrackingAmbiguous,
                                                   DiagnosticCode::kMbcNotTransformed,
                                                   DiagnosticCode::kMbcEigenFailed,
                                                   DiagnosticCode::kNoRotatingStates,
                                                   DiagnosticCode::kMultiBladeCoordinates,
                                                   DiagnosticCode::kAzimuthsUneven,
                                                   DiagnosticCode::kRotorSpeedsDiffer,
                                                   DiagnosticCode::kMatrixDropped};
  return kAll;
}

std::string_view CodeName(DiagnosticCode code) {
  switch (code) {
    case DiagnosticCode::kSegmentIntegrationFailed:
      return "segment_integration_failed";
    case DiagnosticCode::kSegmentRefinementStopped:
      return "segment_refinement_stopped";
    case DiagnosticCode::kWorkEstimate:
      return "work_estimate";
    case DiagnosticCode::kStatesBalanced:
      return "states_balanced";
    case DiagnosticCode::kIntegratorChosen:
      return "integrator_chosen";
    case DiagnosticCode::kSegmentsChosen:
      return "segments_chosen";
    case DiagnosticCode::kMultipliersRegrouped:
      return "multipliers_regrouped";
    case DiagnosticCode::kMultipliersSingleShot:
      return "multipliers_single_shot";
    case DiagnosticCode::kMultipliersFailed:
      return "multipliers_failed";
    case DiagnosticCode::kErrorEstimateFallback:
      return "error_estimate_fallback";
    case DiagnosticCode::kErrorEstimateFailed:
      return "error_estimate_failed";
    case DiagnosticCode::kModesNotComputed:
      return "modes_not_computed";
    case DiagnosticCode::kModeSamplesPropagated:
      return "mode_samples_propagated";
    case DiagnosticCode::kModesUnderResolved:
      return "modes_under_resolved";
    case DiagnosticCode::kModeShapeFailed:
      return "mode_shape_failed";
    case DiagnosticCode::kNoModeShapes:
      return "no_mode_shapes";
    case DiagnosticCode::kModeMatrixIllConditioned:
      return "mode_matrix_ill_conditioned";
    case DiagnosticCode::kBranchOnStripEdge:
      return "branch_on_strip_edge";
    case DiagnosticCode::kBranchAmbiguous:
      return "branch_ambiguous";
    case DiagnosticCode::kRigidBodyMode:
      return "rigid_body_mode";
    case DiagnosticCode::kLiouvilleCheckFailed:
      return "liouville_check_failed";
    case DiagnosticCode::kStabilityMarginal:
      return "stability_marginal";
    case DiagnosticCode::kVerdictPerModeBand:
      return "verdict_per_mode_band";
    case DiagnosticCode::kModelErrorIncluded:
      return "model_error_included";
    case DiagnosticCode::kModesBelowSummary:
      return "modes_below_summary";
    case DiagnosticCode::kAllModesBelowCutoff:
      return "all_modes_below_cutoff";
    case DiagnosticCode::kNoModesBelowCutoff:
      return "no_modes_below_cutoff";
    case DiagnosticCode::kCutoffsDisagree:
      return "cutoffs_disagree";
    case DiagnosticCode::kFourierFitted:
      return "fourier_fitted";
    case DiagnosticCode::kFourierFitNotConverged:
      return "fourier_fit_not_converged";
    case DiagnosticCode::kHillSolverChosen:
      return "hill_solver_chosen";
    case DiagnosticCode::kHillSolverFellBack:
      return "hill_solver_fell_back";
    case DiagnosticCode::kHillFallbackTooCostly:
      return "hill_fallback_too_costly";
    case DiagnosticCode::kHillSolverFailed:
      return "hill_solver_failed";
    case DiagnosticCode::kRitzPairsUnconverged:
      return "ritz_pairs_unconverged";
    case DiagnosticCode::kExponentFamiliesMissing:
      return "exponent_families_missing";
    case DiagnosticCode::kSelectionRuleFailed:
      return "selection_rule_failed";
    case DiagnosticCode::kEigenvectorsAtTruncationEdge:
      return "eigenvectors_at_truncation_edge";
    case DiagnosticCode::kBranchesMoveWithTruncation:
      return "branches_move_with_truncation";
    case DiagnosticCode::kTruncationNotConverged:
      return "truncation_not_converged";
    case DiagnosticCode::kTruncationLimited:
      return "truncation_limited";
    case DiagnosticCode::kTruncationUnresolved:
      return "truncation_unresolved";
    case DiagnosticCode::kKoopmanHillSkipped:
      return "koopman_hill_skipped";
    case DiagnosticCode::kKoopmanHillDisagrees:
      return "koopman_hill_disagrees";
    case DiagnosticCode::kHarmonicsChosen:
      return "harmonics_chosen";
    case DiagnosticCode::kToleranceNotReached:
      return "tolerance_not_reached";
    case DiagnosticCode::kConvergenceRateUnknown:
      return "convergence_rate_unknown";
    case DiagnosticCode::kDiscontinuousCoefficients:
      return "discontinuous_coefficients";
    case DiagnosticCode::kRoutesChosen:
      return "routes_chosen";
    case DiagnosticCode::kRouteFailed:
      return "route_failed";
    case DiagnosticCode::kRoutesDisagree:
      return "routes_disagree";
    case DiagnosticCode::kRoutesCompared:
      return "routes_compared";
    case DiagnosticCode::kModalUnreliable:
      return "modal_unreliable";
    case DiagnosticCode::kModalSamplesFailed:
      return "modal_samples_failed";
    case DiagnosticCode::kModalSpectrumUnresolved:
      return "modal_spectrum_unresolved";
    case DiagnosticCode::kFloquetFailed:
      return "floquet_failed";
    case DiagnosticCode::kSystemUnstable:
      return "system_unstable";
    case DiagnosticCode::kResonance:
      return "resonance";
    case DiagnosticCode::kForcedResponseFailed:
      return "forced_response_failed";
    case DiagnosticCode::kShootingSingular:
      return "shooting_singular";
    case DiagnosticCode::kNoSteadyState:
      return "no_steady_state";
    case DiagnosticCode::kSettlingTime:
      return "settling_time";
    case DiagnosticCode::kRouteSummary:
      return "route_summary";
    case DiagnosticCode::kCheckRouteUnavailable:
      return "check_route_unavailable";
    case DiagnosticCode::kNormInfinite:
      return "norm_infinite";
    case DiagnosticCode::kNormUnresolved:
      return "norm_unresolved";
    case DiagnosticCode::kNormNotComputed:
      return "norm_not_computed";
    case DiagnosticCode::kNonFiniteValues:
      return "non_finite_values";
    case DiagnosticCode::kZerosSummary:
      return "zeros_summary";
    case DiagnosticCode::kZerosUnpaired:
      return "zeros_unpaired";
    case DiagnosticCode::kFrequencyMovedToGrid:
      return "frequency_moved_to_grid";
    case DiagnosticCode::kFrequenciesMerged:
      return "frequencies_merged";
    case DiagnosticCode::kRecordGaps:
      return "record_gaps";
    case DiagnosticCode::kRecordClipped:
      return "record_clipped";
    case DiagnosticCode::kInputPhaseMoves:
      return "input_phase_moves";
    case DiagnosticCode::kNoNoiseEstimate:
      return "no_noise_estimate";
    case DiagnosticCode::kLinesNotSeparable:
      return "lines_not_separable";
    case DiagnosticCode::kSynchronousResponse:
      return "synchronous_response";
    case DiagnosticCode::kNonlinearResponse:
      return "nonlinear_response";
    case DiagnosticCode::kSpeedOffModel:
      return "speed_off_model";
    case DiagnosticCode::kExcitationFrequencyMoved:
      return "excitation_frequency_moved";
    case DiagnosticCode::kSpeedChanges:
      return "speed_changes";
    case DiagnosticCode::kLinesUnderDetermined:
      return "lines_under_determined";
    case DiagnosticCode::kResidualBias:
      return "residual_bias";
    case DiagnosticCode::kBroadbandFit:
      return "broadband_fit";
    case DiagnosticCode::kLineLost:
      return "line_lost";
    case DiagnosticCode::kOverdampedLinesLeftOut:
      return "overdamped_lines_left_out";
    case DiagnosticCode::kLineLockedToHarmonic:
      return "line_locked_to_harmonic";
    case DiagnosticCode::kTrackingAmbiguous:
      return "tracking_ambiguous";
    case DiagnosticCode::kMbcNotTransformed:
      return "mbc_not_transformed";
    case DiagnosticCode::kMbcEigenFailed:
      return "mbc_eigen_failed";
    case DiagnosticCode::kNoRotatingStates:
      return "no_rotating_states";
    case DiagnosticCode::kMultiBladeCoordinates:
      return "multi_blade_coordinates";
    case DiagnosticCode::kAzimuthsUneven:
      return "azimuths_uneven";
    case DiagnosticCode::kRotorSpeedsDiffer:
      return "rotor_speeds_differ";
    case DiagnosticCode::kMatrixDropped:
      return "matrix_dropped";
  }
  return "unknown";
}

bool HasCode(const std::vector<Diagnostic>& diagnostics, DiagnosticCode code) {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [code](const Diagnostic& d) { return d.code == code; });
}

std::vector<std::string> Texts(const std::vector<Diagnostic>& diagnostics) {
  std::vector<std::string> texts;
  texts.reserve(diagnostics.size());
  for (const Diagnostic& d : diagnostics) texts.push_back(d.text);
  return texts;
}

// Grouped by code and the text's shape without numbers.
std::vector<Diagnostic> CollapseRepeated(const std::vector<Diagnostic>& diagnostics, int keep) {
  using Key = std::pair<DiagnosticCode, std::string>;
  std::map<Key, size_t> count;
  for (const Diagnostic& d : diagnostics) ++count[{d.code, NumberShape(d.text)}];
  std::map<Key, size_t> seen;
  std::vector<Diagnostic> out;
  for (const Diagnostic& d : diagnostics) {
    const Key key{d.code, NumberShape(d.text)};
    const size_t k = ++seen[key];
    if (k <= static_cast<size_t>(keep) || count[key] <= static_cast<size_t>(keep) + 1) {
      out.push_back(d);
    } else if (k == static_cast<size_t>(keep) + 1) {
      out.push_back({d.code, d.severity,
                     "… and " + std::to_string(count[key] - keep) + " more like the above"});
    }
  }
  return out;
}

}  // namespace ltp
