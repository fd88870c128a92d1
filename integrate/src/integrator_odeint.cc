// kDopri5 and kRkf78: Boost.Odeint controlled Runge–Kutta steppers on vec(Φ) (n² doubles);
// kBulirschStoer: ltp's allocation-free copy of Boost's Bulirsch–Stoer (bulirsch_stoer.h).
// We drive try_step ourselves rather than calling integrate_adaptive: that lets us stop
// exactly at each restart point, count steps, and give up after max_steps without throwing.
// odeint default-constructs fixed-size Eigen states (uninitialised by design) and copies them
// before the first write; GCC cannot see that and warns inside the library headers.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <lapacke.h>

#include <array>
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <vector>

#include "bulirsch_stoer.h"
#include "integrator_internal.h"
#include "ltp/integrate/detail/matrix_product.h"

namespace ltp::internal {

namespace {

namespace odeint = boost::numeric::odeint;

// vec(Φ): heap storage for any n, or a fixed-size Eigen vector for small n. The fixed-size
// state lets the stepper's stage combinations compile to straight-line code without
// allocation: about 3x faster for the 2x2 Mathieu system, which matters in stability charts
// that integrate 10^5 small systems.
using DynamicState = std::vector<double>;
template <int N>
using FixedState = Eigen::Matrix<double, N * N, 1>;

// Φ' = A(t) Φ: one evaluation of A(t) into a preallocated matrix and one n×n·n×n product.
template <class State, int N = Eigen::Dynamic>
class MatrixRhs {
 public:
  MatrixRhs(const PeriodicSystem& system, long* evals)
      : system_(system), n_(system.states()), a_(n_, n_), evals_(evals) {
    if constexpr (N == Eigen::Dynamic) {
      a_.setZero(n_, n_);
    } else {
      a_.setZero();
      series_ = system.RealSeriesA(&harmonics_);
      omega_ = system.omega();
      if (series_) {
        a_ = Block(series_);
        series_second_order_ = SecondOrderForm() && SeriesKeepsSecondOrderForm();
      }
    }
  }
  MatrixRhs(const MatrixRhs&) = delete;  // passed by std::ref: no copy (and allocation) per step
  MatrixRhs& operator=(const MatrixRhs&) = delete;

  void SetPiece(double a, double b) {
    window_ = PieceWindow(a, b);
    for (auto& slot : cache_) slot.t = std::numeric_limits<double>::quiet_NaN();
  }

  void operator()(const State& x, State& dxdt, double t) {
    const double tw = window_(t);
    if constexpr (N != Eigen::Dynamic) {
      if (cache_stages_) {
        // Runge–Kutta–Fehlberg 7(8) evaluates at 13 stage times of which only 9 are distinct
        // (c = 0, 1/6 and 1 repeat, and the next step starts where this one ended): remember
        // the last few A(t).
        for (const auto& slot : cache_)
          if (slot.t == tw) {
            a_ = slot.a;
            Multiply(x, dxdt);
            return;
          }
      }
      // Fourier form: A(t) from the real series with fixed-size arithmetic, inline (the
      // general EvalA costs as much as the sincos for n = 2).
      if (series_)
        EvalSeries(tw);
      else
        system_.EvalA(tw, a_);
      if (cache_stages_) {
        cache_[next_slot_] = {tw, a_};
        next_slot_ = (next_slot_ + 1) % kCacheSlots;
      }
    } else {
      system_.EvalA(tw, a_);
    }
    ++*evals_;
    Multiply(x, dxdt);
  }

  void CacheStages(bool on) { cache_stages_ = on; }

  // A(t) = A₀ + Σ_w (cos wΩt C_w + sin wΩt S_w); in second-order form only the lower rows
  // change (the upper ones stay [0 I] from A₀).
  void EvalSeries(double t) {
    if constexpr (N != Eigen::Dynamic && N % 2 == 0) {
      if (series_second_order_) {
        AddSeries<N / 2>(t, N / 2);
        return;
      }
    }
    AddSeries<N>(t, 0);
  }

  // a_'s last `Rows` rows (from row `first`) from the series.
  template <int Rows>
  void AddSeries(double t, int first) {
    auto rows = a_.template middleRows<Rows>(first);
    rows = Block(series_).template middleRows<Rows>(first);
    if (harmonics_ == 0) return;
    double c1, s1;
    BasePhasor(t, c1, s1);
    double c = c1, s = s1;
    for (int w = 1; w <= harmonics_; ++w) {
      const double* cw = series_ + kBlockSize * (2 * w - 1);
      rows += c * Block(cw).template middleRows<Rows>(first) +
              s * Block(cw + kBlockSize).template middleRows<Rows>(first);
      const double next_c = c * c1 - s * s1;
      s = s * c1 + c * s1;
      c = next_c;
    }
  }

