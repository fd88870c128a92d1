// kTaylor: Taylor-series steps of Φ' = A(t) Φ for systems whose A(t) is a trigonometric
// polynomial (the Fourier form). There every derivative of A at a step's start is exact and
// cheap — harmonic w contributes (wΩ)^j/j! times its cos/sin turned by jπ/2 — so the series of Φ
// follows from the recurrence Φ_{k+1} = Σ_j A_j Φ_{k−j} / (k + 1) without evaluating A anywhere
// else, and one step of order p ≈ −ln(tol) spans what Bulirsch–Stoer covers in many. The
// convolution is summed per harmonic: Σ_j A_j Φ_{k−j} = Ā Φ_k + Σ_w (C_w X_w + S_w Y_w) with
// X_w, Y_w scalar-weighted sums of the Φ_i, so an order costs 1 + 2H products, not k + 1
// (docs/taylor-integrator.md: the order and step rule, and what they cost).
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "integrator_internal.h"
#include "ltp/integrate/detail/matrix_product.h"

namespace ltp::internal {

namespace {

template <int N>
class TaylorSeriesStepper {
 public:
  using Matrix = Eigen::Matrix<double, N, N>;

  TaylorSeriesStepper(const PeriodicSystem& system, const IntegratorOptions& options)
      : n_(system.states()),
        order_(TaylorOrder(options.rel_tol)),
        check_orders_(options.carry_local_errors ? kCheckOrders : 0),
        series_order_(order_ + check_orders_),
        omega_(system.omega()),
        rel_tol_(options.rel_tol),
        abs_tol_(options.abs_tol) {
    series_ = system.RealSeriesA(nullptr);
    shape_ = std::move(*ShapeOfSeries(system));
    terms_.setZero(static_cast<Eigen::Index>(n_) * n_, series_order_ + 1);
    weights_.assign(static_cast<size_t>(2 * shape_.harmonics) * (series_order_ + 1), 0.0);
    inner_ = shape_.constant_damping ? n_ / 2 : n_;
    if (shape_.second_order) upper_diagonal_ = shape_.upper_diagonal;
    // The BLAS path's buffers (a stability map builds a stepper per point: n = 2 skips them);
    // the fixed sizes' series of A.
    if constexpr (N != Eigen::Dynamic) a_.resize(static_cast<size_t>(series_order_) + 1);
    if constexpr (N == Eigen::Dynamic) {
      const int rows = shape_.second_order ? n_ / 2 : n_;
      lower_.setZero(rows, n_);
      term_sizes_.assign(static_cast<size_t>(series_order_) + 1, 0.0);
      harmonic_sums_.setZero(static_cast<Eigen::Index>(2 * shape_.harmonics) * inner_, n_);
      harmonic_blocks_.resize(rows, static_cast<Eigen::Index>(2 * shape_.harmonics) * inner_);
      for (int column = 0; column < 2 * shape_.harmonics; ++column)
        harmonic_blocks_.middleCols(static_cast<Eigen::Index>(column) * inner_, inner_) =
            Block(1 + column).bottomLeftCorner(rows, inner_);
    }
  }

  /// Φ(t1, t0) into `result` (steps and products added); false when a step's series is not
  /// finite (overflow) or the step budget `steps_left` runs out. With carry_local_errors, also
  /// the lower-order product's offset in result.local_error_effect (CheckedStep).
  bool Transition(double t0, double t1, TransitionResult& result, long& steps_left) {
    Matrix phi = Matrix::Identity(n_, n_);
    Matrix lower;  // the product of the steps' order-p sums (carry_local_errors)
    if (check_orders_ > 0) lower = Matrix::Identity(n_, n_);
    double t = t0;
    while (t < t1) {
      if (steps_left-- <= 0) {
        result.message = "Taylor series: more than max_steps steps";
        return false;
      }
      SeriesOfHarmonics(t);
      if constexpr (N != Eigen::Dynamic) SeriesOfA();
      const double scale = phi.cwiseAbs().maxCoeff();
      // The step's own transition S (from I) when both products are kept; else Φ's series.
      const double tol =
          check_orders_ > 0 ? rel_tol_ + abs_tol_ / scale : abs_tol_ + rel_tol_ * scale;
      // Steps that cannot reach t1 skip the check for an early end (on n = 2 it costs about a
      // quarter of the step).
      const bool may_end = t1 - t <= full_step_;
      const int order = check_orders_ > 0
                            ? SeriesOfPhi(Matrix::Identity(n_, n_), tol, may_end ? t1 - t : 0)
                            : SeriesOfPhi(phi, tol, may_end ? t1 - t : 0);
      double h = t1 - t;  // reached early: the series' last terms at t1 are within tol
      if (order == order_) {
        full_step_ = StepLength(tol, order);
        h = std::min(h, full_step_);
      }
      if (!(h > 0) || !std::isfinite(h)) {
        result.message = kNotFiniteMessage;
        return false;
      }
      if (check_orders_ > 0) {
        CheckedStep(order, h, phi, lower);
      } else {
        phi = Sum(order, h);
      }
      t = h == t1 - t ? t1 : t + h;
      ++result.steps;
      result.rhs_evals += std::lround((order + check_orders_) * shape_.ProductsPerOrder()) +
                          (check_orders_ > 0 ? 2 : 0);
    }
    result.phi = phi;
    if (check_orders_ > 0) result.local_error_effect = lower - phi;
    return true;
  }

