// Eigenvalues and periodic eigenvectors of a cyclic matrix product Φ_K ⋯ Φ_1.
//
// Eigenvalues and the periodic Schur form: SLICOT chain MB03VD → (MB03VY) → MB03BD, one call
// path (RunPeriodicQz) for the eigenvalues alone and for the Schur form with its vectors.
//   MB03VD reduces the product A_1 A_2 ⋯ A_K to periodic Hessenberg-triangular form
//   (A_1 Hessenberg, the others upper triangular) by orthogonal transformations
//   Q_j' A_j Q_{j+1}, Q_{K+1} = Q_1, which leave the eigenvalues of the product unchanged.
//   MB03BD (periodic QZ, JOB='E' or 'S', signatures S = +1, Hessenberg index H = 1) returns each
//   eigenvalue as (ALPHAR + j ALPHAI)/BETA · BASE^SCAL with ALPHA of order one, so log ρ is
//   formed from the pieces and never from ρ itself (which may lie far outside double range).
//   SLICOT's product is ordered A_1 A_2 ⋯ A_K (A_1 leftmost), so A_j = Φ_{K+1-j}.
//
// Eigenvectors: from the periodic Schur form (periodic_schur_vectors.cc) for isolated
// multipliers, else null vectors of the block-cyclic "lifted" matrix by sparse inverse
// iteration (see ComputePeriodicEigenvectors below); docs/periodic-eigenvectors.md.
#include "ltp/floquet/periodic_eigen.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "ltp/core/error.h"
#include "ltp/integrate/detail/matrix_product.h"
#include "periodic_schur_testing.h"
#include "periodic_schur_vectors.h"
#include "slicot.h"

