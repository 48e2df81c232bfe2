#pragma once
/// \file nonlinear_solve.hpp
/// Square nonlinear systems F(x) = 0 in R^n with user residual and Jacobian:
/// Newton–Raphson through SUNDIALS KINSOL, and Levenberg–Marquardt through
/// Ceres as the robust fallback from poor guesses. Neither library appears
/// in this header.

#include <functional>
#include <limits>
#include <string>

#include <Eigen/Dense>

namespace impactkit {

/// Returns false when F cannot be evaluated at x (the impact map loses an
/// impact, say); the solvers then shorten their step.
using Residual = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* f)>;
using Jacobian = std::function<bool(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian)>;

enum class SolveTermination {
  kConverged,      ///< max |F(x)| <= residual_tolerance at the returned x
  kNoConvergence,  ///< iterations or step size ran out; x is the last iterate
  kFailure,        ///< the solver could not proceed (F failed everywhere it tried)
};

std::string ToString(SolveTermination termination);

struct NewtonOptions {
  /// Converged when max |F| is at most this (KINSOL's default stops near 1e-8).
  double residual_tolerance = 1e-11;
  /// Stop when a scaled step is below this.
  double step_tolerance = 1e-15;
  int max_iterations = 50;
  /// Backtracking line search on 0.5 |F|² (KINSOL's KIN_LINESEARCH).
  bool line_search = true;
  bool IsValid(std::string* error) const;
};

struct SolveSummary {
  SolveTermination termination = SolveTermination::kFailure;
  std::string message;
  int iterations = 0;
  double residual_norm = std::numeric_limits<double>::infinity();  ///< max |F(x)|
  double seconds = 0.0;
  std::string BriefReport() const;
};

/// Newton–Raphson through KINSOL (dense direct linear solver, the user's
/// Jacobian). x holds the guess on entry and the last iterate on exit.
SolveSummary SolveNewton(const Residual& residual, const Jacobian& jacobian,
                         const NewtonOptions& options, Eigen::VectorXd* x);

/// Levenberg–Marquardt on 0.5 |F|² through Ceres; converged only if
/// max |F| <= residual_tolerance at the end.
SolveSummary SolveLeastSquares(const Residual& residual, const Jacobian& jacobian,
                               const NewtonOptions& options, Eigen::VectorXd* x);

}  // namespace impactkit
