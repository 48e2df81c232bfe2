#pragma once
/// \file reference_run.hpp
/// What a reference integrator returns: the impacts it found and where it
/// stopped. Shared by cvode_impacts.hpp and odeint_impacts.hpp.

#include <Eigen/Dense>
#include <vector>

namespace impactkit::reference {

struct ReferenceImpact {
  double t;         ///< impact time
  double velocity;  ///< the speed towards the stop just before the impact (> 0)
  int stop = 0;     ///< which stop (an index into System::stops)
};

struct ReferenceRun {
  std::vector<ReferenceImpact> impacts;
  /// State at t: at t_end, or just after the last impact when the run stopped
  /// early (chatter_detected).
  Eigen::VectorXd x, v;
  double t = 0.0;
  /// True if the run stopped early because impacts accumulate (an
  /// inter-impact interval, observed or predicted, below min_interimpact; or
  /// the mass held at the stop) or max_impacts was reached. Neither
  /// reference integrator can follow chatter or sticking.
  bool chatter_detected = false;
  long rhs_evaluations = 0;  ///< calls of the right-hand side M^{-1}(...)
};

}  // namespace impactkit::reference