namespace ltp {
namespace {

using Complex = std::complex<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// arg in (−π, π]: a negative real eigenvalue reports +π whatever the sign of its zero
/// imaginary part.
double PrincipalArg(double re, double im) {
  if (im == 0) im = 0.0;  // drops a negative zero
  const double arg = std::atan2(im, re);
  return arg <= -std::numbers::pi ? std::numbers::pi : arg;
}

/// Descending log|ρ|. The two members of a conjugate pair may differ in the last bit of
/// log|ρ| (SLICOT scales each separately); they are made exact conjugates and listed with the
/// positive arg first, so the order is reproducible.
void SortDescending(std::vector<Complex>& values) {
  std::sort(values.begin(), values.end(), [](const Complex& a, const Complex& b) {
    if (a.real() != b.real()) return a.real() > b.real();
    return a.imag() > b.imag();
  });
  constexpr double kPairTol = 16 * std::numeric_limits<double>::epsilon();
  for (std::size_t i = 0; i + 1 < values.size(); ++i) {
    const Complex a = values[i], b = values[i + 1];
    if (!std::isfinite(a.real()) || a.imag() == 0 || b.imag() == 0) continue;
    const bool conjugate =
        std::abs(a.real() - b.real()) <= kPairTol * std::max(1.0, std::abs(a.real())) &&
        std::abs(a.imag() + b.imag()) <= kPairTol * std::max(1.0, std::abs(a.imag()));
    if (!conjugate) continue;
    const double re = 0.5 * (a.real() + b.real());
    const double im = 0.5 * (std::abs(a.imag()) + std::abs(b.imag()));
    values[i] = Complex(re, im);
    values[i + 1] = Complex(re, -im);
    ++i;
  }
}

/// Empty when all factors are square, of one size and finite; otherwise what is wrong.
std::string CheckFactors(const std::vector<Eigen::MatrixXd>& factors) {
  if (factors.empty()) return "no factors given";
  const Eigen::Index n = factors[0].rows();
  for (std::size_t i = 0; i < factors.size(); ++i) {
    const Eigen::MatrixXd& f = factors[i];
    if (f.rows() != n || f.cols() != n) {
      return "factor " + std::to_string(i) + " is " + std::to_string(f.rows()) + "x" +
             std::to_string(f.cols()) + ", expected " + std::to_string(n) + "x" + std::to_string(n);
    }
    if (!f.allFinite()) return "factor " + std::to_string(i) + " has non-finite entries";
  }
  return {};
}

}  // namespace

namespace {
std::atomic<int> injected_failures{0};  // periodic_schur_testing.h (sweeps call from threads)
}  // namespace

void internal::InjectPeriodicSchurFailures(int count) { injected_failures = count; }

namespace {

/// One periodic QZ run, in SLICOT's order: n×n×K column-major arrays with A_j = Φ_{K−j}.
struct PeriodicQz {
  std::vector<double> a;  ///< the factors: with Schur form, in periodic Schur form
  std::vector<double> q;  ///< the orthogonal Q_j (with Schur form only)
  std::vector<double> alphar, alphai, beta;
  std::vector<int> scal;
  int iwarn = 0;
  std::string failure;  ///< empty on success
};

/// MB03VD: periodic Hessenberg-triangular form of A_1 ⋯ A_K (A_1 Hessenberg), with MB03VY's
/// orthogonal factors in qz.q when `vectors`. The reflectors MB03VD leaves below the band are
/// zeroed, as MB03BD expects. False (and qz.failure) when SLICOT reports an error.
bool HessenbergTriangular(int n, int k, bool vectors, PeriodicQz& qz) {
  const int ilo = 1, ihi = n, lda = n, ldtau = std::max(1, n - 1);
  std::vector<double> tau(static_cast<std::size_t>(ldtau) * k);
  std::vector<double> dwork(static_cast<std::size_t>(std::max(1, n)) * 32);
  const int ldwork = static_cast<int>(dwork.size());
  int info = 0;
  mb03vd_(&n, &k, &ilo, &ihi, qz.a.data(), &lda, &lda, tau.data(), &ldtau, dwork.data(), &info);
  if (info != 0) {
    qz.failure = "SLICOT MB03VD failed, INFO = " + std::to_string(info);
    return false;
  }
  if (vectors) {  // from the reflectors, before they are zeroed below
    qz.q = qz.a;
    mb03vy_(&n, &k, &ilo, &ihi, qz.q.data(), &lda, &lda, tau.data(), &ldtau, dwork.data(), &ldwork,
            &info);
    if (info != 0) {
      qz.failure = "SLICOT MB03VY failed, INFO = " + std::to_string(info);
      return false;
    }
  }
  const std::ptrdiff_t block = static_cast<std::ptrdiff_t>(n) * n;
  for (int j = 0; j < k; ++j) {
    Eigen::Map<Eigen::MatrixXd> aj(qz.a.data() + j * block, n, n);
    for (int c = 0; c < n; ++c)
      for (int r = c + (j == 0 ? 2 : 1); r < n; ++r) aj(r, c) = 0.0;
  }
  return true;
}

/// The one SLICOT call path of this library: MB03VD (+ MB03VY) then MB03BD (signatures +1,
/// Hessenberg index H = 1, careful deflation), eigenvalues only (JOB = 'E') or with the periodic
/// Schur form and its vectors (JOB = 'S', COMPQ = 'U'). The factors are checked by the caller
/// (square, one size n ≥ 1, finite), so SLICOT's XERBLA (which would print) is never reached.
PeriodicQz RunPeriodicQz(const std::vector<Eigen::MatrixXd>& factors, bool schur_form) {
  const int n = static_cast<int>(factors[0].rows());
  const int k = static_cast<int>(factors.size());
  const std::ptrdiff_t block = static_cast<std::ptrdiff_t>(n) * n;
  PeriodicQz qz;
  qz.a.resize(static_cast<std::size_t>(block * k));
  for (int j = 0; j < k; ++j)  // A(:,:,j) = Φ_{K+1-j}, so that A_1 ⋯ A_K = Φ_K ⋯ Φ_1
    Eigen::Map<Eigen::MatrixXd>(qz.a.data() + j * block, n, n) = factors[k - 1 - j];
  if (!HessenbergTriangular(n, k, schur_form, qz)) return qz;

  // Workspace: the larger of the SLICOT 5.0 and 5.7 minimums (5.0 has no workspace query; a
  // too-short workspace would make it call XERBLA).
  const char job = schur_form ? 'S' : 'E', defl = 'C', compq = schur_form ? 'U' : 'N';
  const int h = 1, ilo = 1, ihi = n, lda = n, ldq = schur_form ? n : 1;
  std::vector<int> qind(k, 0), signature(k, 1), iwork(2 * k + n);
  const int liwork = static_cast<int>(iwork.size());
  const int ldwork = k + std::max(2 * n, 8 * k);
  std::vector<double> dwork(ldwork);
  double q_unused = 0.0;
  qz.alphar.resize(n);
  qz.alphai.resize(n);
  qz.beta.resize(n);
  qz.scal.resize(n);
  int info = 0;
  mb03bd_(&job, &defl, &compq, qind.data(), &k, &n, &h, &ilo, &ihi, signature.data(), qz.a.data(),
          &lda, &lda, schur_form ? qz.q.data() : &q_unused, &ldq, &ldq, qz.alphar.data(),
          qz.alphai.data(), qz.beta.data(), qz.scal.data(), iwork.data(), &liwork, dwork.data(),
          &ldwork, &qz.iwarn, &info, 1, 1, 1);
  // The test hook fails the eigenvalue route only (periodic_schur_testing.h).
  if (!schur_form && injected_failures.load(std::memory_order_relaxed) > 0 &&
      injected_failures-- > 0)
    info = n;  // as MB03BD reports an iteration that did not converge
  if (info != 0) {
    qz.failure = "SLICOT MB03BD (periodic QZ) failed, INFO = " + std::to_string(info) +
                 (info > 0 ? " (iteration did not converge)" : "");
  }
  return qz;
}

std::string IwarnMessage(int iwarn) {
  if (iwarn == 0) return {};
  return "SLICOT MB03BD warning IWARN = " + std::to_string(iwarn) +
         ": eigenvalues of the leading 2x2 blocks (up to index " + std::to_string(iwarn + 1) +
         ") may be inaccurate";
}

}  // namespace

LogEigenvalues PeriodicSchurLogEigenvalues(const std::vector<Eigen::MatrixXd>& factors) {
  LogEigenvalues result;
  if (std::string problem = CheckFactors(factors); !problem.empty()) {
    result.message = "PeriodicSchurLogEigenvalues: " + problem;
    return result;
  }
  const int n = static_cast<int>(factors[0].rows());
  if (n == 0) {
    result.ok = true;
    return result;
  }
  const PeriodicQz qz = RunPeriodicQz(factors, /*schur_form=*/false);
  if (!qz.failure.empty()) {
    result.message = qz.failure;
    return result;
  }
  // log ρ = log|ALPHA| − log|BETA| + SCAL·log(BASE) + j arg(ALPHA); BETA is 1 or 0 (0 = infinite
  // eigenvalue, impossible here since no factor is inverted, but kept for completeness).
  const double log_base = std::log(static_cast<double>(std::numeric_limits<double>::radix));
  result.log_values.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double re = qz.alphar[i], im = qz.alphai[i], beta = qz.beta[i];
    const double modulus = std::hypot(re, im);
    if (beta == 0.0) {
      result.log_values.emplace_back(kInf, PrincipalArg(re, im));
    } else if (modulus == 0.0) {
      result.log_values.emplace_back(-kInf, 0.0);
    } else {
      const double log_abs = std::log(modulus) - std::log(std::abs(beta)) + qz.scal[i] * log_base;
      result.log_values.emplace_back(log_abs, PrincipalArg(re * beta, im * beta));
    }
  }
  SortDescending(result.log_values);
  result.ok = true;
  result.message = IwarnMessage(qz.iwarn);
  return result;
}

