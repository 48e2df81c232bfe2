#include "continuation/critical_point.hpp"

#include <cmath>

#include "continuation/defining_function.hpp"

namespace impactkit::detail {

std::optional<Eigen::VectorXd> SolveCriticalPoint(const BranchProblem& problem,
                                                  const Eigen::VectorXd& guess, double lambda,
                                                  const NewtonOptions& newton) {
  Eigen::MatrixXd dp;
  if (!problem.MapJacobian(guess, &dp)) return std::nullopt;
  const SigmaBorders borders = MultiplierBorders(dp, lambda);
  // The map varies on a scale that shrinks as D P grows (near a slow
  // impact of speed v, D P ~ 1/v and the map's curvature ~ 1/v³), so the
  // σ row's difference step shrinks with it: on the paper's P(10,4) near a
  // graze (‖D P‖ ≈ 7400) the step 1e-6 left the gradient 45 % wrong and
  // Newton linear; 1e-6 / √‖D P‖ makes it quadratic, and leaves short
  // orbits (‖D P‖ ~ 1) at the curves' step.
  const double step = kDefiningStep / std::sqrt(1.0 + dp.norm());
  const Rows sigma = [&](const Eigen::VectorXd& x, Eigen::VectorXd* g) {
    Eigen::MatrixXd jacobian;
    if (!problem.MapJacobian(x, &jacobian)) return false;
    g->resize(1);
    (*g)(0) = kMultiplierRowWeight * MultiplierFunction(jacobian, lambda, borders);
    return g->allFinite();
  };
  const int n = problem.Size() - 1;
  const impactkit::Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    Eigen::VectorXd u, g;
    if (!problem.Residual(x, &u) || !sigma(x, &g)) return false;
    *f << u, g;
    return f->allFinite();
  };
  const impactkit::Jacobian jacobian = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    Eigen::MatrixXd ju, gradient;
    Eigen::VectorXd u;
    if (!problem.Jacobian(x, &ju) || !problem.Residual(x, &u)) return false;
    // σ is differenced only between maps that follow x's impacts.
    const Rows same_impacts = [&](const Eigen::VectorXd& at, Eigen::VectorXd* g) {
      Eigen::VectorXd u_at;
      return problem.Residual(at, &u_at) && SameImpacts(u_at - u, ju * (at - x)) && sigma(at, g);
    };
    if (!CentralDifferenceGradient(same_impacts, x, step, &gradient)) return false;
    j->topRows(n) = ju;
    j->bottomRows(1) = gradient;
    return j->allFinite();
  };
  // Full steps: the guess is close, and on a long orbit |U| reaches the
  // map's rounding (~1e-11) where a line search finds no decrease and stalls.
  NewtonOptions full_steps = newton;
  full_steps.line_search = false;
  Eigen::VectorXd x = guess;
  if (SolveNewton(residual, jacobian, full_steps, &x).termination != Termination::kConverged) {
    return std::nullopt;
  }
  return x;
}

}  // namespace impactkit::detail
