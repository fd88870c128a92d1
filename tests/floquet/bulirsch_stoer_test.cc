// ltp's allocation-free Bulirsch–Stoer stepper against the one it copies, Boost.Odeint's
// bulirsch_stoer: the same algorithm must take the same steps and give the same values (the
// only differences allowed are none at all: the arithmetic is the same, operation for operation).
// And against closed forms, so the pair is not only self-consistent.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // odeint's fixed-size Eigen states
#include "bulirsch_stoer.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>
#include <cmath>
#include <numbers>
#include <vector>

namespace ltp::internal {
namespace {

namespace odeint = boost::numeric::odeint;

// Φ' = A(t)Φ on vec(Φ) for the damped Mathieu-like system x'' + c x' + (a − 2q cos 2t) x = 0
// (n = 2) or two such oscillators coupled by k (n = 4).
template <class State>
struct MatrixRhs {
  int n;
  double a, q, c, k;
  void operator()(const State& x, State& dxdt, double t) const {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    const int h = n / 2;
    A.topRightCorner(h, h).setIdentity();
    for (int i = 0; i < h; ++i) {
      A(h + i, i) = -(a * (i + 1) - 2 * q * std::cos(2 * t));
      A(h + i, h + i) = -c;
      if (h > 1) A(h + i, (i + 1) % h) += k;
    }
    Eigen::Map<const Eigen::MatrixXd> phi(x.data(), n, n);
    Eigen::Map<Eigen::MatrixXd> dphi(dxdt.data(), n, n);
    dphi = A * phi;
  }
};

bool Accepted(odeint::controlled_step_result result) { return result == odeint::success; }
bool Accepted(bool accepted) { return accepted; }

struct Trace {
  std::vector<double> t, dt;  // after every attempt
  std::vector<bool> accepted;
  Eigen::VectorXd x;
};

// Drives a stepper over [0, T] the way ltp's integrator does: the last step is cut to land on T.
template <class State, class Stepper>
Trace Drive(Stepper& stepper, const MatrixRhs<State>& rhs, double T, double dt0) {
  State x(rhs.n * rhs.n);
  Eigen::Map<Eigen::MatrixXd>(x.data(), rhs.n, rhs.n).setIdentity();
  Trace trace;
  double t = 0, dt = dt0;
  while (t < T && trace.t.size() < 10000) {
    const bool last = dt >= T - t;
    double h = last ? T - t : dt;
    const bool ok = Accepted(stepper.try_step(rhs, x, t, h));
    if (ok && last) t = T;
    trace.t.push_back(t);
    trace.dt.push_back(h);
    trace.accepted.push_back(ok);
    dt = h;
  }
  trace.x = Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
  return trace;
}

// Returns how many attempts were rejected.
template <class State>
long ExpectSameAsBoost(const MatrixRhs<State>& rhs, double tol, double dt0) {
  using Algebra = odeint::vector_space_algebra;
  odeint::bulirsch_stoer<State, double, State, double, Algebra> boost_bs(tol, tol);
  BulirschStoer<State> ltp_bs(tol, tol, rhs.n * rhs.n);
  const double T = std::numbers::pi;
  const Trace want = Drive(boost_bs, rhs, T, dt0);
  const Trace got = Drive(ltp_bs, rhs, T, dt0);
  EXPECT_GT(want.t.size(), 3u);
  EXPECT_EQ(got.t, want.t);
  EXPECT_EQ(got.dt, want.dt);
  EXPECT_EQ(got.accepted, want.accepted);
  EXPECT_EQ(got.x, want.x);  // bit for bit
  return std::count(want.accepted.begin(), want.accepted.end(), false);
}

TEST(BulirschStoer, TakesBoostsStepsAndValues) {
  using Fixed = Eigen::Matrix<double, 4, 1>;
  for (double q : {0.0, 1.5, 6.0})
    for (double tol : {1e-6, 1e-10, 1e-13}) {
      SCOPED_TRACE(testing::Message() << "q = " << q << ", tol = " << tol);
      ExpectSameAsBoost(MatrixRhs<Fixed>{2, 4.99, q, 0.1, 0}, tol, 0.01);
    }
  // Dynamic size (n = 4, 16 doubles), with a rejected first step (dt0 far too long).
  EXPECT_GT(ExpectSameAsBoost(MatrixRhs<Eigen::VectorXd>{4, 3.0, 2.0, 0.05, 0.3}, 1e-10, 2.0), 0);
}

TEST(BulirschStoer, MatchesTheHarmonicOscillatorsClosedForm) {
  // q = c = 0: x'' + a x = 0, Φ(T) = [cos ωT, sin ωT / ω; −ω sin ωT, cos ωT], ω = √a.
  using Fixed = Eigen::Matrix<double, 4, 1>;
  const double a = 4.99, w = std::sqrt(a), T = std::numbers::pi;
  BulirschStoer<Fixed> bs(1e-12, 1e-12, 4);
  const Trace got = Drive(bs, MatrixRhs<Fixed>{2, a, 0, 0, 0}, T, 0.01);
  const Eigen::Vector4d want(std::cos(w * T), -w * std::sin(w * T), std::sin(w * T) / w,
                             std::cos(w * T));
  EXPECT_LT((got.x - want).cwiseAbs().maxCoeff(), 1e-10);
}

}  // namespace
}  // namespace ltp::internal
