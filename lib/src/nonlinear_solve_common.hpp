#pragma once
/// \file nonlinear_solve_common.hpp
/// The convergence test both nonlinear solvers end with.

#include "impactkit/nonlinear_solve.hpp"

namespace impactkit {

/// Throws InvalidInput for invalid options or an empty or non-finite guess.
void ValidateSolveInput(const NewtonOptions& options, const Eigen::VectorXd& x);

/// Sets residual_norm = max |F(x)| and decides convergence from it alone,
/// whatever the solver's own norms said; records the elapsed seconds.
void FinishSolve(const Residual& residual, const NewtonOptions& options, const Eigen::VectorXd& x,
                 double seconds, SolveSummary* summary);

}  // namespace impactkit
