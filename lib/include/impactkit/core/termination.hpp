#pragma once
/// \file termination.hpp
/// How every computation of the library ends, in one vocabulary: the
/// solvers, FindOrbit and the map fit (which run to a tolerance), the
/// simulator and the section maps (which run over time or events), and the
/// drivers — sweeps, branches, curves, diagrams (which run over a range).
/// Each result carries one Termination and a message saying why in the
/// computation's words; each function documents which reasons it gives.

#include <cstdint>
#include <string>

namespace impactkit {

enum class Termination {
  // Runs to a tolerance: solvers, FindOrbit, FitSqrtMap.
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

  // Any run.
  /// The run did all it was asked: a simulation reached its end time, a
  /// map followed every impact or release, a sweep or a diagram every
  /// value or start.
  kCompleted,
  /// Asked to stop: by an observer, or by the run's RunControl
  /// (cancellation); the result holds what was done.
  kStopped,

  // Simulations and the maps, which follow events.
  kEventLimit,  ///< SimulationOptions::max_events reached
  kWorkLimit,   ///< SimulationOptions::max_events_per_period reached
  kStalled,     ///< events kept repeating at one instant

  // Contacts: why a map cannot follow an orbit, or where a branch or a
  // curve ends because its orbits stop existing.
  kNoImpact,  ///< no further impact (the flight outlasts the map's bound)
  /// An arrival at zero speed (its bounce height unresolved) with the mass
  /// moving away after it: an impact is born or dies here.
  kGrazing,
  /// Such an arrival with the mass pressed into the stop: sticking begins.
  kSticking,
  kOtherStop,     ///< the last impact or release is at another stop than the section's
  kNotReleased,   ///< not a release: the contact force still presses the mass into the stop
  kNoChatter,     ///< impacts without a chatter sequence accumulating
  kNoSticking,    ///< the chatter accumulates with Fs <= 0: the mass is not held
  kNoRelease,     ///< held without a release (the stuck phase outlasts the map's bound)
  kMetWhileHeld,  ///< a mass reaches its stop while another stop holds a mass
  kEarlyRelease,  ///< a sticking family: Fs touches 0 inside a stuck phase

  // Continuation: branches, curves, diagrams.
  kParameterBound,   ///< reached an end of the parameter's range
  kBranchPoint,      ///< met the branch of a shorter orbit traversed several times
  kMaxPoints,        ///< a bound on points (a diagram's: on branches or depth) reached
  kCorrectorFailed,  ///< no convergence even with the smallest step
  kClosed,           ///< the curve came back to its start: a closed loop
};

/// The reason's name, as files and Python give it: "converged",
/// "no_convergence", "completed", "grazing", "parameter_bound", ...
std::string ToString(Termination termination);

/// The reason in a few words, for messages: "no further impact", ...
std::string Describe(Termination termination);

/// The fields every result's summary starts with (the shape of each
/// Solve/Find/Fit/Run function of the library: problem, options → result).
struct Summary {
  Termination termination = Termination::kFailure;
  /// Why it ended, in the computation's words (e.g. "KINSOL KIN_SUCCESS").
  std::string message;
  /// The units of work done: iterations of a method (both methods, if a
  /// fallback ran), events simulated, values swept, branches traced.
  std::int64_t iterations = 0;
  double seconds = 0.0;  ///< wall time
};

}  // namespace impactkit