namespace {

/// log ρ of the 2×2 block in rows p, p+1 (a complex pair; the pair with the positive arg first).
/// |ρ|² = Π_k det B_k, summed as logs; the arg from the eigenvalues of the blocks' product,
/// normalised after each factor. Two real eigenvalues (a block SLICOT could not split: IWARN)
/// come from that normalised product with its log scale.
void BlockLogValues(const std::vector<Eigen::MatrixXd>& t, int p, std::vector<Complex>& out) {
  double log_det = 0, log_scale = 0;
  Eigen::Matrix2d product = Eigen::Matrix2d::Identity();
  for (const Eigen::MatrixXd& tk : t) {
    const Eigen::Matrix2d b = tk.block<2, 2>(p, p);
    log_det += std::log(std::abs(b.determinant()));
    product = (b * product).eval();
    const double norm = product.norm();
    if (norm > 0 && std::isfinite(norm)) {
      product /= norm;
      log_scale += std::log(norm);
    }
  }
  const Eigen::Vector2cd mu = Eigen::EigenSolver<Eigen::Matrix2d>(product, false).eigenvalues();
  if (mu(0).imag() != 0) {
    const double arg = std::abs(std::arg(mu(0)));
    out.emplace_back(0.5 * log_det, arg);
    out.emplace_back(0.5 * log_det, -arg);
    return;
  }
  for (int i = 0; i < 2; ++i) {
    const double m = std::abs(mu(i).real());
    out.emplace_back(m == 0 ? -kInf : std::log(m) + log_scale, PrincipalArg(mu(i).real(), 0.0));
  }
}

/// log ρ along the diagonal of a periodic Schur form whose factor K−1 is quasi-triangular.
std::vector<Complex> DiagonalLogValues(const std::vector<Eigen::MatrixXd>& t) {
  const int n = static_cast<int>(t[0].rows());
  const Eigen::MatrixXd& quasi = t.back();
  std::vector<Complex> out;
  out.reserve(n);
  for (int p = 0; p < n; ++p) {
    if (p + 1 < n && quasi(p + 1, p) != 0.0) {
      BlockLogValues(t, p++, out);
      continue;
    }
    double log_abs = 0;
    int negatives = 0;
    for (const Eigen::MatrixXd& tk : t) {
      log_abs += std::log(std::abs(tk(p, p)));  // −inf for a zero entry
      negatives += tk(p, p) < 0;
    }
    out.emplace_back(log_abs, std::isinf(log_abs) && log_abs < 0
                                  ? 0.0
                                  : PrincipalArg(negatives % 2 ? -1.0 : 1.0, 0.0));
  }
  return out;
}

}  // namespace

