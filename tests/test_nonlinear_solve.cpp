#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#if __has_include(<unistd.h>)
#include <unistd.h>
#define IMPACTKIT_TEST_HAS_UNISTD 1
#endif

#include "impactkit/model/system.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using namespace impactkit;

namespace {

using Solver = SolveSummary (*)(const Residual&, const Jacobian&, const NewtonOptions&,
                                Eigen::VectorXd*);

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

/// F = atan(x), root 0. Full Newton steps from |x| > 1.39 overshoot and diverge.
Problem Arctangent() {
  return {[](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
            *f = Eigen::VectorXd::Constant(1, std::atan(x(0)));
            return true;
          },
          [](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
            *j = Eigen::MatrixXd::Constant(1, 1, 1.0 / (1.0 + x(0) * x(0)));
            return true;
          }};
}

/// F = x² + 1: no real root; max |F| >= 1 everywhere.
Problem NoRoot() {
  return {[](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
            *f = Eigen::VectorXd::Constant(1, x(0) * x(0) + 1.0);
            return true;
          },
          [](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
            *j = Eigen::MatrixXd::Constant(1, 1, 2.0 * x(0));
            return true;
          }};
}

#ifdef IMPACTKIT_TEST_HAS_UNISTD
/// Runs `run` with the stdout and stderr file descriptors (so C stdio and
/// glog too) redirected to a temporary file; returns what was written.
std::string CaptureOutput(const std::function<void()>& run) {
  std::fflush(stdout);
  std::fflush(stderr);
  std::FILE* file = std::tmpfile();
  REQUIRE(file != nullptr);
  const int saved_out = dup(1), saved_err = dup(2);
  dup2(fileno(file), 1);
  dup2(fileno(file), 2);
  auto restore = [&] {
    std::fflush(stdout);
    std::fflush(stderr);
    dup2(saved_out, 1);
    dup2(saved_err, 2);
    close(saved_out);
    close(saved_err);
  };
  try {
    run();
  } catch (...) {
    restore();
    std::fclose(file);
    throw;
  }
  restore();
  std::string text;
  std::rewind(file);
  for (int c; (c = std::fgetc(file)) != EOF;) text += static_cast<char>(c);
  std::fclose(file);
  return text;
}
#endif

}  // namespace

TEST_CASE("Newton through KINSOL converges quadratically to the tolerance", "[solve]") {
  const Problem p = CircleAndDiagonal();
  const Eigen::Vector2d root(std::sqrt(2.0), std::sqrt(2.0));
  // The Jacobian is evaluated once per iteration, at the current iterate.
  std::vector<double> errors;
  const Jacobian recording = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    errors.push_back((x - root).norm());
    return p.jacobian(x, j);
  };
  Eigen::VectorXd x = Eigen::Vector2d(3.0, 1.0);
  const SolveSummary s = SolveNewton(p.residual, recording, NewtonOptions{}, &x);
  INFO(s.BriefReport());
  CHECK(s.termination == Termination::kConverged);
  CHECK(s.residual_norm <= 1e-11);
  CHECK(s.iterations <= 8);                       // 5 observed
  CHECK(s.jacobian_evaluations == s.iterations);  // exact Newton: a fresh Jacobian each time
  CHECK(s.residual_evaluations >= s.iterations + 1);
  CHECK_THAT(x(0), WithinAbs(root(0), 1e-12));
  CHECK_THAT(x(1), WithinAbs(root(1), 1e-12));
  // Quadratic: once close, e_{k+1} <= C e_k² with C of the order of
  // |F''| / |F'| (here 1/(2√2) ~ 0.35 along the diagonal).
  REQUIRE(errors.size() >= 3);
  int quadratic_steps = 0;
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    if (errors[k] < 0.1 && errors[k + 1] > 1e-14) {
      CHECK(errors[k + 1] <= 1.0 * errors[k] * errors[k]);
      ++quadratic_steps;
    }
  }
  CHECK(quadratic_steps >= 1);
}

