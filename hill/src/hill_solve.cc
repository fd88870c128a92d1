// Eigenpairs of the Hill matrix: dense (all of them) and structured (the few near the
// expected exponents, by banded shift-invert Arnoldi, cost linear in N).
#include <complex>
// LAPACKE with std::complex<double> arguments (same layout as Fortran COMPLEX*16).
#define lapack_complex_float std::complex<float>
#define lapack_complex_double std::complex<double>
#include <lapacke.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hill_internal.h"
#include "ltp/core/error.h"

namespace ltp::hill_internal {
namespace {

// Converged when ||H x − μ x|| <= kTol ||H|| ||x||; pairs up to kLooseTol are kept with a note.
constexpr double kTol = 1e-12;
constexpr double kLooseTol = 1e-8;
constexpr int kMaxRestarts = 4;

double RelativeResidual(const FourierMatrix& A, double omega, int N, double norm_h, cd mu,
                        const Eigen::VectorXcd& x) {
  return (HillMultiply(A, omega, N, x) - mu * x).norm() / (norm_h * x.norm());
}

bool IsReal(const FourierMatrix& A) { return A.HermitianDefect() <= 1e-14 * (1 + A[0].norm()); }

// Mirror pair of a real system: (μ, x) ↦ (conj μ, y_v = conj x_{−v}).
Eigen::VectorXcd Mirror(const Eigen::VectorXcd& x, int n, int N) {
  Eigen::VectorXcd y(x.size());
  for (int v = -N; v <= N; ++v) y.segment((v + N) * n, n) = x.segment((-v + N) * n, n).conjugate();
  return y;
}

// x shifted by k blocks: y_v = x_{v+k} (zero outside the truncation).
Eigen::VectorXcd ShiftBlocks(const Eigen::VectorXcd& x, int n, int N, int k) {
  Eigen::VectorXcd y = Eigen::VectorXcd::Zero(x.size());
  for (int v = -N; v <= N; ++v)
    if (std::abs(v + k) <= N) y.segment((v + N) * n, n) = x.segment((v + k + N) * n, n);
  return y;
}

double Centroid(const Eigen::VectorXcd& x, int n, int N) {
  const std::vector<double> e = BlockEnergies(x, n, N);
  double c = 0;
  for (int v = -N; v <= N; ++v) c += v * e[v + N];
  return c;
}

// Collects converged pairs without duplicates (same value and parallel vectors).
class Pool {
 public:
  explicit Pool(double scale) : scale_(scale) {}
  void Add(cd mu, Eigen::VectorXcd x, double residual) {
    x.normalize();
    for (size_t i = 0; i < values.size(); ++i)
      if (std::abs(values[i] - mu) <= 1e-8 * scale_ && std::abs(vectors[i].dot(x)) > 0.99) {
        if (residual < residuals[i]) {
          values[i] = mu;
          vectors[i] = std::move(x);
          residuals[i] = residual;
        }
        return;
      }
    values.push_back(mu);
    vectors.push_back(std::move(x));
    residuals.push_back(residual);
  }
  std::vector<cd> values;
  std::vector<Eigen::VectorXcd> vectors;
  std::vector<double> residuals;

 private:
  double scale_;
};

// Shift-invert Arnoldi with the factored operator: Ritz pairs (μ = σ + 1/θ, x), nearest first.
void Arnoldi(const BandedShiftInvert& op, cd shift, const Eigen::VectorXcd& start, int m,
             std::vector<cd>& mu, std::vector<Eigen::VectorXcd>& x) {
  const int dim = op.size();
  m = std::min(m, dim);
  Eigen::MatrixXcd V(dim, m + 1);
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(m + 1, m);
  V.col(0) = start.normalized();
  int steps = m;
  for (int j = 0; j < m; ++j) {
    Eigen::VectorXcd w = V.col(j);
    op.Solve(w);
    for (int pass = 0; pass < 2; ++pass) {  // classical Gram–Schmidt, twice (stable enough)
      const Eigen::VectorXcd c = V.leftCols(j + 1).adjoint() * w;
      w.noalias() -= V.leftCols(j + 1) * c;
      h.col(j).head(j + 1) += c;
    }
    const double beta = w.norm();
    h(j + 1, j) = beta;
    if (beta <= 1e-14 * h.col(j).norm()) {  // invariant subspace found
      steps = j + 1;
      break;
    }
    if (j + 1 <= m) V.col(j + 1) = w / beta;
  }
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(h.topLeftCorner(steps, steps));
  std::vector<int> order(steps);
  for (int i = 0; i < steps; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(es.eigenvalues()(a)) > std::abs(es.eigenvalues()(b));
  });
  mu.clear();
  x.clear();
  for (int i : order) {
    const cd theta = es.eigenvalues()(i);
    if (std::abs(theta) == 0) continue;
    mu.push_back(shift + 1.0 / theta);
    x.push_back(V.leftCols(steps) * es.eigenvectors().col(i));
  }
}

// Factors H − σI, nudging σ off an exact eigenvalue.
void FactorNear(BandedShiftInvert& op, cd shift, double scale) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    if (op.Factor(shift)) return;
    shift += cd(1, 1) * (1e-10 * scale * (attempt + 1));
  }
}

