#include "impactkit/hybrid/simulator.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>

#include "hybrid/chatter_rule.hpp"
#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/segment.hpp"

namespace impactkit {

std::string ToString(ChatterMethod method) {
  return method == ChatterMethod::kAccumulation ? "accumulation" : "threshold";
}

std::string ToString(SimulationStatus status) {
  switch (status) {
    case SimulationStatus::kReachedEnd:
      return "reached end";
    case SimulationStatus::kEventLimit:
      return "event limit reached";
    case SimulationStatus::kStopped:
      return "stopped by observer";
    case SimulationStatus::kStalled:
      return "stalled: events repeat at one instant";
    case SimulationStatus::kWorkLimit:
      return "work bound reached: too many events in one forcing period";
  }
  return "unknown";
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
  return fmt::format(
      "{}: {} impacts, {} landings, {} chatter sequences ended, {} releases, stuck {:.6g} "
      "time units, {:.3g} s",
      ToString(status), impacts, landings, chatter_jumps, releases, stuck_time, elapsed_seconds);
}

/// The hybrid system (both modes' flows, decomposed once) and the options.
struct Simulator::Impl {
  std::shared_ptr<const HybridSystem> hybrid;
  SimulationOptions options;
  EventOptions event_options;

  Impl(std::shared_ptr<const HybridSystem> h, const SimulationOptions& o)
      : hybrid(std::move(h)), options(o) {
    std::string error;
    if (!options.IsValid(&error)) throw InvalidInput(error);
    event_options.time_tolerance = options.event_time_tolerance;
    event_options.time_scale = hybrid->TimeScale();
  }
};

namespace {

/// One run: the loop of simulate.hpp's pseudocode over a hybrid state.
class HybridRun {
 public:
  HybridRun(const HybridSystem& hybrid, const SimulationOptions& options,
            const EventOptions& events, HybridState& state, double t_end, Observer& observer)
      : hybrid_(hybrid),
        options_(options),
        events_(events),
        state_(state),
        t_end_(t_end),
        observer_(observer),
        rule_(options, hybrid.GetStop().Restitution(), hybrid.TimeScale()),
        force_scratch_(hybrid_.GetSystem().Dof()),
        acceleration_scratch_(hybrid_.GetSystem().Dof()) {}

  SimulationSummary Execute();

 private:
  void FreePhase();
  void StuckPhase();
  void ArriveAtStop(double te, double speed);
  void ApplyImpact(double te, double speed);
  bool OverWorkBound();
  double LengthScale() const;
  /// Where the current phase's search stops if no event comes first: t_end,
  /// or kPhaseSlice forcing periods on, so that a run without events still
  /// asks its observers (ShouldStop: Ctrl-C, progress) as it goes.
  double SliceEnd() const {
    return std::min(t_end_, state_.t + kPhaseSlice * hybrid_.GetSystem().ForcingPeriod());
  }
  static constexpr double kPhaseSlice = 1000;
  EventOptions Search() const;
  EventOptions HeldSearch() const;
  void JumpToAccumulation(double te, double t_star);
  void LandAtStop();
  std::int64_t Events() const {
    return summary_.impacts + summary_.landings + summary_.releases + summary_.chatter_jumps;
  }

