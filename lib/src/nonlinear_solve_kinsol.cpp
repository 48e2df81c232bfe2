/// Newton–Raphson through SUNDIALS KINSOL (the only file that includes it).

#include <chrono>
#include <cstdlib>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "impactkit/model.hpp"
#include "impactkit/nonlinear_solve.hpp"
#include "nonlinear_solve_common.hpp"

namespace impactkit {
namespace {

/// What the C callbacks need, and what they report back.
struct Callbacks {
  const Residual& residual;
  const Jacobian& jacobian;
  Eigen::VectorXd x, f;
  Eigen::MatrixXd j;
  std::string last_error;
};

Eigen::Map<Eigen::VectorXd> View(N_Vector v) {
  return {N_VGetArrayPointer(v), N_VGetLength(v)};
}

int EvaluateResidual(N_Vector u, N_Vector f, void* data) {
  auto& c = *static_cast<Callbacks*>(data);
  c.x = View(u);
  if (!c.residual(c.x, &c.f) || !c.f.allFinite()) return 1;  // recoverable: shorten the step
  View(f) = c.f;
  return 0;
}

int EvaluateJacobian(N_Vector u, N_Vector, SUNMatrix jacobian, void* data, N_Vector, N_Vector) {
  auto& c = *static_cast<Callbacks*>(data);
  c.x = View(u);
  if (!c.jacobian(c.x, &c.j) || !c.j.allFinite()) return 1;
  const sunindextype n = SUNDenseMatrix_Rows(jacobian);
  Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(jacobian), n, n) = c.j;  // column-major
  return 0;
}

void KeepError(int, const char*, const char*, char* message, void* data) {
  static_cast<Callbacks*>(data)->last_error = message;  // instead of printing to stderr
}

/// The SUNDIALS objects of one solve, released in reverse order.
struct KinsolSession {
  SUNContext context = nullptr;
  N_Vector u = nullptr, scale = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  void* memory = nullptr;

  explicit KinsolSession(sunindextype n) {
    SUNContext_Create(nullptr, &context);
    u = N_VNew_Serial(n, context);
    scale = N_VNew_Serial(n, context);
    N_VConst(1.0, scale);
    matrix = SUNDenseMatrix(n, n, context);
    linear_solver = SUNLinSol_Dense(u, matrix, context);
    memory = KINCreate(context);
  }
  ~KinsolSession() {
    KINFree(&memory);
    SUNLinSolFree(linear_solver);
    SUNMatDestroy(matrix);
    N_VDestroy(scale);
    N_VDestroy(u);
    SUNContext_Free(&context);
  }
  KinsolSession(const KinsolSession&) = delete;
  KinsolSession& operator=(const KinsolSession&) = delete;
};

std::string FlagName(int flag) {
  // KINGetReturnFlagName allocates the name; the caller frees it.
  const std::unique_ptr<char, decltype(&std::free)> name(KINGetReturnFlagName(flag), &std::free);
  return name ? name.get() : fmt::format("flag {}", flag);
}

void RequireSetUp(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(fmt::format("KINSOL set-up failed in {} ({})", what, flag));
}

}  // namespace

SolveSummary SolveNewton(const Residual& residual, const Jacobian& jacobian,
                         const NewtonOptions& options, Eigen::VectorXd* x) {
  const auto start = std::chrono::steady_clock::now();
  ValidateSolveInput(options, *x);
  Callbacks callbacks{residual, jacobian, {}, {}, {}, {}};
  KinsolSession kinsol(x->size());
  View(kinsol.u) = *x;
  RequireSetUp(KINInit(kinsol.memory, EvaluateResidual, kinsol.u), "KINInit");
  RequireSetUp(KINSetUserData(kinsol.memory, &callbacks), "KINSetUserData");
  RequireSetUp(KINSetErrHandlerFn(kinsol.memory, KeepError, &callbacks), "KINSetErrHandlerFn");
  RequireSetUp(KINSetLinearSolver(kinsol.memory, kinsol.linear_solver, kinsol.matrix),
               "KINSetLinearSolver");
  RequireSetUp(KINSetJacFn(kinsol.memory, EvaluateJacobian), "KINSetJacFn");
  // Exact Newton: a fresh Jacobian at every iteration.
  RequireSetUp(KINSetMaxSetupCalls(kinsol.memory, 1), "KINSetMaxSetupCalls");
  RequireSetUp(KINSetNumMaxIters(kinsol.memory, options.max_iterations), "KINSetNumMaxIters");
  RequireSetUp(KINSetFuncNormTol(kinsol.memory, options.residual_tolerance), "KINSetFuncNormTol");
  RequireSetUp(KINSetScaledStepTol(kinsol.memory, options.step_tolerance), "KINSetScaledStepTol");
  const int flag = KINSol(kinsol.memory, kinsol.u,
                          options.line_search ? KIN_LINESEARCH : KIN_NONE, kinsol.scale,
                          kinsol.scale);
  long iterations = 0;
  KINGetNumNonlinSolvIters(kinsol.memory, &iterations);
  *x = View(kinsol.u);

  SolveSummary summary;
  summary.iterations = static_cast<int>(iterations);
  summary.termination = flag >= 0 ? SolveTermination::kConverged
                                  : (flag == KIN_MAXITER_REACHED || flag == KIN_LINESEARCH_NONCONV)
                                        ? SolveTermination::kNoConvergence
                                        : SolveTermination::kFailure;
  if (flag < 0) summary.message = "KINSOL: " + (callbacks.last_error.empty() ? FlagName(flag) : callbacks.last_error);
  FinishSolve(residual, options, *x,
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), &summary);
  return summary;
}

}  // namespace impactkit
