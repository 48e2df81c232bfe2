#include "impactkit/orbits/sticking_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "dynamics/subsystem.hpp"
#include "hybrid/chatter_rule.hpp"
#include "hybrid/event_time.hpp"
#include "impactkit/dynamics/events.hpp"

namespace impactkit {

std::string ToString(StickingMapStatus status) {
  switch (status) {
    case StickingMapStatus::kOk:
      return "ok";
    case StickingMapStatus::kNotReleased:
      return "not a release (the stop still pushes on the mass: Fs > 0)";
    case StickingMapStatus::kNoImpact:
      return "no impact after the release";
    case StickingMapStatus::kNoChatter:
      return "impacts without a chatter sequence accumulating";
    case StickingMapStatus::kNoSticking:
      return "the chatter ends with Fs <= 0: the mass is not held (no sticking)";
    case StickingMapStatus::kNoRelease:
      return "no release: the mass stays stuck";
  }
  return "unknown";
}

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
        c_(hybrid.GetSystem().SoleStop("the sticking map").dof),
        events_{options.simulation.event_time_tolerance, hybrid.TimeScale()},
        rule_(options.simulation, hybrid.GetStop(0).Restitution(), hybrid.TimeScale(),
              hybrid.Free().Contact(0)) {
    const LinearOutput release =
        hybrid.GetStop(0)
            .Release(hybrid.GetSystem(), hybrid.Holding(StopBit(0)).Moving(),
                     hybrid.Holding(StopBit(0)).HeldPositions())
            .output;
    release_gradient_.resize(2 * (n_ - 1));
    release_gradient_ << release.wx, release.wv;
    if (with_contacts_) {
      contact_velocity_ = hybrid.FreeFlow().Prepare(
          {Eigen::RowVectorXd::Zero(n_), Eigen::RowVectorXd::Unit(n_, c_), 0.0, 0.0});
    }
  }

  /// Follows one release to the next; the new section state in *next.
  StickingMapStatus Run(const Eigen::VectorXd& s, Eigen::VectorXd* next, Eigen::MatrixXd* jacobian,
                        StickingCycle* cycle);

 private:
  std::optional<double> NextImpact(bool from_release, StickingMapStatus* status);
  /// The least distance from the stop of x_c's interior turns towards it on
  /// the flight [begin, end] (the zeros of v_c), infinity if there are none.
  double FlightClearance(double t0, const Eigen::VectorXd& z0, double begin, double end) const;
  /// The least interior minimum of Fs on (begin, end), from w = −Fs: its
  /// maxima are the zeros of w' where it falls; infinity if there is none.
  double HoldMargin(const Signal& release, double begin, double end) const;
  bool ArrivalEndsChatter(double te, double previous, StickingCycle* cycle, double* t_star);
  StickingMapStatus StickAndRelease(double te, double t_star, StickingCycle* cycle);
  /// The state-and-time Jacobian through a flight from (t0, y0) to an event
  /// at t1 with witness gradient l and slope ẇ(t1): G = Φ (dy0 − f0 dt0),
  /// dt1 = −l G / ẇ, dy1 = G + f1 dt1.
  void ThroughFlight(const Eigen::MatrixXd& transition, const Eigen::VectorXd& f0,
                     const Eigen::VectorXd& f1, const Eigen::RowVectorXd& gradient, double slope);
  Eigen::MatrixXd HeldRows(const Eigen::MatrixXd& full) const;

  /// How long after a release the search for the first impact begins, as
  /// a fraction of the system's shortest time scale: far below any flight,
  /// far above the spurious root of a Newton iterate 1e-8 off the surface.
  static constexpr double kReleaseClearance = 1e-3;

  const HybridSystem& hybrid_;
  const StickingMapOptions& options_;
  const bool with_jacobian_, with_contacts_;
  const int n_, c_;
  PreparedOutput contact_velocity_;  ///< v_c on the free flow (with contacts)
  const EventOptions events_;
  Eigen::RowVectorXd release_gradient_;
  double t_ = 0.0;
  double deadline_ = 0.0;   ///< the cycle must stick before this time
  double clearance_ = 0.0;  ///< the cycle's so far (with contacts)
  const ChatterRule rule_;
  double arrival_acceleration_ = 0.0;  ///< the gap's curvature at the last arrival
  double gap_scale_ = 1.0;             ///< and the gap's length scale (GapLengthScale)
  Eigen::VectorXd x_, v_;
  Eigen::MatrixXd dy_;     ///< ∂y/∂s of the current state
  Eigen::RowVectorXd dt_;  ///< ∂t/∂s of the current time
};