PeriodicSchurForm PeriodicSchurDecomposition(const std::vector<Eigen::MatrixXd>& factors) {
  PeriodicSchurForm result;
  if (std::string problem = CheckFactors(factors); !problem.empty()) {
    result.message = "PeriodicSchurDecomposition: " + problem;
    return result;
  }
  const int n = static_cast<int>(factors[0].rows());
  const int k = static_cast<int>(factors.size());
  result.quasi_triangular = k - 1;
  if (n == 0) {
    result.t.assign(k, Eigen::MatrixXd(0, 0));
    result.z.assign(k, Eigen::MatrixXd(0, 0));
    result.ok = true;
    return result;
  }
  const PeriodicQz qz = RunPeriodicQz(factors, /*schur_form=*/true);
  if (!qz.failure.empty()) {
    result.message = qz.failure;
    return result;
  }
  // SLICOT: Q_jᵀ A_j Q_{j+1} = S_j with A_j = Φ_{K−j}, so T_i = S_{K−i}, Z_i = Q_{(K−i) mod K + 1}.
  const std::ptrdiff_t block = static_cast<std::ptrdiff_t>(n) * n;
  result.t.resize(k);
  result.z.resize(k);
  for (int i = 0; i < k; ++i) {
    result.t[i] = Eigen::Map<const Eigen::MatrixXd>(qz.a.data() + (k - 1 - i) * block, n, n);
    result.z[i] = Eigen::Map<const Eigen::MatrixXd>(qz.q.data() + ((k - i) % k) * block, n, n);
  }
  result.log_values = DiagonalLogValues(result.t);
  result.ok = true;
  result.message = IwarnMessage(qz.iwarn);
  return result;
}

LogEigenvalues LogEigenvaluesOf(const PeriodicSchurForm& form) {
  LogEigenvalues result;
  result.ok = form.ok;
  result.message = form.message;
  if (!form.ok) return result;
  result.log_values = form.log_values;
  SortDescending(result.log_values);
  return result;
}

LogEigenvalues SingleShotLogEigenvalues(const Eigen::MatrixXd& product) {
  LogEigenvalues result;
  if (product.rows() != product.cols()) {
    result.message = "SingleShotLogEigenvalues: product is " + std::to_string(product.rows()) +
                     "x" + std::to_string(product.cols()) + ", not square";
    return result;
  }
  if (!product.allFinite()) {
    result.message = "SingleShotLogEigenvalues: product has non-finite entries";
    return result;
  }
  if (product.rows() == 0) {
    result.ok = true;
    return result;
  }
  Eigen::EigenSolver<Eigen::MatrixXd> solver(product, /*computeEigenvectors=*/false);
  if (solver.info() != Eigen::Success) {
    result.message = "SingleShotLogEigenvalues: Eigen::EigenSolver did not converge";
    return result;
  }
  for (const Complex& rho : solver.eigenvalues()) {
    const double modulus = std::abs(rho);
    result.log_values.emplace_back(modulus == 0.0 ? -kInf : std::log(modulus),
                                   modulus == 0.0 ? 0.0 : PrincipalArg(rho.real(), rho.imag()));
  }
  SortDescending(result.log_values);
  result.ok = true;
  return result;
}

