#include "ltp/core/diagnostic.h"

#include <algorithm>
#include <array>
#include <map>
#include <utility>

#include "ltp/core/text.h"

namespace ltp {

namespace {

struct CodeAndName {
  DiagnosticCode code;
  std::string_view name;
};

// Every code with its name, in the enum's order (checked below): the one list of the codes.
constexpr auto kCodeNames = std::to_array<CodeAndName>({
    {DiagnosticCode::kSegmentIntegrationFailed, "segment_integration_failed"},
    {DiagnosticCode::kSegmentRefinementStopped, "segment_refinement_stopped"},
    {DiagnosticCode::kWorkEstimate, "work_estimate"},
    {DiagnosticCode::kStatesBalanced, "states_balanced"},
    {DiagnosticCode::kIntegratorChosen, "integrator_chosen"},
    {DiagnosticCode::kSegmentsChosen, "segments_chosen"},
    {DiagnosticCode::kMultipliersRegrouped, "multipliers_regrouped"},
    {DiagnosticCode::kMultipliersSingleShot, "multipliers_single_shot"},
    {DiagnosticCode::kMultipliersFailed, "multipliers_failed"},
    {DiagnosticCode::kErrorEstimateFallback, "error_estimate_fallback"},
    {DiagnosticCode::kErrorEstimateFailed, "error_estimate_failed"},
    {DiagnosticCode::kModesNotComputed, "modes_not_computed"},
    {DiagnosticCode::kModeSamplesPropagated, "mode_samples_propagated"},
    {DiagnosticCode::kModesUnderResolved, "modes_under_resolved"},
    {DiagnosticCode::kModeShapeFailed, "mode_shape_failed"},
    {DiagnosticCode::kNoModeShapes, "no_mode_shapes"},
    {DiagnosticCode::kModeMatrixIllConditioned, "mode_matrix_ill_conditioned"},
    {DiagnosticCode::kBranchOnStripEdge, "branch_on_strip_edge"},
    {DiagnosticCode::kBranchAmbiguous, "branch_ambiguous"},
    {DiagnosticCode::kRigidBodyMode, "rigid_body_mode"},
    {DiagnosticCode::kLiouvilleCheckFailed, "liouville_check_failed"},
    {DiagnosticCode::kStabilityMarginal, "stability_marginal"},
    {DiagnosticCode::kVerdictPerModeBand, "verdict_per_mode_band"},
    {DiagnosticCode::kModelErrorIncluded, "model_error_included"},
    {DiagnosticCode::kModesBelowSummary, "modes_below_summary"},
    {DiagnosticCode::kAllModesBelowCutoff, "all_modes_below_cutoff"},
    {DiagnosticCode::kNoModesBelowCutoff, "no_modes_below_cutoff"},
    {DiagnosticCode::kCutoffsDisagree, "cutoffs_disagree"},
    {DiagnosticCode::kFourierFitted, "fourier_fitted"},
    {DiagnosticCode::kFourierFitNotConverged, "fourier_fit_not_converged"},
    {DiagnosticCode::kHillSolverChosen, "hill_solver_chosen"},
    {DiagnosticCode::kHillSolverFellBack, "hill_solver_fell_back"},
    {DiagnosticCode::kHillFallbackTooCostly, "hill_fallback_too_costly"},
    {DiagnosticCode::kHillSolverFailed, "hill_solver_failed"},
    {DiagnosticCode::kRitzPairsUnconverged, "ritz_pairs_unconverged"},
    {DiagnosticCode::kExponentFamiliesMissing, "exponent_families_missing"},
    {DiagnosticCode::kSelectionRuleFailed, "selection_rule_failed"},
    {DiagnosticCode::kEigenvectorsAtTruncationEdge, "eigenvectors_at_truncation_edge"},
    {DiagnosticCode::kBranchesMoveWithTruncation, "branches_move_with_truncation"},
    {DiagnosticCode::kTruncationNotConverged, "truncation_not_converged"},
    {DiagnosticCode::kTruncationLimited, "truncation_limited"},
    {DiagnosticCode::kTruncationUnresolved, "truncation_unresolved"},
    {DiagnosticCode::kKoopmanHillSkipped, "koopman_hill_skipped"},
    {DiagnosticCode::kKoopmanHillDisagrees, "koopman_hill_disagrees"},
    {DiagnosticCode::kHarmonicsChosen, "harmonics_chosen"},
    {DiagnosticCode::kToleranceNotReached, "tolerance_not_reached"},
    {DiagnosticCode::kConvergenceRateUnknown, "convergence_rate_unknown"},
    {DiagnosticCode::kDiscontinuousCoefficients, "discontinuous_coefficients"},
    {DiagnosticCode::kRoutesChosen, "routes_chosen"},
    {DiagnosticCode::kRouteFailed, "route_failed"},
    {DiagnosticCode::kRoutesDisagree, "routes_disagree"},
    {DiagnosticCode::kRoutesCompared, "routes_compared"},
    {DiagnosticCode::kModalUnreliable, "modal_unreliable"},
    {DiagnosticCode::kModalSamplesFailed, "modal_samples_failed"},
    {DiagnosticCode::kModalSpectrumUnresolved, "modal_spectrum_unresolved"},
    {DiagnosticCode::kFloquetFailed, "floquet_failed"},
    {DiagnosticCode::kSystemUnstable, "system_unstable"},
    {DiagnosticCode::kResonance, "resonance"},
    {DiagnosticCode::kForcedResponseFailed, "forced_response_failed"},
    {DiagnosticCode::kShootingSingular, "shooting_singular"},
    {DiagnosticCode::kNoSteadyState, "no_steady_state"},
    {DiagnosticCode::kSettlingTime, "settling_time"},
    {DiagnosticCode::kRouteSummary, "route_summary"},
    {DiagnosticCode::kCheckRouteUnavailable, "check_route_unavailable"},
    {DiagnosticCode::kNormInfinite, "norm_infinite"},
    {DiagnosticCode::kNormUnresolved, "norm_unresolved"},
    {DiagnosticCode::kNormNotComputed, "norm_not_computed"},
    {DiagnosticCode::kNonFiniteValues, "non_finite_values"},
    {DiagnosticCode::kZerosSummary, "zeros_summary"},
    {DiagnosticCode::kZerosUnpaired, "zeros_unpaired"},
    {DiagnosticCode::kFrequencyMovedToGrid, "frequency_moved_to_grid"},
    {DiagnosticCode::kFrequenciesMerged, "frequencies_merged"},
    {DiagnosticCode::kRecordGaps, "record_gaps"},
    {DiagnosticCode::kRecordClipped, "record_clipped"},
    {DiagnosticCode::kInputPhaseMoves, "input_phase_moves"},
    {DiagnosticCode::kNoNoiseEstimate, "no_noise_estimate"},
    {DiagnosticCode::kLinesNotSeparable, "lines_not_separable"},
    {DiagnosticCode::kSynchronousResponse, "synchronous_response"},
    {DiagnosticCode::kNonlinearResponse, "nonlinear_response"},
    {DiagnosticCode::kSpeedOffModel, "speed_off_model"},
    {DiagnosticCode::kExcitationFrequencyMoved, "excitation_frequency_moved"},
    {DiagnosticCode::kSpeedChanges, "speed_changes"},
    {DiagnosticCode::kLinesUnderDetermined, "lines_under_determined"},
    {DiagnosticCode::kResidualBias, "residual_bias"},
    {DiagnosticCode::kBroadbandFit, "broadband_fit"},
    {DiagnosticCode::kLineLost, "line_lost"},
    {DiagnosticCode::kOverdampedLinesLeftOut, "overdamped_lines_left_out"},
    {DiagnosticCode::kLineLockedToHarmonic, "line_locked_to_harmonic"},
    {DiagnosticCode::kTrackingAmbiguous, "tracking_ambiguous"},
    {DiagnosticCode::kMbcNotTransformed, "mbc_not_transformed"},
    {DiagnosticCode::kMbcEigenFailed, "mbc_eigen_failed"},
    {DiagnosticCode::kNoRotatingStates, "no_rotating_states"},
    {DiagnosticCode::kMultiBladeCoordinates, "multi_blade_coordinates"},
    {DiagnosticCode::kAzimuthsUneven, "azimuths_uneven"},
    {DiagnosticCode::kRotorSpeedsDiffer, "rotor_speeds_differ"},
    {DiagnosticCode::kMatrixDropped, "matrix_dropped"},
    {DiagnosticCode::kOperatingSpeedDiffers, "operating_speed_differs"},
    {DiagnosticCode::kAzimuthSamplesResolve, "azimuth_samples_resolve"},
    {DiagnosticCode::kTooFewAzimuths, "too_few_azimuths"},
    {DiagnosticCode::kExponentsModuloRotorSpeed, "exponents_modulo_rotor_speed"},
    {DiagnosticCode::kBranchesMatched, "branches_matched"},
    {DiagnosticCode::kDistanceToMbc, "distance_to_mbc"},
    {DiagnosticCode::kLinesAboveBandLeftOut, "lines_above_band_left_out"},
    {DiagnosticCode::kModulesLeftOut, "modules_left_out"},
});

constexpr bool InEnumOrder() {
  for (size_t i = 0; i < kCodeNames.size(); ++i)
    if (static_cast<size_t>(kCodeNames[i].code) != i) return false;
  return true;
}
static_assert(InEnumOrder(), "kCodeNames must list every DiagnosticCode in the enum's order");
static_assert(static_cast<size_t>(DiagnosticCode::kCount) == kCodeNames.size(),
              "kCodeNames must name every DiagnosticCode");

}  // namespace

const std::vector<DiagnosticCode>& AllDiagnosticCodes() {
  static const std::vector<DiagnosticCode> kAll = [] {
    std::vector<DiagnosticCode> all;
    for (const CodeAndName& c : kCodeNames) all.push_back(c.code);
    return all;
  }();
  return kAll;
}

std::string_view CodeName(DiagnosticCode code) {
  const auto i = static_cast<size_t>(code);
  return i < kCodeNames.size() ? kCodeNames[i].name : "unknown";
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