TEST_CASE("a linear system is solved in one Newton iteration, far from the guess", "[solve]") {
  // Solution of norm ~ 40 from the guess 0: KINSOL's default step cap
  // (1000 |x0|, at least 1) would take capped steps and give up after five.
  Eigen::MatrixXd a(5, 5);
  a << 4, 1, 0, 0, 2,  //
      1, 5, 1, 0, 0,   //
      0, 1, 6, 1, 0,   //
      0, 0, 1, 7, 1,   //
      2, 0, 0, 1, 8;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(5, -100.0, 200.0);
  const Eigen::VectorXd expected = a.colPivHouseholderQr().solve(b);
  REQUIRE(expected.norm() > 10.0);
  const Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    *f = a * x - b;
    return true;
  };
  const Jacobian jacobian = [&](const Eigen::VectorXd&, Eigen::MatrixXd* j) {
    *j = a;
    return true;
  };
  for (const bool line_search : {true, false}) {
    NewtonOptions options;
    options.line_search = line_search;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(5);
    const SolveSummary s = SolveNewton(residual, jacobian, options, &x);
    INFO(s.BriefReport());
    CHECK(s.termination == Termination::kConverged);
    CHECK(s.iterations >= 1);
    CHECK(s.iterations <= 2);  // 1 observed
    CHECK((x - expected).cwiseAbs().maxCoeff() <= 1e-12 * expected.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("a residual that fails in part of the domain makes Newton shorten its step", "[solve]") {
  // atan(x), but F cannot be evaluated for x < -1 (returns false, or NaN).
  // The full Newton step from 1.5 lands at 1.5 - atan(1.5)(1 + 1.5²) =
  // -1.694: KINSOL must halve it (-0.097) and go on from there.
  const Problem p = Arctangent();
  for (const bool report_nan : {false, true}) {
    int failures = 0;
    const Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
      if (x(0) < -1.0) {
        ++failures;
        if (!report_nan) return false;
        *f = Eigen::VectorXd::Constant(1, std::numeric_limits<double>::quiet_NaN());
        return true;
      }
      return p.residual(x, f);
    };
    for (const bool line_search : {true, false}) {
      NewtonOptions options;
      options.line_search = line_search;
      failures = 0;
      Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.5);
      const SolveSummary s = SolveNewton(residual, p.jacobian, options, &x);
      INFO(s.BriefReport() << " (NaN: " << report_nan << ", line search: " << line_search << ")");
      CHECK(failures >= 1);  // the failing region was really visited
      CHECK(s.termination == Termination::kConverged);
      CHECK_THAT(x(0), WithinAbs(0.0, 1e-11));
    }
    // Levenberg-Marquardt rejects the failed step and shrinks its region.
    failures = 0;
    Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.5);
    const SolveSummary s = SolveLeastSquares(residual, p.jacobian, NewtonOptions{}, &x);
    INFO(s.BriefReport());
    CHECK(s.termination == Termination::kConverged);
    CHECK_THAT(x(0), WithinAbs(0.0, 1e-11));
  }
}

