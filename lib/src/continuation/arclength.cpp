#include "continuation/arclength.hpp"

#include <fmt/format.h>

#include <cmath>

namespace impactkit {

std::optional<std::string> StepControlProblem(double min_step, double initial_step, double max_step,
                                              int max_points, int corrector_iterations,
                                              double max_correction) {
  if (!(min_step > 0 && min_step <= initial_step && initial_step <= max_step &&
        std::isfinite(max_step))) {
    return fmt::format(
        "steps must satisfy 0 < min_step <= initial_step <= max_step (finite), got min_step = "
        "{}, initial_step = {}, max_step = {}",
        min_step, initial_step, max_step);
  }
  if (max_points < 2) return fmt::format("max_points must be >= 2, got {}", max_points);
  if (corrector_iterations < 1) {
    return fmt::format("corrector_iterations must be >= 1, got {}", corrector_iterations);
  }
  if (!(max_correction > 0 && max_correction <= 1)) {
    return fmt::format("max_correction must be in (0, 1], got {}", max_correction);
  }
  return std::nullopt;
}

std::optional<std::string> UserTestProblem(const std::vector<UserTest>& tests) {
  for (std::size_t k = 0; k < tests.size(); ++k) {
    if (tests[k].name.empty() || !tests[k].value) {
      return fmt::format("user test {} needs a name and a value function", k + 1);
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (tests[j].name == tests[k].name) {
        return fmt::format("two user tests are named '{}'", tests[k].name);
      }
    }
  }
  return std::nullopt;
}

std::optional<Eigen::VectorXd> ArclengthTangent(const Eigen::MatrixXd& j,
                                                const Eigen::VectorXd& previous) {
  const Eigen::Index size = j.cols();
  Eigen::VectorXd t;
  if (previous.size() == size) {
    Eigen::MatrixXd bordered(size, size);
    bordered << j, previous.transpose();
    t = bordered.fullPivLu().solve(Eigen::VectorXd::Unit(size, size - 1));
  } else {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeFullV);
    t = svd.matrixV().col(size - 1);
  }
  if (!t.allFinite() || t.norm() == 0.0) return std::nullopt;
  return t.normalized();
}

std::optional<Eigen::VectorXd> CorrectBordered(const Residual& residual, const Jacobian& jacobian,
                                               const Eigen::VectorXd& guess,
                                               const Eigen::VectorXd& c, double value,
                                               const NewtonOptions& newton, int* iterations) {
  const Eigen::Index n = guess.size() - 1;
  const Residual bordered = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    Eigen::VectorXd fx;
    if (!residual(x, &fx)) return false;
    *f << fx, c.dot(x) - value;
    return f->allFinite();
  };
  const Jacobian bordered_jacobian = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    Eigen::MatrixXd jx;
    if (!jacobian(x, &jx)) return false;
    j->topRows(n) = jx;
    j->row(n) = c.transpose();
    return true;
  };
  Eigen::VectorXd x = guess;
  const SolveSummary summary = SolveNewton(bordered, bordered_jacobian, newton, &x);
  *iterations = summary.iterations;
  if (summary.termination != Termination::kConverged) return std::nullopt;
  return x;
}

}  // namespace impactkit
