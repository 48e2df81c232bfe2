/// What the two nonlinear solvers share: options, summaries, the guarded
/// callbacks, and the one convergence test (max |F| at the returned point).

#include "impactkit/solvers/nonlinear_solve.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "impactkit/core/errors.hpp"
#include "solvers/nonlinear_solve_common.hpp"

namespace impactkit {

bool NewtonOptions::IsValid(std::string* error) const {
  auto fail = [&](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (!(residual_tolerance > 0 && std::isfinite(residual_tolerance))) {
    return fail(
        fmt::format("residual_tolerance must be finite and > 0, got {}", residual_tolerance));
  }
  if (!(step_tolerance > 0 && std::isfinite(step_tolerance))) {
    return fail(fmt::format("step_tolerance must be finite and > 0, got {}", step_tolerance));
  }
  if (max_iterations < 1) {
    return fail(fmt::format("max_iterations must be >= 1, got {}", max_iterations));
  }
  return true;
}

std::string SolveSummary::BriefReport() const {
  return fmt::format(
      "{}: max|F| = {:.3g} after {} iterations ({} F, {} J evaluations, {:.3g} s){}{}",
      Describe(termination), residual_norm, iterations, residual_evaluations, jacobian_evaluations,
      seconds, message.empty() ? "" : "; ", message);
}

void ValidateSolveInput(const NewtonOptions& options, const Eigen::VectorXd& x) {
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  if (x.size() == 0 || !x.allFinite()) {
    throw InvalidInput("the initial guess must be non-empty and finite");
  }
}

GuardedProblem::GuardedProblem(const Residual& residual, const Jacobian& jacobian, Eigen::Index n)
    : residual_(residual), jacobian_(jacobian), n_(n), x_(n), f_(n), j_(n, n) {}

GuardedProblem::Outcome GuardedProblem::Hold(std::exception_ptr error) {
  error_ = std::move(error);
  return Outcome::kAbort;
}

GuardedProblem::Outcome GuardedProblem::EvaluateResidual(const double* x) {
  if (error_) return Outcome::kAbort;
  x_ = Eigen::Map<const Eigen::VectorXd>(x, n_);
  if (!x_.allFinite()) return Outcome::kNotEvaluable;
  f_.resize(n_);
  bool ok = false;
  ++residual_evaluations_;
  try {
    ok = residual_(x_, &f_);
  } catch (...) {
    return Hold(std::current_exception());
  }
  if (!ok) return Outcome::kNotEvaluable;
  if (f_.size() != n_) {
    return Hold(std::make_exception_ptr(InvalidInput(
        fmt::format("the residual must have the size of x, {}, but has size {}", n_, f_.size()))));
  }
  if (!f_.allFinite()) return Outcome::kNotEvaluable;
  const double norm = f_.cwiseAbs().maxCoeff();
  if (norm < best_norm_) {
    best_norm_ = norm;
    best_x_ = x_;
  }
  return Outcome::kOk;
}

GuardedProblem::Outcome GuardedProblem::EvaluateJacobian(const double* x) {
  if (error_) return Outcome::kAbort;
  x_ = Eigen::Map<const Eigen::VectorXd>(x, n_);
  if (!x_.allFinite()) return Outcome::kNotEvaluable;
  j_.resize(n_, n_);
  bool ok = false;
  ++jacobian_evaluations_;
  try {
    ok = jacobian_(x_, &j_);
  } catch (...) {
    return Hold(std::current_exception());
  }
  if (!ok) return Outcome::kNotEvaluable;
  if (j_.rows() != n_ || j_.cols() != n_) {
    return Hold(std::make_exception_ptr(InvalidInput(fmt::format(
        "the Jacobian must be {0} x {0}, but is {1} x {2}", n_, j_.rows(), j_.cols()))));
  }
  return j_.allFinite() ? Outcome::kOk : Outcome::kNotEvaluable;
}

void GuardedProblem::Finish(const NewtonOptions& options,
                            std::chrono::steady_clock::time_point start, Eigen::VectorXd* x,
                            SolveSummary* summary) const {
  if (error_) std::rethrow_exception(error_);
  summary->residual_evaluations = residual_evaluations_;
  summary->jacobian_evaluations = jacobian_evaluations_;
  if (best_x_.size() == n_) *x = best_x_;
  summary->residual_norm = best_norm_;
  if (best_norm_ <= options.residual_tolerance) {
    summary->termination = Termination::kConverged;
  } else if (summary->termination == Termination::kConverged) {
    summary->termination = Termination::kNoConvergence;
  }
  summary->seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace impactkit