// What the structured solver's stages share: the problem, the banded shift-invert operator
// and the pool of converged pairs.
struct StructuredSearch {
  StructuredSearch(const FourierMatrix& a, double omega_p, int harmonics)
      : A(a),
        omega(omega_p),
        n(a.rows()),
        N(harmonics),
        scale(HillNormEstimate(a, omega_p, harmonics)),
        real(IsReal(a)),
        op(a, omega_p, harmonics),
        pool(scale) {}

  // A converged pair, and its mirror pair for a real system.
  void Add(cd mu, const Eigen::VectorXcd& x, double res) {
    pool.Add(mu, x, res);
    if (real && std::abs(mu.imag()) > 1e-12 * scale) pool.Add(std::conj(mu), Mirror(x, n, N), res);
  }

  const FourierMatrix& A;
  const double omega;
  const int n, N;
  const double scale;
  const bool real;
  BandedShiftInvert op;
  Pool pool;
};

struct Cluster {
  cd center;
  int count;
};

// Shifts closer than Ωp/4 share one factorisation; a real system's spectrum is symmetric
// under (μ, x) ↦ (conj μ, mirrored conj x), so only Im σ >= 0 is searched there.
std::vector<Cluster> ClusterShifts(const std::vector<cd>& shifts, bool real, double omega) {
  std::vector<Cluster> clusters;
  for (cd s : shifts) {
    if (real && s.imag() < 0) s = std::conj(s);
    bool merged = false;
    for (Cluster& c : clusters)
      if (std::abs(c.center - s) <= 0.25 * omega) {
        c.center = (c.center * double(c.count) + s) / double(c.count + 1);
        ++c.count;
        merged = true;
        break;
      }
    if (!merged) clusters.push_back({s, 1});
  }
  return clusters;
}

// Deterministic start on the central block: the wanted eigenvectors are centred there.
Eigen::VectorXcd CentralStart(int n, int N, int dim) {
  Eigen::VectorXcd start0 = Eigen::VectorXcd::Zero(dim);
  for (int i = 0; i < n; ++i) start0(N * n + i) = cd(1.0 + 0.1 * i, 0.3 - 0.05 * i);
  if (N > 0)
    for (int i = 0; i < n; ++i) {
      start0((N - 1) * n + i) = 0.1;
      start0((N + 1) * n + i) = 0.1;
    }
  return start0;
}

// Arnoldi around one cluster's centre, restarted from the unconverged Ritz vectors; the
// converged pairs go to the pool. Returns how many of the wanted pairs did not converge.
int SearchCluster(StructuredSearch& s, const Cluster& c, const Eigen::VectorXcd& start0,
                  std::vector<cd>& mu, std::vector<Eigen::VectorXcd>& x) {
  const int dim = s.op.size();
  const int want = std::min(dim, 2 * c.count + 2);
  const int m = std::min(dim, 3 * want + 20);
  FactorNear(s.op, c.center, s.scale);
  Eigen::VectorXcd start = start0;
  int missing = 0;
  for (int restart = 0; restart <= kMaxRestarts; ++restart) {
    Arnoldi(s.op, c.center, start, m, mu, x);
    Eigen::VectorXcd next = Eigen::VectorXcd::Zero(dim);
    missing = 0;
    for (int i = 0; i < std::min<int>(want, static_cast<int>(mu.size())); ++i) {
      const double res = RelativeResidual(s.A, s.omega, s.N, s.scale, mu[i], x[i]);
      if (res <= kTol || (restart == kMaxRestarts && res <= kLooseTol)) {
        s.Add(mu[i], x[i], res);
      } else {
        next += x[i].normalized();
        ++missing;
      }
    }
    if (missing == 0) break;
    start = next;
  }
  return missing;
}

