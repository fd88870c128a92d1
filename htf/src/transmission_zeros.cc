// Transmission zeros of a square periodic system by two routes (docs/htf-operator.md, "Zeros"):
//   hill           the generalized eigenvalues of the truncated harmonic Rosenbrock pencil
//                  M − sE, M = [[𝒜 − 𝒩, 𝓑], [𝒞, 𝒟]], E = diag(I, 0) (LAPACK zggev). Every zero
//                  appears once per shift z + jmΩp; the member whose eigenvector is centred on
//                  harmonic 0 is kept, and N grows to N + Δ until no zero moves any more.
//   zero dynamics  for D(t) invertible, the Floquet exponents of A − B D⁻¹ C; for D = 0 with
//                  C(t)B(t) invertible, those of A − B (CB)⁻¹ (CA + C') less the m exponents 0
//                  of the directions C sees (that closed loop keeps C x constant).
#include <lapacke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "ltp/core/elapsed.h"
#include "ltp/core/error.h"
#include "ltp/core/exponent_match.h"
#include "ltp/hill/hill.h"
#include "ltp/htf/harmonic_transfer_function.h"

namespace ltp {

namespace {
using cd = std::complex<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A generalized eigenvalue |s| beyond this × the pencil's 1-norm counts as infinite: the
// infinite eigenvalues of a relative degree k >= 1 form Jordan blocks that round-off splits into
// |s| ~ ‖M‖ eps^{−1/(k+1)} (about 1e6 ‖M‖ measured at k = 2, N = 8).
constexpr double kFiniteLimit = 1e4;
// A centroid within this of ±1/2 is a tie between z and z ∓ jΩp (both kept until deduplicated).
constexpr double kTieMargin = 0.05;
// D(t) (or C(t)B(t)) counts as invertible when σmin/σmax exceeds this at every sample.
constexpr double kInvertible = 1e-8;
constexpr int kSamples = 64;
// The smallest estimate of a zero, relative to max(|z|, Ωp).
constexpr double kRoundOff = 1e-14;

lapack_complex_double* Lapack(cd* p) { return reinterpret_cast<lapack_complex_double*>(p); }

// The finite generalized eigenpairs of M − sE, E = diag(I_states, 0).
struct PencilEigen {
  bool ok = false;
  std::vector<cd> values;
  Eigen::MatrixXcd vectors;  ///< column i belongs to values[i]
  int infinite = 0;
};

PencilEigen SolvePencil(Eigen::MatrixXcd m, int state_rows) {
  const int size = static_cast<int>(m.rows());
  Eigen::MatrixXcd e = Eigen::MatrixXcd::Zero(size, size);
  e.topLeftCorner(state_rows, state_rows).setIdentity();
  const double norm = m.cwiseAbs().colwise().sum().maxCoeff();
  std::vector<cd> alpha(size), beta(size);
  Eigen::MatrixXcd right(size, size);
  PencilEigen out;
  const lapack_int info = LAPACKE_zggev(
      LAPACK_COL_MAJOR, 'N', 'V', size, Lapack(m.data()), size, Lapack(e.data()), size,
      Lapack(alpha.data()), Lapack(beta.data()), nullptr, 1, Lapack(right.data()), size);
  if (info != 0) return out;
  out.ok = true;
  std::vector<int> finite;
  for (int i = 0; i < size; ++i) {
    if (std::abs(alpha[i]) <= kFiniteLimit * norm * std::abs(beta[i]) && beta[i] != 0.0) {
      finite.push_back(i);
      out.values.push_back(alpha[i] / beta[i]);
    } else {
      ++out.infinite;
    }
  }
  out.vectors.resize(size, static_cast<Eigen::Index>(finite.size()));
  for (size_t k = 0; k < finite.size(); ++k) out.vectors.col(k) = right.col(finite[k]);
  return out;
}

// Energy centroid over the harmonics −N…N of an eigenvector [X; U] (X: blocks of n, U: of m).
double HarmonicCentroid(const Eigen::VectorXcd& v, int n, int m, int N) {
  const int xs = (2 * N + 1) * n;
  double total = 0, moment = 0;
  for (int k = -N; k <= N; ++k) {
    const double energy =
        v.segment((k + N) * n, n).squaredNorm() + v.segment(xs + (k + N) * m, m).squaredNorm();
    total += energy;
    moment += k * energy;
  }
  return total > 0 ? moment / total : 0.0;
}

struct Candidate {
  cd value;  ///< the centred member
  double centroid = 0;
};

// Of two candidates that are the same zero shifted by a non-zero multiple of Ωp (a tie near a
// centroid of ±1/2), the better centred one.
std::vector<Candidate> WithoutTies(std::vector<Candidate> c, double omega) {
  std::vector<bool> dropped(c.size(), false);
  for (size_t i = 0; i < c.size(); ++i)
    for (size_t j = i + 1; j < c.size(); ++j) {
      const cd d = c[i].value - c[j].value;
      const double scale = std::max(std::abs(c[i].value), omega);
      const bool shifted = std::lround(d.imag() / omega) != 0;
      if (shifted && ExponentDistance(c[i].value, c[j].value, omega) <= 1e-6 * scale)
        dropped[std::abs(c[i].centroid) <= std::abs(c[j].centroid) ? j : i] = true;
    }
  std::vector<Candidate> kept;
  for (size_t i = 0; i < c.size(); ++i)
    if (!dropped[i]) kept.push_back(c[i]);
  return kept;
}

// The Hill route at one truncation: the finite eigenvalues centred on harmonic 0.
struct PencilRun {
  bool ok = false;
  int harmonics = 0, size = 0, infinite = 0, uncentred = 0;
  std::vector<Candidate> zeros;
};

PencilRun RunPencil(const SystemFourier& f, double omega, int N) {
  const int n = f.A.series.rows(), m = f.B.series.cols();
  PencilRun run;
  run.harmonics = N;
  const PencilEigen eig = SolvePencil(internal::HarmonicPencil(f, omega, N), (2 * N + 1) * n);
  run.size = (2 * N + 1) * (n + m);
  run.ok = eig.ok;
  run.infinite = eig.infinite;
  std::vector<Candidate> centred;
  for (size_t i = 0; i < eig.values.size(); ++i) {
    const double c = HarmonicCentroid(eig.vectors.col(i), n, m, N);
    if (std::abs(c) <= 0.5 + kTieMargin) centred.push_back({eig.values[i], c});
  }
  run.zeros = WithoutTies(std::move(centred), omega);
  run.uncentred = static_cast<int>(eig.values.size() - run.zeros.size());
  return run;
}

std::vector<cd> ValuesOf(const std::vector<Candidate>& c) {
  std::vector<cd> v;
  for (const Candidate& x : c) v.push_back(x.value);
  return v;
}

// The pencil's Fourier series decay algebraically (a coefficient jumps): the change from N to
// N + Δ is then only part of the error; (N + Δ)/Δ covers the slowest rate (as Hill's exponents).
double TailFactor(const SystemFourier& f, int N, int delta) {
  for (const FourierFit* fit : {&f.A, &f.B, &f.C, &f.D})
    if (fit->decay == FourierDecay::kAlgebraic) return double(N + delta) / delta;
  return 1;
}

// The Hill route converged (or stopped) over the truncations: the values at N + Δ and each
// one's change from N.
struct HillOutcome {
  PencilRun fine;
  int harmonics = 0, delta = 0;
  std::vector<double> change;  ///< parallel to fine.zeros
  int lost = 0;                ///< zeros at N without a partner at N + Δ
  bool converged = false;
  std::string failure;
  std::vector<Diagnostic> notes;
};

void CompareTruncations(const PencilRun& coarse, double omega, double tol, HillOutcome& h) {
  const std::vector<cd> fine = ValuesOf(h.fine.zeros), previous = ValuesOf(coarse.zeros);
  h.change = MatchExponents(fine, previous, omega);
  h.lost = std::max(0, static_cast<int>(previous.size()) - static_cast<int>(fine.size()));
  h.converged = h.lost == 0;
  for (size_t i = 0; i < fine.size(); ++i)
    h.converged = h.converged && h.change[i] <= tol * std::max(std::abs(fine[i]), omega);
}

int PencilRows(int n, int m, int N) { return (2 * N + 1) * (n + m); }

class TruncationPlan {
 public:
  TruncationPlan(const ZerosOptions& o, int n, int m) : o_(o), n_(n), m_(m) {}
  int Delta(int N) const { return o_.delta > 0 ? o_.delta : std::max(2, N / 2); }
  bool Fits(int N) const { return PencilRows(n_, m_, N + Delta(N)) <= o_.max_pencil_size; }
  // The first N: the one asked for, or the Hill route's capped so that N + Δ fits.
  int Start(int hill_harmonics) const {
    if (o_.harmonics > 0) {
      if (!Fits(o_.harmonics)) {
        std::ostringstream s;
        s << "zeros: the pencil at N + Δ = " << o_.harmonics + Delta(o_.harmonics) << " has "
          << PencilRows(n_, m_, o_.harmonics + Delta(o_.harmonics))
          << " rows, more than max_pencil_size = " << o_.max_pencil_size;
        throw ResourceError(s.str());
      }
      return o_.harmonics;
    }
    int N = std::clamp(hill_harmonics, 1, o_.max_harmonics);
    while (N > 1 && !Fits(N)) --N;
    if (!Fits(N))
      throw ResourceError("zeros: even the pencil at N = 1 has more than max_pencil_size = " +
                          std::to_string(o_.max_pencil_size) + " rows");
    return N;
  }

