// kDopri5 and kRkf78: Boost.Odeint controlled Runge–Kutta steppers on vec(Φ) (n² doubles).
// We drive try_step ourselves rather than calling integrate_adaptive: that lets us stop
// exactly at each restart point, count steps, and give up after max_steps without throwing.
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <vector>

#include "integrator_internal.h"

namespace ltp::internal {

namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;

// Φ' = A(t) Φ: one evaluation of A(t) into a preallocated matrix and one n×n·n×n product.
class MatrixRhs {
 public:
  MatrixRhs(const PeriodicSystem& system, long* evals)
      : system_(system), n_(system.states()), a_(n_, n_), evals_(evals) {}
  MatrixRhs(const MatrixRhs&) = delete;  // passed by std::ref: no copy (and allocation) per step
  MatrixRhs& operator=(const MatrixRhs&) = delete;

  void SetPiece(double a, double b) { window_ = PieceWindow(a, b); }

  void operator()(const State& x, State& dxdt, double t) {
    system_.EvalA(window_(t), a_);
    ++*evals_;
    Eigen::Map<const Eigen::MatrixXd> phi(x.data(), n_, n_);
    Eigen::Map<Eigen::MatrixXd> dphi(dxdt.data(), n_, n_);
    dphi.noalias() = a_ * phi;
  }

  // ||A(t)||_inf, for the initial step.
  double NormA(double t) {
    system_.EvalA(window_(t), a_);
    ++*evals_;
    return a_.lpNorm<Eigen::Infinity>();
  }

 private:
  const PeriodicSystem& system_;
  int n_;
  Eigen::MatrixXd a_;
  long* evals_;
  PieceWindow window_;
};

bool AllFinite(const State& x) {
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return true;
}

// Integrates every piece from Φ = I and multiplies the pieces' transitions.
template <class Controlled>
TransitionResult Run(Controlled stepper, int order, const PeriodicSystem& system,
                     const std::vector<double>& points, const IntegratorOptions& options) {
  const int n = system.states();
  TransitionResult result;
  result.phi = Eigen::MatrixXd::Identity(n, n);
  State x(static_cast<size_t>(n) * n);
  Eigen::Map<Eigen::MatrixXd> piece_phi(x.data(), n, n);
  Eigen::MatrixXd product(n, n);
  MatrixRhs rhs(system, &result.rhs_evals);
  long attempts = 0;

  for (size_t p = 0; p + 1 < points.size(); ++p) {
    const double a = points[p], b = points[p + 1];
    piece_phi.setIdentity();
    rhs.SetPiece(a, b);
    // Forget the FSAL derivative of the previous piece (dopri5): A may jump at a.
    if constexpr (requires { stepper.reset(); }) stepper.reset();
    double t = a;
    double dt = InitialStep(rhs.NormA(0.5 * (a + b)), b - a, options.rel_tol, order);
    while (t < b) {
      if (attempts >= options.max_steps) {
        std::ostringstream s;
        s << ToString(options.type) << ": max_steps = " << options.max_steps
          << " reached at t = " << t << " (interval [" << points.front() << ", " << points.back()
          << "]); the system may be stiff: try cvode";
        result.message = s.str();
        product.noalias() = piece_phi * result.phi;  // Φ(t, t0) so far, for diagnostics
        result.phi.swap(product);
        return result;
      }
      ++attempts;
      const bool last = dt >= b - t;
      double h = last ? b - t : dt;
      if (stepper.try_step(std::ref(rhs), x, t, h) == odeint::success) {
        ++result.steps;
        if (last) t = b;  // land exactly on the restart point
        if (!AllFinite(x)) {
          result.phi.setConstant(std::numeric_limits<double>::quiet_NaN());
          result.message = kNotFiniteMessage;
          return result;
        }
      }
      dt = h;  // the controller's proposal (larger after success, smaller after a rejection)
      if (t < b && t + dt == t) {
        std::ostringstream s;
        s << ToString(options.type) << ": step size underflow at t = " << t;
        result.message = s.str();
        return result;
      }
    }
    product.noalias() = piece_phi * result.phi;
    result.phi.swap(product);
  }
  result.ok = true;
  return result;
}

}  // namespace

TransitionResult OdeintTransition(const PeriodicSystem& system, const std::vector<double>& points,
                                  const IntegratorOptions& options) {
  if (options.type == IntegratorType::kRkf78) {
    return Run(odeint::make_controlled(options.abs_tol, options.rel_tol,
                                       odeint::runge_kutta_fehlberg78<State>()),
               7, system, points, options);
  }
  return Run(odeint::make_controlled(options.abs_tol, options.rel_tol,
                                     odeint::runge_kutta_dopri5<State>()),
             4, system, points, options);
}

}  // namespace ltp::internal
