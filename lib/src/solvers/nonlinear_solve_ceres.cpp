/// Levenberg–Marquardt through Ceres: the only translation unit that
/// includes Ceres (it is heavy to compile).

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "impactkit/solvers/nonlinear_solve.hpp"
#include "solvers/nonlinear_solve_common.hpp"

namespace impactkit {
namespace {

using Outcome = GuardedProblem::Outcome;

/// What the cost function and the iteration callback share.
struct CeresState {
  GuardedProblem& problem;
  double tolerance;
  /// F or J failed where Ceres asked for the Jacobian too (the guess, or a
  /// point it has just accepted).
  bool failed_with_jacobian = false;
};

/// F as one residual block of size n over one parameter block of size n,
/// with the user's analytic Jacobian.
///
/// Ceres 2.1 logs an ERROR through glog, whatever logging_type says, when an
/// evaluation with Jacobian fails (RETURN_IF_ERROR_AND_LOG in
/// trust_region_minimizer.cc), but stays silent when a trial point fails
/// (it rejects the step and shrinks the region). So only trial points return
/// false; a failure with Jacobian returns zeros, is recorded, and
/// StopWhenDone ends the solve at the end of that iteration.
class ResidualCost : public ceres::CostFunction {
 public:
  ResidualCost(CeresState* state, int n) : state_(*state), n_(n) {
    set_num_residuals(n);
    mutable_parameter_block_sizes()->push_back(n);
  }

  bool Evaluate(const double* const* parameters, double* residuals,
                double** jacobians) const override {
    GuardedProblem& problem = state_.problem;
    const bool with_jacobian = jacobians && jacobians[0];
    if (problem.EvaluateResidual(parameters[0]) == Outcome::kOk &&
        (!with_jacobian || problem.EvaluateJacobian(parameters[0]) == Outcome::kOk)) {
      Eigen::Map<Eigen::VectorXd>(residuals, n_) = problem.residual();
      if (with_jacobian) {
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            jacobians[0], n_, n_) = problem.jacobian();  // Ceres wants row-major
      }
      return true;
    }
    if (!with_jacobian) return false;
    state_.failed_with_jacobian = true;
    Eigen::Map<Eigen::VectorXd>(residuals, n_).setZero();
    Eigen::Map<Eigen::VectorXd>(jacobians[0], n_ * n_).setZero();
    return true;
  }

 private:
  CeresState& state_;
  int n_;
};

/// Ends the solve as soon as some evaluated point meets the tolerance, or
/// when it cannot go on (see ResidualCost).
class StopWhenDone : public ceres::IterationCallback {
 public:
  explicit StopWhenDone(const CeresState& state) : state_(state) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    if (state_.failed_with_jacobian || state_.problem.aborted()) return ceres::SOLVER_ABORT;
    return state_.problem.best_norm() <= state_.tolerance ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                                          : ceres::SOLVER_CONTINUE;
  }

 private:
  const CeresState& state_;
};

}  // namespace

SolveSummary SolveLeastSquares(const Residual& residual, const Jacobian& jacobian,
                               const NewtonOptions& options, Eigen::VectorXd* x) {
  const auto start = std::chrono::steady_clock::now();
  ValidateSolveInput(options, *x);
  const int n = static_cast<int>(x->size());
  GuardedProblem guarded(residual, jacobian, n);
  CeresState state{guarded, options.residual_tolerance};
  Eigen::VectorXd parameters = *x;  // Ceres's copy; x gets the best point
  ceres::Problem problem;
  problem.AddResidualBlock(new ResidualCost(&state, n), nullptr, parameters.data());

  StopWhenDone stop(state);
  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = 10 * options.max_iterations;
  // Converge on max |F| (StopWhenDone), not on Ceres's relative tests of
  // the cost and gradient; only a stalled step ends the solve otherwise.
  solver_options.function_tolerance = 0.0;
  solver_options.gradient_tolerance = 0.0;
  solver_options.parameter_tolerance = options.step_tolerance;
  // Invalid steps (no model decrease, e.g. J = 0) shrink the region until
  // its minimum radius ends the solve quietly; Ceres's own limit (5) would
  // end it with a logged error.
  solver_options.max_num_consecutive_invalid_steps = solver_options.max_num_iterations;
  solver_options.callbacks.push_back(&stop);
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &problem, &ceres_summary);

  SolveSummary summary;
  // Ceres's iteration 0 is the evaluation at the guess, not a step.
  summary.iterations = std::max(0, static_cast<int>(ceres_summary.iterations.size()) - 1);
  summary.termination = ceres_summary.termination_type == ceres::FAILURE ||
                                ceres_summary.termination_type == ceres::USER_FAILURE
                            ? Termination::kFailure
                            : Termination::kNoConvergence;  // Finish decides convergence
  summary.message =
      state.failed_with_jacobian
          ? "Ceres Levenberg-Marquardt: F or its Jacobian failed at the guess or an accepted point"
          : fmt::format("Ceres Levenberg-Marquardt {}: {}",
                        ceres::TerminationTypeToString(ceres_summary.termination_type),
                        ceres_summary.message);
  guarded.Finish(options, start, x, &summary);
  return summary;
}

}  // namespace impactkit
