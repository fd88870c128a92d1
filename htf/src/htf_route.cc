// Route 2: the truncated harmonic transfer function (Wereley). For u = U e^{st} (s = jω on the
// frequency axis) and x = Σ_u X_u e^{(s+juΩp)t}, harmonic balance gives for v = −N..N
//   (s + jvΩp) X_v − Σ_u A_{v−u} X_u = B_v U,
// i.e. (sI + 𝒩 − 𝒜) X = ℬ with block bandwidth H_A (the harmonics of A). The matrix is
// solved as banded (LAPACK zgbtrf/zgbtrs, scalar bandwidth (H_A+1)n − 1): never densely.
// Then Y_z = Σ_u C_{z−u} X_u + D_z U.
#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "ltp/core/error.h"
#include "ltp/htf/pfrf.h"
#include "ltp/integrate/threads.h"
#include "shifted_hessenberg.h"

namespace ltp {

namespace {
using cd = std::complex<double>;

int MaxHarmonic(const FourierMatrix& f) { return f.rows() > 0 ? f.max_harmonic() : 0; }

cd Entry(const FourierMatrix& f, int w, int i, int j) {
  if (f.rows() == 0 || std::abs(w) > f.max_harmonic()) return 0;
  return f[w](i, j);
}
}  // namespace

void HtfOptions::Validate() const {
  const OptionCheck check("HtfOptions");
  if (harmonics < 0) check.Fail("harmonics", harmonics, ">= 0 (0 = automatic)");
  if (delta < 0) check.Fail("delta", delta, ">= 0 (0 = automatic)");
  if (!(tol > 0) || !std::isfinite(tol)) check.Fail("tol", tol, "finite and > 0");
  if (max_harmonics < 1) check.Fail("max_harmonics", max_harmonics, ">= 1");
  if (max_dense_size < 0)
    check.Fail("max_dense_size", max_dense_size, ">= 0 (0 = never reduce densely)");
}

HtfSolver::HtfSolver(const PeriodicSystem& system, const HtfOptions& options)
    : n_(system.states()),
      m_(system.inputs()),
      p_(system.outputs()),
      omega_p_(system.omega()),
      options_(options) {
  options.Validate();
  if (m_ < 1 || p_ < 1)
    throw InputError("partial FRFs need at least one input and one output; the system has " +
                     std::to_string(m_) + " inputs and " + std::to_string(p_) + " outputs");
  fourier_ = ToFourier(system, options.fourier);
  ha_ = MaxHarmonic(fourier_.A.series);
  fourier_tail_ = std::max({fourier_.A.tail, fourier_.B.tail, fourier_.C.tail, fourier_.D.tail});
  if (!fourier_.A.converged || !fourier_.B.converged || !fourier_.C.converged ||
      !fourier_.D.converged) {
    std::ostringstream s;
    s << "htf: Fourier fit of the coefficients not converged (tail " << fourier_tail_ << ", decay "
      << ToString(fourier_.A.decay) << "): the truncated HTF carries that error";
    diagnostics_.push_back({DiagnosticCode::kFourierFitNotConverged, Severity::kWarning, s.str()});
  }
  harmonics_ = options.harmonics > 0 ? options.harmonics : 8;
}

int HtfSolver::delta() const {
  return options_.delta > 0 ? options_.delta : std::max(2, harmonics_ / 4);
}

namespace {

// The banded Hill matrix at truncation N must fit before a sweep starts: sweeps allocate one per
// thread inside their parallel loops, where an allocation failure cannot be reported (it
// aborted the process: htf_harmonics = 10^7). 2 GiB, the Hill route's limit too.
constexpr double kMaxBandBytes = 2.0 * 1024 * 1024 * 1024;

double BandBytes(int n, int N, int ha) {
  const double size = (2.0 * N + 1) * n;
  const double kl = std::min((std::min<double>(ha, N) + 1) * n - 1, size - 1);
  return (3 * kl + 1) * size * sizeof(cd);
}

void CheckBandMemory(int n, int N, int ha) {
  const double bytes = BandBytes(n, N, ha);
  if (bytes > kMaxBandBytes) {
    std::ostringstream s;
    s << "htf: truncation N = " << N << " of a system with " << n
      << " states needs a band matrix of " << bytes / (1024.0 * 1024 * 1024)
      << " GiB per frequency solved at once, more than the limit of 2 GiB: lower the truncation "
         "(htf harmonics)";
    throw ResourceError(s.str());
  }
}

}  // namespace

int HtfSolver::ChooseTruncation(int min_order, int max_order,
                                const std::vector<double>& probe_omegas) {
  const int Z = std::max(std::abs(min_order), std::abs(max_order));
  if (options_.harmonics > 0) {
    harmonics_ = std::max(options_.harmonics, Z);
    CheckBandMemory(n_, harmonics_, ha_);
    return harmonics_;
  }
  // A couples neighbours H_A harmonics apart, so X_{±Z} needs about H_A more on each side.
  int N = std::max({2 * Z, Z + std::min(ha_, 8), 8});
  N = std::min(N, std::max(options_.max_harmonics, Z));
  truncation_converged_ = true;
  for (bool first = true;; first = false) {
    if (!first && BandBytes(n_, N + std::max(2, N / 4), ha_) > kMaxBandBytes) {
      std::ostringstream s;
      s << "htf: truncation stopped at N = " << harmonics_
        << ": the next would not fit in memory (more than 2 GiB of band matrix)";
      diagnostics_.push_back({DiagnosticCode::kTruncationLimited, Severity::kWarning, s.str()});
      truncation_converged_ = false;
      break;
    }
    harmonics_ = N;
    CheckBandMemory(n_, N + delta(), ha_);
    const int probes = static_cast<int>(probe_omegas.size());
    std::vector<double> changes(probes, 0.0), scales(probes, 0.0);
#pragma omp parallel for schedule(dynamic) num_threads(ThreadsFor(0))  // independent solves
    for (int q = 0; q < probes; ++q) {
      const PartialFrfs a = Evaluate(probe_omegas[q], min_order, max_order, N);
      const PartialFrfs b = Evaluate(probe_omegas[q], min_order, max_order, N + delta());
      for (size_t z = 0; z < a.size(); ++z) {
        const double d = (a[z] - b[z]).cwiseAbs().maxCoeff();
        changes[q] = std::max(changes[q], std::isfinite(d) ? d : 0.0);
        scales[q] = std::max(scales[q], b[z].cwiseAbs().maxCoeff());
      }
    }
    const double change = probes ? *std::max_element(changes.begin(), changes.end()) : 0.0;
    const double scale = probes ? *std::max_element(scales.begin(), scales.end()) : 0.0;
    if (change <= options_.tol * scale) break;
    if (N >= options_.max_harmonics) {
      std::ostringstream s;
      s << "htf: truncation N = " << N << " (max_harmonics) still changes H_z by " << change / scale
        << " (relative) against N + " << delta();
      diagnostics_.push_back(
          {DiagnosticCode::kTruncationNotConverged, Severity::kWarning, s.str()});
      truncation_converged_ = false;
      break;
    }
    N = std::min(options_.max_harmonics, N + std::max(2, N / 2));
  }
  return harmonics_;
}

namespace {

// Visits the entries of 𝒩 − 𝒜 at truncation N (𝒩 = diag(jvΩp), the ω term excluded):
// add(row, column, value). Harmonics of A beyond N are dropped with the truncation (they would
// only couple X_u and X_v with |v − u| > N; for algebraically decaying A this keeps the band at
// ~2N + 1 blocks).
// Scalar half-bandwidth of the Hill matrix at truncation N: A couples blocks up to
// min(H_A, N) apart.
int HillBandwidth(int n, int N, int ha) {
  return std::min((std::min(ha, N) + 1) * n - 1, (2 * N + 1) * n - 1);
}

template <class Add>
void VisitHillOperator(const FourierMatrix& A, int n, int N, int ha, double omega_p, Add add) {
  for (int v = -N; v <= N; ++v)
    for (int u = std::max(-N, v - ha); u <= std::min(N, v + ha); ++u) {
      const Eigen::MatrixXcd& a = A[v - u];
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) add((v + N) * n + i, (u + N) * n + j, -a(i, j));
    }
  for (int v = -N; v <= N; ++v)
    for (int i = 0; i < n; ++i) add((v + N) * n + i, (v + N) * n + i, cd(0, v * omega_p));
}

}  // namespace