// ---------------------------------------------------------------------------------------------
// Periodic eigenvectors.
//
// The vectors (v_0, …, v_{K−1}) with Φ_i v_i = σ_i v_{i+1} form the null vector of the nK×nK
// block-cyclic matrix C whose block row i holds Φ_i at block column i and −σ_i I at block
// column i+1 (mod K). Each block row is divided by ||Φ_i||_F + |σ_i|, so that every row has
// unit scale whatever the magnitude of the factor or of σ_i; then inverse iteration with a
// sparse LU of C − μI converges to the null vector. No product of factors is ever formed.
// ---------------------------------------------------------------------------------------------
namespace {

using SparseMatrixC = Eigen::SparseMatrix<Complex>;
using SparseLUC = Eigen::SparseLU<SparseMatrixC, Eigen::COLAMDOrdering<int>>;

// Shift μ of the equilibrated C (whose block rows have norm ≈ 1): far below the next singular
// value of C in any well-conditioned problem, yet about 100× the LU rounding level, so that
// an exactly singular C never gives a zero pivot and all null directions of a cluster are
// amplified alike (with μ at rounding level some would win by orders of magnitude and the
// others be lost in the orthonormalisation).
constexpr double kShift = 1e-14;
// log ρ closer than this (relative to max(1, |log ρ|)) are treated as one cluster.
constexpr double kClusterTol = 1e-8;
// Each CᴴC step damps the other directions by (μ / s₂(C))², ≤ 1e-12 unless s₂ < 1e-8.
constexpr int kClusterSteps = 2;  // block inverse-iteration steps on a cluster's subspace
constexpr int kMemberSteps = 2;   // further steps with each member's own σ
// Plain steps on C − μI at the end; each damps a close neighbour (gap s₂) by μ / s₂ only.
constexpr int kPlainSteps = 2;

/// ||Φ_i||_F + |σ_i|, the scale of block row i; 1 for a zero factor with σ_i = 0 (a zero
/// multiplier of a zero factor), where any vector satisfies the relation.
double RowScale(double factor_norm, Complex sigma) {
  const double scale = factor_norm + std::abs(sigma);
  return scale > 0 ? scale : 1.0;
}

struct CyclicSystem {
  std::vector<Complex> sigma;  // σ_i
  SparseMatrixC shifted;       // equilibrated C − μI
  double shift = 0;            // μ
  SparseLUC lu;                // of `shifted`
  bool ok = false;
};

/// Builds the equilibrated C − μI for one log ρ and factors it; retries with a larger shift in
/// the (unexpected) case that the LU still meets a zero pivot.
void FactorCyclic(const std::vector<Eigen::MatrixXd>& factors, const std::vector<double>& norms,
                  const std::vector<double>& dt, double period, Complex log_rho,
                  CyclicSystem& sys) {
  const int k = static_cast<int>(factors.size());
  const Eigen::Index n = factors[0].rows();
  sys.sigma.resize(k);
  for (int i = 0; i < k; ++i) sys.sigma[i] = std::exp(log_rho * (dt[i] / period));

  for (double shift = kShift; shift < 1e-6; shift *= 100) {
    std::vector<Eigen::Triplet<Complex>> triplets;
    triplets.reserve(static_cast<std::size_t>(k) * (n * n + 2 * n));
    for (int i = 0; i < k; ++i) {
      const double row_scale = 1.0 / RowScale(norms[i], sys.sigma[i]);
      const Eigen::Index row0 = i * n;
      const Eigen::Index col_next = ((i + 1) % k) * n;
      for (Eigen::Index c = 0; c < n; ++c) {
        for (Eigen::Index r = 0; r < n; ++r) {
          if (factors[i](r, c) != 0.0) {
            triplets.emplace_back(row0 + r, row0 + c, factors[i](r, c) * row_scale);
          }
        }
        // Duplicates are summed, which also covers K = 1 (Φ_0 − σ_0 I in one block).
        triplets.emplace_back(row0 + c, col_next + c, -sys.sigma[i] * row_scale);
        triplets.emplace_back(row0 + c, row0 + c, Complex(-shift, 0.0));
      }
    }
    sys.shifted.resize(k * n, k * n);
    sys.shifted.setFromTriplets(triplets.begin(), triplets.end());
    sys.shifted.makeCompressed();
    sys.shift = shift;
    sys.lu.compute(sys.shifted);
    if (sys.lu.info() == Eigen::Success) {
      sys.ok = true;
      return;
    }
  }
  sys.ok = false;
}

/// One step of inverse iteration on (C − μI)ᴴ(C − μI) for each column — the null vectors of C
/// are its smallest singular vectors — then orthonormalisation of the columns (so a cluster
/// keeps spanning its whole subspace instead of collapsing onto one vector). Iterating with
/// the Hermitian CᴴC rather than C matters: C is far from normal, its left and right null
/// vectors can be nearly orthogonal, and plain inverse iteration on C then stalls at a
/// residual of (LU backward error)/|uᴴv|, observed up to 1e-12.
void InverseIterationStep(CyclicSystem& sys, Eigen::MatrixXcd& x) {
  Eigen::MatrixXcd w = sys.lu.adjoint().solve(x);
  x = sys.lu.solve(w);
  if (x.cols() == 1) {
    x /= x.norm();
  } else {
    Eigen::HouseholderQR<Eigen::MatrixXcd> qr(x);
    x = qr.householderQ() * Eigen::MatrixXcd::Identity(x.rows(), x.cols());
  }
}

/// ||C x|| / ||x|| of the equilibrated (unshifted) C.
double EquilibratedResidual(const CyclicSystem& sys, const Eigen::VectorXcd& x) {
  return (sys.shifted * x + sys.shift * x).norm() / x.norm();
}

/// Final refinement of a converged vector. The CᴴC iteration converges to the smallest
/// singular vector of C − μI, which differs from the null vector of C by O(μ / s₂(C)). Plain
/// inverse-iteration steps on C − μI remove that bias (the null vector is an exact
/// eigenvector of C − μI, so the shift cancels) and usually brings the residual to rounding
/// level; when left and right null vectors are nearly orthogonal it can instead stall higher,
/// so the iterate with the smallest ||C x|| is kept.
Eigen::VectorXcd Refine(const CyclicSystem& sys, const Eigen::VectorXcd& x) {
  Eigen::VectorXcd best = x, plain = x;
  double best_residual = EquilibratedResidual(sys, x);
  for (int step = 0; step < kPlainSteps; ++step) {
    plain = sys.lu.solve(plain).eval();
    plain /= plain.norm();
    if (!plain.allFinite()) break;
    const double residual = EquilibratedResidual(sys, plain);
    if (residual <= best_residual) {
      best = plain;
      best_residual = residual;
    }
  }
  return best;
}

/// Splits the stacked vector into K blocks of n and scales them to max_i ||v_i|| = 1 with the
/// largest entry of the largest block real positive (a fixed phase). The residual is left 0 to
/// be measured, or +inf when the vector is not finite or zero.
PeriodicEigenvector Normalised(const Eigen::VectorXcd& stacked, int k, Eigen::Index n) {
  PeriodicEigenvector out;
  if (!stacked.allFinite()) {
    out.v.assign(k, Eigen::VectorXcd::Zero(n));
    out.residual = kInf;
    return out;
  }
  int largest = 0;
  double largest_norm = -1;
  for (int i = 0; i < k; ++i) {
    const double norm = stacked.segment(i * n, n).norm();
    if (norm > largest_norm) {
      largest_norm = norm;
      largest = i;
    }
  }
  Eigen::Index pivot = 0;
  stacked.segment(largest * n, n).cwiseAbs().maxCoeff(&pivot);
  const Complex anchor = stacked(largest * n + pivot);
  const Complex scale =
      largest_norm > 0 ? std::conj(anchor) / (std::abs(anchor) * largest_norm) : Complex(0.0);
  out.v.reserve(k);
  for (int i = 0; i < k; ++i) out.v.push_back(stacked.segment(i * n, n) * scale);
  if (largest_norm <= 0) out.residual = kInf;
  return out;
}

/// The normalised vectors with their cyclic residuals max_i ||Φ_i v_i − σ_i v_{i+1}|| /
/// RowScale: per segment, Φ_i times every mode's v_i in one real product for each of the real
/// and imaginary parts (one matrix–vector product per mode and segment was 0.2 s of a 250-state
/// analysis). sigma[q][i] is mode q's σ_i. Each stacked
/// vector is released once split into its blocks (not held twice: 32 MB at 250 states).
std::vector<PeriodicEigenvector> FinishVectors(const std::vector<Eigen::MatrixXd>& factors,
                                               const std::vector<double>& norms,
                                               const std::vector<std::vector<Complex>>& sigma,
                                               const std::vector<Eigen::VectorXcd*>& stacked,
                                               int threads) {
  const int k = static_cast<int>(factors.size());
  const Eigen::Index n = factors[0].rows();
  const long count = static_cast<long>(stacked.size());
  std::vector<PeriodicEigenvector> out(stacked.size());
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1))
  for (long q = 0; q < count; ++q) {
    out[q] = Normalised(*stacked[q], k, n);
    *stacked[q] = Eigen::VectorXcd();
  }
  std::vector<long> finite;  // the modes whose residual is to be measured
  for (long q = 0; q < count; ++q)
    if (out[q].residual != kInf) finite.push_back(q);
  const auto m = static_cast<Eigen::Index>(finite.size());
  if (m == 0) return out;
  Eigen::MatrixXd residuals = Eigen::MatrixXd::Zero(m, k);  // mode × segment
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1))
  for (int i = 0; i < k; ++i) {
    Eigen::MatrixXd re(n, m), im(n, m), phi_re(n, m), phi_im(n, m);
    for (Eigen::Index c = 0; c < m; ++c) {
      re.col(c) = out[finite[c]].v[i].real();
      im.col(c) = out[finite[c]].v[i].imag();
    }
    internal::MultiplyInto(factors[i], re, phi_re);
    internal::MultiplyInto(factors[i], im, phi_im);
    for (Eigen::Index c = 0; c < m; ++c) {
      const Complex s = sigma[finite[c]][i];
      const Eigen::VectorXcd& next = out[finite[c]].v[(i + 1) % k];
      double squared = 0;
      for (Eigen::Index r = 0; r < n; ++r)
        squared += std::norm(Complex(phi_re(r, c), phi_im(r, c)) - s * next(r));
      residuals(c, i) = std::sqrt(squared) / RowScale(norms[i], s);
    }
  }
  for (Eigen::Index c = 0; c < m; ++c) out[finite[c]].residual = residuals.row(c).maxCoeff();
  return out;
}