  // Every harmonic block of the series has zero upper rows, so A(t) keeps A₀'s [0 I] there.
  bool SeriesKeepsSecondOrderForm() const {
    if constexpr (N == Eigen::Dynamic || N % 2 != 0) {
      return false;
    } else {
      for (int b = 1; b <= 2 * harmonics_; ++b)
        if (!Block(series_ + kBlockSize * b).template topRows<N / 2>().isZero(0)) return false;
      return true;
    }
  }

  // cos Ωt, sin Ωt. Bulirsch–Stoer's modified-midpoint sequences evaluate at equally spaced
  // times t0 + h, t0 + 2h, … (a new h per sequence, each from the step's start t0), so the
  // phasor usually is the previous one turned by the same angle: one complex multiplication
  // instead of a sincos, which otherwise is a third of a small system's cost. When the spacing
  // changes (a new sequence), the phasor is turned from the anchor — the last phasor computed
  // from t itself, the step's start: a step begins where its predecessor's last sequence
  // ended — by t − anchor, which is the new spacing: one sincos per sequence instead of two.
  // Times t0 + kh round to the grid of t, so successive differences agree only to a few ulps
  // of t: turning by the cached angle then evaluates A at a time within those ulps — what
  // rounding t itself does. At most 32 turns between fresh phasors bound the drift by ~1e-14.
  void BasePhasor(double t, double& c1, double& s1) {
    const double omega = omega_;
    const double ulps = 4 * std::numeric_limits<double>::epsilon() * std::abs(t);
    const double d = t - last_t_;
    if (turns_ < kMaxTurns && std::abs(d - turn_d_) <= ulps) {
      Turn(last_c_, last_s_, c1, s1);
      ++turns_;
    } else if (std::abs(d) > ulps && std::isfinite(t - anchor_t_)) {
      turn_d_ = t - anchor_t_;
      turn_c_ = std::cos(omega * turn_d_);
      turn_s_ = std::sin(omega * turn_d_);
      Turn(anchor_c_, anchor_s_, c1, s1);
      turns_ = 1;
    } else {  // the first call, or a step's start (the time of the previous evaluation)
      c1 = std::cos(omega * t);
      s1 = std::sin(omega * t);
      turns_ = 0;
      turn_d_ = std::numeric_limits<double>::quiet_NaN();
      anchor_t_ = t;
      anchor_c_ = c1;
      anchor_s_ = s1;
    }
    last_t_ = t;
    last_c_ = c1;
    last_s_ = s1;
  }

  void Turn(double c, double s, double& c1, double& s1) const {
    c1 = c * turn_c_ - s * turn_s_;
    s1 = s * turn_c_ + c * turn_s_;
  }

  void Multiply(const State& x, State& dxdt) const {
    Eigen::Map<const Eigen::Matrix<double, N, N>> phi(x.data(), n_, n_);
    Eigen::Map<Eigen::Matrix<double, N, N>> dphi(dxdt.data(), n_, n_);
    if constexpr (N == Eigen::Dynamic) {
      if (SecondOrderForm(false)) {
        const int h = n_ / 2;
        dphi.topRows(h) = a_.topRightCorner(h, h).diagonal().asDiagonal() * phi.bottomRows(h);
        MultiplyInto(a_.bottomRows(h), phi, dphi.bottomRows(h));
        return;
      }
      MultiplyInto(a_, phi, dphi);
      return;
    } else if constexpr (N % 2 == 0) {
      if (series_second_order_) {
        dphi.template topRows<N / 2>() = phi.template bottomRows<N / 2>();
        dphi.template bottomRows<N / 2>().noalias() = a_.template bottomRows<N / 2>() * phi;
        return;
      }
    }
    dphi.noalias() = a_ * phi;
  }

  // The first-order form of a second-order system, A = [0 I; A₂₁ A₂₂] (every second-order
  // scene): the upper half of AΦ is the lower half of Φ, and only the lower half needs a
  // product, half the flops. Checked at every evaluation (n²/2 comparisons against n³
  // multiply-adds), so a system that has that form only at some times is still right. With
  // `unit` false the upper right block may be any diagonal D: balanced states
  // (docs/model-sizes.md) turn I into powers of two, and the upper half of AΦ is then D times
  // the lower half of Φ (the finite-element rotor in SI units, always balanced: products halved).
  bool SecondOrderForm(bool unit = true) const {
    if (n_ % 2 != 0) return false;
    const int h = n_ / 2;
    for (int j = 0; j < n_; ++j) {
      const double* column = a_.data() + static_cast<size_t>(j) * n_;
      for (int i = 0; i < h; ++i)
        if (j == i + h ? unit && column[i] != 1.0 : column[i] != 0.0) return false;
    }
    return true;
  }

