// kMagnusFilon (docs/magnus-filon.md): Magnus in the interaction picture of the period mean.
// With Ā = A_0 = VΛV⁻¹ and z = V⁻¹x, a step [t0, t0 + h] is z(t0 + h) = e^{Λh} exp(Ω) z(t0) for
// y' = B(s) y, B(s) = e^{−Λs} Q(t0 + s) e^{Λs}, Q(t) = Σ_m Q_m e^{jmΩt}, Q_m = V⁻¹A_mV. The
// entries of B are exponentials e^{(λ_j − λ_i + jmΩ)s}, so the first two Magnus terms are exact
// sums of exponential integrals (Filon quadrature): the error is a power of h‖Q‖, whatever the
// fastest mode of Ā — the step need not resolve its oscillations.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include "integrator_internal.h"
#include "ltp/core/error.h"
#include "ltp/integrate/detail/matrix_exponential.h"
#include "ltp/integrate/detail/matrix_product.h"
#include "ltp/integrate/detail/modal_basis.h"
#include "ltp/integrate/integrator_choice.h"
#include "oscillatory_integrals.h"
#include "task_threads.h"

namespace ltp::internal {

namespace {

// Entries with |(λ_j − λ_i + jmΩ)h| below this are summed one by one with the stable weights;
// above it the weights split into products of terms of size h/|b| for a sum of size h², an
// absolute error of ε·h/|b| = ε·h²/kResonant at most: 100 ε against Ω2's own h²‖Q‖². Larger
// thresholds send most pairs of a dense spectrum down the O(n³) path (0.25 did: 5× the time).
constexpr double kResonant = 1e-2;
// Steps keep h·(max Re λ − min Re λ) below this: B's entries grow by at most e^2 over a step.
constexpr double kDecaySpreadPerStep = 2;
const double kDecayGrowth = std::exp(kDecaySpreadPerStep);  // B's largest growth over a step
// Eigenvector matrices worse conditioned than this (Frobenius estimate) make the transformation's
// round-off, ε·cond, larger than the tolerances this method is for: it declines.
constexpr double kMaxCondition = 1e7;
// Step lengths this close share generators (and the piece is stepped by the cached length): the
// pieces of a segment grid differ in their last bits (1.4e-14 relative on a 6 s period), and
// steps of h(1 + 1e-13) end a piece 1e-13 of its length late — a few ulps of the grid's own
// times, as if the grid had been rounded once more.
constexpr double kSameStep = 1e-13;
// Splits (systems) and step lengths kept: the analysis, its refined run and the other models of
// a sampled set, with the doubling loop's last lengths; 4H + 1 n×n complex matrices per length
// (20 MB per system at n = 250, H = 1).
constexpr size_t kSplitsKept = 3;
constexpr size_t kGeneratorsKept = 4;

using Matrix = Eigen::MatrixXcd;

}  // namespace

// The mean's eigen-decomposition and the harmonics in its eigenbasis, shared by every transition
// of one system on every thread, with the generators of the step lengths already used.
struct MagnusFilonIntegrator::Split {
  Eigen::VectorXcd lambda;
  Matrix v, v_inv;
  std::vector<Matrix> q;  // Q_m at m + harmonics; Q_0 = V⁻¹A_0V − Λ, the decomposition's residue
  int harmonics = 0;
  double omega = 0;
  double max_step = 0;  // from the decay spread; infinity when every Re λ is equal
  std::string unsuitable;
  std::vector<Eigen::MatrixXcd> key;  // A's coefficients, to recognise the system

  struct Generators {
    double h = 0;
    /// G_q = G1_q + G2_q (G1_q = 0 for |q| > H), column q + 2H holding G_q's n² entries: a
    /// step's Ω = Σ_q e^{jqΩt} G_q is then one matrix–vector product (13 scaled sums of
    /// 250 × 250 matrices per step were 6 % of a 250-state analysis).
    Matrix stacked;
  };
  std::mutex mutex;  // guards `generators`: one thread forms a step length's, the others wait
  std::vector<std::shared_ptr<const Generators>> generators;  // most recent last

