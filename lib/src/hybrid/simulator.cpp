#include "impactkit/hybrid/simulator.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <vector>

#include "hybrid/chatter_rule.hpp"
#include "hybrid/phase_events.hpp"
#include "impactkit/dynamics/segment.hpp"

namespace impactkit {

std::string ToString(ChatterMethod method) {
  return method == ChatterMethod::kAccumulation ? "accumulation" : "threshold";
}

bool SimulationOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!(chatter_span > 0 && chatter_span <= 1)) {
    return fail(fmt::format("chatter_span must be in (0, 1], got {}", chatter_span));
  }
  if (!(chatter_threshold > 0 && std::isfinite(chatter_threshold))) {
    return fail(fmt::format("chatter_threshold must be finite and > 0, got {}", chatter_threshold));
  }
  if (!(event_time_tolerance > 0 && event_time_tolerance < 1e-3)) {
    return fail(
        fmt::format("event_time_tolerance must be in (0, 1e-3), got {}", event_time_tolerance));
  }
  if (max_events < 1) return fail(fmt::format("max_events must be >= 1, got {}", max_events));
  if (!(bounce_height_resolution >= 0 && bounce_height_resolution < 1e-3)) {
    return fail(fmt::format("bounce_height_resolution must be in [0, 1e-3), got {}",
                            bounce_height_resolution));
  }
  if (max_events_per_period < 1) {
    return fail(fmt::format("max_events_per_period must be >= 1, got {}", max_events_per_period));
  }
  return true;
}

std::string SimulationSummary::BriefReport() const {
  // Cuts are named only where there were any: each is a sequence that did
  // not end at its accumulation point (docs/theory.md §4).
  const std::string cuts = chatter_cuts > 0 ? fmt::format(" ({} cut)", chatter_cuts) : "";
  return fmt::format(
      "{}: {} impacts, {} landings, {} chatter sequences ended{}, {} releases, stuck {:.6g} "
      "time units, {:.3g} s",
      Describe(termination), impacts, landings, chatter_jumps, cuts, releases, stuck_time, seconds);
}

/// The hybrid system (both modes' flows, decomposed once) and the options.
struct Simulator::Impl {
  std::shared_ptr<const HybridSystem> hybrid;
  SimulationOptions options;

  Impl(std::shared_ptr<const HybridSystem> h, const SimulationOptions& o)
      : hybrid(std::move(h)), options(o) {
    std::string error;
    if (!options.IsValid(&error)) throw InvalidInput(error);
    hybrid->PrepareHeldModes();
  }
};

namespace {

/// One run: the loop of simulate.hpp's pseudocode over a hybrid state, in
/// the mode of the stops that hold their masses (none: free flight).
class HybridRun {
 public:
  HybridRun(const HybridSystem& hybrid, const SimulationOptions& options, HybridState& state,
            double t_end, Observer& observer)
      : hybrid_(hybrid),
        options_(options),
        state_(state),
        t_end_(t_end),
        observer_(observer),
        phase_events_(hybrid, options),
        last_impacts_(hybrid.StopCount(), -std::numeric_limits<double>::infinity()),
        stick_begins_(hybrid.StopCount(), state.t) {}

  SimulationSummary Execute();

 private:
  void Phase();
  void MoveTo(const Mode& mode, double t0, const Eigen::VectorXd& z0, double t);
  void ArriveAtStop(int stop, double te, double speed);
  void ApplyImpact(int stop, double te, double speed, double arrival_acceleration);
  bool OverWorkBound();
  /// Where the current phase's search stops if no event comes first: t_end,
  /// or kPhaseSlice forcing periods on, so that a run without events still
  /// asks its observers (ShouldStop: Ctrl-C, progress) as it goes.
  double SliceEnd() const {
    return std::min(t_end_, state_.t + kPhaseSlice * hybrid_.GetSystem().ForcingPeriod());
  }
  static constexpr double kPhaseSlice = 1000;
  void EndChatter(int stop, double te, const PhaseEvents::SequenceEnd& end);
  void LandAtStop(int stop);
  std::int64_t Events() const {
    return summary_.impacts + summary_.landings + summary_.releases + summary_.chatter_jumps;
  }

