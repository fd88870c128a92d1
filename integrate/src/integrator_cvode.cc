// kCvodeBdf and kCvodeAdams: SUNDIALS 6 CVODE on y = vec(Φ) (n² entries, column-major).
//
// BDF needs Newton solves with I − γJ, J = kron(I_n, A(t)) (block diagonal). A dense n²×n²
// Jacobian would cost O(n⁶) per factorisation; instead GMRES (SPGMR) gets J·v = A(t)·V as
// jtimes and a left preconditioner that applies (I − γA)⁻¹ to each column of V. That
// preconditioner is the exact inverse of the Newton matrix, so GMRES converges in one
// iteration and each setup costs one n×n LU. Adams uses the fixed-point nonlinear solver
// (no Jacobian at all), the usual choice for non-stiff problems.
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>

#include "integrator_internal.h"

namespace ltp::internal {

namespace {

// CVODE controls the local error in a weighted RMS norm; on our test problems its global
// error came out 10–100× rel_tol (odeint's max-norm controllers stay at or below rel_tol).
// Tightening CVODE's tolerances by this factor puts rel_tol on the same footing for every
// integrator (measured on the Meissner and constant-A tests of integrator_test.cc).
constexpr double kCvodeToleranceScale = 0.01;
// Below this CVODE answers CV_TOO_MUCH_ACC.
constexpr double kCvodeMinRelTol = 4 * std::numeric_limits<double>::epsilon();

// A SUNDIALS call failed; carries the message for TransitionResult (never leaves this file).
struct CvodeFailure {
  std::string message;
};

std::string FlagName(int flag) {
  char* name = CVodeGetReturnFlagName(flag);  // malloc'ed by SUNDIALS
  std::string s = name ? name : "unknown flag";
  std::free(name);
  return s;
}

// The one place every SUNDIALS return code is checked.
void Check(int flag, const char* call) {
  if (flag >= 0) return;
  throw CvodeFailure{std::string(call) + " failed: " + FlagName(flag)};
}

template <class T>
T* CheckPtr(T* p, const char* call) {
  if (p == nullptr) throw CvodeFailure{std::string(call) + " failed to allocate"};
  return p;
}

// CVODE reports through this handler; the library never prints, so it is silent. The
// flags it would print reach the caller through the return codes instead.
void SilentErrorHandler(int, const char*, const char*, char*, void*) {}

// RAII owners of the SUNDIALS objects. Declared in creation order, destroyed in reverse.
struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver s) const { SUNNonlinSolFree(s); }
};
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
template <class Handle, class Deleter>
using Owned = std::unique_ptr<std::remove_pointer_t<Handle>, Deleter>;

// Everything the callbacks need. A(t) is cached by time: CVODE calls the RHS and jtimes at
// the same t within a Newton iteration.
struct UserData {
  const PeriodicSystem* system;
  int n;
  PieceWindow window;  // the current smooth piece
  long evals = 0;
  double a_time = std::nan("");
  Eigen::MatrixXd a;      // A(a_time)
  Eigen::MatrixXd a_jac;  // A at the last preconditioner setup (may be reused when jok)
  double lu_gamma = std::nan("");
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;  // of I − lu_gamma · a_jac
  Eigen::MatrixXd work;
  bool not_finite = false;
  std::exception_ptr error;  // an exception from A(t): rethrown once CVODE has returned

  const Eigen::MatrixXd& A(double t) {
    t = window(t);
    if (!(t == a_time)) {
      system->EvalA(t, a);
      ++evals;
      a_time = t;
    }
    return a;
  }
  void Factor(double gamma) {
    work.setIdentity();
    work.noalias() -= gamma * a_jac;
    lu.compute(work);
    lu_gamma = gamma;
  }
};

Eigen::Map<Eigen::MatrixXd> AsMatrix(N_Vector v, int n) {
  return Eigen::Map<Eigen::MatrixXd>(N_VGetArrayPointer(v), n, n);
}

// Callbacks: exceptions must not cross the C frames of CVODE, so they are stored and a
// non-recoverable failure (-1) is returned.
// A non-finite derivative is an unrecoverable failure: Φ' = AΦ overflowing means Φ is about
// to, and a "recoverable" answer only makes CVODE shrink h to nothing until max_steps.
int Rhs(double t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* d = static_cast<UserData*>(user_data);
  try {
    auto dphi = AsMatrix(ydot, d->n);
    dphi.noalias() = d->A(t) * AsMatrix(y, d->n);
    if (!dphi.allFinite()) {
      d->not_finite = true;
      return -1;
    }
    return 0;
  } catch (...) {
    d->error = std::current_exception();
    return -1;
  }
}

