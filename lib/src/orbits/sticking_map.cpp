#include "impactkit/orbits/sticking_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "dynamics/subsystem.hpp"
#include "hybrid/event_time.hpp"
#include "hybrid/phase_events.hpp"
#include "impactkit/dynamics/events.hpp"

namespace impactkit {

bool StickingMapOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!(max_free_periods > 0 && std::isfinite(max_free_periods))) {
    return fail(fmt::format("max_free_periods must be finite and > 0, got {}", max_free_periods));
  }
  if (!(max_stuck_periods > 0 && std::isfinite(max_stuck_periods))) {
    return fail(fmt::format("max_stuck_periods must be finite and > 0, got {}", max_stuck_periods));
  }
  if (max_impacts < 1) return fail(fmt::format("max_impacts must be >= 1, got {}", max_impacts));
  if (stop < 0)
    return fail(fmt::format("stop must be >= 0 (an index into the stops), got {}", stop));
  return simulation.IsValid(error);
}

/// One application of P_R from a section state: the motion and, if asked,
/// the Jacobian carried along as (∂y/∂s, ∂t/∂s) of the current state.
class StickingMap::Cycle {
 public:
  Cycle(const HybridSystem& hybrid, const StickingMapOptions& options, bool with_jacobian,
        bool with_contacts)
      : hybrid_(hybrid),
        options_(options),
        with_jacobian_(with_jacobian),
        with_contacts_(with_contacts),
        n_(hybrid.GetSystem().Dof()),
        measured_(hybrid.GetStop(options.stop).Dof()),
        events_{options.simulation.event_time_tolerance, hybrid.TimeScale()},
        phase_events_(hybrid, options.simulation),
        previous_(hybrid.StopCount()) {
    for (int k = 0; k < hybrid.StopCount(); ++k) {
      const Mode& held = hybrid.Holding(StopBit(k));
      const LinearOutput release =
          hybrid.GetStop(k).Release(hybrid.GetSystem(), held.Moving(), held.HeldPositions()).output;
      release_gradients_.emplace_back(2 * (n_ - 1));
      release_gradients_.back() << release.wx, release.wv;
    }
    for (int j = 0; with_contacts_ && j < hybrid.StopCount(); ++j) {
      contact_velocities_.push_back(hybrid.FreeFlow().Prepare(
          {Eigen::RowVectorXd::Zero(n_), Eigen::RowVectorXd::Unit(n_, hybrid.GetStop(j).Dof()), 0.0,
           0.0}));
    }
  }

  /// Follows a release from stop `from` (s its section state: without that
  /// stop's DOF) to the next release, from whichever stop the chatter
  /// sticks at (cycle->stop); that release's section state in *next.
  Termination Run(const Eigen::VectorXd& s, int from, Eigen::VectorXd* next,
                  Eigen::MatrixXd* jacobian, StickingCycle* cycle);
  /// StickingMap::Follow.
  StickingFlight Follow(const HybridState& from, double until, std::optional<int> released);