TEST_CASE("Levenberg-Marquardt converges where Newton from a poor guess does not", "[solve]") {
  SECTION("Powell's example: the line search stalls at a point that is not stationary") {
    // Powell (1970): F = (x, 10x/(x + 0.1) + 2y²), root (0, 0). The Jacobian
    // is singular on y = 0; from (1, 0.5) the line-search Newton directions
    // turn orthogonal to the gradient of |F|² and the iterates stall near
    // (0.897, -0.001) with max|F| ~ 9, while the gradient there is ~ (9.9, 0):
    // no minimum at all. KINSOL stays there for 1000 iterations. LM takes
    // ~160 steps (the root is singular, so the last ones are slow).
    // (Not chosen: Rosenbrock's residuals (10(y - x²), 1 - x) from (-1.2, 1),
    // which Newton solves exactly in 2 full steps, 14 with the line search;
    // Powell's badly scaled function from (0, 1), where the line search is
    // merely slow: 51 iterations, just over the default 50.)
    const Residual residual = [](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
      *f = Eigen::Vector2d(x(0), 10.0 * x(0) / (x(0) + 0.1) + 2.0 * x(1) * x(1));
      return true;
    };
    const Jacobian jacobian = [](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
      const double d = x(0) + 0.1;
      *j = (Eigen::Matrix2d() << 1.0, 0.0, 1.0 / (d * d), 4.0 * x(1)).finished();
      return true;
    };
    const Eigen::Vector2d guess(1.0, 0.5);
    NewtonOptions options;
    options.max_iterations = 200;
    Eigen::VectorXd x = guess;
    const SolveSummary newton = SolveNewton(residual, jacobian, options, &x);
    INFO(newton.BriefReport());
    CHECK(newton.termination == Termination::kNoConvergence);
    CHECK(newton.residual_norm > 1.0);
    CHECK(x.allFinite());

    x = guess;
    const SolveSummary lm = SolveLeastSquares(residual, jacobian, NewtonOptions{}, &x);
    INFO(lm.BriefReport());
    CHECK(lm.termination == Termination::kConverged);
    CHECK(lm.residual_norm <= 1e-11);
    // At a singular root the tolerance on F bounds x to 1e-11 but y only to
    // about sqrt((1e-11 + 100 |x|) / 2) ~ 2e-5.
    CHECK_THAT(x(0), WithinAbs(0.0, 1e-11));
    CHECK_THAT(x(1), WithinAbs(0.0, 1e-4));
  }

  SECTION("full Newton steps diverge on atan; x is then the best point, the guess") {
    const Problem p = Arctangent();
    NewtonOptions options;
    options.line_search = false;
    Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 2.0);
    const SolveSummary newton = SolveNewton(p.residual, p.jacobian, options, &x);
    INFO(newton.BriefReport());
    CHECK(newton.termination == Termination::kNoConvergence);  // KIN_MXNEWT_5X_EXCEEDED
    CHECK(x(0) == 2.0);
    CHECK_THAT(newton.residual_norm, WithinRel(std::atan(2.0), 1e-15));

    const SolveSummary lm = SolveLeastSquares(p.residual, p.jacobian, options, &x);
    INFO(lm.BriefReport());
    CHECK(lm.termination == Termination::kConverged);
    CHECK_THAT(x(0), WithinAbs(0.0, 1e-11));
  }
}

TEST_CASE("no root is never reported as converged", "[solve]") {
  const Problem p = NoRoot();
  for (const Solver solve : {&SolveNewton, &SolveLeastSquares}) {
    for (const double guess : {0.7, -3.0}) {
      Eigen::VectorXd x = Eigen::VectorXd::Constant(1, guess);
      const SolveSummary s = solve(p.residual, p.jacobian, NewtonOptions{}, &x);
      INFO(s.BriefReport());
      CHECK(s.termination != Termination::kConverged);
      CHECK(x.allFinite());
      CHECK(s.residual_norm >= 1.0);
      CHECK(std::isfinite(s.residual_norm));
      Eigen::VectorXd f;
      p.residual(x, &f);
      CHECK(s.residual_norm == f(0));  // the norm is that of the returned point
    }
  }
}

TEST_CASE("NaN in the residual is never reported as converged", "[solve]") {
  const Jacobian identity = [](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    *j = Eigen::MatrixXd::Identity(x.size(), x.size());
    return true;
  };
  SECTION("NaN everywhere: failure, the guess is kept") {
    const Residual nan = [](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
      *f = Eigen::VectorXd::Constant(x.size(), std::numeric_limits<double>::quiet_NaN());
      return true;
    };
    for (const Solver solve : {&SolveNewton, &SolveLeastSquares}) {
      Eigen::VectorXd x = Eigen::Vector2d(0.7, 0.1);
      const SolveSummary s = solve(nan, identity, NewtonOptions{}, &x);
      INFO(s.BriefReport());
      CHECK(s.termination == Termination::kFailure);
      CHECK(s.iterations == 0);
      CHECK(x == Eigen::Vector2d(0.7, 0.1));
      CHECK(s.residual_norm == std::numeric_limits<double>::infinity());
    }
  }
  SECTION("NaN near the root: the root is never reached, nor claimed") {
    // F = x - 1, but NaN within 1e-3 of the root.
    const Residual nan_at_root = [](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
      *f = x - Eigen::VectorXd::Ones(x.size());
      if (f->cwiseAbs().maxCoeff() < 1e-3) f->setConstant(std::nan(""));
      return true;
    };
    for (const Solver solve : {&SolveNewton, &SolveLeastSquares}) {
      Eigen::VectorXd x = Eigen::Vector2d(3.0, -2.0);
      const SolveSummary s = solve(nan_at_root, identity, NewtonOptions{}, &x);
      INFO(s.BriefReport());
      CHECK(s.termination != Termination::kConverged);
      CHECK(x.allFinite());
      CHECK(s.residual_norm >= 1e-3);
      CHECK(std::isfinite(s.residual_norm));
    }
  }
}

