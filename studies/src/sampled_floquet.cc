// Floquet analysis from azimuth samples beside MBC3 (see ltp/studies/sampled_floquet.h).
#include "ltp/studies/sampled_floquet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/floquet/model_error.h"

namespace ltp {
namespace {

using std::complex;

// `x` moved by a multiple of jΩ onto the branch nearest `target`.
complex<double> OntoBranch(complex<double> x, complex<double> target, double omega) {
  const double m = std::round((target.imag() - x.imag()) / omega);
  return {x.real(), x.imag() + m * omega};
}

// Without MBC: the rigid rotation is the exponent with a positive real multiplier, nearest 0,
// whose mode shape at t = 0 is led by the azimuth state.
int RigidExponent(const FloquetResult& r, const LinOperatingPoint& op, double omega) {
  if (!op.azimuth_state) return -1;
  const std::vector<int> rate_of = RateOf(op.states);
  int best = -1;
  for (size_t k = 0; k < r.modes.size(); ++k) {
    const complex<double> l = r.modes[k].exponent;
    if (std::abs(std::remainder(l.imag(), omega)) > 1e-6 * omega) continue;
    if (!r.mode_samples.empty()) {
      const Eigen::VectorXcd xi = r.mode_samples.front().col(static_cast<int>(k));
      int lead = -1;
      for (int i = 0; i < xi.size(); ++i)
        if (rate_of[i] < 0 && (lead < 0 || std::abs(xi[i]) > std::abs(xi[lead]))) lead = i;
      if (lead != *op.azimuth_state) continue;
    }
    if (best < 0 || std::abs(l.real()) < std::abs(r.modes[best].exponent.real()))
      best = static_cast<int>(k);
  }
  return best;
}

std::string Format(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// The two routes on the samples: held constant between them (exact under expm) and
// trigonometrically interpolated.
void RunBothRoutes(const LinOperatingPoint& used, const SampledFloquetOptions& options,
                   bool with_mbc, SampledFloquetResult* r) {
  // The table shows each exponent on the branch of the mode it is matched to (OntoBranch), so
  // the periodic mode shapes are read only to find the rigid rotation when MBC does not apply
  // (RigidExponent, hold route).
  FloquetOptions hold_options = options.floquet;
  hold_options.integrator.type = IntegratorType::kExpm;  // exact for the held samples
  hold_options.compute_modes =
      options.floquet.compute_modes && (options.hold_mode_shapes || !with_mbc);
  FloquetOptions trig_options = options.floquet;
  trig_options.compute_modes = false;
  // The second route is there to be compared with the first, at differences far above the
  // tolerance: one run with its local errors carried instead of a second run at a 100× tighter
  // tolerance — Bulirsch–Stoer's previous extrapolation row (200 states: 6.6 → 2.9 s) or Taylor
  // series' order-p product (`auto`'s choice for most fitted series). Others take the refined
  // run.
  trig_options.error_estimate_method = ErrorEstimateMethod::kLocalErrors;
  hold_options.on_progress = PrefixedProgress(options.floquet.on_progress, "hold route: ");
  trig_options.on_progress = PrefixedProgress(options.floquet.on_progress, "trigonometric route: ");
  r->hold =
      AnalyzeFloquet(BuildLinSystem(used, SampleInterpolation::kNearestConstant), hold_options);
  // Both routes interpolate the same samples, so their factors grow alike: the trigonometric
  // route starts from the grid the hold route chose instead of refining up to it again
  // (200 states: one integration of the period fewer).
  if (r->hold.grid_segments > 0 && options.floquet.segments == 0 &&
      options.floquet.initial_segments == 0)
    trig_options.initial_segments = r->hold.grid_segments;
  r->trig = AnalyzeFloquet(BuildLinSystem(used, SampleInterpolation::kTrigonometric), trig_options);
}

// The exponents both routes are matched to.
struct References {
  std::vector<complex<double>> exponents;
  std::vector<int> mode;  // MBC mode of each reference, −1 for a conjugate
  std::vector<bool> rigid;
};

// References: every MBC eigenvalue (both members of a complex pair), or the hold route's.
References CollectReferences(const Mbc3Result& mbc, const SampledFloquetOptions& options,
                             const FloquetResult& hold_result, const LinOperatingPoint& used,
                             double omega) {
  References refs;
  if (mbc.applicable && !mbc.modes.empty()) {
    for (size_t k = 0; k < mbc.modes.size(); ++k) {
      // The modes below a cut-off are those of the mean of the samples, which is MBC3's
      // averaged matrix: the analysed exponents match the MBC modes below it.
      if (options.floquet.modes_below > 0 &&
          std::abs(mbc.modes[k].eigenvalue) > options.floquet.modes_below)
        continue;
      refs.exponents.push_back(mbc.modes[k].eigenvalue);
      refs.mode.push_back(static_cast<int>(k));
      refs.rigid.push_back(mbc.modes[k].rigid_body);
      if (mbc.modes[k].eigenvalue.imag() > 0) {
        refs.exponents.push_back(std::conj(mbc.modes[k].eigenvalue));
        refs.mode.push_back(-1);
        refs.rigid.push_back(false);
      }
    }
  } else {
    const std::vector<complex<double>> hold = Exponents(hold_result.modes);
    const int rigid = RigidExponent(hold_result, used, omega);
    for (size_t k = 0; k < hold.size(); ++k) {
      refs.exponents.push_back(hold[k]);
      refs.mode.push_back(hold[k].imag() >= 0 ? static_cast<int>(k) : -1);
      refs.rigid.push_back(static_cast<int>(k) == rigid);
    }
  }
  return refs;
}

// Each reference's exponent from either route, on the reference's branch: the table's modes,
// max Re λ of each route and the routes' largest differences.
void MatchRoutes(const References& refs, double omega, bool with_mbc, SampledFloquetResult* r) {
  const std::vector<complex<double>> hold = Exponents(r->hold.modes),
                                     trig = Exponents(r->trig.modes);
  const std::vector<int> to_hold = MatchExponentIndices(refs.exponents, hold, omega);
  const std::vector<int> to_trig = MatchExponentIndices(refs.exponents, trig, omega);
  r->max_real_hold = r->max_real_trig = -std::numeric_limits<double>::infinity();
  r->max_to_reference = with_mbc ? 0 : -1;
  for (size_t i = 0; i < refs.exponents.size(); ++i) {
    if (to_hold[i] < 0 || to_trig[i] < 0) continue;
    const complex<double> ref = refs.exponents[i];
    const complex<double> h = OntoBranch(hold[to_hold[i]], ref, omega);
    const complex<double> t = OntoBranch(trig[to_trig[i]], h, omega);
    if (!refs.rigid[i]) {
      r->max_real_hold = std::max(r->max_real_hold, h.real());
      r->max_real_trig = std::max(r->max_real_trig, t.real());
    }
    if (refs.mode[i] < 0) continue;
    SampledFloquetMode m;
    if (with_mbc) m.mbc_mode = static_cast<size_t>(refs.mode[i]);
    m.reference = ref;
    m.hold = h;
    m.trig = t;
    m.difference = std::abs(h - t);
    m.rigid_body = refs.rigid[i];
    if (with_mbc) m.to_reference = std::max(std::abs(h - ref), std::abs(t - ref));
    r->max_difference = std::max(r->max_difference, m.difference);
    if (with_mbc) r->max_to_reference = std::max(r->max_to_reference, m.to_reference);
    r->modes.push_back(m);
  }
  std::stable_sort(r->modes.begin(), r->modes.end(),
                   [](const SampledFloquetMode& a, const SampledFloquetMode& b) {
                     if (a.mbc_mode && b.mbc_mode) return *a.mbc_mode < *b.mbc_mode;
                     return std::abs(a.hold) < std::abs(b.hold);
                   });
}

// The error band on max Re λ and the stability verdict.
void ClassifyRoutes(SampledFloquetResult* r) {
  // The trigonometric route is the more accurate one; the two routes' difference is its
  // sampling error term, as for `ltp floquet` (IncludeModelError).
  // Each mode with its own difference (as IncludeModelError): the band on max Re λ.
  const double integration = r->trig.error_estimate.value_or(0);
  std::vector<double> real_parts, own;
  std::vector<bool> rigid;
  for (const SampledFloquetMode& m : r->modes) {
    real_parts.push_back(m.trig.real());
    own.push_back(m.difference);
    rigid.push_back(m.rigid_body);
  }
  r->error_estimate = PerExponentBand(real_parts, own, rigid, integration, r->max_real_trig,
                                      integration + r->max_difference);
  r->verdict = ClassifyStability(r->ok, r->max_real_trig, r->error_estimate);
  // An analysis of the modes below a cut-off is stable only if the modes left out cannot
  // reach Re λ = 0 either (its own verdict says so).
  if (r->trig.reduction && r->verdict == StabilityVerdict::kStable &&
      r->trig.verdict != StabilityVerdict::kStable)
    r->verdict = r->trig.verdict;
  r->stable = r->verdict == StabilityVerdict::kStable;
}

// Notes on branches, the rigid rotation and the distance to MBC.
void AddMatchNotes(bool with_mbc, SampledFloquetResult* r) {
  r->diagnostics.push_back(
      {DiagnosticCode::kBranchesMatched, Severity::kNote,
       "each Floquet exponent (defined modulo jΩ) is shown on the branch of the " +
           std::string(with_mbc ? "MBC eigenvalue" : "hold route's exponent") +
           " it is matched to" +
           (with_mbc ? " (modes whose exponents coincide modulo jΩ, such as the backward and "
                       "forward whirl of a nearly isotropic rotor, are told apart by proximity "
                       "only)"
                     : std::string())});
  for (const SampledFloquetMode& m : r->modes)
    if (m.rigid_body)
      r->diagnostics.push_back(
          {DiagnosticCode::kRigidBodyMode, Severity::kNote,
           "rigid-body mode: exponent " + Format("%.3g", m.hold.real()) + " (hold) and " +
               Format("%.3g", m.trig.real()) +
               " (trig) 1/s instead of 0 — the sampling error on the rigid rotation; excluded "
               "from max Re λ"});
  if (with_mbc)
    r->diagnostics.push_back(
        {DiagnosticCode::kDistanceToMbc, Severity::kNote,
         "distance to the MBC eigenvalues up to " + Format("%.3g", r->max_to_reference) +
             " 1/s: the periodicity that azimuth averaging discards, plus sampling error"});
}

}  // namespace

SampledFloquetResult AnalyzeSampledFloquet(const LinOperatingPoint& op, const Mbc3Result& mbc,
                                           const SampledFloquetOptions& options) {
  if (!(op.rotor_speed > 0))
    throw InputError(
        "rotor speed 0: a parked rotor is time-invariant, so there is no period and "
        "no Floquet analysis (the MBC eigen-analysis still applies)");
  SampledFloquetResult r;
  const bool use_mbc = mbc.applicable && options.multiblade_coordinates;
  const LinOperatingPoint used = use_mbc ? InMultiBladeCoordinates(op, mbc) : op;
  r.coordinates = use_mbc ? "multi-blade coordinates" : "the files' coordinates";
  r.samples = op.size();
  r.resolved_harmonics = (op.size() - 1) / 2;
  const double omega = op.rotor_speed;

  const bool with_mbc = mbc.applicable && !mbc.modes.empty();
  RunBothRoutes(used, options, with_mbc, &r);
  r.ok = r.hold.ok && r.trig.ok;
  r.diagnostics = LinCaveats(used);
  if (!r.ok) {
    r.diagnostics.push_back({DiagnosticCode::kFloquetFailed, Severity::kFailure,
                             std::string(r.hold.ok ? "the trigonometric" : "the nearest-sample") +
                                 " route failed: see its diagnostics"});
    return r;
  }
  MatchRoutes(CollectReferences(mbc, options, r.hold, used, omega), omega, with_mbc, &r);
  ClassifyRoutes(&r);
  AddMatchNotes(with_mbc, &r);
  return r;
}

}  // namespace ltp
