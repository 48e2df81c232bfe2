/// What the two nonlinear solvers share: options, summaries, and the one
/// convergence test (max |F| at the returned point).

#include <cmath>

#include <fmt/format.h>

#include "impactkit/model.hpp"
#include "impactkit/nonlinear_solve.hpp"
#include "nonlinear_solve_common.hpp"

namespace impactkit {

std::string ToString(SolveTermination termination) {
  switch (termination) {
    case SolveTermination::kConverged: return "converged";
    case SolveTermination::kNoConvergence: return "no convergence";
    case SolveTermination::kFailure: return "failure";
  }
  return "unknown";
}

bool NewtonOptions::IsValid(std::string* error) const {
  auto fail = [&](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (!(residual_tolerance > 0 && std::isfinite(residual_tolerance))) {
    return fail(fmt::format("residual_tolerance must be finite and > 0, got {}", residual_tolerance));
  }
  if (!(step_tolerance > 0 && std::isfinite(step_tolerance))) {
    return fail(fmt::format("step_tolerance must be finite and > 0, got {}", step_tolerance));
  }
  if (max_iterations < 1) return fail(fmt::format("max_iterations must be >= 1, got {}", max_iterations));
  return true;
}

std::string SolveSummary::BriefReport() const {
  return fmt::format("{}: max|F| = {:.3g} after {} iterations{}{}", ToString(termination),
                     residual_norm, iterations, message.empty() ? "" : ", ", message);
}

void ValidateSolveInput(const NewtonOptions& options, const Eigen::VectorXd& x) {
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  if (x.size() == 0 || !x.allFinite()) {
    throw InvalidInput("the initial guess must be non-empty and finite");
  }
}

/// Decides convergence from max |F| at the returned point: whatever the
/// solver's own norms said, the user's tolerance is the test.
void FinishSolve(const Residual& residual, const NewtonOptions& options, const Eigen::VectorXd& x,
            double seconds, SolveSummary* summary) {
  Eigen::VectorXd f;
  const bool evaluated = x.allFinite() && residual(x, &f) && f.allFinite();
  summary->residual_norm =
      evaluated ? (f.size() ? f.cwiseAbs().maxCoeff() : 0.0) : std::numeric_limits<double>::infinity();
  if (evaluated && summary->residual_norm <= options.residual_tolerance) {
    summary->termination = SolveTermination::kConverged;
  } else if (summary->termination == SolveTermination::kConverged) {
    summary->termination = SolveTermination::kNoConvergence;
  }
  summary->seconds = seconds;
}

}  // namespace impactkit
