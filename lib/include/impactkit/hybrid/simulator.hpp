#pragma once
/// \file simulator.hpp
/// The exact hybrid simulator.
///
/// Between events the motion is linear and harmonically forced, so it is
/// known in closed form (flow.hpp); the simulator only has to find events.
/// The state's mode is the set of stops holding their masses (none: free
/// flight; hybrid/mode.hpp); every stop watches its witness on the mode's
/// flow, its gap g = s (x_c - xs) while its mass moves (s = +1 above,
/// -1 below), -Fs while it holds the mass. One step of Simulate(), with
/// y = (x, v) and c the DOF of the stop whose event comes first:
///
///       F  <- closed-form flow of the mode from (t, y)
///       te <- first time in (t, t_end] where any stop's witness reaches 0
///             from below (events.hpp: a bound on |w''| makes a skipped pair
///             of crossings impossible; te refined to ~1e-13; each stop
///             searched only up to the earliest time found so far)
///       observer.OnSegment(F on [t, min(te, t_end)])
///       no te: t <- t_end, stop
///       a release: the stop lets go, observer.OnRelease({stop, ts, tr}); next step
///     at an arrival (c moving, at its stop):
///       y- <- F(te)
///       an arrival whose bounce height is unresolved is a landing: v_c <- 0,
///           no impact (docs/theory.md §4); observer.OnLanding({stop, te});
///           then as after chatter, below
///       otherwise v_c(te+) <- -r v_c(te-);  observer.OnImpact(...)
///       chatter (hybrid/chatter_rule.hpp), r < 1: once the rebound's
///           height is unresolved, or the chatter map is exact to the
///           rounding of time from here (docs/theory.md §4):
///         the chatter map sums the remaining bounces under the contact
///               mass's acceleration along the stuck flow (Budd & Dux, with
///               the acceleration's variation and the damping) to t*;
///         the other masses follow the stuck subsystem to t* (a chatter
///               segment, not sticking), x_c = xs, v_c = 0;
///               observer.OnChatter({stop, te, t*})
///       elastic chatter (r near 1) is cut at a short bounce (counted);
///           the threshold method ends at a short interval between impacts
///       if v_c = 0 at the stop: held (the stop joins the mode) if its
///           contact force Fs > 0 there
///
/// A mass past a stop at the start of a step (an event at another stop
/// came first by less than the time tolerance) meets it at once, so that
/// near-simultaneous events at two stops are both taken, in order.
///
/// On return the state is the hybrid state at t_end (or where the run
/// stopped, with the reason in the summary).

#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "impactkit/core/termination.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/dynamics/segment.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

/// How chatter (an accumulating sequence of impacts) is ended.
enum class ChatterMethod {
  /// Predict the accumulation time of the geometric impact sequence from the
  /// local acceleration and jump to it (Budd & Dux 1994). Default.
  kAccumulation,
  /// The paper's rule (Cusumano & Bai 1993): stick once the interval between
  /// two impacts falls below `chatter_threshold`.
  kThreshold,
};

std::string ToString(ChatterMethod method);

struct SimulationOptions {
  ChatterMethod chatter = ChatterMethod::kAccumulation;
  /// Elastic chatter (r >= 0.99862, whose bounces shrink too slowly to be
  /// followed to the rounding floor, and never accumulate when r = 1) is cut
  /// at its first bounce 2u/a shorter than this fraction of the system's
  /// shortest time scale τ (min of 2π/Ω and 2π/ω_max): the mass is then at
  /// the stop to within a (chatter_span τ)²/8. Each cut is counted
  /// (SimulationSummary::chatter_cuts). Chatter with r below that is not
  /// cut: its tail is summed by the chatter map (docs/theory.md §4).
  double chatter_span = 1e-4;
  /// kThreshold: inter-impact interval (time units) below which the mass
  /// is taken to stick.
  double chatter_threshold = 1e-4;
  /// Event times are refined until the bracket is below this (time units).
  double event_time_tolerance = 1e-13;
  /// The height resolution (docs/theory.md §4): an arrival at the stop
  /// whose bounce height u² / (2|a|) is below this fraction of the gap's
  /// length scale L (the magnitudes it is computed from) is contact, not
  /// flight: a landing (counted), and a rebound that low ends a chatter
  /// sequence through the chatter map. The default, 64 ulps, is the rounding
  /// of the gap: every arrival resolved in double precision is an impact.
  double bounce_height_resolution = 64 * std::numeric_limits<double>::epsilon();
  /// The work bound: a run that needs more events than this within one
  /// forcing period stops with status kWorkLimit instead of crawling.
  std::int64_t max_events_per_period = 100'000;
  /// Guard against pathological inputs: the run stops (status kEventLimit)
  /// after this many events.
  std::int64_t max_events = 200'000'000;

  bool IsValid(std::string* error) const;
};