StickingMapStatus StickingMap::Cycle::Run(const Eigen::VectorXd& s, Eigen::VectorXd* next,
                                          Eigen::MatrixXd* jacobian, StickingCycle* cycle) {
  const System& system = hybrid_.GetSystem();
  const int held = n_ - 1, m = 2 * n_ - 1;
  t_ = s(m - 1);
  x_ = EmbedAtStop(s.head(held), c_, system.stops[0].position);
  v_ = EmbedAtStop(s.segment(held, held), c_, 0.0);
  if (with_jacobian_) {
    dy_ = Eigen::MatrixXd::Zero(2 * n_, m);
    for (int j = 0, k = 0; j < n_; ++j) {
      if (j == c_) continue;
      dy_(j, k) = 1.0;
      dy_(n_ + j, held + k) = 1.0;
      ++k;
    }
    dt_ = Eigen::RowVectorXd::Unit(m, m - 1);
  }
  cycle->release = t_;
  cycle->impacts.clear();
  clearance_ = std::numeric_limits<double>::infinity();
  deadline_ = t_ + options_.max_free_periods * system.ForcingPeriod();
  double previous = -std::numeric_limits<double>::infinity();
  StickingMapStatus status = StickingMapStatus::kOk;
  for (int k = 0; k < options_.max_impacts; ++k) {
    const std::optional<double> te = NextImpact(k == 0, &status);
    if (!te) return status;
    double t_star;
    if (ArrivalEndsChatter(*te, previous, cycle, &t_star)) {
      cycle->clearance = clearance_;
      status = StickAndRelease(*te, t_star, cycle);
      if (status != StickingMapStatus::kOk) return status;
      next->resize(m);
      *next << WithoutIndex(x_, c_), WithoutIndex(v_, c_), t_;
      if (with_jacobian_) {
        jacobian->resize(m, m);
        *jacobian << HeldRows(dy_), dt_;
      }
      return StickingMapStatus::kOk;
    }
    previous = *te;
  }
  return StickingMapStatus::kNoChatter;
}

std::optional<double> StickingMap::Cycle::NextImpact(bool from_release, StickingMapStatus* status) {
  const System& system = hybrid_.GetSystem();
  const LinearFlow& flow = hybrid_.FreeFlow();
  const Eigen::VectorXd z0 = flow.Transient(t_, x_, v_);
  Signal gap = flow.Output(hybrid_.Gap(0), t_, z0);
  const Stop& stop = hybrid_.GetStop(0);
  gap.AnchorAt(stop.GapOf(x_), stop.SpeedTowards(v_(c_)));
  // At a release the gap leaves 0 with zero speed and acceleration. Off
  // the release surface (a Newton iterate) a pressing force would turn that
  // tangency into a spurious impact at t0; searching from a short time later
  // keeps the map smooth there, and a gap still closed then means the state
  // is no release.
  double begin = t_;
  if (from_release) {
    begin = t_ + kReleaseClearance * hybrid_.TimeScale();
    if (gap.Value(begin) >= 0) {
      *status = StickingMapStatus::kNotReleased;
      return std::nullopt;
    }
  }
  const double scale = GapLengthScale(hybrid_, 0, x_, v_, gap);
  const std::optional<double> te =
      FirstUpcrossing(gap, begin, deadline_, ArrivalSearch(events_, scale));
  if (!te) {
    *status = from_release ? StickingMapStatus::kNoImpact : StickingMapStatus::kNoChatter;
    return std::nullopt;
  }
  if (with_contacts_) clearance_ = std::min(clearance_, FlightClearance(t_, z0, begin, *te));
  double value, slope;
  gap.ValueSlopeCurvature(*te, &value, &slope, &arrival_acceleration_);
  gap_scale_ = scale;
  const Eigen::VectorXd x0 = x_, v0 = v_;
  const double t0 = t_;
  flow.StateFrom(t0, x0, v0, z0, *te, &x_, &v_);
  x_(c_) = system.stops[0].position;
  t_ = *te;
  if (with_jacobian_) {
    ThroughFlight(flow.Transition(*te - t0), hybrid_.VectorField(t0, x0, v0),
                  hybrid_.VectorField(*te, x_, v_), Eigen::RowVectorXd::Unit(2 * n_, c_), v_(c_));
  }
  return te;
}