// Right-hand side ℬ: block v holds B_v.
Eigen::MatrixXcd HtfSolver::HillRhs(int N) const {
  const FourierMatrix& B = fourier_.B.series;
  Eigen::MatrixXcd rhs = Eigen::MatrixXcd::Zero((2 * N + 1) * n_, m_);
  for (int v = -N; v <= N; ++v)
    for (int j = 0; j < m_; ++j)
      for (int i = 0; i < n_; ++i) rhs((v + N) * n_ + i, j) = Entry(B, v, i, j);
  return rhs;
}

bool HtfSolver::PaysToReduce(int frequencies, int N) const {
  const double s = (2 * N + 1) * n_, kl = HillBandwidth(n_, N, ha_);
  // Banded LU ≈ 2·size·kl² complex operations per frequency at BLAS-3 speed; the reduction
  // ≈ 10/3·size³ at about half that speed, then ~4·size² per frequency (measured on
  // tower-rotor, docs/speed-notes.md).
  const double banded = frequencies * 2 * s * kl * kl;
  const double reduced = 2 * (10.0 / 3) * s * s * s + frequencies * 4 * s * s;
  return s <= options_.max_dense_size && reduced < banded;
}

std::shared_ptr<const internal::ShiftedHessenbergSolver> HtfSolver::Reduce(int N) const {
  const int size = (2 * N + 1) * n_, ha = std::min(ha_, N);
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(size, size);
  VisitHillOperator(fourier_.A.series, n_, N, ha, omega_p_,
                    [&](int i, int j, cd value) { h(i, j) += value; });
  // Output rows of every order whose Y_z the truncated X reaches: z = −N − H_C … N + H_C.
  const FourierMatrix& C = fourier_.C.series;
  const int hc = MaxHarmonic(C), zr = N + hc;
  Eigen::MatrixXcd g = Eigen::MatrixXcd::Zero((2 * zr + 1) * p_, size);
  for (int z = -zr; z <= zr; ++z)
    for (int u = std::max(-N, z - hc); u <= std::min(N, z + hc); ++u)
      g.block((z + zr) * p_, (u + N) * n_, p_, n_) = C[z - u];
  auto solver =
      std::make_shared<const internal::ShiftedHessenbergSolver>(std::move(h), HillRhs(N), g);
  return solver->ok() ? solver : nullptr;
}