 private:
  using Arrival = PhaseEvents::Event;
  /// From the current state (a release from stop `released`, or a free
  /// state) to the next release, or to horizon_ if that comes first
  /// (*at_horizon).
  Termination ToNextRelease(std::optional<int> released, StickingCycle* cycle, bool* at_horizon);
  /// The free flight to the first arrival at any stop (PhaseEvents), the
  /// first of a cycle from a release at stop `released`; or, none coming
  /// before horizon_, to horizon_ (*at_horizon, and no arrival).
  std::optional<Arrival> NextArrival(std::optional<int> released, StickingCycle* cycle,
                                     Termination* status, bool* at_horizon);
  /// Takes into `cycle` the interior turns (the zeros of a velocity) on the
  /// flight [begin, end]: the least distance from its stop of each stop's
  /// mass at a turn towards that stop (its clearance), and the section
  /// stop's mass's extent.
  void MeasureFlight(double t0, const Eigen::VectorXd& z0, double begin, double end,
                     StickingCycle* cycle) const;
  /// The section stop's mass's extent while stop `stop`, on another mass,
  /// holds its: its turns on the held flow over (begin, end).
  void MeasureHeld(int stop, double t0, const Eigen::VectorXd& z0, double begin, double end,
                   StickingCycle* cycle) const;
  /// The least interior minimum of Fs on (begin, end), from w = −Fs: its
  /// maxima are the zeros of w' where it falls; infinity if there is none.
  double HoldMargin(const Signal& release, double begin, double end) const;
  /// True if, while stop `stop` holds its mass from te to `end`, another
  /// stop's mass reaches that stop.
  bool HeldMeetsOtherStop(int stop, const LinearFlow& flow, double te, const Eigen::VectorXd& z0,
                          double end) const;
  bool ArrivalEndsChatter(const Arrival& arrival, StickingCycle* cycle, double* t_star);
  /// Stuck at stop `stop` from te to the release, or to horizon_ if that
  /// comes first (*at_horizon).
  Termination StickAndRelease(int stop, double te, double t_star, StickingCycle* cycle,
                              bool* at_horizon);
  /// The state-and-time Jacobian through a flight from (t0, y0) to an event
  /// at t1 with witness gradient l and slope ẇ(t1): G = Φ (dy0 − f0 dt0),
  /// dt1 = −l G / ẇ, dy1 = G + f1 dt1.
  void ThroughFlight(const Eigen::MatrixXd& transition, const Eigen::VectorXd& f0,
                     const Eigen::VectorXd& f1, const Eigen::RowVectorXd& gradient, double slope);
  /// The same to the fixed time horizon_: dy1 = Φ (dy0 − f0 dt0), dt1 = 0.
  void ToHorizon(const Eigen::MatrixXd& transition, const Eigen::VectorXd& f0);
  /// The rows of ∂y/∂s without those of the held DOF `dof`.
  Eigen::MatrixXd HeldRows(const Eigen::MatrixXd& full, int dof) const;

  /// How long after a release the search for the first impact begins, as
  /// a fraction of the system's shortest time scale: far below any flight,
  /// far above the spurious root of a Newton iterate 1e-8 off the surface.
  static constexpr double kReleaseClearance = 1e-3;

  const HybridSystem& hybrid_;
  const StickingMapOptions& options_;
  const bool with_jacobian_, with_contacts_;
  const int n_;
  const int measured_;  ///< the section stop's mass, whose extent the cycle measures
  std::vector<PreparedOutput> contact_velocities_;  ///< each stop's v_dof on the free flow
  const EventOptions events_;
  /// Per stop: ∂(−Fs)/∂(x, v) of the masses that move while it holds its.
  std::vector<Eigen::RowVectorXd> release_gradients_;
  PhaseEvents phase_events_;  ///< the current flight's
  double t_ = 0.0;
  double deadline_ = 0.0;  ///< the cycle must stick before this time
  /// Follow's fixed end time (infinity for P_R).
  double horizon_ = std::numeric_limits<double>::infinity();
  std::vector<double> previous_;  ///< each stop's last impact time
  int last_stop_ = 0;             ///< the stop of the last event (PhaseEvents::First's order)
  Eigen::VectorXd x_, v_;
  Eigen::MatrixXd dy_;     ///< ∂y/∂s of the current state
  Eigen::RowVectorXd dt_;  ///< ∂t/∂s of the current time
};

Termination StickingMap::Cycle::Run(const Eigen::VectorXd& s, int from, Eigen::VectorXd* next,
                                    Eigen::MatrixXd* jacobian, StickingCycle* cycle) {
  const int held = n_ - 1, m = 2 * n_ - 1;
  const Stop& released = hybrid_.GetStop(from);
  t_ = s(m - 1);
  x_ = EmbedAtStop(s.head(held), released.Dof(), released.Position());
  v_ = EmbedAtStop(s.segment(held, held), released.Dof(), 0.0);
  if (with_jacobian_) {
    dy_ = Eigen::MatrixXd::Zero(2 * n_, m);
    for (int j = 0, k = 0; j < n_; ++j) {
      if (j == released.Dof()) continue;
      dy_(j, k) = 1.0;
      dy_(n_ + j, held + k) = 1.0;
      ++k;
    }
    dt_ = Eigen::RowVectorXd::Unit(m, m - 1);
  }
  horizon_ = std::numeric_limits<double>::infinity();
  bool at_horizon = false;
  const Termination status = ToNextRelease(from, cycle, &at_horizon);
  if (status != Termination::kCompleted) return status;
  const int dof = hybrid_.GetStop(cycle->stop).Dof();
  next->resize(m);
  *next << WithoutIndex(x_, dof), WithoutIndex(v_, dof), t_;
  if (with_jacobian_) {
    jacobian->resize(m, m);
    *jacobian << HeldRows(dy_, dof), dt_;
  }
  return Termination::kCompleted;
}

