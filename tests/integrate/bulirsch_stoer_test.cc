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

// The estimate's local error (docs/local-error-estimate.md): after an accepted step,
// previous_row_scale() · local_error() must be T_{k−1,k−1} − T_kk, the previous row's best
// value minus the accepted one. Reference: the extrapolation table built here from scratch for
// x' = λx — Gragg's modified midpoint rule with n = 2, 4, …, 2(k + 1) substeps and the
// Aitken–Neville recursion in h² — with k read off the scale (−(k + 1)²).
TEST(BulirschStoer, PreviousRowOffsetIsTheTablesLowerOrderValue) {
  using State = Eigen::Matrix<double, 1, 1>;
  const double lambda = -1.3;
  auto rhs = [lambda](const State& x, State& dxdt, double) { dxdt = lambda * x; };
  for (double tol : {1e-4, 1e-8, 1e-12}) {
    SCOPED_TRACE(testing::Message() << "tol = " << tol);
    BulirschStoer<State> bs(tol, tol, 1);
    State x = State::Constant(1.0);
    double t = 0, dt = 0.7, h = 0;  // a rejected attempt shortens dt: h is the accepted step
    for (int attempt = 0; attempt < 20 && h == 0; ++attempt) {
      const double tried = dt;
      if (bs.try_step(rhs, x, t, dt)) h = tried;
    }
    ASSERT_GT(h, 0);
    const int k = static_cast<int>(std::lround(std::sqrt(-bs.previous_row_scale()))) - 1;
    ASSERT_GE(k, 1);
    std::vector<std::vector<double>> table(k + 1);
    for (int j = 0; j <= k; ++j) {
      const int n = 2 * (j + 1);
      const double step = h / n;
      double x0 = 1.0, x1 = 1.0 + step * lambda;
      for (int i = 1; i < n; ++i) {
        const double next = x0 + 2 * step * lambda * x1;
        x0 = x1;
        x1 = next;
      }
      table[j].push_back(0.5 * (x0 + x1 + step * lambda * x1));
      for (int m = 1; m <= j; ++m) {
        const double r = static_cast<double>(n) / (2 * (j - m + 1));
        table[j].push_back(table[j][m - 1] + (table[j][m - 1] - table[j - 1][m - 1]) / (r * r - 1));
      }
    }
    const double accepted = table[k][k], previous = table[k - 1][k - 1];
    EXPECT_NEAR(x[0], accepted, 1e-14);
    EXPECT_NEAR(bs.previous_row_scale() * bs.local_error()[0], previous - accepted,
                1e-14 + 1e-9 * std::abs(previous - accepted));
    EXPECT_LT(std::abs(accepted - std::exp(lambda * h)), std::abs(previous - std::exp(lambda * h)));
  }
}

}  // namespace
}  // namespace ltp::internal