// The block shifts k that move a pair of centroid c onto block 0: round(c), and for a centroid
// near a half-integer also its tie partner on the other side.
std::vector<int> RecentringShifts(double c) {
  std::vector<int> ks;
  if (std::lround(c) != 0) ks.push_back(static_cast<int>(std::lround(c)));
  if (0.5 - std::abs(std::remainder(c, 1.0)) < 0.1) {
    const int other = c > std::lround(c) ? static_cast<int>(std::lround(c)) + 1
                                         : static_cast<int>(std::lround(c)) - 1;
    if (other != 0 || ks.empty()) ks.push_back(other);
  }
  return ks;
}

// Re-centre every pair on block 0 (and add the tie partner of pairs near a half-integer
// centroid), refined by inverse iteration: the shift may have found a shifted copy λ + jmΩp.
void RecentrePairs(StructuredSearch& s) {
  const FourierMatrix& A = s.A;
  const double omega = s.omega, scale = s.scale;
  const int n = s.n, N = s.N;
  const size_t found = s.pool.values.size();
  for (size_t i = 0; i < found; ++i) {
    for (int k : RecentringShifts(Centroid(s.pool.vectors[i], n, N))) {
      // y_v = x_{v+k} is an eigenvector for μ + jkΩp, with centroid c − k.
      cd m2 = s.pool.values[i] + cd(0, k * omega);
      Eigen::VectorXcd y = ShiftBlocks(s.pool.vectors[i], n, N, k);
      if (y.norm() == 0) continue;
      FactorNear(s.op, m2 + cd(1, 1) * (1e-9 * scale), scale);
      for (int it = 0; it < 3; ++it) {
        s.op.Solve(y);
        y.normalize();
        m2 = y.dot(HillMultiply(A, omega, N, y));  // Rayleigh quotient (y normalised)
      }
      const double res = RelativeResidual(A, omega, N, scale, m2, y);
      if (res <= kLooseTol) s.Add(m2, y, res);
    }
  }
}

}  // namespace

std::vector<double> BlockEnergies(const Eigen::VectorXcd& x, int n, int harmonics) {
  std::vector<double> e(2 * harmonics + 1);
  double total = 0;
  for (int b = 0; b < 2 * harmonics + 1; ++b) total += e[b] = x.segment(b * n, n).squaredNorm();
  if (total > 0)
    for (double& v : e) v /= total;
  return e;
}

Eigenpairs SolveDense(const FourierMatrix& A, double omega, int harmonics) {
  Eigen::MatrixXcd H = HillMatrix(A, omega, harmonics);
  const int dim = static_cast<int>(H.rows());
  Eigenpairs out;
  std::vector<cd> w(dim);
  out.vectors.resize(dim, dim);
  const lapack_int info = LAPACKE_zgeev(LAPACK_COL_MAJOR, 'N', 'V', dim, H.data(), dim, w.data(),
                                        nullptr, 1, out.vectors.data(), dim);
  if (info != 0) {
    out.notes.push_back({DiagnosticCode::kHillSolverFailed, Severity::kFailure,
                         "LAPACK zgeev failed (info = " + std::to_string(info) + ")"});
    return out;
  }
  out.values = std::move(w);
  out.ok = true;
  return out;
}

Eigenpairs SolveStructured(const FourierMatrix& A, double omega, int harmonics,
                           const std::vector<cd>& shifts) {
  StructuredSearch search(A, omega, harmonics);
  const int dim = search.op.size();
  Eigenpairs out;

  const Eigen::VectorXcd start0 = CentralStart(search.n, search.N, dim);
  int unconverged = 0;
  std::vector<cd> mu;
  std::vector<Eigen::VectorXcd> x;
  for (const Cluster& c : ClusterShifts(shifts, search.real, omega))
    unconverged += SearchCluster(search, c, start0, mu, x);
  if (unconverged > 0) {
    std::ostringstream s;
    s << "structured solver: " << unconverged
      << " of the Ritz pairs asked for around the shifts did not converge and were left out "
         "(exponents are chosen among converged pairs only; too few of them fall back to the "
         "dense solver or fail)";
    out.notes.push_back({DiagnosticCode::kRitzPairsUnconverged, Severity::kWarning, s.str()});
  }
  RecentrePairs(search);

  const Pool& pool = search.pool;
  out.values = pool.values;
  out.residual = pool.residuals;
  out.vectors.resize(dim, static_cast<Eigen::Index>(pool.vectors.size()));
  for (size_t i = 0; i < pool.vectors.size(); ++i) out.vectors.col(i) = pool.vectors[i];
  out.ok = true;
  return out;
}

}  // namespace ltp::hill_internal