 private:
  // The lowest order an interval's end may be reached with (fewer terms than this say
  // little about the tail).
  static constexpr int kMinOrder = 4;

  // The terms beyond the step's order p that the checked product takes: each shrinks the tail
  // by about ωh/k ≈ 0.15 at the steps the order rule takes, so four make the order-(p + 4) sum
  // ~10³ times more accurate than the order-p one (docs/taylor-integrator.md).
  static constexpr int kCheckOrders = 4;
  // The most terms a series stores (TaylorOrder's largest order and the checked ones).
  static constexpr int kMaxTerms = 36 + kCheckOrders + 1;

  // Horner: Σ_{k ≤ order} Φ_k h^k.
  Matrix Sum(int order, double h) const {
    Matrix sum = Term(order);
    for (int k = order - 1; k >= 0; --k) sum = Term(k) + h * sum;
    return sum;
  }

  // Carry_local_errors: the terms p + 1 … p + q of the step's transition S as well, then
  // Φ ← S_{p+q} Φ (the numbers reported) and Φ_lower ← S_p Φ_lower (held only to the
  // tolerance). Φ_lower − Φ is the first run's error of a refined-run estimate, on the same steps.
  void CheckedStep(int order, double h, Matrix& phi, Matrix& lower) {
    for (int k = order; k < order + check_orders_; ++k) NextTerm(k);
    const Matrix low = Sum(order, h);
    // The higher sum as the lower one plus its tail h^{p+1} Σ_j S_{p+1+j} h^j; from the top
    // when h^{p+1} overflows (a long step of a slow system).
    Matrix high = Term(order + check_orders_);
    for (int k = order + check_orders_ - 1; k > order; --k) high = Term(k) + h * high;
    const double power = std::pow(h, order + 1);
    high = std::isfinite(power) ? Matrix(low + power * high) : Sum(order + check_orders_, h);
    Multiply(high, phi);
    Multiply(low, lower);
  }

  // x ← step · x, through BLAS for large n.
  void Multiply(const Matrix& step, Matrix& x) const {
    Matrix product(n_, n_);
    if constexpr (N == Eigen::Dynamic) {
      MultiplyInto(step, x, product);
    } else {
      product.noalias() = step * x;
    }
    x.swap(product);
  }

  // The order from the tolerance: for coefficients decaying like (ωh)^k/k! a step of order p
  // spans h ∝ p tol^{1/p}. p = −ln tol (23 at 1e-10) keeps the largest term, e^{ωh}, and with
  // it the rounding, small (docs/taylor-integrator.md). Clamped to where the series stays cheap.
  static int TaylorOrder(double rel_tol) {
    return std::clamp(static_cast<int>(std::ceil(-std::log(rel_tol))), 8, 36);
  }

  // Φ_k, the k-th Taylor coefficient of Φ at the step's start (a column of terms_).
  Eigen::Map<Matrix> Term(int k) { return Eigen::Map<Matrix>(terms_.col(k).data(), n_, n_); }
  Eigen::Map<const Matrix> Term(int k) const {
    return Eigen::Map<const Matrix>(terms_.col(k).data(), n_, n_);
  }

  Eigen::Map<const Matrix> Block(int b) const {
    return Eigen::Map<const Matrix>(series_ + static_cast<size_t>(b) * n_ * n_, n_, n_);
  }

