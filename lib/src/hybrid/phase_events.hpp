#pragma once
/// \file phase_events.hpp (private)
/// The event that ends a phase of the hybrid motion, and how an arrival is
/// judged: the one search the simulator, the impact map and the release
/// map make, so that an orbit and a simulation of it meet the same event at
/// the same time and call it by the same name.
///
/// A phase runs on one mode's exact flow (hybrid/mode.hpp). Every stop
/// watches its witness there: a stop whose mass moves its gap (anchored at
/// the phase's start, Signal::AnchorAt), a held one −Fs. The phase ends at
/// the earliest upward crossing of any of them; each witness is searched
/// only up to the earliest crossing found so far, and a crossing that ties
/// goes to the stop searched first. An event is due at once when the
/// phase starts on it: a mass at its stop moving in, or past it (an event
/// at another stop came first by less than the time tolerance), or a held
/// mass its stop no longer pushes on (Stop::Holds).
///
/// An arrival is then an impact or a landing by its stop's ChatterRule
/// (hybrid/chatter_rule.hpp), judged on the gap's curvature and length scale
/// at the arrival; after an impact the same rule says whether and where its
/// chatter sequence ends (AfterImpact).

#include <optional>
#include <vector>

#include "hybrid/chatter_rule.hpp"
#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit {

class PhaseEvents {
 public:
  /// `options` must outlive this (the rules refer to it).
  PhaseEvents(const HybridSystem& hybrid, const SimulationOptions& options);

  /// Stop `stop`'s witness crossing at `t`, and what it triggers.
  struct Event {
    int stop = -1;
    double t = 0.0;
    EventAction action = EventAction::kArrival;
  };
  /// A stop whose search begins only at `begin` (> the phase's start): the
  /// release map's own stop just after a release, where the gap leaves 0
  /// tangentially and a Newton iterate off the release surface would meet
  /// it again at once (sticking_map.cpp).
  struct LateStart {
    int stop = -1;
    double begin = 0.0;
  };

  /// Prepares every stop's witness on `mode`'s flow for a phase from
  /// `state` (all N coordinates), `z0` the flow's transient there.
  void Begin(const Mode& mode, const HybridState& state, const Eigen::VectorXd& z0);
  /// The earliest event of the phase in (t0, end], the stops after `last`
  /// searched first: in a clearance the mass crosses to the other side, and
  /// the search of the stop it left then ends there.
  std::optional<Event> First(double end, int last, const LateStart& late);
  std::optional<Event> First(double end, int last) { return First(end, last, LateStart{}); }

  /// Stop `stop`'s witness on the phase's flow (after Begin).
  const Signal& Witness(int stop) const { return witnesses_[stop]; }
  /// The length scale of stop `stop`'s gap on the phase (GapLengthScale).
  double LengthScale(int stop) const { return length_scales_[stop]; }
  const ChatterRule& Rule(int stop) const { return rules_[stop]; }

  /// The arrival rule at stop `stop`'s arrival at te found by First, the
  /// mass arriving at `speed` >= 0: true when its height is unresolved (a
  /// landing, or a grazing touch). *acceleration: the gap's curvature there.
  bool IsLanding(int stop, double te, double speed, double* acceleration) const;

  /// Where a chatter sequence ends: at t (from the stop's mass at rest
  /// there the motion goes on stuck, or free if the stop does not push),
  /// counted as a cut if the rule cut it (ChatterRule).
  struct SequenceEnd {
    double t = 0.0;
    bool cut = false;
  };
  /// After the impact at `stop` at te that this phase ends with, its reset
  /// applied (the state x, v just after it, `v_before` just before;
  /// `previous` the stop's impact before; `arrival_acceleration` the gap's
  /// curvature at the arrival): the end of its chatter sequence — at once,
  /// at a cut, or where the chatter map sums its tail on the flow with the
  /// stop holding its mass — or none while the impacts go on.
  std::optional<SequenceEnd> AfterImpact(int stop, double te, double previous,
                                         const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                         const Eigen::VectorXd& v_before,
                                         double arrival_acceleration);

  /// The release search on a held phase's witness −Fs: it starts where the
  /// contact force may be 0 to the rounding of its terms, and a dip of the
  /// force below 0 that returns within that rounding is no release (a
  /// mass at rest on the stop with no force, at an antiresonance, would
  /// otherwise be certified piece by tiny piece).
  EventOptions HeldSearch(const Signal& release) const;

