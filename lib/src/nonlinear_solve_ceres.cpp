/// Levenberg–Marquardt through Ceres: the only translation unit that
/// includes Ceres (it is heavy to compile).

#include <chrono>

#include <ceres/ceres.h>
#include <fmt/format.h>

#include "impactkit/model.hpp"
#include "impactkit/nonlinear_solve.hpp"
#include "nonlinear_solve_common.hpp"

namespace impactkit {
namespace {

/// F as one residual block over one parameter block of size n, with the
/// user's analytic Jacobian.
class ResidualCost : public ceres::CostFunction {
 public:
  ResidualCost(const Residual& residual, const Jacobian& jacobian, int n)
      : residual_(residual), jacobian_(jacobian), n_(n) {
    set_num_residuals(n);
    mutable_parameter_block_sizes()->push_back(n);
  }

  bool Evaluate(const double* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(parameters[0], n_);
    Eigen::VectorXd f;
    if (!residual_(x, &f) || !f.allFinite()) return false;  // Ceres shrinks the step
    Eigen::Map<Eigen::VectorXd>(residuals, n_) = f;
    if (jacobians && jacobians[0]) {
      Eigen::MatrixXd j;
      if (!jacobian_(x, &j) || !j.allFinite()) return false;
      // Ceres wants row-major.
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          jacobians[0], n_, n_) = j;
    }
    return true;
  }

 private:
  const Residual& residual_;
  const Jacobian& jacobian_;
  int n_;
};

}  // namespace

SolveSummary SolveLeastSquares(const Residual& residual, const Jacobian& jacobian,
                               const NewtonOptions& options, Eigen::VectorXd* x) {
  const auto start = std::chrono::steady_clock::now();
  ValidateSolveInput(options, *x);
  ceres::Problem problem;
  problem.AddResidualBlock(new ResidualCost(residual, jacobian, static_cast<int>(x->size())),
                           nullptr, x->data());
  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = 10 * options.max_iterations;
  // Converge on the residual, not on Ceres's relative tests.
  solver_options.function_tolerance = 1e-30;
  solver_options.gradient_tolerance = 1e-30;
  solver_options.parameter_tolerance = options.step_tolerance;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(solver_options, &problem, &ceres_summary);

  SolveSummary summary;
  summary.iterations = static_cast<int>(ceres_summary.iterations.size());
  summary.termination = ceres_summary.IsSolutionUsable() ? SolveTermination::kConverged
                                                         : SolveTermination::kFailure;
  summary.message = "Levenberg-Marquardt (Ceres): " + ceres_summary.message;
  FinishSolve(residual, options, *x,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              &summary);
  return summary;
}

}  // namespace impactkit