  // The scalar series of each harmonic at the step's start t: weights_ holds, for harmonic w
  // and j = 0 … p, (wΩ)^j/j! · cos(wΩt + jπ/2) and · sin(wΩt + jπ/2), the Taylor coefficients
  // of cos wΩ(t + τ) and sin wΩ(t + τ) in τ (the jπ/2 turns are sign swaps).
  void SeriesOfHarmonics(double t) {
    const double c1 = std::cos(omega_ * t), s1 = std::sin(omega_ * t);
    double c = c1, s = s1;
    for (int w = 1; w <= shape_.harmonics; ++w) {
      double* cos_w = Weights(2 * (w - 1));
      double* sin_w = Weights(2 * (w - 1) + 1);
      double scale = 1;       // (wΩ)^j / j!
      double cj = c, sj = s;  // cos and sin of wΩt + jπ/2
      for (int j = 0; j <= series_order_; ++j) {
        cos_w[j] = scale * cj;
        sin_w[j] = scale * sj;
        const double turned = -sj;
        sj = cj;
        cj = turned;
        scale *= w * omega_ / (j + 1);
      }
      const double next_c = c * c1 - s * s1;
      s = s * c1 + c * s1;
      c = next_c;
    }
  }

  // Φ_0 = Φ, Φ_{k+1} = Σ_{j ≤ k} A_j Φ_{k−j} / (k + 1), up to the order; returns the order
  // computed. With left > 0, stops early when the series already reaches the end of the
  // interval, `left` ahead, within the tolerance — the last step of an interval, short
  // segments.
  int SeriesOfPhi(const Matrix& phi, double tol, double left) {
    Term(0) = phi;
    double power = 1;                                            // left^(k+1)
    double last_term = std::numeric_limits<double>::infinity();  // ‖Φ_k‖ left^k
    for (int k = 0; k < order_; ++k) {
      NextTerm(k);
      if (left == 0) continue;
      power *= left;
      const double term = terms_.col(k + 1).cwiseAbs().maxCoeff() * power;
      if (k + 1 >= kMinOrder && term <= tol && last_term <= tol) return k + 1;
      last_term = term;
    }
    return order_;
  }

  // Φ_{k+1} = (Ā Φ_k + Σ_w C_w X_w + S_w Y_w) / (k + 1), X_w = Σ_j cos_w[j] Φ_{k−j} and Y_w
  // likewise. In second-order form A = [0 D; A₂₁ A₂₂] with every harmonic in the lower rows:
  // the upper half of Φ_{k+1} is D times the lower half of Φ_k/(k + 1), and only the lower rows
  // need products; with constant damping (harmonics only in A₂₁) only the upper rows of X_w
  // and Y_w enter.
  void NextTerm(int k) {
    if constexpr (N == Eigen::Dynamic) {
      NextTermInBlas(k);
    } else {
      NextTermFixed(k);
    }
  }

  // Large n: Ā Φ_k, then the 2H sums stacked, [X_1; Y_1; …] (their rows that enter), and all
  // harmonics in one product with [C_1 S_1 …] — every product through BLAS. The sums take the
  // terms j whose weights are not lost in rounding (SummedTerms).
  void NextTermInBlas(int k) {
    MultiplyInto(Block(0).bottomRows(lower_.rows()), Term(k), lower_);
    if (shape_.harmonics > 0) {
      term_sizes_[static_cast<size_t>(k)] = Term(k).topRows(inner_).cwiseAbs().maxCoeff();
      // Column by column, so that a column of the sums stays in L1 while the terms pass once.
      const int terms = SummedTerms(k), sums = 2 * shape_.harmonics;
      for (int c = 0; c < n_; ++c) {
        auto out = harmonic_sums_.col(c);
        for (int j = 0; j < terms; ++j) {
          const auto term = Term(k - j).col(c).head(inner_);
          for (int column = 0; column < sums; ++column) {
            auto sum = out.segment(static_cast<Eigen::Index>(column) * inner_, inner_);
            if (j == 0) {
              sum = Weights(column)[0] * term;
            } else {
              sum += Weights(column)[j] * term;
            }
          }
        }
      }
      MultiplyInto(harmonic_blocks_, harmonic_sums_, lower_, 1.0);
    }
    FinishTerm(k, lower_);
  }