  const HybridSystem& hybrid_;
  const SimulationOptions& options_;
  HybridState& state_;
  const double t_end_;
  Observer& observer_;
  PhaseEvents phase_events_;
  SimulationSummary summary_;
  Signal held_witness_;               ///< −Fs of a mode a stop may join (reused storage)
  std::vector<double> last_impacts_;  ///< per stop
  std::vector<double> stick_begins_;  ///< per stop
  Impact impact_;                     ///< reused: no allocation per impact
  Eigen::VectorXd phase_transient_;   ///< the current phase's z0 (reused storage)
  static constexpr int kMaxStalledPhases = 1000;
  int stalled_phases_ = 0;
  int last_event_stop_ = 0;         ///< the stop of the last event (PhaseEvents::First's order)
  double window_begin_ = 0.0;       ///< start of the work bound's current window
  std::int64_t window_events_ = 0;  ///< Events() at window_begin_
};

SimulationSummary HybridRun::Execute() {
  const auto start = std::chrono::steady_clock::now();
  window_begin_ = state_.t;
  summary_.termination = Termination::kCompleted;
  while (state_.t < t_end_) {
    if (Events() >= options_.max_events) {
      summary_.termination = Termination::kEventLimit;
      break;
    }
    if (OverWorkBound()) {
      summary_.termination = Termination::kWorkLimit;
      break;
    }
    const double before = state_.t;
    Phase();
    // Events at one instant, over and over, would loop forever.
    stalled_phases_ = state_.t > before ? 0 : stalled_phases_ + 1;
    if (stalled_phases_ > kMaxStalledPhases) {
      summary_.termination = Termination::kStalled;
      break;
    }
    if (observer_.ShouldStop()) {
      summary_.termination = Termination::kStopped;
      break;
    }
  }
  summary_.message = Describe(summary_.termination);
  summary_.iterations = Events();
  summary_.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary_;
}

/// One phase of the current mode: its exact motion up to the first event
/// of any stop (or the slice's end), then that event.
void HybridRun::Phase() {
  const Mode& mode = hybrid_.Holding(state_.held);
  const LinearFlow& flow = mode.Flow();
  const double t0 = state_.t;
  // In free flight the state is the flow's own (no reduced copies).
  if (mode.Held() == 0) {
    flow.Transient(t0, state_.x, state_.v, &phase_transient_);
  } else {
    flow.Transient(t0, mode.Reduced(state_.x), mode.Reduced(state_.v), &phase_transient_);
  }
  const Eigen::VectorXd& z0 = phase_transient_;
  phase_events_.Begin(mode, state_, z0);
  const std::optional<PhaseEvents::Event> event = phase_events_.First(SliceEnd(), last_event_stop_);
  if (event) last_event_stop_ = event->stop;
  const double end = event ? event->t : SliceEnd();
  const bool stuck = state_.Stuck();
  if (end > t0) {
    observer_.OnSegment(Segment(flow, t0, z0, t0, end,
                                stuck ? SegmentMode::kStuck : SegmentMode::kFree, mode.Moving(),
                                mode.HeldPositions()));
  }
  MoveTo(mode, t0, z0, end);
  if (stuck) summary_.stuck_time += end - t0;
  if (!event) return;
  const int k = event->stop;
  switch (event->action) {
    case EventAction::kRelease:
      state_.held &= ~StopBit(k);
      ++summary_.releases;
      observer_.OnRelease({k, stick_begins_[k], end});
      return;
    case EventAction::kArrival: {
      const Stop& stop = hybrid_.GetStop(k);
      state_.x(stop.Dof()) = stop.Position();
      ArriveAtStop(k, end, std::max(stop.SpeedTowards(state_.v(stop.Dof())), 0.0));
      return;
    }
  }
}

/// The state at t along the mode's flow from z0.
void HybridRun::MoveTo(const Mode& mode, double t0, const Eigen::VectorXd& z0, double t) {
  state_.t = t;
  if (mode.Held() == 0) {
    mode.Flow().State(t0, z0, t, &state_.x, &state_.v);
    return;
  }
  Eigen::VectorXd x, v;
  mode.Flow().State(t0, z0, t, &x, &v);
  mode.Expand(x, v, &state_.x, &state_.v);
}

/// Counts events per window of one forcing period; true once a window holds
/// more than the bound (the windows start at events, so a window is at most
/// a period long plus the one phase that ended it).
bool HybridRun::OverWorkBound() {
  const System& s = hybrid_.GetSystem();
  if (state_.t - window_begin_ >= s.ForcingPeriod()) {
    window_begin_ = state_.t;
    window_events_ = Events();
  }
  return Events() - window_events_ > options_.max_events_per_period;
}

/// Stop `stop`'s mass reached it with speed `speed` >= 0: a landing when
/// the arrival's height is unresolved (chatter_rule.hpp), otherwise an
/// impact. The gap's curvature there is the arrival's acceleration.
void HybridRun::ArriveAtStop(int stop, double te, double speed) {
  double acceleration;
  if (phase_events_.IsLanding(stop, te, speed, &acceleration)) {
    // Resting on the stop and pushed into it, or touching it tangentially:
    // sticking or a grazing touch, not an impact.
    const Stop& s = hybrid_.GetStop(stop);
    if (s.SpeedTowards(state_.v(s.Dof())) > 0) {
      s.Absorb(state_.v, hybrid_.Holding(state_.held).ImpulseDirection(stop));
    }
    ++summary_.landings;
    observer_.OnLanding({stop, te});
    LandAtStop(stop);
    return;
  }
  ApplyImpact(stop, te, speed, acceleration);
}

void HybridRun::ApplyImpact(int stop, double te, double speed, double arrival_acceleration) {
  const System& system = hybrid_.GetSystem();
  const Stop& s = hybrid_.GetStop(stop);
  const Mode& mode = hybrid_.Holding(state_.held);
  const int c = s.Dof();
  impact_.t = te;
  impact_.phase = system.Phase(te);
  impact_.velocity = speed;
  impact_.stop = stop;
  impact_.x = state_.x;
  impact_.v = state_.v;
  state_.v(c) = s.Sign() * speed;
  s.Reset(state_.v, mode.ImpulseDirection(stop));
  impact_.v_after = state_.v;
  observer_.OnImpact(impact_);
  ++summary_.impacts;
  const double previous = last_impacts_[stop];
  last_impacts_[stop] = te;
  const std::optional<PhaseEvents::SequenceEnd> end = phase_events_.AfterImpact(
      stop, te, previous, state_.x, state_.v, impact_.v, arrival_acceleration);
  if (end) EndChatter(stop, te, *end);
}

/// The chatter sequence at stop `stop` ends after its impact at te, at
/// end.t (PhaseEvents::AfterImpact). The other masses follow the stuck
/// subsystem to that end (a chatter segment, not sticking); there x_c = xs,
/// v_c = 0, and the mass sticks if the stop pushes on it.
void HybridRun::EndChatter(int stop, double te, const PhaseEvents::SequenceEnd& end) {
  if (end.cut) ++summary_.chatter_cuts;
  const double t_star = std::min(t_end_, end.t);
  if (t_star > te) {
    const Mode& held = hybrid_.Holding(state_.held | StopBit(stop));
    held.Flow().Transient(te, held.Reduced(state_.x), held.Reduced(state_.v), &phase_transient_);
    observer_.OnSegment(Segment(held.Flow(), te, phase_transient_, te, t_star,
                                SegmentMode::kChatter, held.Moving(), held.HeldPositions()));
    MoveTo(held, te, phase_transient_, t_star);
  }
  state_.t = t_star;
  state_.v(hybrid_.GetStop(stop).Dof()) = 0.0;
  ++summary_.chatter_jumps;
  observer_.OnChatter({stop, te, t_star});
  LandAtStop(stop);
}

/// Stop `stop`'s mass at rest on it: held from here if the stop pushes on
/// it (Stop::Holds on the held mode's release witness).
void HybridRun::LandAtStop(int stop) {
  const Stop& s = hybrid_.GetStop(stop);
  state_.x(s.Dof()) = s.Position();
  state_.v(s.Dof()) = 0.0;
  const StopSet candidate = state_.held | StopBit(stop);
  const Mode& held = hybrid_.Holding(candidate);
  const Eigen::VectorXd z0 =
      held.Flow().Transient(state_.t, held.Reduced(state_.x), held.Reduced(state_.v));
  held.Flow().Output(held.Witness(stop)->output, state_.t, z0, &held_witness_);
  if (!Stop::Holds(held_witness_, state_.t, phase_events_.HeldSearch(held_witness_))) return;
  state_.held = candidate;
  stick_begins_[stop] = state_.t;
}

}  // namespace