StickingFlight StickingMap::Cycle::Follow(const HybridState& from, double until,
                                          std::optional<int> released) {
  t_ = from.t;
  x_ = from.x;
  v_ = from.v;
  horizon_ = until;
  if (with_jacobian_) {
    dy_ = Eigen::MatrixXd::Identity(2 * n_, 2 * n_);
    dt_ = Eigen::RowVectorXd::Zero(2 * n_);
  }
  StickingFlight flight;
  for (bool at_horizon = false; !at_horizon;) {
    flight.cycles.emplace_back();
    flight.termination = ToNextRelease(released, &flight.cycles.back(), &at_horizon);
    if (flight.termination != Termination::kCompleted) return flight;
    if (at_horizon) break;
    released = flight.cycles.back().stop;
    // Released, the mass's coordinates are the stop's again: fixed.
    const int dof = hybrid_.GetStop(*released).Dof();
    if (with_jacobian_) dy_ = WithZeroRow(WithZeroRow(dy_, dof), n_ + dof);
  }
  flight.state = {t_, x_, v_};
  if (with_jacobian_) flight.jacobian = dy_;
  return flight;
}

Termination StickingMap::Cycle::ToNextRelease(std::optional<int> released, StickingCycle* cycle,
                                              bool* at_horizon) {
  const System& system = hybrid_.GetSystem();
  cycle->release = t_;
  last_stop_ = released.value_or(last_stop_);
  cycle->impacts.clear();
  cycle->clearance = std::numeric_limits<double>::infinity();
  cycle->contact_min = cycle->contact_max = x_(measured_);
  deadline_ = t_ + options_.max_free_periods * system.ForcingPeriod();
  std::fill(previous_.begin(), previous_.end(), -std::numeric_limits<double>::infinity());
  Termination status = Termination::kCompleted;
  for (int i = 0; i < options_.max_impacts; ++i) {
    const std::optional<Arrival> arrival =
        NextArrival(i == 0 ? released : std::nullopt, cycle, &status, at_horizon);
    if (*at_horizon) return Termination::kCompleted;
    if (!arrival) return status;
    last_stop_ = arrival->stop;
    double t_star;
    if (!ArrivalEndsChatter(*arrival, cycle, &t_star)) {
      previous_[arrival->stop] = arrival->t;
      continue;
    }
    return StickAndRelease(arrival->stop, arrival->t, t_star, cycle, at_horizon);
  }
  return Termination::kNoChatter;
}