double StickingMap::Cycle::FlightClearance(double t0, const Eigen::VectorXd& z0, double begin,
                                           double end) const {
  const LinearFlow& flow = hybrid_.FreeFlow();
  const Signal velocity = flow.Output(contact_velocity_, t0, z0);
  double clearance = std::numeric_limits<double>::infinity();
  Eigen::VectorXd x, v;
  const Stop& stop = hybrid_.GetStop(0);
  for (const double t : SignChanges(velocity, begin, end, events_)) {
    // Only the turns towards the stop: maxima of x_c below an upper stop,
    // minima above a lower one.
    if (stop.Sign() * velocity.Derivative().Value(t) >= 0) continue;
    flow.State(t0, z0, t, &x, &v);
    clearance = std::min(clearance, stop.Sign() * (stop.Position() - x(c_)));
  }
  return clearance;
}

double StickingMap::Cycle::HoldMargin(const Signal& release, double begin, double end) const {
  const Signal slope = release.Derivative();
  double margin = std::numeric_limits<double>::infinity();
  for (const double t : SignChanges(slope, begin, end, events_)) {
    if (slope.Derivative().Value(t) < 0) margin = std::min(margin, -release.Value(t));
  }
  return margin;
}

/// The simulator's rules at an arrival (hybrid/chatter_rule.hpp): a landing
/// ends the chatter at once and is no impact; an impact is recorded and
/// reset, and the chatter ends where the rule says: at once, or at the end
/// of its tail by the chatter map, if the tail accumulates. True if it
/// ends, at *t_star.
bool StickingMap::Cycle::ArrivalEndsChatter(double te, double previous, StickingCycle* cycle,
                                            double* t_star) {
  const Stop& stop = hybrid_.GetStop(0);
  // The speed towards the stop (on either side of the mass), at least 0:
  // the search places the crossing to rounding, where it may have the
  // other sign.
  const double speed = std::max(stop.SpeedTowards(v_(c_)), 0.0);
  v_(c_) = stop.Sign() * speed;
  *t_star = te;
  if (rule_.IsLanding(speed, arrival_acceleration_, gap_scale_)) {
    stop.Absorb(v_);
    if (with_jacobian_) dy_ = stop.AbsorbJacobian(n_) * dy_;
    return true;
  }
  cycle->impacts.push_back({te, speed});
  stop.Reset(v_);
  if (with_jacobian_) dy_ = stop.ResetJacobian(n_) * dy_;
  double jerk;
  Eigen::VectorXd force(n_), acceleration(n_);
  // Towards the stop, as the simulator has it.
  const double a =
      stop.Sign() * hybrid_.ContactAcceleration(0, te, x_, v_, &jerk, &force, &acceleration);
  const double rebound = -stop.SpeedTowards(v_(c_));
  const ChatterDecision decision = rule_.Decide(te, previous, rebound, a, gap_scale_);
  if (decision != ChatterDecision::kSumTail) return decision != ChatterDecision::kGoesOn;
  const LinearFlow& flow = hybrid_.StuckFlow(0);
  const Signal release = flow.Output(
      hybrid_.Release(0), te, flow.Transient(te, WithoutIndex(x_, c_), WithoutIndex(v_, c_)));
  const ChatterTail tail = rule_.SumTail(release, hybrid_.Free().Contact(0), te, rebound);
  *t_star = tail.end;
  return tail.accumulates;
}

/// From the impact at te that ends the chatter, the stuck flow: through
/// the chatter's tail to its end t*, then stuck to the release.
StickingMapStatus StickingMap::Cycle::StickAndRelease(double te, double t_star,
                                                      StickingCycle* cycle) {
  const System& system = hybrid_.GetSystem();
  const LinearFlow& flow = hybrid_.StuckFlow(0);
  const Eigen::VectorXd x0 = WithoutIndex(x_, c_), v0 = WithoutIndex(v_, c_);
  const Eigen::VectorXd z0 = flow.Transient(te, x0, v0);
  Eigen::VectorXd x1, v1;
  flow.StateFrom(te, x0, v0, z0, t_star, &x1, &v1);
  cycle->accumulation = t_star;
  cycle->contact_force = hybrid_.ContactForce(0, t_star, x1, v1);
  if (!Stop::Holds(cycle->contact_force)) return StickingMapStatus::kNoSticking;
  const Signal release = flow.Output(hybrid_.Release(0), te, z0);
  const std::optional<double> tr = FirstUpcrossing(
      release, t_star, t_star + options_.max_stuck_periods * system.ForcingPeriod(), events_);
  if (!tr) return StickingMapStatus::kNoRelease;
  if (with_contacts_) cycle->hold_margin = HoldMargin(release, t_star, *tr);
  flow.StateFrom(te, x0, v0, z0, *tr, &x1, &v1);
  if (with_jacobian_) {
    double value, slope;
    release.ValueAndSlope(*tr, &value, &slope);
    dy_ = HeldRows(dy_);
    const Mode& stuck = hybrid_.Holding(StopBit(0));
    ThroughFlight(flow.Transition(*tr - te), stuck.VectorField(te, x0, v0),
                  stuck.VectorField(*tr, x1, v1), release_gradient_, slope);
  }
  x_ = EmbedAtStop(x1, c_, system.stops[0].position);
  v_ = EmbedAtStop(v1, c_, 0.0);
  t_ = *tr;
  cycle->next_release = *tr;
  return StickingMapStatus::kOk;
}

