#pragma once
/// \file nonlinear_solve_common.hpp
/// What the KINSOL and Ceres solvers share: the input checks, and the user's
/// callbacks wrapped the way both libraries need them.

#include <chrono>
#include <exception>
#include <limits>

#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit {

/// Throws InvalidInput for invalid options or an empty or non-finite guess.
void ValidateSolveInput(const NewtonOptions& options, const Eigen::VectorXd& x);

/// The user's residual and Jacobian as the libraries call them: counted,
/// checked (sizes, finite values), exceptions held back until the library
/// has returned (none may cross KINSOL's C frames), and the best point seen
/// kept, so that convergence is decided by max |F| at a point we evaluated.
class GuardedProblem {
 public:
  enum class Outcome {
    kOk,
    kNotEvaluable,  ///< the callback returned false, or a non-finite value
    kAbort,         ///< an exception is held: stop the library at once
  };

  GuardedProblem(const Residual& residual, const Jacobian& jacobian, Eigen::Index n);

  /// F at x[0..n); on kOk the value is in residual().
  Outcome EvaluateResidual(const double* x);
  /// dF/dx at x[0..n); on kOk the value is in jacobian().
  Outcome EvaluateJacobian(const double* x);
  const Eigen::VectorXd& residual() const { return f_; }
  const Eigen::MatrixXd& jacobian() const { return j_; }
  /// max |F| at the best point so far (infinity before the first success).
  double best_norm() const { return best_norm_; }
  /// True once a callback has thrown (or returned the wrong size).
  bool aborted() const { return static_cast<bool>(error_); }

  /// Rethrows a held exception; otherwise completes the summary: counts,
  /// time, x = the best point (unchanged if F never evaluated),
  /// residual_norm there, and kConverged iff it meets the tolerance —
  /// else the solver's own kNoConvergence or kFailure stands.
  void Finish(const NewtonOptions& options, std::chrono::steady_clock::time_point start,
              Eigen::VectorXd* x, SolveSummary* summary) const;

 private:
  Outcome Hold(std::exception_ptr error);

  const Residual& residual_;
  const Jacobian& jacobian_;
  Eigen::Index n_;
  Eigen::VectorXd x_, f_;
  Eigen::MatrixXd j_;
  int residual_evaluations_ = 0, jacobian_evaluations_ = 0;
  Eigen::VectorXd best_x_;
  double best_norm_ = std::numeric_limits<double>::infinity();
  std::exception_ptr error_;
};

}  // namespace impactkit
