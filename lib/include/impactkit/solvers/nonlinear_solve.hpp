#pragma once
/// \file nonlinear_solve.hpp
/// Square nonlinear systems F(x) = 0, F: R^n -> R^n, with the user's
/// residual and Jacobian: Newton–Raphson through SUNDIALS KINSOL, and
/// Levenberg–Marquardt through Ceres as the robust fallback from poor
/// guesses. Neither library appears in this header.
///
/// Both solvers decide convergence the same way, by the user's tolerance on
/// max_i |F_i| at the returned point, whatever the library's own tests said;
/// a point where F is not finite never counts.

#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <string>

#include "impactkit/core/termination.hpp"

namespace impactkit {

/// Writes F(x) into f, which arrives sized n. Returns false when F cannot be
/// evaluated at x (the impact map loses an impact, say); the solvers then
/// shorten their step. A non-finite f counts as false. Exceptions propagate
/// out of the solve.
using Residual = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* f)>;
/// Writes dF/dx (n x n) into jacobian, which arrives sized n x n. Returns
/// false when it cannot be evaluated; both solvers then stop (kFailure).
using Jacobian = std::function<bool(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian)>;

struct NewtonOptions {
  /// Converged when max_i |F_i(x)| is at most this (KINSOL's own default,
  /// cbrt(machine epsilon) ~ 6e-6, is far too loose for orbits).
  double residual_tolerance = 1e-11;
  /// Stop when the step is this small relative to x: for Newton, KINSOL's
  /// max_i |Δx_i| / (1 + |x_i|); for Levenberg–Marquardt, Ceres's
  /// |Δx| <= step_tolerance (|x| + step_tolerance).
  double step_tolerance = 1e-15;
  /// Newton iterations; Levenberg–Marquardt gets 10 times as many steps
  /// (it is the fallback from poor guesses, and counts rejected steps).
  int max_iterations = 50;
  /// Newton only: backtracking line search on 0.5 |F|² (KINSOL's
  /// KIN_LINESEARCH) instead of full steps.
  bool line_search = true;

  /// False, with the reason in *error (if given), when a field is out of range.
  bool IsValid(std::string* error) const;
};

/// Summary::iterations counts Newton iterations, or LM steps tried.
struct SolveSummary : Summary {
  int residual_evaluations = 0;                                    ///< calls of the user's residual
  int jacobian_evaluations = 0;                                    ///< calls of the user's Jacobian
  double residual_norm = std::numeric_limits<double>::infinity();  ///< max |F(x)| at the returned x

  /// One line: termination, max|F|, counts, time and message.
  std::string BriefReport() const;
};

/// Newton–Raphson through KINSOL: dense direct linear solver, the user's
/// Jacobian at every iteration, optional line search, tolerances set
/// explicitly. x holds the guess on entry and the best point found (least
/// max |F|) on exit.
/// Throws InvalidInput for invalid options, an empty or non-finite guess, or
/// callbacks that return the wrong sizes.
SolveSummary SolveNewton(const Residual& residual, const Jacobian& jacobian,
                         const NewtonOptions& options, Eigen::VectorXd* x);

/// Levenberg–Marquardt on 0.5 |F|² through Ceres (dense QR, the user's
/// Jacobian); it stops as soon as max |F| <= residual_tolerance. x and the
/// exceptions as for SolveNewton.
SolveSummary SolveLeastSquares(const Residual& residual, const Jacobian& jacobian,
                               const NewtonOptions& options, Eigen::VectorXd* x);

}  // namespace impactkit