/// Summary::termination says why Simulate() returned: kCompleted (the
/// state is at t_end), kEventLimit or kWorkLimit (the state is at the last
/// event), kStopped (an observer asked; the state is where it asked) or
/// kStalled (events kept repeating at one instant; the state is there);
/// iterations counts the events.
struct SimulationSummary : Summary {
  std::int64_t impacts = 0;        ///< impacts with the stop
  std::int64_t chatter_jumps = 0;  ///< chatter sequences ended by accumulation or threshold
  /// Of those, the ones cut without accumulating (elastic chatter at a
  /// short bounce, SimulationOptions::chatter_span, or the chatter map's
  /// bound on bounces): each leaves the mass within a (chatter_span τ)²/8
  /// of the stop.
  std::int64_t chatter_cuts = 0;
  std::int64_t releases = 0;  ///< ends of sticking
  /// Arrivals at the stop at zero speed or from below the height resolution
  /// (rounding, by default): landings (sticking or a touch), not impacts.
  std::int64_t landings = 0;
  /// Total time stuck at the stop, each sticking phase from the
  /// accumulation point of the chatter that led to it (the chatter's tail
  /// before it is impacting, not sticking).
  double stuck_time = 0.0;
  std::string BriefReport() const;
};

/// An impact of a mass with one of the stops.
struct Impact {
  double t = 0.0;
  int stop = 0;        ///< which: an index into System::stops
  double phase = 0.0;  ///< t mod 2π/Ω, in [0, T)
  /// s v_c(t−) > 0, the speed towards the stop just before impact; a mass reaching the stop
  /// at zero speed (or from below the bounce height resolution) lands and is
  /// not an impact.
  double velocity = 0.0;
  Eigen::VectorXd x;  ///< positions at impact (x_c = xs)
  Eigen::VectorXd v;  ///< velocities just before impact
  /// Velocities just after it, by the stop's law (v_c -> -r v_c). At the
  /// last simulated impact of a chatter sequence the motion that follows is
  /// modelled held at the stop; this is still the rebound.
  Eigen::VectorXd v_after;
};

/// A chatter sequence at stop `stop` beginning with the impact at t_first,
/// ended at its accumulation point t_end (x_c = xs, v_c = 0 there).
struct ChatterEnd {
  int stop = 0;  ///< index into System::stops
  double t_first = 0.0;
  double t_end = 0.0;
};

/// Stop `stop`'s mass arrives at it at t too slowly for a resolved bounce
/// (a landing: no impact); it is held from there if the stop pushes on it.
struct Landing {
  int stop = 0;  ///< index into System::stops
  double t = 0.0;
};

/// Stop `stop`'s mass leaves it at t_release after sticking since t_begin.
struct Release {
  int stop = 0;  ///< index into System::stops
  double t_begin = 0.0;
  double t_release = 0.0;
};

/// Receives what the simulator finds, every event with the stop it belongs
/// to; every method has an empty default. A segment is valid only during
/// the call.
class Observer {
 public:
  virtual ~Observer() = default;
  /// A piece of exact motion on [segment.Begin(), segment.End()].
  virtual void OnSegment(const Segment& segment) { (void)segment; }
  virtual void OnImpact(const Impact& impact) { (void)impact; }
  virtual void OnChatter(const ChatterEnd& chatter) { (void)chatter; }
  virtual void OnLanding(const Landing& landing) { (void)landing; }
  virtual void OnRelease(const Release& release) { (void)release; }
  /// Return true to stop the run after the current event.
  virtual bool ShouldStop() const { return false; }
};

/// The simulator for one system: the free flow and the stuck subsystem are
/// decomposed once, then any number of runs reuse them.
class Simulator {
 public:
  /// Throws InvalidInput for an invalid system or options.
  Simulator(const System& system, const SimulationOptions& options = {});
  /// On a hybrid system already decomposed (shared with an impact map, say).
  /// Throws InvalidInput for invalid options.
  Simulator(std::shared_ptr<const HybridSystem> hybrid, const SimulationOptions& options = {});
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  /// Advances `state` to t_end (>= state.t), reporting to `observer`.
  /// Throws InvalidInput for an invalid state.
  SimulationSummary Run(HybridState& state, double t_end, Observer& observer) const;
  SimulationSummary Run(HybridState& state, double t_end) const;

  const System& GetSystem() const;

 private:
  struct Impl;  ///< the hybrid system and the options
  std::unique_ptr<Impl> impl_;
};

/// Advances `state` to t_end (> state.t), reporting to `observer`.
/// Throws InvalidInput for an invalid system, state or options.
SimulationSummary Simulate(const System& system, const SimulationOptions& options,
                           HybridState& state, double t_end, Observer& observer);

/// Same, without an observer.
SimulationSummary Simulate(const System& system, const SimulationOptions& options,
                           HybridState& state, double t_end);

}  // namespace impactkit