  // ||A(t)||_inf, for the initial step.
  double NormA(double t) {
    system_.EvalA(window_(t), a_);
    ++*evals_;
    return a_.template lpNorm<Eigen::Infinity>();
  }

 private:
  const PeriodicSystem& system_;
  int n_;
  Eigen::Matrix<double, N, N> a_;
  long* evals_;
  PieceWindow window_;
  struct Slot {
    double t = std::numeric_limits<double>::quiet_NaN();  // NaN never compares equal
    Eigen::Matrix<double, N == Eigen::Dynamic ? 1 : N, N == Eigen::Dynamic ? 1 : N> a;
  };
  static constexpr int kCacheSlots = 16;
  std::array<Slot, N == Eigen::Dynamic ? 1 : kCacheSlots> cache_{};
  int next_slot_ = 0;
  bool cache_stages_ = false;
  // Fourier form with fixed N: evaluated inline, as blocks of N × N column-major doubles.
  static constexpr int kBlockSize = N == Eigen::Dynamic ? 1 : N * N;
  using Block = Eigen::Map<
      const Eigen::Matrix<double, N == Eigen::Dynamic ? 1 : N, N == Eigen::Dynamic ? 1 : N>>;
  const double* series_ = nullptr;
  int harmonics_ = 0;
  bool series_second_order_ = false;  // A = [0 I; A₂₁(t) A₂₂(t)] at every t
  // BasePhasor's state: last time and phasor, the last turn (and how many since a fresh
  // phasor), the anchor (the last phasor computed from t itself).
  static constexpr int kMaxTurns = 32;
  double last_t_ = std::numeric_limits<double>::quiet_NaN(), last_c_ = 1, last_s_ = 0;
  double turn_d_ = std::numeric_limits<double>::quiet_NaN(), turn_c_ = 1, turn_s_ = 0;
  int turns_ = 0;
  double anchor_t_ = std::numeric_limits<double>::quiet_NaN(), anchor_c_ = 1, anchor_s_ = 0;
  double omega_ = 0;
};

bool Accepted(odeint::controlled_step_result result) { return result == odeint::success; }
bool Accepted(bool accepted) { return accepted; }

template <class State>
bool AllFinite(const State& x) {
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return true;
}

template <class State>
bool BelowOverflow(const State& x) {
  for (double v : x)
    if (!(std::abs(v) < 1e300)) return false;
  return true;
}

// solved = y⁻¹ rhs (rhs: the n² entries of an n × n matrix); LAPACK for large n. A singular y
// leaves non-finite entries, which drop the carried errors (ComputeSegmentGrid).
template <class Y, class State, class Square>
void SolveInto(const Y& y, const State& rhs, Square& lu, std::vector<lapack_int>& pivots,
               Square& solved) {
  const Eigen::Index n = y.rows();
  if constexpr (Square::RowsAtCompileTime == Eigen::Dynamic) {
    lu = y;
    solved = Eigen::Map<const Square>(rhs.data(), n, n);
    const lapack_int m = static_cast<lapack_int>(n);
    if (LAPACKE_dgesv(LAPACK_COL_MAJOR, m, m, lu.data(), m, pivots.data(), solved.data(), m) != 0)
      solved.setConstant(std::numeric_limits<double>::quiet_NaN());
  } else {
    solved = y.partialPivLu().solve(Eigen::Map<const Square>(rhs.data(), n, n));
  }
}

// Integrates every piece from Φ = I and multiplies the pieces' transitions into the current
// factor; a piece ending at an output point closes the factor (one TransitionResult each).
// At a jump of A (a piece with `restart`) the stepper starts afresh from an initial step; across
// an output point that is not a jump it keeps its step size and order, so splitting a period
// into many factors costs little more than integrating it in one go.
template <class State, int N, class Controlled>
class PieceIntegration {
 public:
  PieceIntegration(Controlled& stepper, int order, const PeriodicSystem& system,
                   const std::vector<Piece>& pieces, const IntegratorOptions& options)
      : stepper_(stepper),
        order_(order),
        options_(options),
        pieces_(pieces),
        n_(system.states()),
        x_(StateOfSize(n_)),
        piece_phi_(x_.data(), n_, n_),
        product_(n_, n_),
        pivots_(carry_ ? n_ : 0),
        rhs_(system, &rhs_evals_) {
    result_.phi = Eigen::MatrixXd::Identity(n_, n_);
    if (carry_) {
      carried_.setZero(n_, n_);
      result_.local_error_effect.setZero(n_, n_);
    }
    // Repeated stage times: Runge–Kutta tableaus (rkf78, dopri5), not Bulirsch–Stoer's substeps.
    rhs_.CacheStages(options.type != IntegratorType::kBulirschStoer);
  }
  PieceIntegration(const PieceIntegration&) = delete;  // piece_phi_ points into x_
  PieceIntegration& operator=(const PieceIntegration&) = delete;

