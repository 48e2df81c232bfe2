#include "impactkit/hybrid/simulator.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/segment.hpp"
#include "dynamics/subsystem.hpp"

namespace impactkit {

std::string ToString(ChatterMethod method) {
  return method == ChatterMethod::kAccumulation ? "accumulation" : "threshold";
}

std::string ToString(SimulationStatus status) {
  switch (status) {
    case SimulationStatus::kReachedEnd: return "reached end";
    case SimulationStatus::kEventLimit: return "event limit reached";
    case SimulationStatus::kStopped: return "stopped by observer";
    case SimulationStatus::kStalled: return "stalled: events repeat at one instant";
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
    return fail(fmt::format("event_time_tolerance must be in (0, 1e-3), got {}",
                            event_time_tolerance));
  }
  if (max_events < 1) return fail(fmt::format("max_events must be >= 1, got {}", max_events));
  return true;
}

std::string SimulationSummary::BriefReport() const {
  return fmt::format("{}: {} impacts, {} chatter sequences ended, {} releases, stuck {:.6g} time "
                     "units, {:.3g} s",
                     ToString(status), impacts, chatter_jumps, releases, stuck_time,
                     elapsed_seconds);
}

/// Everything that depends only on the system: both flows, decomposed once,
/// and the outputs the event loop evaluates.
struct Simulator::Impl {
  System system;
  SimulationOptions options;
  EventOptions event_options;
  LinearFlow free_flow;
  LinearFlow stuck_flow;
  PreparedOutput gap;             ///< x_c - xs, free flight
  LinearOutput contact_force;     ///< Fs, stuck subsystem
  PreparedOutput release_witness; ///< -Fs, stuck subsystem
  Eigen::RowVectorXd inverse_mass_row;  ///< e_cᵀ M⁻¹
  Eigen::MatrixXd inverse_mass;
  double time_scale = 1.0;

  Impl(const System& s, const SimulationOptions& o);
  /// a_c and its rate of change in free flight, using `force` and
  /// `acceleration` (size N) as scratch.
  double FreeAcceleration(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                          Eigen::VectorXd* force, Eigen::VectorXd* acceleration,
                          double* jerk) const;
  double ContactForce(double t, const Eigen::VectorXd& xs, const Eigen::VectorXd& vs) const;
};

namespace {

/// Fs = row c of (A cos Ωt - C v - K x - M a) with x_c = xs, v_c = a_c = 0 and
/// a the accelerations of the stuck subsystem: linear in its state.
LinearOutput ContactForceOutput(const System& s) {
  const int c = s.contact_dof;
  const Eigen::MatrixXd ms = WithoutIndex(s.mass, c);
  const Eigen::RowVectorXd coupling =
      WithoutIndex(Eigen::VectorXd(s.mass.row(c).transpose()), c).transpose() * ms.inverse();
  auto row = [&](const Eigen::MatrixXd& m) {
    return Eigen::RowVectorXd(WithoutIndex(Eigen::VectorXd(m.row(c).transpose()), c).transpose());
  };
  auto column = [&](const Eigen::MatrixXd& m) {
    return WithoutIndex(Eigen::VectorXd(m.col(c)), c);
  };
  LinearOutput f;
  f.wx = -row(s.stiffness) + coupling * WithoutIndex(s.stiffness, c);
  f.wv = -row(s.damping) + coupling * WithoutIndex(s.damping, c);
  f.cos_amplitude = s.forcing(c) - coupling.dot(WithoutIndex(s.forcing, c));
  f.offset = (-s.stiffness(c, c) + coupling.dot(column(s.stiffness))) * s.stop;
  return f;
}

LinearOutput Negated(LinearOutput output) {
  output.wx = -output.wx;
  output.wv = -output.wv;
  output.cos_amplitude = -output.cos_amplitude;
  output.offset = -output.offset;
  return output;
}

}  // namespace

Simulator::Impl::Impl(const System& s, const SimulationOptions& o) : system(s), options(o) {
  Validate(system);
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  const int n = s.Dof(), c = s.contact_dof;
  free_flow = LinearFlow(s.mass, s.damping, s.stiffness, s.forcing, Eigen::VectorXd::Zero(n),
                         s.omega);
  stuck_flow = LinearFlow(WithoutIndex(s.mass, c), WithoutIndex(s.damping, c),
                          WithoutIndex(s.stiffness, c), WithoutIndex(s.forcing, c),
                          -WithoutIndex(Eigen::VectorXd(s.stiffness.col(c)), c) * s.stop,
                          s.omega);
  LinearOutput gap_output{Eigen::RowVectorXd::Unit(n, c), Eigen::RowVectorXd::Zero(n), 0.0,
                          -s.stop};
  gap = free_flow.Prepare(gap_output);
  contact_force = ContactForceOutput(s);
  release_witness = stuck_flow.Prepare(Negated(contact_force));
  inverse_mass = s.mass.inverse();
  inverse_mass_row = inverse_mass.row(c);
  time_scale = free_flow.ShortestPeriod();
  event_options.time_tolerance = options.event_time_tolerance;
  event_options.time_scale = time_scale;
}

double Simulator::Impl::FreeAcceleration(double t, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& v, Eigen::VectorXd* force,
                                         Eigen::VectorXd* acceleration, double* jerk) const {
  const double wt = system.omega * t;
  force->noalias() = -system.damping * v;
  force->noalias() -= system.stiffness * x;
  *force += system.forcing * std::cos(wt);
  acceleration->noalias() = inverse_mass * *force;
  // d/dt of the force: -A Ω sin Ωt - C a - K v.
  force->noalias() = -system.damping * *acceleration;
  force->noalias() -= system.stiffness * v;
  *force -= system.forcing * (system.omega * std::sin(wt));
  *jerk = inverse_mass_row.dot(*force);
  return (*acceleration)(system.contact_dof);
}

double Simulator::Impl::ContactForce(double t, const Eigen::VectorXd& xs,
                                     const Eigen::VectorXd& vs) const {
  return contact_force.wx.dot(xs) + contact_force.wv.dot(vs) +
         contact_force.cos_amplitude * std::cos(system.omega * t) + contact_force.offset;
}

namespace {

/// One run: the loop of simulate.hpp's pseudocode over a hybrid state.
class HybridRun {
 public:
  HybridRun(const Simulator::Impl& impl, HybridState& state, double t_end, Observer& observer)
      : impl_(impl),
        state_(state),
        t_end_(t_end),
        observer_(observer),
        force_scratch_(impl.system.Dof()),
        acceleration_scratch_(impl.system.Dof()) {}