TEST_CASE("solver options are checked", "[solve]") {
  std::string error;
  CHECK(NewtonOptions{}.IsValid(&error));
  CHECK(NewtonOptions{}.IsValid(nullptr));
  NewtonOptions bad;
  bad.residual_tolerance = -1.0;
  CHECK_FALSE(bad.IsValid(&error));
  CHECK_THAT(error, Contains("residual_tolerance"));
  bad = NewtonOptions{};
  bad.residual_tolerance = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(bad.IsValid(&error));
  bad = NewtonOptions{};
  bad.step_tolerance = 0.0;  // KINSOL would quietly take 0 as "use the default"
  CHECK_FALSE(bad.IsValid(&error));
  CHECK_THAT(error, Contains("step_tolerance"));
  bad = NewtonOptions{};
  bad.max_iterations = 0;
  CHECK_FALSE(bad.IsValid(&error));
  CHECK_THAT(error, Contains("max_iterations"));

  const Problem p = CircleAndDiagonal();
  for (const Solver solve : {&SolveNewton, &SolveLeastSquares}) {
    NewtonOptions zero_iterations;
    zero_iterations.max_iterations = 0;
    Eigen::VectorXd x = Eigen::Vector2d(3.0, 1.0);
    CHECK_THROWS_AS(solve(p.residual, p.jacobian, zero_iterations, &x), InvalidInput);
    Eigen::VectorXd empty;
    CHECK_THROWS_AS(solve(p.residual, p.jacobian, NewtonOptions{}, &empty), InvalidInput);
    Eigen::VectorXd infinite = Eigen::Vector2d(3.0, std::numeric_limits<double>::infinity());
    CHECK_THROWS_AS(solve(p.residual, p.jacobian, NewtonOptions{}, &infinite), InvalidInput);
  }
}

TEST_CASE("callbacks of the wrong size, or that throw, end the solve with an exception",
          "[solve]") {
  const Problem p = CircleAndDiagonal();
  const Residual too_long = [](const Eigen::VectorXd&, Eigen::VectorXd* f) {
    *f = Eigen::Vector3d(1.0, 2.0, 3.0);
    return true;
  };
  const Jacobian not_square = [](const Eigen::VectorXd&, Eigen::MatrixXd* j) {
    *j = Eigen::MatrixXd::Ones(2, 3);
    return true;
  };
  const Residual throws = [](const Eigen::VectorXd&, Eigen::VectorXd*) -> bool {
    throw std::runtime_error("from the residual");
  };
  // Throws on the third call, in mid-solve.
  int calls = 0;
  const Residual throws_later = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    if (++calls == 3) throw std::runtime_error("from the residual, later");
    return p.residual(x, f);
  };
  for (const Solver solve : {&SolveNewton, &SolveLeastSquares}) {
    Eigen::VectorXd x = Eigen::Vector2d(3.0, 1.0);
    CHECK_THROWS_AS(solve(too_long, p.jacobian, NewtonOptions{}, &x), InvalidInput);
    CHECK_THROWS_AS(solve(p.residual, not_square, NewtonOptions{}, &x), InvalidInput);
    CHECK_THROWS_WITH(solve(throws, p.jacobian, NewtonOptions{}, &x), "from the residual");
    calls = 0;
    CHECK_THROWS_WITH(solve(throws_later, p.jacobian, NewtonOptions{}, &x),
                      "from the residual, later");
    CHECK(calls == 3);  // nothing called after the exception
  }
}