std::optional<StickingMap::Cycle::Arrival> StickingMap::Cycle::NextArrival(
    std::optional<int> released, StickingCycle* cycle, Termination* status, bool* at_horizon) {
  const bool from_release = released.has_value();
  const LinearFlow& flow = hybrid_.FreeFlow();
  HybridState from;
  from.t = t_;
  from.x = x_;
  from.v = v_;
  const Eigen::VectorXd z0 = flow.Transient(t_, x_, v_);
  phase_events_.Begin(hybrid_.Free(), from, z0);
  // At a release the gap leaves 0 with zero speed and acceleration. Off
  // the release surface (a Newton iterate) a pressing force would turn that
  // tangency into a spurious impact at t0; searching from a short time later
  // keeps the map smooth there, and a gap still closed then means the state
  // is no release.
  PhaseEvents::LateStart late;
  if (from_release) {
    late = {*released, t_ + kReleaseClearance * hybrid_.TimeScale()};
    if (phase_events_.Witness(*released).Value(late.begin) >= 0) {
      *status = Termination::kNotReleased;
      return std::nullopt;
    }
  }
  const std::optional<Arrival> first =
      phase_events_.First(std::min(deadline_, horizon_), last_stop_, late);
  const Eigen::VectorXd x0 = x_, v0 = v_;
  const double t0 = t_;
  if (!first && horizon_ <= deadline_) {
    flow.StateFrom(t0, x0, v0, z0, horizon_, &x_, &v_);
    t_ = horizon_;
    if (with_jacobian_) ToHorizon(flow.Transition(horizon_ - t0), hybrid_.VectorField(t0, x0, v0));
    *at_horizon = true;
    return std::nullopt;
  }
  if (!first) {
    *status = from_release ? Termination::kNoImpact : Termination::kNoChatter;
    return std::nullopt;
  }
  const double end = first->t, measured_from = from_release ? late.begin : t_;
  if (with_contacts_) MeasureFlight(t_, z0, measured_from, end, cycle);
  flow.StateFrom(t0, x0, v0, z0, end, &x_, &v_);
  const Stop& stop = hybrid_.GetStop(first->stop);
  x_(stop.Dof()) = stop.Position();
  t_ = end;
  if (with_jacobian_) {
    ThroughFlight(flow.Transition(end - t0), hybrid_.VectorField(t0, x0, v0),
                  hybrid_.VectorField(end, x_, v_), Eigen::RowVectorXd::Unit(2 * n_, stop.Dof()),
                  v_(stop.Dof()));
  }
  return first;
}

void StickingMap::Cycle::MeasureFlight(double t0, const Eigen::VectorXd& z0, double begin,
                                       double end, StickingCycle* cycle) const {
  const LinearFlow& flow = hybrid_.FreeFlow();
  Eigen::VectorXd x, v;
  for (int j = 0; j < hybrid_.StopCount(); ++j) {
    const Stop& stop = hybrid_.GetStop(j);
    const Signal velocity = flow.Output(contact_velocities_[j], t0, z0);
    for (const double t : SignChanges(velocity, begin, end, events_)) {
      flow.State(t0, z0, t, &x, &v);
      if (stop.Dof() == measured_) {
        cycle->contact_min = std::min(cycle->contact_min, x(measured_));
        cycle->contact_max = std::max(cycle->contact_max, x(measured_));
      }
      // Only the turns towards the stop count for its clearance: maxima of
      // x below an upper stop, minima above a lower one.
      if (stop.Sign() * velocity.Derivative().Value(t) < 0 && -stop.GapOf(x) < cycle->clearance) {
        cycle->clearance = -stop.GapOf(x);
        cycle->clearance_time = t;
        cycle->clearance_stop = j;
      }
    }
  }
}

double StickingMap::Cycle::HoldMargin(const Signal& release, double begin, double end) const {
  const Signal slope = release.Derivative();
  double margin = std::numeric_limits<double>::infinity();
  for (const double t : SignChanges(slope, begin, end, events_)) {
    if (slope.Derivative().Value(t) < 0) margin = std::min(margin, -release.Value(t));
  }
  return margin;
}

void StickingMap::Cycle::MeasureHeld(int stop, double t0, const Eigen::VectorXd& z0, double begin,
                                     double end, StickingCycle* cycle) const {
  const Mode& held = hybrid_.Holding(StopBit(stop));
  const std::vector<int>& moving = held.Moving();
  const auto index = std::find(moving.begin(), moving.end(), measured_) - moving.begin();
  const int size = static_cast<int>(moving.size());
  const LinearFlow& flow = held.Flow();
  const Signal velocity =
      flow.Output(flow.Prepare({Eigen::RowVectorXd::Zero(size),
                                Eigen::RowVectorXd::Unit(size, index), 0.0, 0.0}),
                  t0, z0);
  Eigen::VectorXd x, v;
  for (const double t : SignChanges(velocity, begin, end, events_)) {
    flow.State(t0, z0, t, &x, &v);
    cycle->contact_min = std::min(cycle->contact_min, x(index));
    cycle->contact_max = std::max(cycle->contact_max, x(index));
  }
}

