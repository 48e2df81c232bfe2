#pragma once
/// \file swept_diagram.hpp
/// The connected bifurcation diagram seeded by brute force: a sweep
/// (sweep.hpp) over the diagram's parameter range, each periodic window's
/// orbit refined by Newton (orbit.hpp) into a seed, and the branch network
/// traced from those seeds and the caller's (diagram.hpp). Isolated
/// branches — periodic windows inside a chaotic range — so join the
/// diagram without being named.
///
/// It lives in analysis, above continuation, because the seeds come from
/// the sweep; the network itself needs only orbits (continuation/diagram.hpp).

#include <functional>
#include <string>
#include <vector>

#include "impactkit/analysis/sweep.hpp"
#include "impactkit/continuation/diagram.hpp"

namespace impactkit {

struct SweepSeedOptions {
  /// A window is this many consecutive sweep values or more showing one
  /// P(p, q), or sticking with one q; shorter runs are transitions, not
  /// windows.
  int min_values = 2;
  /// Seeds of windows with more impacts per orbit are skipped.
  int max_p = 16;
  /// Newton's tolerances and the map's options; p and q come from the window.
  OrbitOptions orbit;
  bool IsValid(std::string* error) const;
};

/// One seed per periodic window of `sweep` (in sweep order): the orbit
/// through the last impact of the window's middle value, refined by
/// FindOrbit; of a sticking window P(∞, q), the sticking orbit of the
/// middle value's own simulation (the sweep's transient), refined by
/// FindOrbit. Windows whose refinement does not converge give none.
/// `sweep` must come from RunSweep on `system` (any value of the parameter).
std::vector<DiagramSeed> SeedsFromSweep(const System& system, const SweepOptions& sweep_options,
                                        const SweepResult& sweep, const SweepSeedOptions& options);

struct SweptDiagramOptions {
  /// The sweep; its parameter, from and to are set from diagram.continuation
  /// (parameter, lower, upper). Its transients run whole by default: a
  /// settled cell hands the next a state 1e-10 from its orbit where a whole
  /// transient hands one at rounding, and in a chaotic stretch that moves
  /// which windows appear, so which branches the network finds would
  /// depend on the shortcut (docs/grids.md, "Early certainty").
  SweepOptions sweep = [] {
    SweepOptions whole;
    whole.full_transient = true;
    return whole;
  }();
  SweepSeedOptions seeds;
  DiagramOptions diagram;
  bool IsValid(std::string* error) const;
};

struct SweptDiagram {
  SweepResult sweep;               ///< the brute-force points under the diagram
  std::vector<DiagramSeed> seeds;  ///< the caller's, then the sweep's
  Diagram diagram;
};

/// Sweeps `system` over the range, seeds from the windows, and traces the
/// network from `seeds` (first) and the sweep's. Throws InvalidInput for
/// bad options or seeds. Progress: the sweep's, then the diagram's stage.
/// Cancelled during the sweep, it traces no diagram (its termination
/// kStopped, no branches).
SweptDiagram TraceSweptDiagram(const System& system, const std::vector<DiagramSeed>& seeds,
                               const SweptDiagramOptions& options, const RunControl& control = {});

}  // namespace impactkit
