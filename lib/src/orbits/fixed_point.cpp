#include "orbits/fixed_point.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace impactkit {

bool FixedPointProblem::Residual(const Eigen::VectorXd& x, Eigen::VectorXd* u) const {
  SectionImage image = map_.Iterate(x, k_, analytic_);
  if (!image.Ok()) return false;
  if (analytic_) {
    cached_x_ = x;
    cached_jacobian_ = std::move(image.jacobian);
  }
  *u = image.state - x;
  (*u)(map_.TimeIndex()) -= shift_;
  return u->allFinite();
}

bool FixedPointProblem::Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian) const {
  if (!analytic_) {
    *jacobian = FiniteDifferenceJacobian(map_, x, k_);
    if (jacobian->size() == 0) return false;
  } else if (cached_x_.size() == x.size() && cached_x_ == x) {
    *jacobian = cached_jacobian_;
  } else {
    SectionImage image = map_.Iterate(x, k_, true);
    if (!image.Ok()) return false;
    *jacobian = std::move(image.jacobian);
  }
  jacobian->diagonal().array() -= 1.0;
  return jacobian->allFinite();
}

FixedPointSolve SolveFixedPoint(const FixedPointProblem& problem, const Eigen::VectorXd& guess,
                                const NewtonOptions& newton, bool least_squares_fallback) {
  const Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* u) {
    return problem.Residual(x, u);
  };
  const Jacobian jacobian = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    return problem.Jacobian(x, j);
  };
  FixedPointSolve result;
  result.x = guess;
  const SectionImage seed = problem.Map().Iterate(guess, problem.Events(), false);
  if (!seed.Ok()) {
    result.solve.termination = Termination::kFailure;
    result.solve.message = "the map failed at the seed: " + seed.failure;
    return result;
  }
  result.solve = SolveNewton(residual, jacobian, newton, &result.x);
  result.iterations = result.solve.iterations;
  if (result.solve.termination != Termination::kConverged && least_squares_fallback) {
    result.x = guess;
    result.solve = SolveLeastSquares(residual, jacobian, newton, &result.x);
    result.iterations += result.solve.iterations;
    result.used_fallback = true;
  }
  result.x = problem.Map().WithPhase(result.x);
  return result;
}

std::string SolveReport(Termination termination, double residual, int iterations) {
  const std::string norm = std::isfinite(residual) ? fmt::format(" residual {:.2e}", residual) : "";
  return fmt::format("{}:{} after {} iterations", Describe(termination), norm, iterations);
}

}  // namespace impactkit