  // How many terms j = 0, 1, … of X_w = Σ_j c_{w,j} Φ_{k−j} to sum: the weights fall like
  // (wΩ)^j/j! while the terms grow like ρ(A)^{k−j}/(k−j)!, so where the harmonics are slow
  // against the fastest mode only the first few j count. The terms left out together bound
  // below half an ulp of the largest one (entrywise, over every harmonic): dropping them changes
  // the sums by less than their own rounding. On the 160-state finite-element shaft 45 % of the
  // terms are summed (docs/taylor-integrator.md).
  int SummedTerms(int k) const {
    double largest = 0, left_out = 0;
    std::array<double, kMaxTerms> bounds{};
    for (int j = 0; j <= k; ++j) {
      double weight = 0;
      for (int column = 0; column < 2 * shape_.harmonics; ++column)
        weight = std::max(
            weight, std::abs(weights_[static_cast<size_t>(column) * (series_order_ + 1) + j]));
      bounds[static_cast<size_t>(j)] = weight * term_sizes_[static_cast<size_t>(k - j)];
      largest = std::max(largest, bounds[static_cast<size_t>(j)]);
    }
    int terms = k + 1;
    while (terms > 1) {
      left_out += bounds[static_cast<size_t>(terms - 1)];
      if (!(left_out <= 0.5 * std::numeric_limits<double>::epsilon() * largest)) break;
      --terms;
    }
    return terms;
  }

  // n = 2, 4: a product is a few flops, so the harmonics are combined into A's series once per
  // step (SeriesOfA) and the recurrence convolves, k + 1 tiny products for order k — cheaper
  // here than 2H weighted sums per order (the 401 × 401 Mathieu map 15 % faster).
  void NextTermFixed(int k) {
    if constexpr (N != Eigen::Dynamic && N % 2 == 0) {
      constexpr int h = N / 2;
      if (shape_.second_order) {
        Eigen::Matrix<double, h, N> lower = a_[0].template bottomRows<h>() * Term(k);
        for (int j = 1; j <= k; ++j) {
          if (shape_.constant_damping) {
            lower.noalias() += a_[static_cast<size_t>(j)].template bottomLeftCorner<h, h>() *
                               Term(k - j).template topRows<h>();
          } else {
            lower.noalias() += a_[static_cast<size_t>(j)].template bottomRows<h>() * Term(k - j);
          }
        }
        FinishTerm(k, lower);
        return;
      }
    }
    Matrix next = a_[0] * Term(k);
    for (int j = 1; j <= k; ++j) next.noalias() += a_[static_cast<size_t>(j)] * Term(k - j);
    FinishTerm(k, next);
  }

  // A_j = A^(j)(t)/j!, j = 0 … p, from the harmonics' series (fixed sizes only).
  void SeriesOfA() {
    for (int j = 0; j <= series_order_; ++j) {
      Matrix& aj = a_[static_cast<size_t>(j)];
      aj = j == 0 ? Matrix(Block(0)) : Matrix::Zero(n_, n_);
      for (int column = 0; column < 2 * shape_.harmonics; ++column)
        aj += Weights(column)[j] * Block(1 + column);
    }
  }

  // Φ_{k+1} from its computed rows (all, or the lower half in second-order form).
  template <typename Rows>
  void FinishTerm(int k, const Rows& computed) {
    const double inv = 1.0 / (k + 1);
    auto next = Term(k + 1);
    constexpr int kRows = Rows::RowsAtCompileTime;
    if constexpr (N != Eigen::Dynamic && kRows != Eigen::Dynamic) {  // fixed sizes throughout
      next.template bottomRows<kRows>() = inv * computed;
      if constexpr (kRows < N)
        next.template topRows<N - kRows>() =
            inv * upper_diagonal_.asDiagonal() * Term(k).template bottomRows<N - kRows>();
    } else {
      const int rows = static_cast<int>(computed.rows()), skip = n_ - rows;
      next.bottomRows(rows) = inv * computed;
      if (skip > 0)
        next.topRows(skip) = inv * upper_diagonal_.asDiagonal() * Term(k).bottomRows(skip);
    }
  }

  // The series of harmonic (column / 2 + 1)'s cosine (even columns) or sine (odd), the
  // weights of C_w and S_w = Block(1 + column).
  double* Weights(int column) {
    return weights_.data() + static_cast<size_t>(column) * (series_order_ + 1);
  }

  // The longest h whose last two terms ‖Φ_k‖ h^k (k = p − 1, p) are within `tol` (the
  // tolerance at Φ's size): two terms, because one coefficient alone can vanish by symmetry
  // (Jorba and Zou 2005).
  double StepLength(double tol, int order) const {
    double h = std::numeric_limits<double>::infinity();
    for (int k : {order - 1, order}) {
      const double size = terms_.col(k).cwiseAbs().maxCoeff();
      if (!std::isfinite(size)) return std::numeric_limits<double>::quiet_NaN();
      if (size > 0) h = std::min(h, std::pow(tol / size, 1.0 / k));
    }
    return h;
  }