  std::vector<TransitionResult> Run() {
    for (const Piece& piece : pieces_) {
      StartPiece(piece);
      if (!IntegratePiece(piece.t0, piece.t1)) return std::move(results_);
      if (carry_) CarryPieceErrors();
      product_.noalias() = piece_phi_ * result_.phi;
      result_.phi.swap(product_);
      if (piece.output) CloseFactor();
    }
    return std::move(results_);
  }

 private:
  static constexpr bool kHasLocalError = requires(Controlled & s) { s.local_error(); };
  static constexpr bool kHasReset = requires(Controlled & s) { s.reset(); };

  static State StateOfSize(int n) {
    State x;
    if constexpr (N == Eigen::Dynamic) x.resize(static_cast<size_t>(n) * n);
    return x;
  }

  // Local-error propagation (docs/local-error-estimate.md): within a piece, the step ending at
  // t_i with local error l_i moves Φ(b, a) by Φ(b, t_i) l_i = Y_b Y_i⁻¹ l_i (Y = piece_phi), so
  // G = Σ Y_i⁻¹ l_i and the piece's effect is Y_b G; across pieces δF ← P δF + (Y_b G) F.
  static bool CarriesLocalErrors(const IntegratorOptions& options) {
    bool carry = false;
    if constexpr (kHasLocalError) carry = options.carry_local_errors;
    return carry;
  }

  // Φ restarts at I; the step size too after a jump (or before the first step).
  void StartPiece(const Piece& piece) {
    const double a = piece.t0, b = piece.t1;
    piece_phi_.setIdentity();
    rhs_.SetPiece(a, b);
    if (piece.restart || dt_ <= 0) {
      if constexpr (kHasReset) stepper_.reset();
      dt_ = InitialStep(rhs_.NormA(0.5 * (a + b)), b - a, options_.rel_tol, order_,
                        TaylorErrorConstant(order_));
    } else if (fsal_) {
      if constexpr (kHasReset) stepper_.reset();
    }
  }

  // Steps from a to b, landing exactly on b; false after a failure (recorded by Fail).
  bool IntegratePiece(double a, double b) {
    double t = a;
    while (t < b) {
      if (attempts_ >= options_.max_steps) {
        std::ostringstream s;
        s << ToString(options_.type) << ": max_steps = " << options_.max_steps
          << " reached at t = " << t << " (interval [" << pieces_.front().t0 << ", "
          << pieces_.back().t1 << "]); the system may be stiff: try cvode";
        return Fail(s.str(), true);
      }
      ++attempts_;
      if (!TryStep(t, b)) return false;
      if (t < b && t + dt_ == t) {
        std::ostringstream s;
        s << ToString(options_.type) << ": step size underflow at t = " << t;
        return Fail(s.str(), false);
      }
    }
    return true;
  }

  // One attempted step from t (advanced when accepted); dt_ becomes the controller's proposal.
  // False after a failure (recorded by Fail).
  bool TryStep(double& t, double b) {
    const bool last = dt_ >= b - t;
    const double proposal = dt_;
    double h = last ? b - t : dt_;
    const double before = t;
    if (Accepted(stepper_.try_step(std::ref(rhs_), x_, t, h))) {
      ++result_.steps;
      if (options_.on_advance) options_.on_advance((last ? b : t) - before);
      if (last) {
        t = b;  // land exactly on the restart point
        // The landing step was cut short; its successor may be as long as the step the
        // controller wanted before the cut.
        h = std::max(h, proposal);
      }
      if (!AllFinite(x_)) return Fail(kNotFiniteMessage, false);
      if constexpr (kHasLocalError) {
        if (carry_) {
          SolveInto(piece_phi_, stepper_.local_error(), lu_, pivots_, solved_);
          carried_ += stepper_.previous_row_scale() * solved_;
        }
      }
    } else if (!BelowOverflow(x_)) {
      // A rejected step of a state near the double range: the error estimate itself
      // overflows (inf − inf), so every smaller step is rejected too (seen with
      // Bulirsch–Stoer's extrapolation). Report the overflow instead of spinning.
      return Fail(kNotFiniteMessage, false);
    }
    dt_ = h;  // the controller's proposal (larger after success, smaller after a rejection)
    return true;
  }

