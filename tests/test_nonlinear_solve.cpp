#include <cmath>

#include <catch2/catch.hpp>

#include "impactkit/model.hpp"
#include "impactkit/nonlinear_solve.hpp"

using Catch::Matchers::WithinAbs;
using namespace impactkit;

namespace {

/// A problem F(x) = 0 with its Jacobian, as the solvers take them.
struct Problem {
  Residual residual;
  Jacobian jacobian;
};

/// x² + y² = 4, x = y: root (√2, √2).
Problem CircleAndDiagonal() {
  return {[](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
            *f = Eigen::Vector2d(x.squaredNorm() - 4.0, x(0) - x(1));
            return true;
          },
          [](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
            *j = (Eigen::Matrix2d() << 2 * x(0), 2 * x(1), 1.0, -1.0).finished();
            return true;
          }};
}

}  // namespace

TEST_CASE("Newton through KINSOL converges quadratically to the tolerance", "[solve]") {
  const Problem p = CircleAndDiagonal();
  Eigen::VectorXd x = Eigen::Vector2d(3.0, 1.0);
  const SolveSummary s = SolveNewton(p.residual, p.jacobian, NewtonOptions{}, &x);
  CHECK(s.termination == SolveTermination::kConverged);
  CHECK(s.residual_norm <= 1e-11);
  CHECK(s.iterations <= 8);
  CHECK_THAT(x(0), WithinAbs(std::sqrt(2.0), 1e-12));
  CHECK_THAT(x(1), WithinAbs(std::sqrt(2.0), 1e-12));
}

TEST_CASE("a linear system is solved in one or two iterations", "[solve]") {
  Eigen::MatrixXd a = Eigen::MatrixXd::Random(5, 5) + 5.0 * Eigen::MatrixXd::Identity(5, 5);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(5, -1.0, 2.0);
  const Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    *f = a * x - b;
    return true;
  };
  const Jacobian jacobian = [&](const Eigen::VectorXd&, Eigen::MatrixXd* j) {
    *j = a;
    return true;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(5);
  const SolveSummary s = SolveNewton(residual, jacobian, NewtonOptions{}, &x);
  CHECK(s.termination == SolveTermination::kConverged);
  CHECK(s.iterations <= 2);
  CHECK((x - a.lu().solve(b)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("a residual that cannot be evaluated everywhere makes Newton shorten its step",
          "[solve]") {
  // F = x - 1, defined on x < 2 only. With a Jacobian of 0.05 instead of 1,
  // the full step from x = 0 lands at x = 20, where F fails: the solver
  // must shorten the step (KINSOL's recoverable error) and still converge.
  const Residual residual = [](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    if (x(0) >= 2.0) return false;
    *f = Eigen::VectorXd::Constant(1, x(0) - 1.0);
    return true;
  };
  const Jacobian jacobian = [](const Eigen::VectorXd&, Eigen::MatrixXd* j) {
    *j = Eigen::MatrixXd::Constant(1, 1, 0.05);
    return true;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  NewtonOptions options;
  options.max_iterations = 200;
  const SolveSummary s = SolveNewton(residual, jacobian, options, &x);
  CHECK(s.termination == SolveTermination::kConverged);
  CHECK_THAT(x(0), WithinAbs(1.0, 1e-11));
}

TEST_CASE("Levenberg-Marquardt converges where Newton from a poor guess does not", "[solve]") {
  // F = (10 (y - x²), 1 - x) (Rosenbrock's residuals), root (1, 1). Plain
  // Newton without a line search from (-1.2, 1) with a 2-iteration budget
  // cannot get there; Levenberg-Marquardt does.
  const Residual residual = [](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    *f = Eigen::Vector2d(10.0 * (x(1) - x(0) * x(0)), 1.0 - x(0));
    return true;
  };
  const Jacobian jacobian = [](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    *j = (Eigen::Matrix2d() << -20.0 * x(0), 10.0, -1.0, 0.0).finished();
    return true;
  };
  NewtonOptions options;
  options.max_iterations = 1;
  options.line_search = false;
  Eigen::VectorXd x = Eigen::Vector2d(-1.2, 1.0);
  CHECK(SolveNewton(residual, jacobian, options, &x).termination !=
        SolveTermination::kConverged);
  x = Eigen::Vector2d(-1.2, 1.0);
  options.max_iterations = 50;
  const SolveSummary s = SolveLeastSquares(residual, jacobian, options, &x);
  CHECK(s.termination == SolveTermination::kConverged);
  CHECK((x - Eigen::Vector2d(1.0, 1.0)).cwiseAbs().maxCoeff() < 1e-10);
}

TEST_CASE("no root, or NaN, is never reported as converged", "[solve]") {
  const Residual no_root = [](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    *f = Eigen::VectorXd::Constant(1, x(0) * x(0) + 1.0);
    return true;
  };
  const Jacobian no_root_jacobian = [](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    *j = Eigen::MatrixXd::Constant(1, 1, 2.0 * x(0));
    return true;
  };
  for (auto solve : {SolveNewton, SolveLeastSquares}) {
    Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 0.7);
    const SolveSummary s = solve(no_root, no_root_jacobian, NewtonOptions{}, &x);
    CHECK(s.termination != SolveTermination::kConverged);
    CHECK(x.allFinite());
    CHECK(s.residual_norm >= 1.0);
  }
  const Residual nan = [](const Eigen::VectorXd&, Eigen::VectorXd* f) {
    *f = Eigen::VectorXd::Constant(1, std::nan(""));
    return true;
  };
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 0.7);
  CHECK(SolveNewton(nan, no_root_jacobian, NewtonOptions{}, &x).termination !=
        SolveTermination::kConverged);
}

TEST_CASE("solver options are checked", "[solve]") {
  std::string error;
  CHECK(NewtonOptions{}.IsValid(&error));
  NewtonOptions bad;
  bad.residual_tolerance = -1.0;
  CHECK_FALSE(bad.IsValid(&error));
  bad = NewtonOptions{};
  bad.max_iterations = 0;
  CHECK_FALSE(bad.IsValid(&error));
  const Problem p = CircleAndDiagonal();
  Eigen::VectorXd empty;
  CHECK_THROWS_AS(SolveNewton(p.residual, p.jacobian, NewtonOptions{}, &empty), InvalidInput);
}