 private:
  const ZerosOptions& o_;
  int n_, m_;
};

HillOutcome ConvergeHill(const SystemFourier& f, double omega, int hill_harmonics,
                         const ZerosOptions& o) {
  const int n = f.A.series.rows(), m = f.B.series.cols();
  const TruncationPlan plan(o, n, m);
  int N = plan.Start(hill_harmonics);
  PencilRun coarse = RunPencil(f, omega, N);
  HillOutcome h;
  for (;;) {
    h.harmonics = N;
    h.delta = plan.Delta(N);
    h.fine = RunPencil(f, omega, N + h.delta);
    if (!coarse.ok || !h.fine.ok) {
      h.failure = "zeros: LAPACK's zggev failed on the pencil at N = " + std::to_string(N);
      return h;
    }
    CompareTruncations(coarse, omega, o.tol, h);
    const int next = N + h.delta;
    if (h.converged || o.harmonics > 0) break;
    if (next >= o.max_harmonics || !plan.Fits(next)) {
      h.notes.push_back({DiagnosticCode::kTruncationLimited, Severity::kWarning,
                         "zeros: the truncation stopped at N = " + std::to_string(N) +
                             (next >= o.max_harmonics ? " (max_harmonics)" : " (max_pencil_size)") +
                             " before every zero converged"});
      break;
    }
    N = next;
    coarse = std::move(h.fine);
  }
  // The change carries the round-off of two eigensolves; a floor keeps an exact case (an LTI
  // system, where every N gives the same zeros) from claiming 0.
  const double factor = TailFactor(f, h.harmonics, h.delta);
  for (size_t i = 0; i < h.change.size(); ++i)
    h.change[i] = std::max(h.change[i] * factor,
                           kRoundOff * std::max(std::abs(h.fine.zeros[i].value), omega));
  return h;
}

double LargestChange(const HillOutcome& h) {
  double largest = h.lost > 0 ? kInf : 0.0;
  for (double c : h.change) largest = std::max(largest, c);
  return largest;
}

// The representative of z modulo jΩp in the strip −Ωp/2 < Im z <= Ωp/2.
cd InStrip(cd z, double omega) {
  double im = std::remainder(z.imag(), omega);
  if (im <= -0.5 * omega * (1 - 1e-12)) im += omega;
  return {z.real(), im};
}

void ReportHill(const HillOutcome& h, double omega, TransmissionZeros& r) {
  r.harmonics = h.harmonics;
  r.delta = h.delta;
  r.pencil_size = h.fine.size;
  r.infinite_eigenvalues = h.fine.infinite;
  r.uncentred_eigenvalues = h.fine.uncentred;
  r.diagnostics = h.notes;
  for (size_t i = 0; i < h.fine.zeros.size(); ++i) {
    TransmissionZero z;
    z.centred = z.hill_value = h.fine.zeros[i].value;
    z.value = InStrip(z.centred, omega);
    z.centroid = h.fine.zeros[i].centroid;
    z.truncation_change = h.change[i];
    z.error_estimate = h.change[i];
    r.zeros.push_back(z);
  }
  std::ostringstream s;
  s << "hill: pencil of " << h.fine.size << " rows at N + Δ = " << h.harmonics + h.delta << ": "
    << r.zeros.size() << " centred on harmonic 0 (the zeros), " << h.fine.uncentred
    << " other finite eigenvalues (shifted members, truncation edge), " << h.fine.infinite
    << " infinite";
  r.diagnostics.push_back({DiagnosticCode::kZerosSummary, Severity::kNote, s.str()});
  if (h.lost > 0)
    r.diagnostics.push_back(
        {DiagnosticCode::kZerosUnpaired, Severity::kWarning,
         "hill: " + std::to_string(h.lost) + " zeros at N have no partner at N + Δ"});
}

}  // namespace

std::string_view ToString(ZeroRoute route) {
  switch (route) {
    case ZeroRoute::kHill:
      return "hill";
    case ZeroRoute::kZeroDynamics:
      return "zero-dynamics";
    case ZeroRoute::kRelativeDegreeOne:
    default:
      return "relative-degree-one";
  }
}

void ZerosOptions::Validate() const {
  const OptionCheck check("ZerosOptions");
  if (harmonics < 0) check.Fail("harmonics", harmonics, "harmonics >= 0 (0 = automatic)");
  if (delta < 0) check.Fail("delta", delta, "delta >= 0 (0 = automatic)");
  if (!(tol > 0 && tol < 0.1)) check.Fail("tol", tol, "0 < tol < 0.1");
  if (max_harmonics < 1) check.Fail("max_harmonics", max_harmonics, "max_harmonics >= 1");
  if (max_pencil_size < 1) check.Fail("max_pencil_size", max_pencil_size, "max_pencil_size >= 1");
  floquet.Validate();
}

namespace internal {

Eigen::MatrixXcd HarmonicPencil(const SystemFourier& f, double omega, int harmonics) {
  const int N = harmonics, n = f.A.series.rows(), m = f.B.series.cols(), p = f.C.series.rows();
  const int xs = (2 * N + 1) * n, us = (2 * N + 1) * m, ys = (2 * N + 1) * p;
  Eigen::MatrixXcd pencil = Eigen::MatrixXcd::Zero(xs + ys, xs + us);
  pencil.topLeftCorner(xs, xs) = HillMatrix(f.A.series, omega, N);
  pencil.topRightCorner(xs, us) = f.B.series.BlockToeplitz(N);
  pencil.bottomLeftCorner(ys, xs) = f.C.series.BlockToeplitz(N);
  if (f.D.series.rows() > 0) pencil.bottomRightCorner(ys, us) = f.D.series.BlockToeplitz(N);
  return pencil;
}

PeriodicSystem ZeroDynamicsSystem(const PeriodicSystem& system) {
  PeriodicSystem::Functions f;
  f.A = [system](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    out = system.A(t) - system.B(t) * system.D(t).partialPivLu().solve(system.C(t));
  };
  return PeriodicSystem::FromFunctions(system.period(), system.states(), 0, 0, std::move(f),
                                       system.breakpoints());
}

PeriodicSystem RelativeDegreeOneSystem(const PeriodicSystem& system, const FourierMatrix& c_dot) {
  PeriodicSystem::Functions f;
  f.A = [system, c_dot](double t, Eigen::Ref<Eigen::MatrixXd> out) {
    const Eigen::MatrixXd a = system.A(t), b = system.B(t), c = system.C(t);
    const Eigen::MatrixXd feedback =
        (c * b).partialPivLu().solve(c * a + c_dot.Evaluate(t, system.omega()));
    out = a - b * feedback;
  };
  return PeriodicSystem::FromFunctions(system.period(), system.states(), 0, 0, std::move(f),
                                       system.breakpoints());
}

}  // namespace internal

namespace {

// The check route: the Floquet exponents of the zero dynamics, where they are the zeros.
struct CheckRun {
  std::optional<ZeroRoute> route;
  bool ok = false;
  std::string failure;
  std::vector<cd> zeros;
  std::vector<double> estimates;
  std::vector<Diagnostic> notes;
};

// min over kSamples of σmin/σmax of f(t) (0 when some sample is zero or singular).
template <class MatrixAt>
double WorstInverseCondition(double period, MatrixAt f) {
  double worst = kInf;
  for (int s = 0; s < kSamples; ++s) {
    const Eigen::VectorXd sv =
        Eigen::JacobiSVD<Eigen::MatrixXd>(f(s * period / kSamples)).singularValues();
    worst = std::min(worst, sv(0) > 0 ? sv(sv.size() - 1) / sv(0) : 0.0);
  }
  return worst;
}

FourierMatrix Derivative(const FourierMatrix& c, double omega) {
  FourierMatrix d(c.rows(), c.cols(), c.max_harmonic());
  for (int w = -c.max_harmonic(); w <= c.max_harmonic(); ++w) d[w] = c[w] * cd(0, w * omega);
  return d;
}

// Which check route applies, or why none does (in `run.notes`).
std::optional<ZeroRoute> ChooseCheck(const PeriodicSystem& system, const SystemFourier& f,
                                     CheckRun& run) {
  const double T = system.period();
  if (internal::MaxFeedthrough(system) > 0) {
    const double d = WorstInverseCondition(T, [&](double t) { return system.D(t); });
    if (d > kInvertible) return ZeroRoute::kZeroDynamics;
    run.notes.push_back({DiagnosticCode::kCheckRouteUnavailable, Severity::kNote,
                         "zeros: no check route: D(t) is not zero but singular somewhere " +
                             std::string("(σmin/σmax down to ") + MessageNumber(d, 2) + ")"});
    return std::nullopt;
  }
  const double cb = WorstInverseCondition(
      T, [&](double t) -> Eigen::MatrixXd { return system.C(t) * system.B(t); });
  if (!(cb > kInvertible)) {
    run.notes.push_back(
        {DiagnosticCode::kCheckRouteUnavailable, Severity::kNote,
         "zeros: no check route: D = 0 and C(t)B(t) is singular somewhere (relative degree "
         "above one): the Hill route stands alone"});
    return std::nullopt;
  }
  if (!f.C.converged) {
    run.notes.push_back(
        {DiagnosticCode::kCheckRouteUnavailable, Severity::kNote,
         "zeros: no check route: C(t)'s Fourier fit did not converge (a jump), so C'(t) of the "
         "relative-degree-one route is not available"});
    return std::nullopt;
  }
  return ZeroRoute::kRelativeDegreeOne;
}

void TakeExponents(const FloquetResult& fr, const std::vector<int>& keep, CheckRun& run) {
  for (int k : keep) {
    const FloquetMode& mode = fr.modes[k];
    run.zeros.push_back(mode.exponent);
    run.estimates.push_back(mode.error_estimate.value_or(fr.error_estimate.value_or(0.0)));
  }
}

// The closed loop of the relative-degree-one route keeps C x constant: m of its exponents are 0,
// those whose mode shapes C(0) sees. The other n − m are the zeros.
void DropDirectionsCSees(const PeriodicSystem& system, const FloquetResult& fr, CheckRun& run) {
  const int n = system.states(), m = system.inputs();
  const Eigen::MatrixXcd xi = fr.ModeMatrix(0.0);
  const Eigen::MatrixXcd c0 = system.C(0.0).cast<cd>();
  std::vector<std::pair<double, int>> seen;  // (‖C ξ‖ / ‖ξ‖, mode)
  for (int k = 0; k < n; ++k)
    seen.push_back({(c0 * xi.col(k)).norm() / std::max(xi.col(k).norm(), 1e-300), k});
  std::sort(seen.begin(), seen.end());
  std::vector<int> keep;
  for (int i = 0; i < n - m; ++i) keep.push_back(seen[i].second);
  std::sort(keep.begin(), keep.end());
  TakeExponents(fr, keep, run);
  for (int i = n - m; i < n; ++i) {
    const FloquetMode& mode = fr.modes[seen[i].second];
    const double own = mode.error_estimate.value_or(fr.error_estimate.value_or(0.0));
    const double off = ExponentDistance(mode.exponent, 0.0, system.omega());
    if (off > 100 * own + 1e-9 * system.omega()) {
      run.ok = false;
      run.failure = "zeros: the relative-degree-one route's exponent of a direction C(t) sees is " +
                    MessageNumber(off, 3) + " from 0, not 0 within its estimate";
    }
  }
}

CheckRun RunCheck(const PeriodicSystem& system, const SystemFourier& f, const ZerosOptions& o) {
  CheckRun run;
  run.route = ChooseCheck(system, f, run);
  if (!run.route) return run;
  const bool relative_one = *run.route == ZeroRoute::kRelativeDegreeOne;
  FloquetOptions fo = o.floquet;
  fo.compute_modes = fo.compute_modes || relative_one;
  const FloquetResult fr = relative_one
                               ? AnalyzeFloquet(internal::RelativeDegreeOneSystem(
                                                    system, Derivative(f.C.series, system.omega())),
                                                fo)
                               : AnalyzeFloquet(internal::ZeroDynamicsSystem(system), fo);
  if (!fr.ok) {
    run.failure = "zeros: the check route's Floquet analysis failed: " + fr.failure;
    return run;
  }
  run.ok = true;
  if (relative_one) {
    DropDirectionsCSees(system, fr, run);
  } else {
    std::vector<int> all(fr.modes.size());
    for (size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
    TakeExponents(fr, all, run);
  }
  return run;
}

// The check route's values replace the Hill route's when its estimates are the smaller ones
// (as H2 reports its better route): each on the Hill route's centred branch.
void ReportCheckValues(double omega, TransmissionZeros& r) {
  double hill = 0, check = 0;
  for (const TransmissionZero& z : r.zeros) {
    hill = std::max(hill, z.truncation_change);
    check = std::max(check, z.check_error_estimate.value_or(kInf));
  }
  if (r.zeros.empty() || !(check < hill)) return;
  r.route = *r.check_route;
  for (TransmissionZero& z : r.zeros) {
    const double shifts = std::round((z.centred - *z.check_value).imag() / omega);
    z.centred = *z.check_value + cd(0, shifts * omega);
    z.value = InStrip(z.centred, omega);
  }
}

// Each Hill zero against its match among the check route's. The reported route's estimate
// takes the disagreement beyond the other's estimate; ok needs equal counts and agreement
// within 10 × the estimates (plus tol).
void CompareWithCheck(const CheckRun& check, double omega, double tol, TransmissionZeros& r,
                      std::string& failure) {
  std::vector<cd> hill;
  for (const TransmissionZero& z : r.zeros) hill.push_back(z.centred);
  const std::vector<int> match = MatchExponentIndices(hill, check.zeros, omega);
  double worst = 0;
  int disagreeing = 0;
  for (size_t i = 0; i < hill.size(); ++i) {
    if (match[i] < 0) continue;
    TransmissionZero& z = r.zeros[i];
    z.check_value = check.zeros[match[i]];
    z.check_error_estimate = check.estimates[match[i]];
    const double d = ExponentDistance(z.centred, *z.check_value, omega);
    worst = std::max(worst, d);
    const double allowed = 10 * (z.truncation_change + *z.check_error_estimate) +
                           tol * std::max(std::abs(z.centred), omega);
    disagreeing += !(d <= allowed);
  }
  ReportCheckValues(omega, r);
  const bool hill_reported = r.route == ZeroRoute::kHill;
  for (size_t i = 0; i < hill.size(); ++i) {
    TransmissionZero& z = r.zeros[i];
    if (!z.check_value) continue;
    const double d = ExponentDistance(hill[i], *z.check_value, omega);
    const double own = hill_reported ? z.truncation_change : *z.check_error_estimate;
    const double other = hill_reported ? *z.check_error_estimate : z.truncation_change;
    z.error_estimate = std::max(own, d - other);
  }
  std::ostringstream s;
  s << "zeros: the " << ToString(*check.route) << " route found " << check.zeros.size()
    << ", the Hill route " << hill.size() << "; largest disagreement " << MessageNumber(worst, 2)
    << "; the values are the " << ToString(r.route) << " route's (the smaller estimates)";
  r.diagnostics.push_back({DiagnosticCode::kRoutesCompared, Severity::kNote, s.str()});
  if (check.zeros.size() != hill.size())
    failure = "zeros: the Hill route found " + std::to_string(hill.size()) + " zeros, the " +
              std::string(ToString(*check.route)) + " route " + std::to_string(check.zeros.size());
  else if (disagreeing > 0)
    failure = "zeros: " + std::to_string(disagreeing) + " zeros of the Hill and " +
              std::string(ToString(*check.route)) + " routes disagree beyond their estimates";
}

// The check route, where it applies, compared with the Hill route's zeros.
void Check(const PeriodicSystem& system, const SystemFourier& f, const ZerosOptions& o,
           TransmissionZeros& r, std::string& failure) {
  const CheckRun check = RunCheck(system, f, o);
  r.diagnostics.insert(r.diagnostics.end(), check.notes.begin(), check.notes.end());
  r.check_route = check.route;
  r.check_zeros = check.zeros;
  if (check.route && !check.ok) failure = check.failure;
  if (check.route && check.ok) CompareWithCheck(check, system.omega(), o.tol, r, failure);
}

// By |Im centred| (positive first), then Re descending, as Floquet modes are listed.
void SortZeros(std::vector<TransmissionZero>& zeros) {
  std::stable_sort(zeros.begin(), zeros.end(),
                   [](const TransmissionZero& a, const TransmissionZero& b) {
                     const double fa = std::abs(a.centred.imag()), fb = std::abs(b.centred.imag());
                     if (std::abs(fa - fb) > 1e-12 * std::max(1.0, fa)) return fa < fb;
                     if ((a.centred.imag() > 0) != (b.centred.imag() > 0))
                       return a.centred.imag() > 0;
                     return a.centred.real() > b.centred.real();
                   });
}

}  // namespace

TransmissionZeros HarmonicTransferFunction::Zeros(const ZerosOptions& options) const {
  options.Validate();
  if (system_.inputs() != system_.outputs())
    throw InputError("zeros need a square system (as many inputs as outputs); this one has " +
                     std::to_string(system_.inputs()) + " inputs and " +
                     std::to_string(system_.outputs()) + " outputs");
  const auto start = std::chrono::steady_clock::now();
  const double omega = system_.omega();
  TransmissionZeros r;
  const HillOutcome hill = ConvergeHill(coefficients(), omega, hill_.harmonics(), options);
  std::string failure = hill.failure;
  // The kind of the failure, by the step that set it: the Hill route, its check, convergence.
  DiagnosticCode failure_code = DiagnosticCode::kHillSolverFailed;
  if (failure.empty()) ReportHill(hill, omega, r);
  if (failure.empty() && options.check) {
    failure_code = DiagnosticCode::kRoutesDisagree;
    Check(system_, coefficients(), options, r, failure);
  }
  if (failure.empty()) failure_code = DiagnosticCode::kTruncationNotConverged;
  if (failure.empty() && !hill.converged) {
    const std::string unconverged =
        "the Hill route's truncation did not converge to tol (largest change " +
        MessageNumber(LargestChange(hill), 2) + ")";
    // Confirmed within its estimate by the check route, whose values are then reported.
    if (r.route != ZeroRoute::kHill)
      r.diagnostics.push_back({DiagnosticCode::kTruncationNotConverged, Severity::kWarning,
                               "zeros: " + unconverged + "; it agrees with the check route"});
    else
      failure = "zeros: " + unconverged;
  }
  SortZeros(r.zeros);
  r.ok = failure.empty();
  r.failure = failure;
  if (!r.ok) r.diagnostics.push_back({failure_code, Severity::kFailure, failure});
  r.elapsed_s = SecondsSince(start);
  return r;
}

}  // namespace ltp