// A vector from the periodic Schur form is kept when its cyclic residual is at this level (the
// block-cyclic inverse iteration reaches ~1e-15); otherwise that mode goes through the inverse
// iteration.
constexpr double kSchurResidual = 1e-12;

/// |a − b| in the log plane, with −inf real parts (zero multipliers) comparing equal.
double LogDistance(Complex a, Complex b) {
  const bool a_zero = std::isinf(a.real()) && a.real() < 0;
  const bool b_zero = std::isinf(b.real()) && b.real() < 0;
  if (a_zero || b_zero) return a_zero && b_zero ? std::abs(a.imag() - b.imag()) : kInf;
  return std::abs(a - b);
}

/// Does log multiplier `b` belong to the cluster of `a` (close enough to share a subspace)?
bool InClusterOf(Complex a, Complex b) {
  return LogDistance(b, a) <= kClusterTol * std::max(1.0, std::abs(a));
}

/// Block-cyclic inverse iteration for every mode not yet done, one cluster of close log ρ at a
/// time (a cluster shares the random starts of one subspace iteration); marks them done.
void InverseIterationVectors(const std::vector<Eigen::MatrixXd>& factors,
                             const std::vector<double>& norms, const std::vector<double>& dt,
                             double period, const std::vector<Complex>& log_rho,
                             std::vector<char>& done, std::vector<PeriodicEigenvector>& result) {
  std::mt19937_64 rng(20240531);
  std::normal_distribution<double> normal;
  const Eigen::Index size = static_cast<Eigen::Index>(factors.size()) * factors[0].rows();
  for (std::size_t first = 0; first < log_rho.size(); ++first) {
    if (done[first]) continue;
    std::vector<std::size_t> cluster;
    for (std::size_t j = first; j < log_rho.size(); ++j) {
      if (!done[j] && InClusterOf(log_rho[first], log_rho[j])) {
        cluster.push_back(j);
        done[j] = 1;
      }
    }

    // Block inverse iteration on the cluster's subspace with the first member's σ, from
    // independent random starts.
    CyclicSystem base;
    FactorCyclic(factors, norms, dt, period, log_rho[first], base);
    const auto m = static_cast<Eigen::Index>(cluster.size());
    Eigen::MatrixXcd x(size, m);
    for (Eigen::Index c = 0; c < m; ++c) {
      for (Eigen::Index r = 0; r < size; ++r) x(r, c) = Complex(normal(rng), normal(rng));
    }
    if (base.ok) {
      for (int step = 0; step < kClusterSteps; ++step) InverseIterationStep(base, x);
    } else {
      x.setConstant(Complex(kInf, 0.0));  // reported as residual = inf below
    }

    // Refine each member with its own σ. Identical log ρ keep their (null-space) vectors
    // unchanged; distinct but close ones move to their own eigenvectors; a defective cluster
    // collapses towards one direction (seen later as an ill-conditioned mode matrix).
    for (Eigen::Index c = 0; c < m; ++c) {
      const std::size_t member = cluster[c];
      Eigen::MatrixXcd xc = x.col(c);
      Eigen::VectorXcd refined;
      CyclicSystem own;
      CyclicSystem* sys = &base;
      if (log_rho[member] != log_rho[first]) {
        FactorCyclic(factors, norms, dt, period, log_rho[member], own);
        sys = &own;
      }
      if (sys->ok && base.ok) {
        for (int step = 0; step < kMemberSteps; ++step) InverseIterationStep(*sys, xc);
        refined = Refine(*sys, xc.col(0));
      } else {
        refined.setConstant(size, Complex(kInf, 0.0));
      }
      result[member] = std::move(FinishVectors(factors, norms, {sys->sigma}, {&refined}, 1)[0]);
    }
  }
}

}  // namespace