  int n_;
  int order_;         // p: the step length and the reported order without checked products
  int check_orders_;  // q: 0, or kCheckOrders with carry_local_errors
  int series_order_;  // p + q: the terms stored
  double omega_, rel_tol_, abs_tol_;
  const double* series_ = nullptr;
  TaylorSeriesShape shape_;
  int inner_ = 0;                // the rows of X_w, Y_w that enter (all, or the upper half)
  Eigen::MatrixXd terms_;        // Φ_0 … Φ_p at the step's start, one column each
  std::vector<double> weights_;  // the harmonics' scalar series (SeriesOfHarmonics)
  // Large n: max |Φ_k| over the rows that enter X_w (SummedTerms), [X_1; Y_1; … Y_H] of those
  // rows, and the lower rows of [C_1 S_1 … S_H]'s columns that multiply them.
  std::vector<double> term_sizes_;
  Eigen::MatrixXd harmonic_sums_;
  Eigen::MatrixXd harmonic_blocks_;
  Eigen::MatrixXd lower_;  // the rows of Φ_{k+1} that need products (large n)
  std::vector<Matrix> a_;  // A's series at the step's start (fixed sizes)
  // D of the second-order form, fixed-size for n = 2, 4.
  Eigen::Matrix<double, N == Eigen::Dynamic ? Eigen::Dynamic : N / 2, 1> upper_diagonal_;
  // The last step taken at the full order: a shorter interval end may be reached early.
  double full_step_ = std::numeric_limits<double>::infinity();
};

}  // namespace

double TaylorSeriesShape::ProductsPerOrder() const {
  // In second-order form a harmonic's product is (n/2 × n)(n × n), with constant damping
  // (n/2 × n/2)(n/2 × n): half a full product, or a quarter.
  const double products_of_harmonics = constant_damping ? 1.0 * harmonics : 2.0 * harmonics;
  return (1 + products_of_harmonics) * (second_order ? 0.5 : 1.0);
}

std::optional<TaylorSeriesShape> ShapeOfSeries(const PeriodicSystem& system) {
  TaylorSeriesShape shape;
  const double* series = system.RealSeriesA(&shape.harmonics);
  if (series == nullptr) return std::nullopt;
  const int n = system.states();
  if (n % 2 != 0) return shape;
  const int h = n / 2;
  auto block = [&](int b) {
    return Eigen::Map<const Eigen::MatrixXd>(series + static_cast<size_t>(b) * n * n, n, n);
  };
  const auto a0 = block(0);
  // A = [0 D; A₂₁ A₂₂], D diagonal, every harmonic zero in the upper rows.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < h; ++i)
      if (j != i + h && a0(i, j) != 0) return shape;
  for (int b = 1; b <= 2 * shape.harmonics; ++b)
    if (!block(b).topRows(h).isZero(0)) return shape;
  shape.second_order = true;
  shape.upper_diagonal = a0.topRightCorner(h, h).diagonal();
  shape.constant_damping = true;
  for (int b = 1; b <= 2 * shape.harmonics; ++b)
    if (!block(b).bottomRightCorner(h, h).isZero(0)) shape.constant_damping = false;
  return shape;
}

namespace {

template <int N>
std::vector<TransitionResult> RunTaylor(const PeriodicSystem& system,
                                        const std::vector<double>& times,
                                        const IntegratorOptions& options) {
  TaylorSeriesStepper<N> stepper(system, options);
  std::vector<TransitionResult> results;
  long steps_left = options.max_steps;
  for (size_t i = 0; i + 1 < times.size(); ++i) {
    TransitionResult r;
    r.ok = stepper.Transition(times[i], times[i + 1], r, steps_left);
    if (r.ok && !r.phi.allFinite()) {
      r.ok = false;
      r.message = kNotFiniteMessage;
    }
    results.push_back(std::move(r));
    if (!results.back().ok) break;
  }
  return results;
}

}  // namespace

std::vector<TransitionResult> TaylorTransitions(const PeriodicSystem& system,
                                                const std::vector<double>& times,
                                                const IntegratorOptions& options) {
  switch (system.states()) {
    case 2:
      return RunTaylor<2>(system, times, options);
    case 4:
      return RunTaylor<4>(system, times, options);
    default:
      return RunTaylor<Eigen::Dynamic>(system, times, options);
  }
}

}  // namespace ltp::internal