int JacTimes(N_Vector v, N_Vector jv, double t, N_Vector, N_Vector, void* user_data, N_Vector) {
  auto* d = static_cast<UserData*>(user_data);
  try {
    AsMatrix(jv, d->n).noalias() = d->A(t) * AsMatrix(v, d->n);
    return 0;
  } catch (...) {
    d->error = std::current_exception();
    return -1;
  }
}

int PrecSetup(double t, N_Vector, N_Vector, sunbooleantype jok, sunbooleantype* jcur, double gamma,
              void* user_data) {
  auto* d = static_cast<UserData*>(user_data);
  try {
    if (!jok) d->a_jac = d->A(t);
    *jcur = jok ? SUNFALSE : SUNTRUE;
    d->Factor(gamma);
    return 0;
  } catch (...) {
    d->error = std::current_exception();
    return -1;
  }
}

int PrecSolve(double, N_Vector, N_Vector, N_Vector r, N_Vector z, double gamma, double, int,
              void* user_data) {
  auto* d = static_cast<UserData*>(user_data);
  // CVODE may call with a γ that moved since the setup; refactoring (n³, no new A) keeps the
  // preconditioner exact for the Newton matrix of this call.
  if (gamma != d->lu_gamma) d->Factor(gamma);
  AsMatrix(z, d->n).noalias() = d->lu.solve(AsMatrix(r, d->n));
  return 0;
}

// The callbacks' buffers sized for n states.
void SizeUserData(const PeriodicSystem& system, UserData& data) {
  const int n = system.states();
  data.system = &system;
  data.n = n;
  data.a.resize(n, n);
  data.a_jac.setZero(n, n);
  data.work.resize(n, n);
  data.lu = Eigen::PartialPivLU<Eigen::MatrixXd>(n);
}

// The SUNDIALS objects of one integration, members in creation order (destroyed in reverse).
struct CvodeSession {
  Owned<SUNContext, ContextDeleter> ctx;
  Owned<N_Vector, VectorDeleter> y;  // vec(Φ) over the current piece
  Owned<SUNLinearSolver, LinearSolverDeleter> linear;
  Owned<SUNNonlinearSolver, NonlinearSolverDeleter> fixed_point;
  Owned<void*, CvodeDeleter> mem;
  void* cv() const { return mem.get(); }
};

CvodeSession OpenSession(int n, bool bdf) {
  CvodeSession s;
  SUNContext raw_ctx = nullptr;
  Check(SUNContext_Create(nullptr, &raw_ctx), "SUNContext_Create");
  s.ctx.reset(raw_ctx);
  s.y.reset(
      CheckPtr(N_VNew_Serial(static_cast<sunindextype>(n) * n, s.ctx.get()), "N_VNew_Serial"));
  s.mem.reset(CheckPtr(CVodeCreate(bdf ? CV_BDF : CV_ADAMS, s.ctx.get()), "CVodeCreate"));
  Check(CVodeSetErrHandlerFn(s.cv(), SilentErrorHandler, nullptr), "CVodeSetErrHandlerFn");
  return s;
}

// The first piece: CVODE initialised at a, tolerances, the nonlinear (and linear) solver.
void InitCvode(CvodeSession& s, UserData& data, double a, bool bdf,
               const IntegratorOptions& options) {
  void* cv = s.cv();
  Check(CVodeInit(cv, Rhs, a, s.y.get()), "CVodeInit");
  Check(CVodeSetUserData(cv, &data), "CVodeSetUserData");
  const double rel_tol = std::max(kCvodeToleranceScale * options.rel_tol, kCvodeMinRelTol);
  Check(CVodeSStolerances(cv, rel_tol, kCvodeToleranceScale * options.abs_tol),
        "CVodeSStolerances");
  if (bdf) {
    s.linear.reset(
        CheckPtr(SUNLinSol_SPGMR(s.y.get(), SUN_PREC_LEFT, 5, s.ctx.get()), "SUNLinSol_SPGMR"));
    Check(CVodeSetLinearSolver(cv, s.linear.get(), nullptr), "CVodeSetLinearSolver");
    Check(CVodeSetJacTimes(cv, nullptr, JacTimes), "CVodeSetJacTimes");
    Check(CVodeSetPreconditioner(cv, PrecSetup, PrecSolve), "CVodeSetPreconditioner");
  } else {
    s.fixed_point.reset(
        CheckPtr(SUNNonlinSol_FixedPoint(s.y.get(), 0, s.ctx.get()), "SUNNonlinSol_FixedPoint"));
    Check(CVodeSetNonlinearSolver(cv, s.fixed_point.get()), "CVodeSetNonlinearSolver");
  }
  Check(CVodeSetMaxNumSteps(cv, options.max_steps), "CVodeSetMaxNumSteps");
}