void StickingMap::Cycle::ThroughFlight(const Eigen::MatrixXd& transition, const Eigen::VectorXd& f0,
                                       const Eigen::VectorXd& f1,
                                       const Eigen::RowVectorXd& gradient, double slope) {
  EventDerivatives d = ThroughEvent(transition * (dy_ - f0 * dt_), gradient, slope, f1);
  dy_ = std::move(d.state);
  dt_ = std::move(d.time);
}

Eigen::MatrixXd StickingMap::Cycle::HeldRows(const Eigen::MatrixXd& full) const {
  if (full.rows() != 2 * n_) return full;  // already the held mode's
  Eigen::MatrixXd rows(2 * (n_ - 1), full.cols());
  rows << WithoutRow(full.topRows(n_), c_), WithoutRow(full.bottomRows(n_), c_);
  return rows;
}

StickingMap::StickingMap(const System& system, const StickingMapOptions& options)
    : StickingMap(std::make_shared<const HybridSystem>(system), options) {}

StickingMap::StickingMap(std::shared_ptr<const HybridSystem> hybrid,
                         const StickingMapOptions& options)
    : hybrid_(std::move(hybrid)), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw InvalidInput(error);
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
  for (int i = 0; i < k; ++i) {
    StickingCycle record;
    result.status = cycle.Run(result.state, &next, &step_jacobian, &record);
    if (result.status != StickingMapStatus::kOk) {
      result.jacobian.resize(0, 0);
      return result;
    }
    result.state = next;
    if (with_jacobian) result.jacobian = step_jacobian * result.jacobian;
    result.cycles.push_back(std::move(record));
    ++result.cycles_done;
  }
  return result;
}

Eigen::MatrixXd StickingMap::FiniteDifferenceJacobian(const Eigen::VectorXd& s, int k,
                                                      double relative_step) const {
  Eigen::MatrixXd jacobian(Size(), Size());
  for (int j = 0; j < Size(); ++j) {
    // t is an absolute time: its natural scale is the forcing period.
    const double scale =
        j == TimeIndex() ? GetSystem().ForcingPeriod() : std::max(1.0, std::abs(s(j)));
    const double h = relative_step * scale;
    Eigen::VectorXd plus = s, minus = s;
    plus(j) += h;
    minus(j) -= h;
    const StickingMapResult forward = Apply(plus, k, false), backward = Apply(minus, k, false);
    if (forward.status != StickingMapStatus::kOk || backward.status != StickingMapStatus::kOk) {
      return {};
    }
    jacobian.col(j) = (forward.state - backward.state) / (2.0 * h);
  }
  return jacobian;
}

HybridState StickingMap::ToState(const Eigen::VectorXd& s) const {
  const int held = GetSystem().Dof() - 1, c = GetSystem().stops[0].dof;
  HybridState state;
  state.t = s(TimeIndex());
  state.x = EmbedAtStop(s.head(held), c, GetSystem().stops[0].position);
  state.v = EmbedAtStop(s.segment(held, held), c, 0.0);
  return state;
}

double StickingMap::ContactForce(const Eigen::VectorXd& s) const {
  const int held = GetSystem().Dof() - 1;
  return hybrid_->ContactForce(0, s(TimeIndex()), s.head(held), s.segment(held, held));
}

Eigen::RowVectorXd StickingMap::ContactForceGradient(const Eigen::VectorXd& s) const {
  const Mode& held = hybrid_->Holding(StopBit(0));
  const LinearOutput force =
      hybrid_->GetStop(0).ContactForce(GetSystem(), held.Moving(), held.HeldPositions());
  const double omega = GetSystem().omega;
  Eigen::RowVectorXd gradient(Size());
  gradient << force.wx, force.wv, -force.cos_amplitude * omega * std::sin(omega * s(TimeIndex()));
  return gradient;
}

}  // namespace impactkit