  const HybridSystem& hybrid_;
  const SimulationOptions& options_;
  const EventOptions& events_;
  HybridState& state_;
  const double t_end_;
  Observer& observer_;
  const ChatterRule rule_;
  SimulationSummary summary_;
  Signal witness_;
  Impact impact_;  ///< reused: no allocation per impact
  Eigen::VectorXd force_scratch_, acceleration_scratch_;
  double last_impact_ = -std::numeric_limits<double>::infinity();
  double length_scale_ = 1.0;  ///< of the current flight (LengthScale())
  double stick_begin_ = 0.0;
  static constexpr int kMaxStalledPhases = 1000;
  static constexpr double kRounding = 64 * std::numeric_limits<double>::epsilon();
  int stalled_phases_ = 0;
  double window_begin_ = 0.0;       ///< start of the work bound's current window
  std::int64_t window_events_ = 0;  ///< Events() at window_begin_
};

SimulationSummary HybridRun::Execute() {
  const auto start = std::chrono::steady_clock::now();
  stick_begin_ = state_.t;
  window_begin_ = state_.t;
  while (state_.t < t_end_) {
    if (Events() >= options_.max_events) {
      summary_.status = SimulationStatus::kEventLimit;
      break;
    }
    if (OverWorkBound()) {
      summary_.status = SimulationStatus::kWorkLimit;
      break;
    }
    const double before = state_.t;
    state_.stuck ? StuckPhase() : FreePhase();
    // Events at one instant, over and over, would loop forever.
    stalled_phases_ = state_.t > before ? 0 : stalled_phases_ + 1;
    if (stalled_phases_ > kMaxStalledPhases) {
      summary_.status = SimulationStatus::kStalled;
      break;
    }
    if (observer_.ShouldStop()) {
      summary_.status = SimulationStatus::kStopped;
      break;
    }
  }
  summary_.elapsed_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary_;
}

void HybridRun::FreePhase() {
  const System& s = hybrid_.GetSystem();
  const LinearFlow& flow = hybrid_.FreeFlow();
  const int c = s.contact_dof;
  const double t0 = state_.t;
  const Eigen::VectorXd z0 = flow.Transient(t0, state_.x, state_.v);
  flow.Output(hybrid_.Gap(), t0, z0, &witness_);
  length_scale_ = LengthScale();
  const bool pressing_now = state_.x(c) == s.stop && state_.v(c) > 0;
  const std::optional<double> te = pressing_now
                                       ? std::optional<double>(t0)
                                       : FirstUpcrossing(witness_, t0, SliceEnd(), Search());
  const double end = te.value_or(SliceEnd());
  if (end > t0) observer_.OnSegment(Segment(flow, t0, z0, t0, end, SegmentMode::kFree, c, s.stop));
  flow.State(t0, z0, end, &state_.x, &state_.v);
  state_.t = end;
  if (!te) return;
  state_.x(c) = s.stop;
  ArriveAtStop(end, std::max(state_.v(c), 0.0));
}

/// The length scale of the flight from the current state: the rounding of
/// its gap comes from the state and the forced response (the gap signal's
/// own coefficients can be far smaller, for a mass barely moving off the
/// stop while the others swing).
double HybridRun::LengthScale() const {
  const double per_radian = hybrid_.TimeScale() / (2 * std::numbers::pi);
  return std::abs(hybrid_.GetSystem().stop) + state_.x.lpNorm<Eigen::Infinity>() +
         state_.v.lpNorm<Eigen::Infinity>() * per_radian + witness_.Scale();
}

/// The event search's options for the flight from the current state: gap
/// heights below the bounce resolution are not resolved (chatter_rule.hpp),
/// and one that leaves the stop from rest starts where the gap and its
/// slope are 0 in truth, to the rounding of the length scale.
EventOptions HybridRun::Search() const {
  const int c = hybrid_.GetSystem().contact_dof;
  EventOptions events = events_;
  events.resolution = options_.bounce_height_resolution * length_scale_;
  if (state_.x(c) == hybrid_.GetSystem().stop && state_.v(c) == 0.0) {
    events.start_noise = kRounding * length_scale_;
  }
  return events;
}

/// The release search's options on the held phase's witness (in witness_):
/// it starts where the contact force may be 0 to the rounding of its terms,
/// and a dip of the force below 0 that returns within the bounce resolution
/// of its scale is no release (a mass at rest on the stop with no force, at
/// an antiresonance, would otherwise be certified piece by tiny piece).
EventOptions HybridRun::HeldSearch() const {
  EventOptions events = events_;
  events.start_noise = kRounding * witness_.Scale();
  events.resolution = options_.bounce_height_resolution * witness_.Scale();
  return events;
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

/// The contact mass reached the stop with speed `speed` >= 0: a landing
/// when the arrival's height is unresolved (chatter_rule.hpp), otherwise an
/// impact. The gap's curvature there is the arrival's acceleration.
void HybridRun::ArriveAtStop(double te, double speed) {
  double gap, slope, acceleration;
  witness_.ValueSlopeCurvature(te, &gap, &slope, &acceleration);
  if (rule_.IsLanding(speed, acceleration, length_scale_)) {
    // Resting on the stop and pushed into it, or touching it tangentially:
    // sticking or a grazing touch, not an impact.
    if (state_.v(hybrid_.GetSystem().contact_dof) > 0) hybrid_.GetStop().Absorb(state_.v);
    ++summary_.landings;
    LandAtStop();
    return;
  }
  ApplyImpact(te, speed);
}

void HybridRun::ApplyImpact(double te, double speed) {
  const System& s = hybrid_.GetSystem();
  const int c = s.contact_dof;
  impact_.t = te;
  impact_.phase = s.Phase(te);
  impact_.velocity = speed;
  impact_.x = state_.x;
  impact_.v = state_.v;
  state_.v(c) = speed;
  hybrid_.GetStop().Reset(state_.v);
  impact_.v_after = state_.v;
  observer_.OnImpact(impact_);
  ++summary_.impacts;
  const double previous = last_impact_;
  last_impact_ = te;
  // The acceleration after the reset (the rebound's), which the chatter
  // prediction models.
  double jerk;
  const double acceleration = hybrid_.ContactAcceleration(te, state_.x, state_.v, &jerk,
                                                          &force_scratch_, &acceleration_scratch_);
  const std::optional<double> t_star =
      rule_.EndsAt(te, previous, speed, -state_.v(c), acceleration, jerk, length_scale_);
  if (t_star) JumpToAccumulation(te, std::min(t_end_, *t_star));
}

void HybridRun::JumpToAccumulation(double te, double t_star) {
  const System& s = hybrid_.GetSystem();
  const LinearFlow& held = hybrid_.StuckFlow();
  const int c = s.contact_dof;
  if (t_star > te) {
    const Eigen::VectorXd z0 = held.Transient(te, hybrid_.Held(state_.x), hybrid_.Held(state_.v));
    // Not sticking yet: the impacts accumulate until t*, where sticking (if
    // the contact force holds the mass) begins.
    observer_.OnSegment(Segment(held, te, z0, te, t_star, SegmentMode::kChatter, c, s.stop));
    Eigen::VectorXd xs, vs;
    held.State(te, z0, t_star, &xs, &vs);
    state_.x = hybrid_.Full(xs, s.stop);
    state_.v = hybrid_.Full(vs, 0.0);
  }
  state_.t = t_star;
  state_.v(c) = 0.0;
  ++summary_.chatter_jumps;
  observer_.OnChatter(te, t_star);
  LandAtStop();
}

void HybridRun::LandAtStop() {
  const System& s = hybrid_.GetSystem();
  state_.x(s.contact_dof) = s.stop;
  state_.v(s.contact_dof) = 0.0;
  const LinearFlow& held = hybrid_.StuckFlow();
  const Eigen::VectorXd z0 =
      held.Transient(state_.t, hybrid_.Held(state_.x), hybrid_.Held(state_.v));
  held.Output(hybrid_.Release(), state_.t, z0, &witness_);
  state_.stuck = Stop::Holds(witness_, state_.t, HeldSearch());
  if (state_.stuck) stick_begin_ = state_.t;
}

void HybridRun::StuckPhase() {
  const System& s = hybrid_.GetSystem();
  const LinearFlow& held = hybrid_.StuckFlow();
  const int c = s.contact_dof;
  const double t0 = state_.t;
  const Eigen::VectorXd z0 = held.Transient(t0, hybrid_.Held(state_.x), hybrid_.Held(state_.v));
  held.Output(hybrid_.Release(), t0, z0, &witness_);
  const EventOptions search = HeldSearch();
  const std::optional<double> tr = !Stop::Holds(witness_, t0, search)
                                       ? std::optional<double>(t0)
                                       : FirstUpcrossing(witness_, t0, SliceEnd(), search);
  const double end = tr.value_or(SliceEnd());
  if (end > t0) observer_.OnSegment(Segment(held, t0, z0, t0, end, SegmentMode::kStuck, c, s.stop));
  Eigen::VectorXd xs, vs;
  held.State(t0, z0, end, &xs, &vs);
  state_.x = hybrid_.Full(xs, s.stop);
  state_.v = hybrid_.Full(vs, 0.0);
  state_.t = end;
  summary_.stuck_time += end - t0;
  if (!tr) return;
  state_.stuck = false;
  ++summary_.releases;
  observer_.OnRelease(stick_begin_, end);
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
  return HybridRun(*impl_->hybrid, impl_->options, impl_->event_options, state, t_end, observer)
      .Execute();
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
