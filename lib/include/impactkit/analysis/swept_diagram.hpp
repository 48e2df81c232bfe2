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

/// Where the seeding sweep is swept again, finer: a window narrower than
/// its spacing (the paper's P(4,6) at 1.772-1.775, under a 481-value
/// sweep's 0.004) shows at one value or none, and is no window; swept at
/// five times the resolution it is. Between two neighbouring values whose
/// motions differ (another P(p,q), kind or q), or of which either has no
/// period (chaotic, unresolved: a window may hide there), the stretch is
/// swept again at `factor` times the resolution; elsewhere the sweep's own
/// values stand. Consecutive such intervals make one stretch, swept in the
/// sweep's direction from `warmup_values` values before it (from the
/// sweep's fixed state, as a chunk's warm-up: sweep.hpp), one stretch per
/// thread. The stretches' values join the sweep's points in sweep order.
struct SweepRefineOptions {
  /// Values per interval after refinement (>= 1; 1: no refinement). The
  /// default 5 on the default 481 values gives the 2401-value grid there.
  int factor = 5;
  int warmup_values = 5;  ///< values before each stretch (>= 0), transients only
  bool IsValid(std::string* error) const;
};

/// The sweep's points with the refined stretches' values between them, in
/// sweep order (SweepRefineOptions). `sweep` must come from RunSweep on
/// `system` with `sweep_options`. Cancelled, it returns the sweep's points.
std::vector<SweepPoint> RefineSweep(const System& system, const SweepOptions& sweep_options,
                                    const SweepResult& sweep, const SweepRefineOptions& options,
                                    const RunControl& control = {});

struct SweptDiagramOptions {
  /// The sweep; its parameter, from and to are set from diagram.continuation
  /// (parameter, lower, upper). 481 values of 300 transient and 40 recorded
  /// periods, periods up to 16, refined (below) where the motion changes.
  /// Its transients run whole: a settled cell hands the next a state 1e-10
  /// from its orbit where a whole transient hands one at rounding, and in a
  /// chaotic stretch that moves which windows appear, so which branches the
  /// network finds would depend on the shortcut (docs/grids.md, "Early
  /// certainty").
  SweepOptions sweep = [] {
    SweepOptions coarse;
    coarse.steps = 481;
    coarse.transient_periods = 300;
    coarse.recorded_periods = 40;
    coarse.classify.period.max_q = 16;
    coarse.full_transient = true;
    return coarse;
  }();
  SweepRefineOptions refine;
  SweepSeedOptions seeds;
  DiagramOptions diagram;
  bool IsValid(std::string* error) const;
};

struct SweptDiagram {
  /// The brute-force points under the diagram: the sweep's and the refined
  /// stretches' (in sweep order; its seconds include the refinement's, its
  /// chunks and iterations are the sweep's own).
  SweepResult sweep;
  int refined_values = 0;          ///< how many of the points the refinement added
  std::vector<DiagramSeed> seeds;  ///< the caller's, then the sweep's
  Diagram diagram;
};

/// Sweeps `system` over the range, refines it where the motion changes,
/// seeds from the windows, and traces the network from `seeds` (first) and
/// the sweep's. Throws InvalidInput for bad options or seeds. Progress: the
/// sweep's (its values, then the refined ones), then the diagram's stage.
/// Cancelled during the sweep, it traces no diagram (its termination
/// kStopped, no branches).
SweptDiagram TraceSweptDiagram(const System& system, const std::vector<DiagramSeed>& seeds,
                               const SweptDiagramOptions& options, const RunControl& control = {});

}  // namespace impactkit
