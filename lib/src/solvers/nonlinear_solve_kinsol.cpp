/// Newton–Raphson through SUNDIALS KINSOL (the only file that includes it).
///
/// What KINSOL does with the settings below (SUNDIALS 6.4, kinsol.c):
///  - it stops with success when max_i |fscale_i F_i| <= fnormtol; with unit
///    fscale that is exactly our max |F| test. Its default fnormtol is
///    cbrt(epsilon) ~ 6e-6, hence the explicit setting;
///  - the line search and the reported KINGetFuncNorm use the L2 norm;
///  - a recoverable failure of F (callback returns > 0) halves the Newton
///    step: 5 tries (down to 1/16 of it), then KIN_REPTD_SYSFUNC_ERR. Once
///    F has been evaluated there, a failure inside the line search (while
///    backtracking, or lengthening the step) is fatal: KIN_SYSFUNC_FAIL;
///  - KIN_STEP_LT_STPTOL (a tiny step without a root) is a non-negative
///    "success" flag, so success is confirmed by max |F| afterwards;
///  - steps are capped at mxnewtstep, by default 1000 |x0| but at least 1
///    (so 1 from x0 = 0), and five capped steps in a row end the solve.

#include <fmt/format.h>
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <chrono>
#include <new>
#include <stdexcept>

#include "impactkit/solvers/nonlinear_solve.hpp"
#include "solvers/nonlinear_solve_common.hpp"

namespace impactkit {
namespace {

using Outcome = GuardedProblem::Outcome;

Eigen::Map<Eigen::VectorXd> View(N_Vector v) { return {N_VGetArrayPointer(v), N_VGetLength(v)}; }

/// KINSOL's callback convention: 0 success, > 0 recoverable (shorten the
/// step), < 0 stop now.
int ToKinsol(Outcome outcome) {
  switch (outcome) {
    case Outcome::kOk:
      return 0;
    case Outcome::kNotEvaluable:
      return 1;
    case Outcome::kAbort:
      return -1;
  }
  return -1;
}

int EvaluateResidual(N_Vector u, N_Vector f, void* data) {
  auto& problem = *static_cast<GuardedProblem*>(data);
  const Outcome outcome = problem.EvaluateResidual(N_VGetArrayPointer(u));
  if (outcome == Outcome::kOk) View(f) = problem.residual();
  return ToKinsol(outcome);
}

int EvaluateJacobian(N_Vector u, N_Vector, SUNMatrix jacobian, void* data, N_Vector, N_Vector) {
  auto& problem = *static_cast<GuardedProblem*>(data);
  const Outcome outcome = problem.EvaluateJacobian(N_VGetArrayPointer(u));
  if (outcome == Outcome::kOk) {
    const sunindextype n = SUNDenseMatrix_Rows(jacobian);  // SUNDIALS is column-major, as Eigen
    Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(jacobian), n, n) = problem.jacobian();
  }
  return ToKinsol(outcome);  // KINSOL treats any failure here as fatal (KIN_LSETUP_FAIL)
}

/// KINSOL's error handler: keeps the message instead of printing it to stderr.
void KeepError(int, const char*, const char*, char* message, void* data) {
  try {
    *static_cast<std::string*>(data) = message;
  } catch (...) {  // nothing may cross KINSOL's C frames; the flag name remains
  }
}

/// The SUNDIALS objects of one solve, released in reverse order.
class KinsolSession {
 public:
  explicit KinsolSession(sunindextype n) {
    if (SUNContext_Create(nullptr, &context) == 0 && context) {
      u = N_VNew_Serial(n, context);
      scale = N_VNew_Serial(n, context);
      matrix = SUNDenseMatrix(n, n, context);
      if (u && matrix) linear_solver = SUNLinSol_Dense(u, matrix, context);
      memory = KINCreate(context);
    }
    if (!(context && u && scale && matrix && linear_solver && memory)) {
      Release();
      throw std::bad_alloc();
    }
    N_VConst(1.0, scale);
  }
  ~KinsolSession() { Release(); }
  KinsolSession(const KinsolSession&) = delete;
  KinsolSession& operator=(const KinsolSession&) = delete;

  SUNContext context = nullptr;
  N_Vector u = nullptr;
  N_Vector scale = nullptr;  ///< unit scaling, for both x and F
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  void* memory = nullptr;