 private:
  std::optional<double> ReleaseTime(int stop, double end) const;
  std::optional<double> ArrivalTime(int stop, double end, const LateStart& late) const;
  /// The arrival search for stop `stop`'s gap from t0 (ArrivalSearch: rises
  /// above the gap's rounding); one that leaves the stop from rest starts
  /// where the gap and its slope are 0 in truth, to the rounding of L.
  EventOptions Search(int stop) const;
  /// An upper bound of the acceleration towards stop `stop` just after an
  /// impact: the arrival's (the gap's curvature) changed by the damping of
  /// the velocity jump from `v_before` to `v`, with a factor 2 and 1e-9 of the motion's
  /// acceleration scale (L (2π/τ)²) over their rounding. Most impacts go on
  /// by this bound alone (ChatterRule::MayEnd), without the acceleration.
  double AccelerationBound(int stop, const Eigen::VectorXd& v, const Eigen::VectorXd& v_before,
                           double arrival_acceleration) const;

  const HybridSystem& hybrid_;
  EventOptions events_;
  std::vector<ChatterRule> rules_;  ///< per stop (restitutions differ)
  const Mode* mode_ = nullptr;
  double t0_ = 0.0;                    ///< the phase's start
  std::vector<Signal> witnesses_;      ///< per stop, on the phase's flow
  std::vector<double> length_scales_;  ///< per stop whose mass moves
  /// Per stop whose mass moves: due at once (at its stop moving in, or
  /// past it), and leaving the stop from rest (x_c = xs, v_c = 0).
  std::vector<char> due_, from_rest_;
  /// Scratch of AfterImpact, reused: no allocation per impact.
  Eigen::VectorXd force_scratch_, acceleration_scratch_, held_transient_;
  Signal held_witness_;
};

// Inline: a simulation makes one phase per event, and these run in each
// (the search itself, FirstUpcrossing, is not inlined).

inline void PhaseEvents::Begin(const Mode& mode, const HybridState& state,
                               const Eigen::VectorXd& z0) {
  mode_ = &mode;
  t0_ = state.t;
  for (int k = 0; k < hybrid_.StopCount(); ++k) {
    const PreparedWitness* witness = mode.Witness(k);
    if (!witness) continue;
    mode.Flow().Output(witness->output, t0_, z0, &witnesses_[k]);
    if (witness->action != EventAction::kArrival) continue;
    const Stop& stop = hybrid_.GetStop(k);
    const double gap = stop.GapOf(state.x), speed = stop.SpeedTowards(state.v(stop.Dof()));
    length_scales_[k] = GapLengthScale(hybrid_, k, state.x, state.v, witnesses_[k]);
    due_[k] = gap > 0 || (gap == 0 && speed > 0);
    from_rest_[k] = gap == 0 && speed == 0;
    witnesses_[k].AnchorAt(gap, speed);
  }
}

inline std::optional<PhaseEvents::Event> PhaseEvents::First(double end, int last,
                                                            const LateStart& late) {
  std::optional<Event> first;
  const int stops = hybrid_.StopCount();
  for (int i = 1; i <= stops; ++i) {
    const int k = (last + i) % stops;
    const PreparedWitness* witness = mode_->Witness(k);
    if (!witness) continue;  // another stop holds its mass
    const std::optional<double> te =
        witness->action == EventAction::kRelease ? ReleaseTime(k, end) : ArrivalTime(k, end, late);
    if (!te || (first && *te >= end)) continue;
    first = Event{k, *te, witness->action};
    end = *te;
    if (end == t0_) break;  // nothing comes earlier
  }
  return first;
}

inline std::optional<double> PhaseEvents::ArrivalTime(int stop, double end,
                                                      const LateStart& late) const {
  if (due_[stop]) return t0_;
  if (stop != late.stop) return FirstUpcrossing(witnesses_[stop], t0_, end, Search(stop));
  if (late.begin >= end) return std::nullopt;
  return FirstUpcrossing(witnesses_[stop], late.begin, end,
                         ArrivalSearch(events_, length_scales_[stop]));
}

inline EventOptions PhaseEvents::Search(int stop) const {
  EventOptions events = ArrivalSearch(events_, length_scales_[stop]);
  if (from_rest_[stop]) events.start_noise = ChatterRule::kRounding * length_scales_[stop];
  return events;
}

inline bool PhaseEvents::IsLanding(int stop, double te, double speed, double* acceleration) const {
  double gap, slope;
  witnesses_[stop].ValueSlopeCurvature(te, &gap, &slope, acceleration);
  return rules_[stop].IsLanding(speed, *acceleration, length_scales_[stop]);
}

}  // namespace impactkit