// Φ = I at a, CVODE (re)started there with a stop time at b and an initial step.
void StartPiece(CvodeSession& s, UserData& data, size_t p, double a, double b, bool bdf,
                const IntegratorOptions& options) {
  void* cv = s.cv();
  AsMatrix(s.y.get(), data.n).setIdentity();
  data.window = PieceWindow(a, b);
  data.a_time = std::nan("");  // A may differ at the same t on the other side of a jump
  data.not_finite = false;
  if (p == 0) {
    InitCvode(s, data, a, bdf, options);
  } else {
    // A may jump at a: restart from order 1 with the history forgotten.
    Check(CVodeReInit(cv, a, s.y.get()), "CVodeReInit");
  }
  Check(CVodeSetStopTime(cv, b), "CVodeSetStopTime");
  // Error constant 1, not BDF1's 1/2: on stiff systems the first step is bounded by the
  // fast modes, and the longer start cost CVODE steps (TransitionStiff test).
  const double h0 = InitialStep(data.A(0.5 * (a + b)).lpNorm<Eigen::Infinity>(), b - a,
                                kCvodeToleranceScale * options.rel_tol, 1, 1.0);
  Check(CVodeSetInitStep(cv, h0), "CVodeSetInitStep");
}

// One internal step per call: we see every accepted state, so an overflowing Φ stops the
// integration at once (Adams' fixed-point solver otherwise went on with inf up to
// max_steps), and the step budget holds over the whole interval. `steps`: those of the earlier
// pieces; result.steps counts on from them.
void StepToStopTime(CvodeSession& s, UserData& data, double a, double b, long steps,
                    const IntegratorOptions& options, TransitionResult& result) {
  void* cv = s.cv();
  const auto phi = AsMatrix(s.y.get(), data.n);
  double t_reached = a;
  while (true) {
    const int flag = CVode(cv, b, s.y.get(), &t_reached, CV_ONE_STEP);
    if (data.error) std::rethrow_exception(data.error);
    if (data.not_finite || !phi.allFinite()) throw CvodeFailure{kNotFiniteMessage};
    long piece_steps = 0;
    Check(CVodeGetNumSteps(cv, &piece_steps), "CVodeGetNumSteps");
    result.steps = steps + piece_steps;
    if (flag < 0) {
      std::ostringstream msg;
      msg << ToString(options.type) << ": CVode failed with " << FlagName(flag)
          << " at t = " << t_reached;
      throw CvodeFailure{msg.str()};
    }
    if (flag == CV_TSTOP_RETURN || t_reached >= b) break;
    if (result.steps >= options.max_steps) {
      std::ostringstream msg;
      msg << ToString(options.type) << ": max_steps = " << options.max_steps
          << " reached at t = " << t_reached << " (CV_TOO_MUCH_WORK)";
      throw CvodeFailure{msg.str()};
    }
  }
}

}  // namespace

TransitionResult CvodeTransition(const PeriodicSystem& system, const std::vector<double>& points,
                                 const IntegratorOptions& options) {
  const int n = system.states();
  const bool bdf = options.type == IntegratorType::kCvodeBdf;
  TransitionResult result;
  result.phi = Eigen::MatrixXd::Identity(n, n);
  UserData data;
  SizeUserData(system, data);

  try {
    CvodeSession session = OpenSession(n, bdf);
    const auto phi = AsMatrix(session.y.get(), n);
    Eigen::MatrixXd product(n, n);
    long steps = 0;
    for (size_t p = 0; p + 1 < points.size(); ++p) {
      const double a = points[p], b = points[p + 1];
      StartPiece(session, data, p, a, b, bdf, options);
      StepToStopTime(session, data, a, b, steps, options, result);
      steps = result.steps;
      product.noalias() = phi * result.phi;
      result.phi.swap(product);
    }
    result.ok = true;
  } catch (const CvodeFailure& failure) {
    result.message = failure.message;
    if (failure.message == kNotFiniteMessage)
      result.phi.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  result.rhs_evals = data.evals;
  return result;
}

}  // namespace ltp::internal