  SimulationSummary Execute();

 private:
  void FreePhase();
  void StuckPhase();
  void ApplyImpact(double te, double speed);
  std::optional<double> AccumulationTime(double te, double speed);
  void JumpToAccumulation(double te, double t_star);
  void LandAtStop();
  std::int64_t Events() const {
    return summary_.impacts + summary_.releases + summary_.chatter_jumps;
  }

  const Simulator::Impl& impl_;
  HybridState& state_;
  const double t_end_;
  Observer& observer_;
  SimulationSummary summary_;
  Signal witness_;
  Impact impact_;  ///< reused: no allocation per impact
  Eigen::VectorXd force_scratch_, acceleration_scratch_;
  double last_impact_ = -std::numeric_limits<double>::infinity();
  double stick_begin_ = 0.0;
  static constexpr int kMaxStalledPhases = 1000;
  int stalled_phases_ = 0;
};

SimulationSummary HybridRun::Execute() {
  const auto start = std::chrono::steady_clock::now();
  stick_begin_ = state_.t;
  while (state_.t < t_end_) {
    if (Events() >= impl_.options.max_events) {
      summary_.status = SimulationStatus::kEventLimit;
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
  const System& s = impl_.system;
  const int c = s.contact_dof;
  const double t0 = state_.t;
  const Eigen::VectorXd z0 = impl_.free_flow.Transient(t0, state_.x, state_.v);
  impl_.free_flow.Output(impl_.gap, t0, z0, &witness_);
  const bool pressing_now = state_.x(c) == s.stop && state_.v(c) > 0;
  const std::optional<double> te =
      pressing_now ? std::optional<double>(t0)
                   : FirstUpcrossing(witness_, t0, t_end_, impl_.event_options);
  const double end = te.value_or(t_end_);
  if (end > t0) observer_.OnSegment(Segment(impl_.free_flow, t0, z0, t0, end, false, c, s.stop));
  impl_.free_flow.State(t0, z0, end, &state_.x, &state_.v);
  state_.t = end;
  if (!te) return;
  state_.x(c) = s.stop;
  ApplyImpact(end, std::max(state_.v(c), 0.0));
}

void HybridRun::ApplyImpact(double te, double speed) {
  const System& s = impl_.system;
  const int c = s.contact_dof;
  impact_.t = te;
  impact_.phase = s.Phase(te);
  impact_.velocity = speed;
  impact_.x = state_.x;
  impact_.v = state_.v;
  observer_.OnImpact(impact_);
  ++summary_.impacts;
  state_.v(c) = -s.restitution * speed;
  const double previous = last_impact_;
  last_impact_ = te;
  if (state_.v(c) == 0.0) {
    LandAtStop();
  } else if (impl_.options.chatter == ChatterMethod::kThreshold) {
    if (te - previous < impl_.options.chatter_threshold) JumpToAccumulation(te, te);
  } else if (const std::optional<double> t_star = AccumulationTime(te, speed)) {
    JumpToAccumulation(te, std::min(t_end_, *t_star));
  }
}

/// The accumulation time of the chatter that starts here, if it is to be
/// jumped to. Budd & Dux: with rebound speed u and acceleration a > 0
/// towards the stop, the impacts that follow come at intervals 2 r^k u / a and end after
/// 2 u / (a (1 - r)). Jump there when that span is short on the system's
/// time scale and the acceleration barely changes over it (the geometric
/// model's premise); otherwise keep simulating impacts one by one.
std::optional<double> HybridRun::AccumulationTime(double te, double speed) {
  const System& s = impl_.system;
  if (s.restitution >= 1.0) return std::nullopt;
  double jerk;
  const double a = impl_.FreeAcceleration(te, state_.x, state_.v, &force_scratch_,
                                          &acceleration_scratch_, &jerk);
  if (!(a > 0)) return std::nullopt;
  const double span = 2.0 * s.restitution * speed / (a * (1.0 - s.restitution));
  if (span > impl_.options.chatter_span * impl_.time_scale || std::abs(jerk) * span > 0.01 * a) {
    return std::nullopt;
  }
  return te + span;
}

void HybridRun::JumpToAccumulation(double te, double t_star) {
  const System& s = impl_.system;
  const int c = s.contact_dof;
  if (t_star > te) {
    const Eigen::VectorXd z0 = impl_.stuck_flow.Transient(te, WithoutIndex(state_.x, c),
                                                          WithoutIndex(state_.v, c));
    observer_.OnSegment(Segment(impl_.stuck_flow, te, z0, te, t_star, true, c, s.stop));
    summary_.stuck_time += t_star - te;
    Eigen::VectorXd xs, vs;
    impl_.stuck_flow.State(te, z0, t_star, &xs, &vs);
    state_.x = EmbedAtStop(xs, c, s.stop);
    state_.v = EmbedAtStop(vs, c, 0.0);
  }
  state_.t = t_star;
  state_.v(c) = 0.0;
  ++summary_.chatter_jumps;
  observer_.OnChatter(te, t_star);
  LandAtStop();
}

void HybridRun::LandAtStop() {
  const int c = impl_.system.contact_dof;
  state_.x(c) = impl_.system.stop;
  state_.v(c) = 0.0;
  state_.stuck = impl_.ContactForce(state_.t, WithoutIndex(state_.x, c),
                                    WithoutIndex(state_.v, c)) > 0;
  if (state_.stuck) stick_begin_ = state_.t;
}

void HybridRun::StuckPhase() {
  const System& s = impl_.system;
  const int c = s.contact_dof;
  const double t0 = state_.t;
  const Eigen::VectorXd z0 =
      impl_.stuck_flow.Transient(t0, WithoutIndex(state_.x, c), WithoutIndex(state_.v, c));
  impl_.stuck_flow.Output(impl_.release_witness, t0, z0, &witness_);
  const std::optional<double> tr = witness_.Value(t0) >= 0
                                       ? std::optional<double>(t0)
                                       : FirstUpcrossing(witness_, t0, t_end_, impl_.event_options);
  const double end = tr.value_or(t_end_);
  if (end > t0) observer_.OnSegment(Segment(impl_.stuck_flow, t0, z0, t0, end, true, c, s.stop));
  Eigen::VectorXd xs, vs;
  impl_.stuck_flow.State(t0, z0, end, &xs, &vs);
  state_.x = EmbedAtStop(xs, c, s.stop);
  state_.v = EmbedAtStop(vs, c, 0.0);
  state_.t = end;
  summary_.stuck_time += end - t0;
  if (!tr) return;
  state_.stuck = false;
  ++summary_.releases;
  observer_.OnRelease(stick_begin_, end);
}

}  // namespace

Simulator::Simulator(const System& system, const SimulationOptions& options)
    : impl_(std::make_unique<Impl>(system, options)) {}
Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

SimulationSummary Simulator::Run(HybridState& state, double t_end, Observer& observer) const {
  ValidateState(impl_->system, state);
  if (!(std::isfinite(t_end) && t_end >= state.t)) {
    throw InvalidInput(fmt::format("the end time must be finite and >= the start time {}, got {}",
                                   state.t, t_end));
  }
  return HybridRun(*impl_, state, t_end, observer).Execute();
}

SimulationSummary Simulator::Run(HybridState& state, double t_end) const {
  Observer none;
  return Run(state, t_end, none);
}

const System& Simulator::GetSystem() const { return impl_->system; }
const SimulationOptions& Simulator::Options() const { return impl_->options; }
const LinearFlow& Simulator::FreeFlow() const { return impl_->free_flow; }

double Simulator::ContactForce(const HybridState& state) const {
  const int c = impl_->system.contact_dof;
  return impl_->ContactForce(state.t, WithoutIndex(state.x, c), WithoutIndex(state.v, c));
}

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