  Matrix Divisor(int m) const;  // D_m(i, j) = λ_j − λ_i + jmΩ
  std::shared_ptr<const Generators> For(double h);
  Generators Form(double h) const;
  Eigen::Matrix<bool, -1, -1> PairsAboveRoundOff(double h) const;
};

namespace {

std::shared_ptr<MagnusFilonIntegrator::Split> MakeSplit(const PeriodicSystem& system,
                                                        const FourierMatrix& a) {
  auto split = std::make_shared<MagnusFilonIntegrator::Split>();
  const int n = system.states(), H = a.max_harmonic();
  split->harmonics = H;
  split->omega = system.omega();
  for (int m = -H; m <= H; ++m) split->key.push_back(a[m]);
  const std::optional<RealEigenbasis> eig = RealEigenDecomposition(a[0].real());
  if (!eig) {
    split->unsuitable = "the eigen-decomposition of the mean A_0 failed";
    return split;
  }
  split->lambda = eig->eigenvalues;
  split->v = ComplexEigenvectors(*eig);
  Eigen::PartialPivLU<Matrix> lu(split->v);
  split->v_inv = lu.inverse();
  const double condition = split->v.norm() * split->v_inv.norm();
  if (!(condition <= kMaxCondition)) {
    std::ostringstream s;
    s << "the mean A_0 is not diagonalisable in a well-conditioned basis (eigenvector "
         "condition "
      << MessageNumber(condition, 2) << " > " << MessageNumber(kMaxCondition, 2)
      << "; a rigid-body or repeated mode?)";
    split->unsuitable = s.str();
    return split;
  }
  for (int m = -H; m <= H; ++m) {
    Matrix am(n, n), qm(n, n);
    MultiplyInto(a[m], split->v, am);
    MultiplyInto(split->v_inv, am, qm);
    if (m == 0) qm.diagonal() -= split->lambda;
    split->q.push_back(std::move(qm));
  }
  const double spread = split->lambda.real().maxCoeff() - split->lambda.real().minCoeff();
  split->max_step =
      spread > 0 ? kDecaySpreadPerStep / spread : std::numeric_limits<double>::infinity();
  return split;
}

// The split of `system`'s A: recomputed only for another series. Shared by the threads (the
// segments' transitions run in parallel), formed by the first that asks.
std::shared_ptr<MagnusFilonIntegrator::Split> SplitOf(const PeriodicSystem& system) {
  const FourierMatrix* a = system.fourier_A();
  if (a == nullptr) {
    auto none = std::make_shared<MagnusFilonIntegrator::Split>();
    none->unsuitable = "A(t) is not a Fourier series";
    return none;
  }
  static std::mutex memo_mutex;
  static std::vector<std::shared_ptr<MagnusFilonIntegrator::Split>> memo;
  const std::lock_guard<std::mutex> lock(memo_mutex);
  const int H = a->max_harmonic();
  for (const auto& s : memo) {
    if (static_cast<int>(s->key.size()) != 2 * H + 1 || s->omega != system.omega()) continue;
    bool same = true;
    for (int m = -H; m <= H && same; ++m)
      same = s->key[m + H].rows() == (*a)[m].rows() && s->key[m + H] == (*a)[m];
    if (same) return s;
  }
  auto split = MakeSplit(system, *a);
  if (memo.size() >= kSplitsKept) memo.erase(memo.begin());
  memo.push_back(split);
  return split;
}

// Σ_j of the second Magnus term's weights one path at a time, for the paths the product form
// skips: ½ Q_m(i, j) Q_m'(j, k) [F(a, b) − F(b, a)], a = D_m(i, j), b = D_m'(j, k).
Complex PathWeight(Complex a, Complex b, double h) {
  return 0.5 * (TriangleIntegral(a, b, h) - TriangleIntegral(b, a, h));
}

}  // namespace

Matrix MagnusFilonIntegrator::Split::Divisor(int m) const {
  const int n = static_cast<int>(lambda.size());
  Matrix d(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) d(i, j) = lambda(j) - lambda(i) + Complex(0, m * omega);
  return d;
}

// Ω = Σ_q e^{jqΩt0} (G1_q + G2_q): the weights depend on h only.
// G1_m = h Q_m ⊙ φ1(D_m h). For G2, with F(a, b) = ∫∫_{s2<s1} e^{a s1 + b s2} and s = a + b,
//   F(a, b) − F(b, a) = h φ1(sh)(1/b − 1/a) − h φ1(ah)/b + h φ1(bh)/a,
// so over the paths j whose a and b are not resonant the sums are matrix products of Q, Q ⊘ D
// and Q ⊙ φ1(Dh); the resonant paths (every diagonal entry once h|mΩ| < kResonant) one by one.
std::shared_ptr<const MagnusFilonIntegrator::Split::Generators> MagnusFilonIntegrator::Split::For(
    double h) {
  const std::lock_guard<std::mutex> lock(mutex);
  for (const auto& g : generators)
    if (std::abs(g->h - h) <= kSameStep * h) return g;
  if (generators.size() >= kGeneratorsKept) generators.erase(generators.begin());
  generators.push_back(std::make_shared<const Generators>(Form(h)));
  return generators.back();
}

// Which harmonic pairs (m, m') the second Magnus term takes, at (m + H, m' + H). A pair's terms in
// Ω2 are at most e²·h²·n‖Q_m‖‖Q_m'‖ entrywise (n paths j, the factors e^{(λ_j − λ_i)s} below e²
// within a step); below ε·h‖Q‖, the rounding of the first term's largest entry, it changes
// nothing the arithmetic keeps, and is skipped: the pairs of harmonics that are the samples'
// rounding (a blade-coordinate interpolant of an isotropic rotor: 1P and 2P at 3e-11 beside a 3P
// of 0.025; 16 of its 36 pairs). Q_0, the decomposition's residue, is round-off of the mean
// itself: its pairs are skipped as before.
Eigen::Matrix<bool, -1, -1> MagnusFilonIntegrator::Split::PairsAboveRoundOff(double h) const {
  const int n = static_cast<int>(lambda.size()), H = harmonics;
  Eigen::VectorXd size(2 * H + 1);  // ‖Q_m‖ at m + H, largest entry
  for (int a = 0; a <= 2 * H; ++a) size(a) = q[a].cwiseAbs().maxCoeff();
  const double round_off = std::numeric_limits<double>::epsilon() * h * size.maxCoeff();
  Eigen::Matrix<bool, -1, -1> pairs =
      ((kDecayGrowth * h * h * n * size) * size.transpose()).array() > round_off;
  pairs.row(H).setConstant(false);
  pairs.col(H).setConstant(false);
  return pairs;
}

MagnusFilonIntegrator::Split::Generators MagnusFilonIntegrator::Split::Form(double h) const {
  const int n = static_cast<int>(lambda.size()), H = harmonics;
  // The analysis's other threads wait for these generators (every segment needs them first):
  // the harmonics', then the frequencies', terms are shared out to them.
  const int threads = TeamThreads();
  std::vector<Matrix> first(2 * H + 1), d = first, x = first, qr = first, yr = first;  // at m + H
  std::vector<Eigen::Matrix<bool, -1, -1>> regular(2 * H + 1);
  RunTasks(2 * H + 1, threads, [&](int a) {
    const int m = a - H;
    d[a] = Divisor(m);
    const Matrix& dm = d[a];
    const Matrix& qm = q[a];
    Matrix g1(n, n), xm = Matrix::Zero(n, n), qrm = Matrix::Zero(n, n), yrm = Matrix::Zero(n, n);
    Eigen::Matrix<bool, -1, -1> reg(n, n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Complex phi = Phi1(dm(i, j) * h);
        g1(i, j) = h * qm(i, j) * phi;
        reg(i, j) = std::norm(dm(i, j)) * (h * h) >= kResonant * kResonant;
        if (reg(i, j)) {
          xm(i, j) = qm(i, j) / dm(i, j);
          qrm(i, j) = qm(i, j);
          yrm(i, j) = qm(i, j) * phi;
        }
      }
    first[a] = std::move(g1);
    x[a] = std::move(xm);
    qr[a] = std::move(qrm);
    yr[a] = std::move(yrm);
    regular[a] = std::move(reg);
  });
  const Eigen::Matrix<bool, -1, -1> pairs = PairsAboveRoundOff(h);
  Matrix stacked(static_cast<Eigen::Index>(n) * n, 4 * H + 1);
  // G_p = G2_p (+ G1_p for |p| ≤ H), p = m + m', one task per frequency, the middle (most
  // pairs) first.
  RunTasks(4 * H + 1, threads, [&](int task) {
    const int p = task % 2 == 0 ? task / 2 : -(task + 1) / 2;
    Matrix cross = Matrix::Zero(n, n), rest = Matrix::Zero(n, n), product(n, n);
    for (int m = std::max(-H, p - H); m <= std::min(H, p + H); ++m) {
      const int a = m + H, b = p - m + H;
      if (!pairs(a, b)) continue;
      MultiplyInto(qr[a], x[b], product);
      cross += product;
      MultiplyInto(x[a], qr[b], product);
      cross -= product;
      MultiplyInto(x[a], yr[b], product);
      rest += product;
      MultiplyInto(yr[a], x[b], product);
      rest -= product;
    }
    const Matrix dp = Divisor(p);
    Matrix g2 = 0.5 * h * rest;
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < n; ++i) g2(i, k) += 0.5 * h * Phi1(dp(i, k) * h) * cross(i, k);
    // The resonant paths: a resonant (any b), then a regular with b resonant.
    for (int m = std::max(-H, p - H); m <= std::min(H, p + H); ++m) {
      const int a = m + H, b = p - m + H;
      if (!pairs(a, b)) continue;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          if (regular[a](i, j)) continue;
          for (int k = 0; k < n; ++k)
            g2(i, k) += q[a](i, j) * q[b](j, k) * PathWeight(d[a](i, j), d[b](j, k), h);
        }
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j) {
          if (regular[b](j, k)) continue;
          for (int i = 0; i < n; ++i)
            if (regular[a](i, j))
              g2(i, k) += q[a](i, j) * q[b](j, k) * PathWeight(d[a](i, j), d[b](j, k), h);
        }
    }
    // One matrix per frequency: a step's Ω is then 4H + 1 terms, not 6H + 2.
    if (std::abs(p) <= H) g2 += first[p + H];
    stacked.col(p + 2 * H) = g2.reshaped();
  });
  return Generators{h, std::move(stacked)};
}