TEST_CASE("Levenberg-Marquardt stops at the tolerance on max|F|", "[solve]") {
  const Problem p = CircleAndDiagonal();
  Eigen::VectorXd x = Eigen::Vector2d(3.0, 1.0);
  const SolveSummary s = SolveLeastSquares(p.residual, p.jacobian, NewtonOptions{}, &x);
  INFO(s.BriefReport());
  CHECK(s.termination == Termination::kConverged);
  CHECK(s.residual_norm <= 1e-11);
  CHECK(s.iterations <= 20);  // 6 observed
  CHECK(s.jacobian_evaluations >= 1);
  CHECK(s.residual_evaluations >= s.jacobian_evaluations);
  CHECK(s.seconds >= 0.0);
  CHECK_THAT(x(0), WithinAbs(std::sqrt(2.0), 1e-11));
  CHECK_THAT(s.BriefReport(), Contains("converged") && Contains("Levenberg-Marquardt"));
}

#ifdef IMPACTKIT_TEST_HAS_UNISTD
TEST_CASE("the solvers print nothing, even when they fail", "[solve]") {
  const Problem no_root = NoRoot();
  const Problem arctangent = Arctangent();
  const Residual never = [](const Eigen::VectorXd&, Eigen::VectorXd*) { return false; };
  // A Jacobian that fails away from the guess: Ceres would log an error if
  // told so at a point it has accepted.
  const Jacobian fails_below_one = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    return x(0) >= 1.0 && arctangent.jacobian(x, j);
  };
  SolveSummary singular, first_call, lm_failure, lm_no_root, jacobian_later, lm_jacobian_later;
  Eigen::VectorXd lm_jacobian_later_x;
  const std::string output = CaptureOutput([&] {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(1);  // J = 0 there
    singular = SolveNewton(no_root.residual, no_root.jacobian, NewtonOptions{}, &x);
    x.setConstant(0.7);
    first_call = SolveNewton(never, no_root.jacobian, NewtonOptions{}, &x);
    lm_failure = SolveLeastSquares(never, no_root.jacobian, NewtonOptions{}, &x);
    lm_no_root = SolveLeastSquares(no_root.residual, no_root.jacobian, NewtonOptions{}, &x);
    x.setConstant(1.5);
    jacobian_later = SolveNewton(arctangent.residual, fails_below_one, NewtonOptions{}, &x);
    x.setConstant(1.5);
    lm_jacobian_later =
        SolveLeastSquares(arctangent.residual, fails_below_one, NewtonOptions{}, &x);
    lm_jacobian_later_x = x;
  });
  INFO("printed: " << output);
  CHECK(output.empty());
  CHECK(singular.termination == Termination::kFailure);
  CHECK_THAT(singular.message, Contains("KIN_LSETUP_FAIL"));
  CHECK(first_call.termination == Termination::kFailure);
  CHECK_THAT(first_call.message, Contains("KIN_FIRST_SYSFUNC_ERR"));
  CHECK(lm_failure.termination == Termination::kFailure);
  CHECK(lm_no_root.termination == Termination::kNoConvergence);
  CHECK(jacobian_later.termination == Termination::kFailure);
  CHECK_THAT(jacobian_later.message, Contains("KIN_LSETUP_FAIL"));
  CHECK(lm_jacobian_later.termination == Termination::kFailure);
  // x is the best point, one where F was fine but J was not (below 1).
  CHECK(lm_jacobian_later_x(0) < 1.0);
  CHECK_THAT(lm_jacobian_later.residual_norm,
             WithinRel(std::abs(std::atan(lm_jacobian_later_x(0))), 1e-15));
  CHECK(lm_jacobian_later.residual_norm < std::atan(1.5));
}
#endif
