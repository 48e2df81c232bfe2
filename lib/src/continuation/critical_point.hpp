#pragma once
/// \file critical_point.hpp (private)
/// A fold or period doubling of a branch solved directly, rather than
/// bracketed along the branch: X = (η, μ) with
///
///     U(η; μ) = 0,   σ(D P − λ I) / (1 + ‖D P‖) = 0     (λ = +1 or −1)
///
/// (defining_function.hpp) by Newton. At a quadratic fold this system is
/// regular where U = 0 at fixed μ is singular (there a fresh solve finds η
/// only to about the square root of the map's rounding, and on a long orbit
/// the multiplier moves by 1e-3 with it); at a transversal period doubling
/// it is regular too. U's Jacobian is the branch's (analytic D P, U_μ by
/// the saltation relation); the σ row's gradient is a central difference.

#include <Eigen/Dense>
#include <optional>

#include "continuation/branch_problem.hpp"

namespace impactkit::detail {

/// The solution X of the system above for the multiplier `lambda` from
/// `guess` (a point near it, such as the best of a bracketing search), by
/// Newton with full steps; empty if it does not converge.
std::optional<Eigen::VectorXd> SolveCriticalPoint(const BranchProblem& problem,
                                                  const Eigen::VectorXd& guess, double lambda,
                                                  const NewtonOptions& newton);

}  // namespace impactkit::detail
