// Periodic eigenvectors from the periodic Schur form, by cyclic back-substitution
// (docs/periodic-eigenvectors.md):
//   1. PeriodicSchurDecomposition (SLICOT MB03VD + MB03VY + MB03BD) gives the real periodic
//      Schur form with its vectors, R_i = U_{i+1}ᵀ Φ_i U_i, every R_i upper triangular except
//      the quasi-triangular R_{K−1};
//   2. each 2×2 block (a complex pair) is split by unitary 2×2 rotations W_i built from the
//      eigenvector of the block's own 2×2 product, giving complex upper triangular T_i;
//   3. for the multiplier at diagonal position j, y_i(j) = 1 and each row above is a scalar
//      cyclic recurrence y_{i+1} = (T_i(l,l) y_i + r_i) / T_i(j,j), solved in the direction in
//      which it contracts (forwards when |ρ_l| < |ρ_j|, backwards otherwise), so nothing grows
//      like the ratio of two multipliers however many decades they span;
//   4. v_i = c_i V_i y_i with the scalars c_i carried as logarithms.
// O(K n³) for all modes, against one sparse LU of the nK × nK lifted matrix per mode.
#include "periodic_schur_vectors.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>

#include "ltp/floquet/periodic_eigen.h"
#include "ltp/integrate/detail/matrix_product.h"