 private:
  void Release() {
    if (memory) KINFree(&memory);
    if (linear_solver) SUNLinSolFree(linear_solver);
    if (matrix) SUNMatDestroy(matrix);
    if (scale) N_VDestroy(scale);
    if (u) N_VDestroy(u);
    if (context) SUNContext_Free(&context);
  }
};

/// KINGetReturnFlagName (6.4) answers "NONE" for the F-failure flags.
std::string FlagName(int flag) {
  switch (flag) {
    case KIN_SUCCESS:
      return "KIN_SUCCESS";
    case KIN_INITIAL_GUESS_OK:
      return "KIN_INITIAL_GUESS_OK";
    case KIN_STEP_LT_STPTOL:
      return "KIN_STEP_LT_STPTOL";
    case KIN_WARNING:
      return "KIN_WARNING";
    case KIN_MEM_NULL:
      return "KIN_MEM_NULL";
    case KIN_ILL_INPUT:
      return "KIN_ILL_INPUT";
    case KIN_NO_MALLOC:
      return "KIN_NO_MALLOC";
    case KIN_MEM_FAIL:
      return "KIN_MEM_FAIL";
    case KIN_LINESEARCH_NONCONV:
      return "KIN_LINESEARCH_NONCONV";
    case KIN_MAXITER_REACHED:
      return "KIN_MAXITER_REACHED";
    case KIN_MXNEWT_5X_EXCEEDED:
      return "KIN_MXNEWT_5X_EXCEEDED";
    case KIN_LINESEARCH_BCFAIL:
      return "KIN_LINESEARCH_BCFAIL";
    case KIN_LINSOLV_NO_RECOVERY:
      return "KIN_LINSOLV_NO_RECOVERY";
    case KIN_LINIT_FAIL:
      return "KIN_LINIT_FAIL";
    case KIN_LSETUP_FAIL:
      return "KIN_LSETUP_FAIL";
    case KIN_LSOLVE_FAIL:
      return "KIN_LSOLVE_FAIL";
    case KIN_SYSFUNC_FAIL:
      return "KIN_SYSFUNC_FAIL";
    case KIN_FIRST_SYSFUNC_ERR:
      return "KIN_FIRST_SYSFUNC_ERR";
    case KIN_REPTD_SYSFUNC_ERR:
      return "KIN_REPTD_SYSFUNC_ERR";
    case KIN_VECTOROP_ERR:
      return "KIN_VECTOROP_ERR";
    case KIN_CONTEXT_ERR:
      return "KIN_CONTEXT_ERR";
  }
  return fmt::format("KINSOL flag {}", flag);
}

/// The method's own verdict; GuardedProblem::Finish then confirms or
/// withdraws kConverged by max |F|.
Termination Classify(int flag) {
  switch (flag) {
    case KIN_SUCCESS:
    case KIN_INITIAL_GUESS_OK:
      return Termination::kConverged;
    case KIN_STEP_LT_STPTOL:
    case KIN_LINESEARCH_NONCONV:
    case KIN_LINESEARCH_BCFAIL:
    case KIN_MAXITER_REACHED:
    case KIN_MXNEWT_5X_EXCEEDED:
      return Termination::kNoConvergence;
    default:  // F or J failed, singular Jacobian
      return Termination::kFailure;
  }
}

void RequireSetUp(int flag, const char* what) {
  if (flag != KIN_SUCCESS) {
    throw std::logic_error(fmt::format("KINSOL set-up failed in {}: {}", what, FlagName(flag)));
  }
}

}  // namespace

SolveSummary SolveNewton(const Residual& residual, const Jacobian& jacobian,
                         const NewtonOptions& options, Eigen::VectorXd* x) {
  const auto start = std::chrono::steady_clock::now();
  ValidateSolveInput(options, *x);
  GuardedProblem problem(residual, jacobian, x->size());
  std::string error;
  KinsolSession kinsol(x->size());
  View(kinsol.u) = *x;
  void* memory = kinsol.memory;
  RequireSetUp(KINSetErrHandlerFn(memory, KeepError, &error), "KINSetErrHandlerFn");
  RequireSetUp(KINInit(memory, EvaluateResidual, kinsol.u), "KINInit");
  RequireSetUp(KINSetUserData(memory, &problem), "KINSetUserData");
  RequireSetUp(KINSetLinearSolver(memory, kinsol.linear_solver, kinsol.matrix),
               "KINSetLinearSolver");
  RequireSetUp(KINSetJacFn(memory, EvaluateJacobian), "KINSetJacFn");
  // Exact Newton: a fresh Jacobian at every iteration.
  RequireSetUp(KINSetMaxSetupCalls(memory, 1), "KINSetMaxSetupCalls");
  RequireSetUp(KINSetNumMaxIters(memory, options.max_iterations), "KINSetNumMaxIters");
  RequireSetUp(KINSetFuncNormTol(memory, options.residual_tolerance), "KINSetFuncNormTol");
  RequireSetUp(KINSetScaledStepTol(memory, options.step_tolerance), "KINSetScaledStepTol");
  // KINSOL's step cap, 1000 |x0|, but not the cap of 1 it falls back to
  // near x0 = 0, which would turn a linear problem into many steps.
  RequireSetUp(KINSetMaxNewtonStep(memory, 1000.0 * std::max(1.0, x->norm())),
               "KINSetMaxNewtonStep");
  const int flag = KINSol(memory, kinsol.u, options.line_search ? KIN_LINESEARCH : KIN_NONE,
                          kinsol.scale, kinsol.scale);
  long iterations = 0;
  KINGetNumNonlinSolvIters(memory, &iterations);

  SolveSummary summary;
  summary.iterations = static_cast<int>(iterations);
  summary.termination = Classify(flag);
  summary.message = "KINSOL " + FlagName(flag) + (error.empty() ? "" : ": " + error);
  problem.Finish(options, start, x, &summary);
  return summary;
}

}  // namespace impactkit