bool HtfSolver::PrepareSweep(int frequencies, const std::vector<int>& truncations) {
  std::vector<int> todo;
  bool all = true;
  for (int N : truncations.empty() ? std::vector<int>{harmonics_} : truncations) {
    if (reduced_.count(N)) continue;
    if (PaysToReduce(frequencies, N))
      todo.push_back(N);
    else
      all = false;
  }
  // Each reduction on its own core (OpenBLAS runs single-threaded under ltp's threads).
  std::vector<std::shared_ptr<const internal::ShiftedHessenbergSolver>> built(todo.size());
  const int jobs = static_cast<int>(todo.size());
#pragma omp parallel for num_threads(std::max(1, std::min(jobs, ThreadsFor(0))))
  for (int q = 0; q < jobs; ++q) built[q] = Reduce(todo[q]);
  for (size_t q = 0; q < todo.size(); ++q) {
    if (built[q])
      reduced_[todo[q]] = std::move(built[q]);
    else
      all = false;
  }
  return all;
}

PartialFrfs HtfSolver::Evaluate(double omega, int min_order, int max_order, int harmonics) const {
  return EvaluateAt(cd(0, omega), min_order, max_order, harmonics);
}

PartialFrfs HtfSolver::EvaluateAt(cd s, int min_order, int max_order, int harmonics) const {
  const int N = harmonics > 0 ? harmonics : harmonics_;
  const auto reduced = reduced_.find(N);
  if (reduced == reduced_.end()) return EvaluateBanded(s, min_order, max_order, N);
  PartialFrfs h(max_order - min_order + 1, Eigen::MatrixXcd::Zero(p_, m_));
  // Only the orders asked for that the truncated X reaches (|z| <= N + H_C).
  const int zr = N + MaxHarmonic(fourier_.C.series);
  const int z0 = std::max(min_order, -zr), z1 = std::min(max_order, zr);
  Eigen::MatrixXcd y;
  if (z0 <= z1 && !reduced->second->Solve(s, (z0 + zr) * p_, (z1 - z0 + 1) * p_, y)) {
    for (auto& x : h) x.setConstant(cd(std::numeric_limits<double>::quiet_NaN(), 0));
    return h;
  }
  const FourierMatrix& D = fourier_.D.series;
  for (int z = min_order; z <= max_order; ++z) {
    Eigen::MatrixXcd& out = h[z - min_order];
    if (z >= z0 && z <= z1) out = y.middleRows((z - z0) * p_, p_);
    if (D.rows() > 0 && std::abs(z) <= D.max_harmonic()) out += D[z];
  }
  return h;
}