namespace ltp::internal {

namespace {

using Complex = std::complex<double>;

/// Complex periodic Schur form T_i = V_{i+1}ᴴ Φ_i V_i, all upper triangular, with
/// V_i = U_i W_i: U_i the real form's orthogonal Z_i, W_i the identity but for the unitary
/// 2×2 rotation of each complex pair's block (rotations[b][i] acting on rows and columns
/// first[b], first[b] + 1). V_i is never formed: V_i y = U_i (W_i y) is two real products.
struct ComplexSchurForm {
  std::vector<Eigen::MatrixXcd> t;
  const std::vector<Eigen::MatrixXd>* u = nullptr;
  std::vector<int> first;
  std::vector<std::vector<Eigen::Matrix2cd>> rotations;
};

/// Splits every 2×2 block of R_{K−1}. With w_0 an eigenvector of the block's product
/// B_{K−1} ⋯ B_0 and w_{i+1} ∝ B_i w_i, the unitary W_i = [w_i, w_i^⊥] make each
/// W_{i+1}ᴴ B_i W_i upper triangular. The w_i are propagated, not the product formed: the two
/// eigenvectors of a conjugate pair grow alike, so the propagation is stable.
bool Complexify(const std::vector<Eigen::MatrixXd>& r, const std::vector<Eigen::MatrixXd>& u,
                ComplexSchurForm& s) {
  const int k = static_cast<int>(r.size());
  const int n = static_cast<int>(r[0].rows());
  s.t.resize(k);
  s.u = &u;
  for (int i = 0; i < k; ++i) s.t[i] = r[i].cast<Complex>();
  std::vector<Eigen::Matrix2cd> w(k);
  for (int p = 0; p + 1 < n; ++p) {
    if (r[k - 1](p + 1, p) == 0.0) continue;
    Eigen::Matrix2d product = Eigen::Matrix2d::Identity();
    for (int i = 0; i < k; ++i) {
      product = (r[i].block<2, 2>(p, p) * product).eval();
      const double norm = product.norm();
      if (!(norm > 0) || !std::isfinite(norm)) return false;
      product /= norm;
    }
    Eigen::ComplexEigenSolver<Eigen::Matrix2cd> eig(product.cast<Complex>());
    if (eig.info() != Eigen::Success) return false;
    const int pick = eig.eigenvalues()(0).imag() >= eig.eigenvalues()(1).imag() ? 0 : 1;
    Eigen::Vector2cd x = eig.eigenvectors().col(pick).normalized();
    for (int i = 0; i < k; ++i) {
      w[i].col(0) = x;
      w[i].col(1) << -std::conj(x(1)), std::conj(x(0));
      x = (r[i].block<2, 2>(p, p).cast<Complex>() * x).normalized();
    }
    for (int i = 0; i < k; ++i) {
      s.t[i].middleCols(p, 2) = (s.t[i].middleCols(p, 2) * w[i]).eval();
      s.t[i].middleRows(p, 2) = (w[(i + 1) % k].adjoint() * s.t[i].middleRows(p, 2)).eval();
      s.t[i](p + 1, p) = 0.0;  // rounding level by construction; the caller's residual checks it
    }
    s.first.push_back(p);
    s.rotations.push_back(w);
    ++p;  // the second row of the block
  }
  return true;
}

/// 1 − e^{d} for Re d ≤ 0, without overflow (e^{d} underflows harmlessly to 0).
Complex OneMinusExp(Complex d) { return d.real() < -700 ? Complex(1.0) : 1.0 - std::exp(d); }

/// The cyclic recurrences of the multiplier at diagonal position j (see the file comment):
/// column i of y is y_i in Schur coordinates, and v_i = c_i V_i y_i with log c_i in log_c.
struct Recurrence {
  Eigen::MatrixXcd y;
  std::vector<Complex> log_c;
};

/// Empty when a recurrence is singular (a repeated multiplier) or the numbers are not finite.
std::optional<Recurrence> SolveRecurrences(const ComplexSchurForm& s, int j,
                                           const std::vector<Complex>& log_diag,
                                           const std::vector<Complex>& log_sigma) {
  const int k = static_cast<int>(s.t.size());
  const int n = static_cast<int>(s.t[0].rows());
  Recurrence out;
  Eigen::MatrixXcd& y = out.y;
  y = Eigen::MatrixXcd::Zero(n, k);
  y.row(j).setOnes();
  std::vector<Complex> tau(k);
  for (int i = 0; i < k; ++i) tau[i] = s.t[i](j, j);
  // rhs(l, i) = Σ_{c > l} T_i(l, c) y(c, i), accumulated a solved row c at a time down the
  // contiguous column T_i(0:c, c) (row by row it was a stride-n walk: 10 % of a 250-state
  // analysis).
  Eigen::MatrixXcd rhs = Eigen::MatrixXcd::Zero(n, k);
  auto accumulate = [&](int c) {
    for (int i = 0; i < k; ++i) rhs.col(i).head(c) += s.t[i].col(c).head(c) * y(c, i);
  };
  accumulate(j);
  for (int l = j - 1; l >= 0; --l) {
    const Complex d = log_diag[l] - log_diag[j];  // log(ρ_l / ρ_j)
    if (d.real() <= 0) {  // forwards: y_{i+1} = (T_i(l,l) y_i + r_i) / τ_i contracts
      Complex x = 0;
      for (int i = 0; i < k; ++i) x = (s.t[i](l, l) * x + rhs(l, i)) / tau[i];
      const Complex denominator = OneMinusExp(d);
      if (!(std::abs(denominator) > 1e-13)) return std::nullopt;
      x /= denominator;
      for (int i = 0; i < k; ++i) {
        y(l, i) = x;
        x = (s.t[i](l, l) * x + rhs(l, i)) / tau[i];
      }
    } else {  // backwards: y_i = (τ_i y_{i+1} − r_i) / T_i(l,l) contracts
      Complex x = 0;
      for (int i = k - 1; i >= 0; --i) x = (tau[i] * x - rhs(l, i)) / s.t[i](l, l);
      const Complex denominator = OneMinusExp(-d);
      if (!(std::abs(denominator) > 1e-13)) return std::nullopt;
      x /= denominator;
      y(l, 0) = x;
      for (int i = k - 1; i >= 1; --i) {
        x = (tau[i] * x - rhs(l, i)) / s.t[i](l, l);
        y(l, i) = x;
      }
    }
    if (!y.row(l).allFinite()) return std::nullopt;
    accumulate(l);
  }
  // c_0 = 1, c_{i+1} = c_i τ_i / σ_i.
  out.log_c.resize(k);
  Complex acc = 0;
  for (int i = 0; i < k; ++i) {
    out.log_c[i] = acc;
    acc += std::log(tau[i]) - log_sigma[i];
  }
  return out;
}

/// v_i = c_i V_i y_i for every solved mode, stacked and scaled by the largest ||v_i||: per
/// segment the pairs' rotations W_i, then one real n × n times n × modes product for each of
/// the real and imaginary parts (what per-mode products would cost, at matrix–matrix speed).
void StackEigenvectors(const ComplexSchurForm& s, const std::vector<std::size_t>& modes,
                       const std::vector<Recurrence>& recurrences,
                       std::vector<Eigen::VectorXcd>& out) {
  const int k = static_cast<int>(s.t.size());
  const int n = static_cast<int>(s.t[0].rows());
  const int count = static_cast<int>(modes.size());
  std::vector<double> top(count, -std::numeric_limits<double>::infinity());
  std::vector<Eigen::VectorXcd> stacked(count, Eigen::VectorXcd(static_cast<Eigen::Index>(k) * n));
  Eigen::MatrixXcd y(n, count), x(n, count);
  Eigen::MatrixXd x_re(n, count), x_im(n, count);
  for (int i = 0; i < k; ++i) {
    for (int q = 0; q < count; ++q) y.col(q) = recurrences[q].y.col(i);
    for (std::size_t b = 0; b < s.first.size(); ++b)
      y.middleRows(s.first[b], 2) = (s.rotations[b][i] * y.middleRows(s.first[b], 2)).eval();
    MultiplyInto((*s.u)[i], y.real(), x_re);
    MultiplyInto((*s.u)[i], y.imag(), x_im);
    x.real() = x_re;
    x.imag() = x_im;
    for (int q = 0; q < count; ++q) {
      stacked[q].segment(static_cast<Eigen::Index>(i) * n, n) = x.col(q);
      top[q] = std::max(top[q], recurrences[q].log_c[i].real() + std::log(x.col(q).norm()));
    }
  }
  for (int q = 0; q < count; ++q) {
    if (!std::isfinite(top[q])) continue;
    for (int i = 0; i < k; ++i)
      stacked[q].segment(static_cast<Eigen::Index>(i) * n, n) *=
          std::exp(recurrences[q].log_c[i] - top[q]);
    if (stacked[q].allFinite()) out[modes[q]] = std::move(stacked[q]);
  }
}

/// Distance of two log multipliers, the imaginary parts compared modulo 2π.
double LogDistance(Complex a, Complex b) {
  return std::hypot(a.real() - b.real(), std::remainder(a.imag() - b.imag(), 2 * std::numbers::pi));
}

/// The vectors at the boundaries of `real`'s factors, whose lengths are `dt`.
std::vector<Eigen::VectorXcd> VectorsOfTheForm(const PeriodicSchurForm& real,
                                               const std::vector<double>& dt,
                                               const std::vector<Complex>& log_rho,
                                               const std::vector<bool>& wanted, int threads) {
  std::vector<Eigen::VectorXcd> out(log_rho.size());
  const int k = static_cast<int>(real.t.size());
  const int n = static_cast<int>(real.t[0].rows());
  double period = 0;
  for (double d : dt) period += d;
  ComplexSchurForm s;
  if (!real.ok || !Complexify(real.t, real.z, s)) return out;
  std::vector<Complex> log_diag(n, 0.0);
  for (int i = 0; i < k; ++i)
    for (int l = 0; l < n; ++l) log_diag[l] += std::log(s.t[i](l, l));
  std::vector<bool> used(n, false);
  std::vector<std::pair<std::size_t, int>> jobs;  // mode, its diagonal position
  for (std::size_t m = 0; m < log_rho.size(); ++m) {
    if (!wanted[m] || !std::isfinite(log_rho[m].real())) continue;
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int l = 0; l < n; ++l) {
      const double d = LogDistance(log_diag[l], log_rho[m]);
      if (!used[l] && d < best_distance) {
        best = l;
        best_distance = d;
      }
    }
    // The same multiplier as the eigenvalue route's, up to that route's rounding.
    if (best < 0 || !(best_distance <= 1e-6 * std::max(1.0, std::abs(log_rho[m])))) continue;
    used[best] = true;
    jobs.emplace_back(m, best);
  }
  std::vector<std::optional<Recurrence>> solutions(jobs.size());
  const long count = static_cast<long>(jobs.size());
#pragma omp parallel for schedule(dynamic) num_threads(std::max(threads, 1))
  for (long q = 0; q < count; ++q) {
    const auto [m, diagonal] = jobs[q];
    std::vector<Complex> log_sigma(k);
    for (int i = 0; i < k; ++i) log_sigma[i] = log_rho[m] * (dt[i] / period);
    solutions[q] = SolveRecurrences(s, diagonal, log_diag, log_sigma);
  }
  std::vector<std::size_t> solved;
  std::vector<Recurrence> recurrences;
  for (long q = 0; q < count; ++q) {
    if (!solutions[q]) continue;
    solved.push_back(jobs[q].first);
    recurrences.push_back(std::move(*solutions[q]));
  }
  StackEigenvectors(s, solved, recurrences, out);
  return out;
}

// Vectors at every boundary of `factors` from those at every r-th (`grouped`, from the form of
// the factors multiplied in groups of r): v_{j+1} = Φ_j v_j / σ_j inside each group, for all
// modes at once. Each step's error is at most the factor's condition times the vector's, and a
// group's conditions multiply to within the grid's limit (StartingGrid); the caller's cyclic
// residual check sees the rest.
std::vector<Eigen::VectorXcd> FillTheGroups(const std::vector<Eigen::MatrixXd>& factors,
                                            const std::vector<double>& dt,
                                            const std::vector<Complex>& log_rho, int r,
                                            std::vector<Eigen::VectorXcd> grouped) {
  const int k = static_cast<int>(factors.size());
  const Eigen::Index n = factors[0].rows();
  double period = 0;
  for (double d : dt) period += d;
  std::vector<std::size_t> modes;
  for (std::size_t m = 0; m < grouped.size(); ++m)
    if (grouped[m].size() > 0) modes.push_back(m);
  const Eigen::Index count = static_cast<Eigen::Index>(modes.size());
  std::vector<Eigen::VectorXcd> out(log_rho.size());
  for (std::size_t m : modes) out[m].resize(static_cast<Eigen::Index>(k) * n);
  Eigen::MatrixXcd x(n, count);
  Eigen::MatrixXd next_re(n, count), next_im(n, count);
  for (int j = 0; j < k; ++j) {
    if (j % r == 0) {
      for (Eigen::Index q = 0; q < count; ++q)
        x.col(q) = grouped[modes[q]].segment(static_cast<Eigen::Index>(j / r) * n, n);
    } else {
      MultiplyInto(factors[j - 1], x.real(), next_re);
      MultiplyInto(factors[j - 1], x.imag(), next_im);
      x.real() = next_re;
      x.imag() = next_im;
      for (Eigen::Index q = 0; q < count; ++q)
        x.col(q) *= std::exp(-log_rho[modes[q]] * (dt[j - 1] / period));
    }
    for (Eigen::Index q = 0; q < count; ++q)
      out[modes[q]].segment(static_cast<Eigen::Index>(j) * n, n) = x.col(q);
  }
  for (std::size_t m : modes)
    if (!out[m].allFinite()) out[m] = Eigen::VectorXcd();  // the caller's other route
  return out;
}

}  // namespace

