#pragma once
/// \file termination.hpp
/// How every iterative computation of the library ends — the Newton and
/// least-squares solvers, FindOrbit, the square-root map fit — in one
/// vocabulary (Ceres's TerminationType). What a driver that runs in time
/// rather than to a tolerance stops for (a simulation's end, a branch's end)
/// is its own reason type: SimulationStatus, BranchEnd, MapStatus.

#include <string>

namespace impactkit {

enum class Termination {
  /// The result meets its tolerance: every field of the result is valid.
  kConverged,
  /// The method ran its course without meeting the tolerance (iterations
  /// ran out, the step stalled, the iterates diverged); the result holds
  /// the best point found.
  kNoConvergence,
  /// The method could not go on (the map or the Jacobian could not be
  /// evaluated, a singular system, a rank-deficient covariance); the result
  /// holds the best point found, or the start if nothing was evaluated.
  kFailure,
};

/// "converged", "no convergence", "failure".
std::string ToString(Termination termination);

/// The fields every solver's summary starts with (Options, problem,
/// Summary: the shape of each Solve/Find/Fit function of the library).
struct Summary {
  Termination termination = Termination::kFailure;
  /// Why it ended, in the solver's words (e.g. "KINSOL KIN_SUCCESS").
  std::string message;
  int iterations = 0;    ///< iterations of the method (both methods, if a fallback ran)
  double seconds = 0.0;  ///< wall time
};

}  // namespace impactkit