bool StickingMap::Cycle::HeldMeetsOtherStop(int stop, const LinearFlow& flow, double te,
                                            const Eigen::VectorXd& z0, double end) const {
  const Mode& held = hybrid_.Holding(StopBit(stop));
  for (int j = 0; j < hybrid_.StopCount(); ++j) {
    // Null for the stops of the held mass: it does not move.
    const PreparedWitness* gap = j == stop ? nullptr : held.Witness(j);
    if (gap && FirstUpcrossing(flow.Output(gap->output, te, z0), te, end, events_)) return true;
  }
  return false;
}

/// The simulator's rules at an arrival (hybrid/phase_events.hpp), with the
/// arrival's stop's law and rule: a landing ends the chatter at once and is
/// no impact; an impact is recorded and reset, and the chatter ends where
/// the rule says: at once, or at the end of its tail by the chatter map, if
/// the tail accumulates. True if it ends, at *t_star.
bool StickingMap::Cycle::ArrivalEndsChatter(const Arrival& arrival, StickingCycle* cycle,
                                            double* t_star) {
  const int k = arrival.stop;
  const double te = arrival.t;
  const Stop& stop = hybrid_.GetStop(k);
  const int dof = stop.Dof();
  // The speed towards the stop (on either side of the mass), at least 0:
  // the search places the crossing to rounding, where it may have the
  // other sign.
  const double speed = std::max(stop.SpeedTowards(v_(dof)), 0.0);
  v_(dof) = stop.Sign() * speed;
  *t_star = te;
  double arrival_acceleration;
  if (phase_events_.IsLanding(k, te, speed, &arrival_acceleration)) {
    stop.Absorb(v_);
    if (with_jacobian_) dy_ = stop.AbsorbJacobian(n_) * dy_;
    return true;
  }
  cycle->impacts.push_back({k, te, speed});
  const Eigen::VectorXd v_before = v_;
  stop.Reset(v_);
  if (with_jacobian_) dy_ = stop.ResetJacobian(n_) * dy_;
  const std::optional<PhaseEvents::SequenceEnd> end =
      phase_events_.AfterImpact(k, te, previous_[k], x_, v_, v_before, arrival_acceleration);
  if (!end) return false;
  *t_star = end->t;
  return true;
}

/// From the impact at te that ends the chatter, the stuck flow: through
/// the chatter's tail to its end t*, then stuck to the release.
Termination StickingMap::Cycle::StickAndRelease(int stop, double te, double t_star,
                                                StickingCycle* cycle, bool* at_horizon) {
  const System& system = hybrid_.GetSystem();
  const LinearFlow& flow = hybrid_.StuckFlow(stop);
  const Stop& holding = hybrid_.GetStop(stop);
  const int c = holding.Dof();
  const Eigen::VectorXd x0 = WithoutIndex(x_, c), v0 = WithoutIndex(v_, c);
  const Eigen::VectorXd z0 = flow.Transient(te, x0, v0);
  Eigen::VectorXd x1, v1;
  flow.StateFrom(te, x0, v0, z0, t_star, &x1, &v1);
  cycle->stop = stop;
  cycle->accumulation = t_star;
  cycle->contact_force = hybrid_.ContactForce(stop, t_star, x1, v1);
  if (!Stop::Holds(cycle->contact_force)) return Termination::kNoSticking;
  const Signal release = flow.Output(hybrid_.Release(stop), te, z0);
  const std::optional<double> tr = FirstUpcrossing(
      release, t_star, t_star + options_.max_stuck_periods * system.ForcingPeriod(), events_);
  if (!tr && t_star + options_.max_stuck_periods * system.ForcingPeriod() < horizon_) {
    return Termination::kNoRelease;
  }
  *at_horizon = !tr || horizon_ < *tr;
  const double end = *at_horizon ? horizon_ : *tr;
  if (HeldMeetsOtherStop(stop, flow, te, z0, end)) return Termination::kMetWhileHeld;
  if (*at_horizon) {
    flow.StateFrom(te, x0, v0, z0, end, &x1, &v1);
    if (with_jacobian_) {
      dy_ = HeldRows(dy_, c);
      ToHorizon(flow.Transition(end - te), hybrid_.Holding(StopBit(stop)).VectorField(te, x0, v0));
      dy_ = WithZeroRow(WithZeroRow(dy_, c), n_ + c);
    }
    x_ = EmbedAtStop(x1, c, holding.Position());
    v_ = EmbedAtStop(v1, c, 0.0);
    t_ = end;
    return Termination::kCompleted;
  }
  if (with_contacts_) {
    cycle->hold_margin = HoldMargin(release, t_star, *tr);
    if (c == measured_) {
      cycle->contact_min = std::min(cycle->contact_min, holding.Position());
      cycle->contact_max = std::max(cycle->contact_max, holding.Position());
    } else {
      MeasureHeld(stop, te, z0, te, *tr, cycle);
    }
  }
  flow.StateFrom(te, x0, v0, z0, *tr, &x1, &v1);
  if (with_jacobian_) {
    double value, slope;
    release.ValueAndSlope(*tr, &value, &slope);
    dy_ = HeldRows(dy_, c);
    const Mode& stuck = hybrid_.Holding(StopBit(stop));
    ThroughFlight(flow.Transition(*tr - te), stuck.VectorField(te, x0, v0),
                  stuck.VectorField(*tr, x1, v1), release_gradients_[stop], slope);
  }
  x_ = EmbedAtStop(x1, c, holding.Position());
  v_ = EmbedAtStop(v1, c, 0.0);
  t_ = *tr;
  cycle->next_release = *tr;
  return Termination::kCompleted;
}