std::vector<Eigen::VectorXcd> SchurPeriodicEigenvectors(const std::vector<Eigen::MatrixXd>& factors,
                                                        const std::vector<double>& dt,
                                                        const std::vector<Complex>& log_rho,
                                                        const std::vector<bool>& wanted,
                                                        int threads,
                                                        const PeriodicSchurForm* form) {
  if (factors.empty() || factors[0].rows() == 0 ||
      std::none_of(wanted.begin(), wanted.end(), [](bool b) { return b; }))
    return std::vector<Eigen::VectorXcd>(log_rho.size());
  const int k = static_cast<int>(factors.size());
  // Real periodic Schur form in time order: R_i = U_{i+1}ᵀ Φ_i U_i, R_{K−1} quasi-triangular.
  const int groups = form && form->ok ? static_cast<int>(form->t.size()) : 0;
  if (groups == 0 || k % groups != 0)
    return VectorsOfTheForm(PeriodicSchurDecomposition(factors), dt, log_rho, wanted, threads);
  if (groups == k) return VectorsOfTheForm(*form, dt, log_rho, wanted, threads);
  const int r = k / groups;
  std::vector<double> group_dt(groups, 0.0);
  for (int j = 0; j < k; ++j) group_dt[j / r] += dt[j];
  return FillTheGroups(factors, dt, log_rho, r,
                       VectorsOfTheForm(*form, group_dt, log_rho, wanted, threads));
}

}  // namespace ltp::internal