MagnusFilonIntegrator::MagnusFilonIntegrator(const PeriodicSystem& system)
    : system_(system), split_(SplitOf(system)) {}

const std::string& MagnusFilonIntegrator::unsuitable() const { return split_->unsuitable; }

Eigen::MatrixXd MagnusFilonIntegrator::Run(const std::vector<double>& points, int steps_per_period,
                                           long refine) {
  Split& s = *split_;
  const int n = system_.states(), H = s.harmonics;
  Matrix z = Matrix::Identity(n, n), next(n, n), w(n, n), step(n, n);
  Eigen::VectorXcd phases(4 * H + 1);
  last_pass_steps_ = 0;
  const double period = system_.period();
  for (size_t p = 0; p + 1 < points.size(); ++p) {
    const double t0 = points[p], length = points[p + 1] - t0;
    long base = StepsOnPiece(steps_per_period, length, period);
    if (std::isfinite(s.max_step))
      base = std::max(base, static_cast<long>(std::ceil(length / s.max_step)));
    const long steps = refine * base;
    const std::shared_ptr<const Split::Generators> generators = s.For(length / steps);
    const Split::Generators& g = *generators;
    const double h = g.h;
    const Eigen::VectorXcd decay = (s.lambda * h).array().exp();
    for (long k = 0; k < steps; ++k) {
      const double t = t0 + k * h;  // not a running sum: no drift over many steps
      phases(2 * H) = 1.0;
      for (int q = 1; q <= 2 * H; ++q) {
        phases(2 * H + q) = std::polar(1.0, q * s.omega * t);
        phases(2 * H - q) = std::conj(phases(2 * H + q));
      }
      MultiplyInto(g.stacked, phases, Eigen::Map<Matrix>(w.data(), w.size(), 1));
      ExpInto(w, step);
      MultiplyInto(step, z, next);
      z = decay.asDiagonal() * next;
    }
    last_pass_steps_ += steps;
  }
  steps_ += last_pass_steps_;
  rhs_evals_ += static_cast<long>(kMagnusFilonProductsPerStep) * last_pass_steps_;
  Matrix vz(n, n), phi(n, n);
  MultiplyInto(s.v, z, vz);
  MultiplyInto(vz, s.v_inv, phi);
  return phi.real();
}

}  // namespace ltp::internal