void StickingMap::Cycle::ThroughFlight(const Eigen::MatrixXd& transition, const Eigen::VectorXd& f0,
                                       const Eigen::VectorXd& f1,
                                       const Eigen::RowVectorXd& gradient, double slope) {
  EventDerivatives d = ThroughEvent(AtFixedTime(transition, dy_, dt_, f0), gradient, slope, f1);
  dy_ = std::move(d.state);
  dt_ = std::move(d.time);
}

void StickingMap::Cycle::ToHorizon(const Eigen::MatrixXd& transition, const Eigen::VectorXd& f0) {
  dy_ = AtFixedTime(transition, dy_, dt_, f0);
  dt_ = Eigen::RowVectorXd::Zero(dt_.size());
}

Eigen::MatrixXd StickingMap::Cycle::HeldRows(const Eigen::MatrixXd& full, int dof) const {
  if (full.rows() != 2 * n_) return full;  // already the held mode's
  Eigen::MatrixXd rows(2 * (n_ - 1), full.cols());
  rows << WithoutRow(full.topRows(n_), dof), WithoutRow(full.bottomRows(n_), dof);
  return rows;
}

StickingMap::StickingMap(const System& system, const StickingMapOptions& options)
    : StickingMap(std::make_shared<const HybridSystem>(system), options) {}

StickingMap::StickingMap(std::shared_ptr<const HybridSystem> hybrid,
                         const StickingMapOptions& options)
    : hybrid_(std::move(hybrid)), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw InvalidInput(error);
  if (options_.stop >= hybrid_->StopCount()) {
    throw InvalidInput(fmt::format("the release map's stop {} (0-based): the system has {} stop{}",
                                   options_.stop, hybrid_->StopCount(),
                                   hybrid_->StopCount() == 1 ? "" : "s"));
  }
}

void StickingMap::ValidateSection(const Eigen::VectorXd& s) const {
  const int n = GetSystem().Dof();
  if (s.size() != Size()) {
    throw InvalidInput(fmt::format(
        "a release state s = (x and v of the {} masses not at the stop, t) has {} entries, got {}",
        n - 1, Size(), s.size()));
  }
  if (!s.allFinite()) throw InvalidInput("the release state has a NaN or infinite entry");
}

