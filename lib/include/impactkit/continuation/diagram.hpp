#pragma once
/// \file diagram.hpp
/// The branch network traced from seeds: each seed's branch is followed
/// both ways (continuation.hpp), and at every special point where another
/// branch starts, that branch is started and followed in turn:
///
///     period doubling   the P(2p, 2q) branch (DoubledBranchStart)
///     grazing, sticking the orbit with one impact more or fewer, seeded on
///                       both sides of the point (SeedsAtGrazing)
///     branch point      the shorter orbit the branch becomes (a doubled
///                       branch's pitchfork back onto its parent)
///     pitchfork         both halves of the P(p, q) branch that crosses
///                       (PitchforkBranchStart: in a symmetric system the
///                       pair of asymmetric orbits)
///
/// A start is reduced to its primitive period (a P(2,2) that is P(1,1)
/// twice is P(1,1)) and traced only if its orbit lies on no branch traced
/// already: recognised by its orbit (primitive p and q, and its impact
/// speeds on the branch's curve at its parameter), not by a label. So the
/// network closes on itself instead of looping, and work is bounded by the
/// parameter range, max_depth, max_branches and the per-branch point cap.
///
/// Starts are taken breadth first (a seed's branch, then what starts on it,
/// ...); those of one generation are traced on `threads` threads, the
/// starts of one family (section, impacts or releases, and q) in order,
/// each only once no earlier start's branch of its family holds it, so no
/// duplicate is traced and the result does not depend on the thread count.

#include <functional>
#include <string>
#include <vector>

#include "impactkit/continuation/continuation.hpp"
#include "impactkit/continuation/diagram_graph.hpp"

namespace impactkit {

struct DiagramOptions {
  /// The parameter, its bounds, steps and orbit tolerances of every branch
  /// (direction is ignored: each seed says its own). orbit.p and orbit.q
  /// are taken from each seed.
  ContinuationOptions continuation;
  bool switch_period_doubling = true;  ///< start the doubled branch at each period doubling
  bool switch_grazing = true;          ///< start the orbit with one impact more or fewer
  bool switch_branch_points = true;    ///< start the shorter orbit at a branch point
  bool switch_pitchforks = true;       ///< start both halves of the crossing branch at a pitchfork
  /// Switches from a seed's branch at most (0: the seeds' branches only).
  int max_depth = 10;
  int max_branches = 200;  ///< branches traced at most
  int threads = 1;         ///< branches of one generation traced at once (>= 1)
  /// Two nodes are one where their parameters differ by less than this
  /// (relative to 1 + |μ|) and their orbits' extents in x_c agree to
  /// node_range_tolerance (relative to 1 + range).
  double node_tolerance = 1e-5;
  double node_range_tolerance = 1e-4;
  /// A start lies on a traced branch of its primitive period when its
  /// sorted impact speeds are this close (relative to 1 + max speed) to
  /// the branch's, interpolated at its parameter.
  double same_branch_tolerance = 2e-3;
  bool IsValid(std::string* error) const;
};

/// Where a branch of the network starts: a converged orbit of `system`.
struct DiagramSeed {
  System system;
  PeriodicOrbit orbit;
  std::string origin;  ///< how the seed was found ("start", "sweep window omega 1.2..1.3")
  /// Which way the seed's branch is followed (branches born at special
  /// points are followed away from them, or both ways from a grazing).
  ContinuationDirection direction = ContinuationDirection::kBoth;
};

/// Traces the network through `seeds` (in order). Throws InvalidInput for
/// bad options or a seed that ContinueBranch refuses (outside the bounds,
/// not an orbit). Progress: stage "diagram", after each accepted point of
/// any branch, with the branches finished so far and the point's parameter.
/// Cancelling `control` stops the branches being traced (each ends
/// kStopped) and the network (Diagram::termination kStopped).
Diagram TraceDiagram(const std::vector<DiagramSeed>& seeds, const DiagramOptions& options,
                     const RunControl& control = {});

/// Whether every point of `branch` lies on `other`: the same P(p,q), and
/// sorted impact speeds within `tolerance` (relative to 1 + the largest
/// speed) of `other`'s, interpolated between two of its consecutive points
/// that bracket the parameter (through a fold, either sheet). A picture
/// draws such a branch once.
bool CoveredBy(const Branch& branch, const Branch& other, double tolerance = 2e-3);

}  // namespace impactkit
