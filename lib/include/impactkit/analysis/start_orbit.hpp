#pragma once
/// \file start_orbit.hpp
/// The orbit a computation starts from — `impactkit orbit`, `continue`,
/// `diagram --start`, `curve`, the paper's branches, Python's find_orbit —
/// found by one rule. From a guess when one is given. Otherwise from a
/// steady simulation from rest: its sticking orbit where the motion sticks
/// periodically (unless p or the kind asks for an impacting orbit), else
/// its last impact with the period it shows.

#include <Eigen/Dense>
#include <optional>

#include "impactkit/model/system.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit {

/// Which orbits a start may be.
enum class StartOrbitKind {
  kAny,        ///< the sticking orbit where the motion sticks, else an impacting one
  kImpacting,  ///< an impacting orbit P(p, q) only
  kSticking,   ///< a sticking orbit P(inf, q) only
};

struct StartOrbitRequest {
  StartOrbitKind kind = StartOrbitKind::kAny;
  /// Impacts per orbit: asks for an impacting orbit, with q. Default: the
  /// simulated motion's (1 with a guess).
  std::optional<int> p;
  /// Forcing periods per orbit. Default: the simulated motion's (1 with a
  /// guess).
  std::optional<int> q;
  /// Sticking phases per orbit: asks for a sticking orbit. Default: the
  /// simulated motion's (1 with a guess).
  std::optional<int> releases;
  /// A section state to refine instead of a simulated one: an impact state
  /// η at `stop`, or for a sticking orbit a release state from it.
  std::optional<Eigen::VectorXd> guess;
  int stop = 0;         ///< the stop of the guess (0-based)
  int transient = 500;  ///< forcing periods simulated from rest before the seed
  /// The solver's settings (Jacobian, Newton, fallbacks); the section, its
  /// stop, p, q and releases are the rule's.
  OrbitOptions solver;
};

struct StartOrbit {
  /// False when the simulated motion offers no seed of the kind asked for:
  /// then summary.message says why and FindOrbit did not run.
  bool seeded = false;
  OrbitOptions options;  ///< those the orbit was solved with
  OrbitSummary summary;  ///< FindOrbit's
  PeriodicOrbit orbit;   ///< valid when summary.termination is kConverged
};

/// Seeds and solves the start orbit. Throws InvalidInput for an
/// inconsistent request (p with releases, p without q, a kind the counts
/// contradict, a stop the system lacks, transient < 0) and whatever
/// FindOrbit throws for its input.
StartOrbit FindStartOrbit(const System& system, const StartOrbitRequest& request);

}  // namespace impactkit
