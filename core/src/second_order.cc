#include "ltp/core/second_order.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <sstream>

#include "ltp/core/error.h"

namespace ltp {
namespace {

using Eigen::MatrixXd;

void CheckMass(const SecondOrderSystem& s, double t, double min_rcond) {
  MatrixXd m(s.dofs, s.dofs);
  s.M(t, m);
  std::ostringstream message;
  message << "mass matrix M(t) is ";
  if (!m.allFinite()) {
    message << "not finite at t = " << t;
    throw SingularMassError(message.str());
  }
  const Eigen::PartialPivLU<MatrixXd> lu(m);
  // Eigen's estimate is meaningless (it can return 1) when a pivot is exactly zero.
  const bool zero_pivot = (lu.matrixLU().diagonal().array() == 0).any();
  const double rcond = zero_pivot ? 0.0 : lu.rcond();
  if (!(rcond >= min_rcond)) {  // also true for a NaN estimate
    message << "singular at t = " << t << " (rcond " << rcond << ")";
    throw SingularMassError(message.str());
  }
}

// The times at which M is checked: a uniform grid plus every breakpoint and both sides of it.
std::vector<double> CheckTimes(const SecondOrderSystem& s, int points) {
  const double T = s.period;
  std::vector<double> times;
  for (int i = 0; i < points; ++i) times.push_back(T * i / points);
  const double side = 1e-9 * T;
  for (double b : s.breakpoints) {
    times.push_back(b);
    times.push_back(b + side < T ? b + side : b + side - T);
    times.push_back(b - side >= 0 ? b - side : b - side + T);
  }
  return times;
}

// Catches a NaN stiffness, damping or input matrix at build time rather than in an integrator.
void CheckFinite(const PeriodicSystem::MatrixFunction& f, const char* name, int rows, int cols,
                 double t) {
  if (!f) return;
  MatrixXd value = MatrixXd::Zero(rows, cols);
  f(t, value);
  if (!value.allFinite())
    throw InputError(std::string("second-order ") + name +
                     "(t) is not finite at t = " + std::to_string(t));
}

}  // namespace

PeriodicSystem FromSecondOrder(const SecondOrderSystem& system, const SecondOrderOptions& options) {
  const int q = system.dofs, m = system.inputs, p = system.outputs;
  if (q <= 0) throw InputError("a second-order system needs at least one coordinate (dofs > 0)");
  if (m < 0 || p < 0) throw InputError("negative number of inputs or outputs");
  if (!system.M) throw InputError("second-order system: the mass matrix M(t) is missing");
  if (!system.K) throw InputError("second-order system: the stiffness matrix K(t) is missing");
  if (m > 0 && !system.F)
    throw InputError("second-order system has inputs but the input matrix F(t) is missing");
  if (options.check_points < 1) throw InputError("check_points must be at least 1");
  if (!std::isfinite(system.period) || system.period <= 0)
    throw InputError("period must be finite and > 0");

  for (double t : CheckTimes(system, options.check_points)) CheckMass(system, t, options.min_rcond);
  CheckFinite(system.K, "K", q, q, 0);
  CheckFinite(system.D, "D", q, q, 0);
  if (m > 0) CheckFinite(system.F, "F", q, m, 0);
  if (p > 0) CheckFinite(system.Cd, "Cd", p, q, 0);
  if (p > 0) CheckFinite(system.Cv, "Cv", p, q, 0);

  // Shared, immutable: every evaluation factorises M afresh, so calls may run in parallel
  // (the work matrices are per thread, kept across calls: no allocation per evaluation).
  auto s = std::make_shared<const SecondOrderSystem>(system);
  PeriodicSystem::Functions functions;
  functions.A = [s](double t, Eigen::Ref<MatrixXd> out) {
    const int n = s->dofs;
    thread_local MatrixXd mass, stiffness_damping, solved;
    thread_local Eigen::PartialPivLU<MatrixXd> lu;
    mass.resize(n, n);
    stiffness_damping.resize(n, 2 * n);
    s->M(t, mass);
    lu.compute(mass);
    s->K(t, stiffness_damping.leftCols(n));
    if (s->D)
      s->D(t, stiffness_damping.rightCols(n));
    else
      stiffness_damping.rightCols(n).setZero();
    solved.noalias() = lu.solve(stiffness_damping);  // M⁻¹[K D] in one solve
    out.topLeftCorner(n, n).setZero();
    out.topRightCorner(n, n).setIdentity();
    out.bottomRows(n) = -solved;
  };
  if (m > 0) {
    functions.B = [s](double t, Eigen::Ref<MatrixXd> out) {
      const int n = s->dofs;
      MatrixXd mass(n, n), f(n, s->inputs);
      s->M(t, mass);
      s->F(t, f);
      out.topRows(n).setZero();
      out.bottomRows(n) = mass.partialPivLu().solve(f);
    };
  }
  if (p > 0) {
    functions.C = [s](double t, Eigen::Ref<MatrixXd> out) {
      const int n = s->dofs;
      out.setZero();
      auto displacement = out.leftCols(n);
      auto velocity = out.rightCols(n);
      if (s->Cd) s->Cd(t, displacement);
      if (s->Cv) s->Cv(t, velocity);
    };
  }
  return PeriodicSystem::FromFunctions(system.period, 2 * q, m, p, std::move(functions),
                                       system.breakpoints);
}

namespace {

// A series' value at t into `out` (zero for an empty series).
PeriodicSystem::MatrixFunction SeriesFunction(const FourierMatrix& f, double omega) {
  if (f.rows() == 0 || f.cols() == 0) return {};
  return [f, omega](double t, Eigen::Ref<MatrixXd> out) { f.Evaluate(t, omega, out); };
}

}  // namespace

PeriodicSystem FromSecondOrderSeries(double period, const FourierMatrix& M, const FourierMatrix& D,
                                     const FourierMatrix& K, const FourierMatrix& F,
                                     const FourierMatrix& Cd, const FourierMatrix& Cv,
                                     const SecondOrderOptions& options) {
  const int q = M.rows();
  auto check = [&](const FourierMatrix& f, const char* name, int rows, int cols, bool optional) {
    if (optional && f.rows() == 0 && f.cols() == 0) return;
    if (f.rows() != rows || f.cols() != cols)
      throw InputError(std::string("second-order ") + name + " is " + std::to_string(f.rows()) +
                       "×" + std::to_string(f.cols()) + ", expected " + std::to_string(rows) + "×" +
                       std::to_string(cols));
  };
  if (q == 0 || M.cols() != q) throw InputError("second-order M must be square and not empty");
  const int m = F.cols();
  const int p = std::max(Cd.rows(), Cv.rows());
  check(D, "D", q, q, true);
  check(K, "K", q, q, false);
  check(F, "F", q, m, true);
  check(Cd, "Cd", p, q, true);
  check(Cv, "Cv", p, q, true);
  if (!std::isfinite(period) || period <= 0) throw InputError("period must be finite and > 0");
  const double omega = 2 * std::acos(-1.0) / period;
  if (M.max_harmonic() > 0) {  // periodic mass: M(t)⁻¹ at every evaluation
    SecondOrderSystem s;
    s.period = period;
    s.dofs = q;
    s.inputs = m;
    s.outputs = p;
    s.M = SeriesFunction(M, omega);
    s.D = SeriesFunction(D, omega);
    s.K = SeriesFunction(K, omega);
    s.F = SeriesFunction(F, omega);
    s.Cd = SeriesFunction(Cd, omega);
    s.Cv = SeriesFunction(Cv, omega);
    return FromSecondOrder(s, options);
  }
  SecondOrderSystem constant;  // for the one mass check
  constant.period = period;
  constant.dofs = q;
  constant.M = SeriesFunction(M, omega);
  CheckMass(constant, 0, options.min_rcond);
  const Eigen::PartialPivLU<MatrixXd> lu(M[0].real());
  auto solve = [&](const Eigen::MatrixXcd& x) -> Eigen::MatrixXcd {
    Eigen::MatrixXcd out(x.rows(), x.cols());
    out.real() = lu.solve(MatrixXd(x.real()));
    out.imag() = lu.solve(MatrixXd(x.imag()));
    return out;
  };
  const int H = std::max(
      {D.max_harmonic(), K.max_harmonic(), F.max_harmonic(), Cd.max_harmonic(), Cv.max_harmonic()});
  FourierMatrix a(2 * q, 2 * q, H), b(2 * q, m, H), c(p, 2 * q, H);
  for (int w = -H; w <= H; ++w) {
    Eigen::MatrixXcd aw = Eigen::MatrixXcd::Zero(2 * q, 2 * q);
    if (w == 0) aw.topRightCorner(q, q).setIdentity();
    if (w >= -K.max_harmonic() && w <= K.max_harmonic()) aw.bottomLeftCorner(q, q) = -solve(K[w]);
    if (D.rows() > 0 && w >= -D.max_harmonic() && w <= D.max_harmonic())
      aw.bottomRightCorner(q, q) = -solve(D[w]);
    a[w] = aw;
    Eigen::MatrixXcd bw = Eigen::MatrixXcd::Zero(2 * q, m);
    if (m > 0 && w >= -F.max_harmonic() && w <= F.max_harmonic()) bw.bottomRows(q) = solve(F[w]);
    b[w] = bw;
    Eigen::MatrixXcd cw = Eigen::MatrixXcd::Zero(p, 2 * q);
    if (Cd.rows() > 0 && w >= -Cd.max_harmonic() && w <= Cd.max_harmonic()) cw.leftCols(q) = Cd[w];
    if (Cv.rows() > 0 && w >= -Cv.max_harmonic() && w <= Cv.max_harmonic()) cw.rightCols(q) = Cv[w];
    c[w] = cw;
  }
  return PeriodicSystem::FromFourier(period, std::move(a), m > 0 ? std::move(b) : FourierMatrix(),
                                     p > 0 ? std::move(c) : FourierMatrix());
}

}  // namespace ltp