PartialFrfs HtfSolver::EvaluateBanded(cd s, int min_order, int max_order, int N) const {
  const int n = n_;
  const int size = (2 * N + 1) * n;
  const int ha = std::min(ha_, N);
  const int kl = HillBandwidth(n, N, ha_), ku = kl;
  const int ldab = 2 * kl + ku + 1;
  std::vector<cd> ab(static_cast<size_t>(ldab) * size, cd(0));
  VisitHillOperator(fourier_.A.series, n, N, ha, omega_p_, [&](int i, int j, cd value) {
    ab[static_cast<size_t>(kl + ku + i - j) + static_cast<size_t>(j) * ldab] += value;
  });
  for (int i = 0; i < size; ++i)
    ab[static_cast<size_t>(kl + ku) + static_cast<size_t>(i) * ldab] += s;
  Eigen::MatrixXcd rhs = HillRhs(N);
  std::vector<lapack_int> ipiv(size);
  // The _work drivers: the plain ones first scan the whole band for NaN (5 % of a tower-rotor
  // sweep); the entries here are finite by construction (a validated system, finite s).
  lapack_int info =
      LAPACKE_zgbtrf_work(LAPACK_COL_MAJOR, size, size, kl, ku,
                          reinterpret_cast<lapack_complex_double*>(ab.data()), ldab, ipiv.data());
  PartialFrfs h(max_order - min_order + 1, Eigen::MatrixXcd::Zero(p_, m_));
  if (info != 0) {
    for (auto& x : h) x.setConstant(cd(std::numeric_limits<double>::quiet_NaN(), 0));
    return h;
  }
  LAPACKE_zgbtrs_work(LAPACK_COL_MAJOR, 'N', size, kl, ku, m_,
                      reinterpret_cast<const lapack_complex_double*>(ab.data()), ldab, ipiv.data(),
                      reinterpret_cast<lapack_complex_double*>(rhs.data()), size);
  const Eigen::MatrixXcd& X = rhs;
  const FourierMatrix& C = fourier_.C.series;
  const FourierMatrix& D = fourier_.D.series;
  const int hc = MaxHarmonic(C);
  for (int z = min_order; z <= max_order; ++z) {
    Eigen::MatrixXcd& y = h[z - min_order];
    for (int u = std::max(-N, z - hc); u <= std::min(N, z + hc); ++u)
      y.noalias() += C[z - u] * X.middleRows((u + N) * n, n);
    if (D.rows() > 0 && std::abs(z) <= D.max_harmonic()) y += D[z];
  }
  return h;
}

}  // namespace ltp