Simulator::Simulator(const System& system, const SimulationOptions& options)
    : Simulator(std::make_shared<const HybridSystem>(system), options) {}
Simulator::Simulator(std::shared_ptr<const HybridSystem> hybrid, const SimulationOptions& options)
    : impl_(std::make_unique<Impl>(std::move(hybrid), options)) {}
Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

SimulationSummary Simulator::Run(HybridState& state, double t_end, Observer& observer) const {
  ValidateState(impl_->hybrid->GetSystem(), state);
  if (!(std::isfinite(t_end) && t_end >= state.t)) {
    throw InvalidInput(fmt::format("the end time must be finite and >= the start time {}, got {}",
                                   state.t, t_end));
  }
  return HybridRun(*impl_->hybrid, impl_->options, state, t_end, observer).Execute();
}

SimulationSummary Simulator::Run(HybridState& state, double t_end) const {
  Observer none;
  return Run(state, t_end, none);
}

const System& Simulator::GetSystem() const { return impl_->hybrid->GetSystem(); }

SimulationSummary Simulate(const System& system, const SimulationOptions& options,
                           HybridState& state, double t_end, Observer& observer) {
  return Simulator(system, options).Run(state, t_end, observer);
}

SimulationSummary Simulate(const System& system, const SimulationOptions& options,
                           HybridState& state, double t_end) {
  Observer none;
  return Simulate(system, options, state, t_end, none);
}

}  // namespace impactkit