  // The piece's carried local errors into the factor's: δF ← P δF + (Y_b G) F.
  void CarryPieceErrors() {
    product_.noalias() = piece_phi_ * result_.local_error_effect;
    solved_.noalias() = piece_phi_ * carried_;
    product_.noalias() += solved_ * result_.phi;
    result_.local_error_effect.swap(product_);
    carried_.setZero(n_, n_);
  }

  // The factor ends at an output point: reported, and the next one starts at I.
  void CloseFactor() {
    result_.ok = true;
    result_.rhs_evals = rhs_evals_;
    rhs_evals_ = 0;
    results_.push_back(std::move(result_));
    result_ = TransitionResult{};
    result_.phi = Eigen::MatrixXd::Identity(n_, n_);
    if (carry_) result_.local_error_effect.setZero(n_, n_);
  }

  // The failed factor as the last result: Φ so far (for diagnostics) or NaN.
  bool Fail(std::string message, bool keep_partial) {
    if (keep_partial) {
      product_.noalias() = piece_phi_ * result_.phi;  // Φ(t, t0) so far, for diagnostics
      result_.phi.swap(product_);
    } else {
      result_.phi.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    result_.message = std::move(message);
    result_.rhs_evals = rhs_evals_;
    results_.push_back(std::move(result_));
    return false;
  }

  using Square = Eigen::Matrix<double, N, N>;
  Controlled& stepper_;
  const int order_;
  const IntegratorOptions& options_;
  const std::vector<Piece>& pieces_;
  const int n_;
  State x_;
  Eigen::Map<Square> piece_phi_;  // Φ over the current piece: x_ as a matrix
  Eigen::MatrixXd product_;
  std::vector<TransitionResult> results_;
  TransitionResult result_;  // the factor being accumulated
  const bool carry_ = CarriesLocalErrors(options_);
  Square carried_, solved_, lu_;
  std::vector<lapack_int> pivots_;
  long rhs_evals_ = 0;
  MatrixRhs<State, N> rhs_;
  // dopri5 keeps the derivative of its last stage (FSAL); Φ restarts at I on every piece, so
  // that derivative is stale there even without a jump.
  const bool fsal_ = options_.type == IntegratorType::kDopri5;
  long attempts_ = 0;
  double dt_ = 0;
};

template <class State, int N, class Controlled>
std::vector<TransitionResult> Run(Controlled stepper, int order, const PeriodicSystem& system,
                                  const std::vector<Piece>& pieces,
                                  const IntegratorOptions& options) {
  PieceIntegration<State, N, Controlled> integration(stepper, order, system, pieces, options);
  return integration.Run();
}

template <class State, int N>
std::vector<TransitionResult> RunOdeint(const PeriodicSystem& system,
                                        const std::vector<Piece>& points,
                                        const IntegratorOptions& options) {
  using Algebra =
      std::conditional_t<N == Eigen::Dynamic, odeint::range_algebra, odeint::vector_space_algebra>;
  if (options.type == IntegratorType::kBulirschStoer) {
    using BsState = std::conditional_t<N == Eigen::Dynamic, Eigen::VectorXd, State>;
    const Eigen::Index size = static_cast<Eigen::Index>(system.states()) * system.states();
    return Run<BsState, N>(BulirschStoer<BsState>(options.abs_tol, options.rel_tol, size), 8,
                           system, points, options);
  }
  if (options.type == IntegratorType::kRkf78) {
    return Run<State, N>(
        odeint::make_controlled(
            options.abs_tol, options.rel_tol,
            odeint::runge_kutta_fehlberg78<State, double, State, double, Algebra>()),
        7, system, points, options);
  }
  return Run<State, N>(
      odeint::make_controlled(options.abs_tol, options.rel_tol,
                              odeint::runge_kutta_dopri5<State, double, State, double, Algebra>()),
      4, system, points, options);
}

}  // namespace

std::vector<TransitionResult> OdeintTransitions(const PeriodicSystem& system,
                                                const std::vector<Piece>& pieces,
                                                const IntegratorOptions& options) {
  switch (system.states()) {
    case 2:
      return RunOdeint<FixedState<2>, 2>(system, pieces, options);
    case 3:
      return RunOdeint<FixedState<3>, 3>(system, pieces, options);
    case 4:
      return RunOdeint<FixedState<4>, 4>(system, pieces, options);
    default:
      return RunOdeint<DynamicState, Eigen::Dynamic>(system, pieces, options);
  }
}

}  // namespace ltp::internal