std::vector<PeriodicEigenvector> ComputePeriodicEigenvectors(
    const std::vector<Eigen::MatrixXd>& factors, const std::vector<double>& dt,
    const std::vector<Complex>& log_rho, int threads, const PeriodicSchurForm* form) {
  if (std::string problem = CheckFactors(factors); !problem.empty()) {
    throw InputError("ComputePeriodicEigenvectors: " + problem);
  }
  const int k = static_cast<int>(factors.size());
  const Eigen::Index n = factors[0].rows();
  if (dt.size() != factors.size()) {
    throw InputError("ComputePeriodicEigenvectors: " + std::to_string(dt.size()) +
                     " segment lengths for " + std::to_string(k) + " factors");
  }
  double period = 0;
  for (double d : dt) {
    if (!std::isfinite(d) || d <= 0) {
      throw InputError("ComputePeriodicEigenvectors: segment lengths must be finite and > 0");
    }
    period += d;
  }
  for (const Complex& l : log_rho) {
    if (std::isnan(l.real()) || !std::isfinite(l.imag()) || l.real() == kInf) {
      throw InputError("ComputePeriodicEigenvectors: log_rho must be finite (or -inf real)");
    }
  }

  std::vector<PeriodicEigenvector> result(log_rho.size());
  if (n == 0) {
    for (auto& r : result) r.v.assign(k, Eigen::VectorXcd());
    return result;
  }
  std::vector<double> norms(k);
  for (int i = 0; i < k; ++i) norms[i] = factors[i].norm();

  // Isolated multipliers from the periodic Schur form (O(K n³) for all of them); the rest, and
  // any whose residual is not at round-off, by block-cyclic inverse iteration.
  std::vector<bool> isolated(log_rho.size(), true);
  for (std::size_t a = 0; a < log_rho.size(); ++a)
    for (std::size_t b = 0; b < log_rho.size(); ++b)
      if (a != b && InClusterOf(log_rho[a], log_rho[b])) isolated[a] = false;
  std::vector<char> done(log_rho.size(), 0);  // not vector<bool>: written concurrently
  {
    std::vector<Eigen::VectorXcd> schur =
        internal::SchurPeriodicEigenvectors(factors, dt, log_rho, isolated, threads, form);
    std::vector<std::size_t> delivered;
    std::vector<Eigen::VectorXcd*> stacked;
    std::vector<std::vector<Complex>> sigma;
    for (std::size_t m = 0; m < log_rho.size(); ++m) {
      if (schur[m].size() == 0) continue;
      delivered.push_back(m);
      stacked.push_back(&schur[m]);
      sigma.emplace_back(k);
      for (int i = 0; i < k; ++i) sigma.back()[i] = std::exp(log_rho[m] * (dt[i] / period));
    }
    std::vector<PeriodicEigenvector> finished =
        FinishVectors(factors, norms, sigma, stacked, threads);
    for (std::size_t q = 0; q < delivered.size(); ++q) {
      if (!(finished[q].residual <= kSchurResidual)) continue;
      finished[q].method = PeriodicEigenvectorMethod::kSchur;
      result[delivered[q]] = std::move(finished[q]);
      done[delivered[q]] = 1;
    }
  }
  InverseIterationVectors(factors, norms, dt, period, log_rho, done, result);
  return result;
}

}  // namespace ltp