StickingMapResult StickingMap::Apply(const Eigen::VectorXd& s, int k, bool with_jacobian,
                                     bool with_contacts) const {
  if (k < 1) throw InvalidInput(fmt::format("the number of releases must be >= 1, got {}", k));
  ValidateSection(s);
  StickingMapResult result;
  result.state = s;
  if (with_jacobian) result.jacobian = Eigen::MatrixXd::Identity(Size(), Size());
  Cycle cycle(*hybrid_, options_, with_jacobian, with_contacts);
  Eigen::VectorXd next;
  Eigen::MatrixXd step_jacobian;
  int from = options_.stop;
  for (int i = 0; i < k; ++i) {
    StickingCycle record;
    result.termination = cycle.Run(result.state, from, &next, &step_jacobian, &record);
    if (result.termination != Termination::kCompleted) {
      result.jacobian.resize(0, 0);
      return result;
    }
    result.state = next;
    if (with_jacobian) result.jacobian = step_jacobian * result.jacobian;
    from = record.stop;
    result.cycles.push_back(std::move(record));
    ++result.cycles_done;
  }
  // P_R^k is a map of the section only if its last release is the
  // section stop's (as an impact map's p-th impact).
  if (from != options_.stop) {
    result.termination = Termination::kOtherStop;
    result.jacobian.resize(0, 0);
  }
  return result;
}

StickingFlight StickingMap::Follow(const HybridState& from, double until, bool with_jacobian,
                                   std::optional<int> released) const {
  const int n = GetSystem().Dof();
  if (from.x.size() != n || from.v.size() != n) {
    throw InvalidInput(
        fmt::format("a state of this system has {} positions and velocities, got {} "
                    "and {}",
                    n, from.x.size(), from.v.size()));
  }
  if (!from.x.allFinite() || !from.v.allFinite() || !std::isfinite(from.t) ||
      !std::isfinite(until)) {
    throw InvalidInput("the state and the time followed to must be finite");
  }
  if (!(until >= from.t)) {
    throw InvalidInput(
        fmt::format("the motion is followed forward: {} is before the start {}", until, from.t));
  }
  if (released && (*released < 0 || *released >= hybrid_->StopCount())) {
    throw InvalidInput(fmt::format("a release from stop {} (0-based): the system has {} stop{}",
                                   *released, hybrid_->StopCount(),
                                   hybrid_->StopCount() == 1 ? "" : "s"));
  }
  Cycle cycle(*hybrid_, options_, with_jacobian, false);
  return cycle.Follow(from, until, released);
}

SectionImage StickingMap::Iterate(const Eigen::VectorXd& s, int k, bool with_jacobian) const {
  SectionImage image;
  if (s.size() != Size() || !s.allFinite()) {
    image.failure = "not a release state";
    return image;
  }
  StickingMapResult result = Apply(s, k, with_jacobian);
  // Past a sticking family's end the chatter either accumulates where the
  // stop no longer pushes, or (the acceleration towards the stop vanishing)
  // no longer accumulates at all: both say it stops ending in sticking.
  image.stops_sticking = result.termination == Termination::kNoSticking ||
                         result.termination == Termination::kNoChatter;
  if (result.termination != Termination::kCompleted) {
    image.failure = fmt::format("after {} of {} releases, {}", result.cycles_done, k,
                                Describe(result.termination));
    return image;
  }
  image.state = std::move(result.state);
  image.jacobian = std::move(result.jacobian);
  return image;
}

HybridState StickingMap::ToState(const Eigen::VectorXd& s) const {
  const StopParameters& stop = GetSystem().stops[options_.stop];
  const int held = GetSystem().Dof() - 1, c = stop.dof;
  HybridState state;
  state.t = s(TimeIndex());
  state.x = EmbedAtStop(s.head(held), c, stop.position);
  state.v = EmbedAtStop(s.segment(held, held), c, 0.0);
  return state;
}

double StickingMap::ContactForce(const Eigen::VectorXd& s) const {
  const int held = GetSystem().Dof() - 1;
  return hybrid_->ContactForce(options_.stop, s(TimeIndex()), s.head(held), s.segment(held, held));
}

Eigen::RowVectorXd StickingMap::ContactForceGradient(const Eigen::VectorXd& s) const {
  const Mode& held = hybrid_->Holding(StopBit(options_.stop));
  const LinearOutput force = hybrid_->GetStop(options_.stop)
                                 .ContactForce(GetSystem(), held.Moving(), held.HeldPositions());
  const double omega = GetSystem().omega;
  Eigen::RowVectorXd gradient(Size());
  gradient << force.wx, force.wv, -force.cos_amplitude * omega * std::sin(omega * s(TimeIndex()));
  return gradient;
}

}  // namespace impactkit
