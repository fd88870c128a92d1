#include "ltp/core/second_order.h"

#include <cmath>
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

}  // namespace ltp
