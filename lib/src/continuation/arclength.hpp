#pragma once
/// \file arclength.hpp
/// What every pseudo-arclength driver (branches, two-parameter curves)
/// shares: the checks of its step controls, so that their messages agree,
/// and the tangent of the solution curve of an underdetermined system.

#include <Eigen/Dense>
#include <optional>
#include <string>

#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit {

/// What is wrong with the step controls, or nothing: 0 < min_step <=
/// initial_step <= max_step (finite), max_points >= 2, corrector_iterations
/// >= 1, max_correction in (0, 1].
std::optional<std::string> StepControlProblem(double min_step, double initial_step, double max_step,
                                              int max_points, int corrector_iterations,
                                              double max_correction);

/// The unit tangent of {x : F(x) = 0} at a point where F's Jacobian `j`
/// (n x (n + 1)) has full rank: with `previous` (a tangent, size n + 1) the
/// solution of the bordered system [J; previousᵀ] t = e_last, regular at
/// folds and continuing `previous` (previous · t = 1 > 0); without (size 0)
/// the null vector of J from its SVD, of either sign. Nothing where J is
/// singular or not finite.
/// The bordered corrector: solves F(x) = 0 (n equations, `residual`, with
/// its n x (n + 1) Jacobian `jacobian`) together with c · x = value (the
/// pseudo-arclength constraint, or a parameter held fixed) by Newton from
/// `guess`. Empty if Newton does not converge; *iterations gets its count.
std::optional<Eigen::VectorXd> CorrectBordered(const Residual& residual, const Jacobian& jacobian,
                                               const Eigen::VectorXd& guess,
                                               const Eigen::VectorXd& c, double value,
                                               const NewtonOptions& newton, int* iterations);

std::optional<Eigen::VectorXd> ArclengthTangent(const Eigen::MatrixXd& j,
                                                const Eigen::VectorXd& previous);

}  // namespace impactkit
