#include "impactkit/orbits/impact_map.hpp"

#include <fmt/format.h>

#include <cmath>

#include "dynamics/subsystem.hpp"
#include "hybrid/event_time.hpp"
#include "hybrid/phase_events.hpp"

namespace impactkit {

bool ImpactMapOptions::IsValid(std::string* error) const {
  if (!(max_flight_periods > 0 && std::isfinite(max_flight_periods))) {
    if (error)
      *error = fmt::format("max_flight_periods must be finite and > 0, got {}", max_flight_periods);
    return false;
  }
  if (!simulation.IsValid(error)) return false;
  if (stop < 0) {
    if (error) *error = fmt::format("the map's section stop must be >= 0, got {}", stop);
    return false;
  }
  return true;
}

ImpactMap::ImpactMap(const System& system, const ImpactMapOptions& options)
    : ImpactMap(std::make_shared<const HybridSystem>(system), options) {}

ImpactMap::ImpactMap(std::shared_ptr<const HybridSystem> hybrid, const ImpactMapOptions& options)
    : hybrid_(std::move(hybrid)), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw InvalidInput(error);
  const int stops = hybrid_->StopCount();
  if (options_.stop >= stops) {
    throw InvalidInput(fmt::format("the map's section is stop {}, but the system has {} stop{}",
                                   options_.stop + 1, stops, stops == 1 ? "" : "s"));
  }
}

Eigen::VectorXd ImpactMap::ToEta(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                 int stop) const {
  const int n = GetSystem().Dof();
  Eigen::VectorXd eta(2 * n);
  eta << WithoutIndex(x, hybrid_->GetStop(stop).Dof()), t, v;
  return eta;
}

HybridState ImpactMap::ToState(const Eigen::VectorXd& eta, int stop) const {
  const int n = GetSystem().Dof();
  const Stop& at = hybrid_->GetStop(stop);
  HybridState state;
  state.t = eta(n - 1);
  state.x = EmbedAtStop(eta.head(n - 1), at.Dof(), at.Position());
  state.v = eta.tail(n);
  return state;
}

double ImpactMap::Speed(const Eigen::VectorXd& eta, int stop) const {
  const Stop& at = hybrid_->GetStop(stop);
  return at.SpeedTowards(eta(GetSystem().Dof() + at.Dof()));
}

void ImpactMap::ValidateEta(const Eigen::VectorXd& eta, int stop) const {
  const int n = GetSystem().Dof();
  const int c = hybrid_->GetStop(stop).Dof();
  if (eta.size() != 2 * n) {
    throw InvalidInput(
        fmt::format("an impact state eta = (x without x{}, t, v1..v{}) has {} entries, got {}",
                    c + 1, n, 2 * n, eta.size()));
  }
  if (!eta.allFinite()) throw InvalidInput("the impact state has a NaN or infinite entry");
  if (!(Speed(eta, stop) > 0)) {
    const bool upper = hybrid_->GetStop(stop).Sign() > 0;
    throw InvalidInput(
        fmt::format("not an impact state: v{} = {} must be {} 0 (the speed {} just "
                    "before impact)",
                    c + 1, eta(n + c), upper ? ">" : "<",
                    upper ? "towards the stop" : "down onto the lower stop"));
  }
}

Eigen::MatrixXd ImpactMap::Embedding(int stop) const {
  const int n = GetSystem().Dof(), c = hybrid_->GetStop(stop).Dof();
  Eigen::MatrixXd embedding = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  for (int j = 0, k = 0; j < n; ++j) {
    if (j != c) embedding(j, k++) = 1.0;
  }
  embedding.bottomRightCorner(n, n).setIdentity();
  return embedding;
}

HybridState ImpactMap::Departure(const Eigen::VectorXd& eta, int stop) const {
  HybridState after = ToState(eta, stop);
  hybrid_->GetStop(stop).Reset(after.v);
  return after;
}

Eigen::MatrixXd ImpactMap::FlightJacobian(int stop, const HybridState& departure, double t) const {
  const int n = GetSystem().Dof();
  return AtFixedTime(hybrid_->FreeFlow().Transition(t - departure.t),
                     hybrid_->GetStop(stop).ResetJacobian(n) * Embedding(stop),
                     Eigen::RowVectorXd::Unit(2 * n, TimeIndex()),
                     hybrid_->VectorField(departure.t, departure.x, departure.v));
}

Eigen::VectorXd ImpactMap::FlightTransient(const Eigen::VectorXd& eta, int stop) const {
  ValidateEta(eta, stop);
  const HybridState after = Departure(eta, stop);
  return hybrid_->FreeFlow().Transient(after.t, after.x, after.v);
}

HybridState ImpactMap::FlightState(const Eigen::VectorXd& eta, double t, int stop) const {
  const Eigen::VectorXd z0 = FlightTransient(eta, stop);
  HybridState state;
  state.t = t;
  hybrid_->FreeFlow().State(eta(TimeIndex()), z0, t, &state.x, &state.v);
  return state;
}

Signal ImpactMap::FlightCoordinate(const Eigen::VectorXd& eta, int dof, int stop) const {
  const int n = GetSystem().Dof();
  if (dof < 0 || dof >= n) {
    throw InvalidInput(fmt::format("coordinate index {} out of range 0..{}", dof, n - 1));
  }
  const Eigen::VectorXd z0 = FlightTransient(eta, stop);
  const LinearFlow& flow = hybrid_->FreeFlow();
  const PreparedOutput coordinate =
      flow.Prepare({Eigen::RowVectorXd::Unit(n, dof), Eigen::RowVectorXd::Zero(n), 0.0, 0.0});
  return flow.Output(coordinate, eta(TimeIndex()), z0);
}

std::optional<ImpactMap::FlightEnd> ImpactMap::FirstArrival(const Eigen::VectorXd& eta, int stop,
                                                            double t_end) const {
  ValidateEta(eta, stop);
  const LinearFlow& flow = hybrid_->FreeFlow();
  FlightEnd end;
  end.start = Departure(eta, stop);
  const Eigen::VectorXd z0 = flow.Transient(end.start.t, end.start.x, end.start.v);
  PhaseEvents events(*hybrid_, options_.simulation);
  events.Begin(hybrid_->Free(), end.start, z0);
  const std::optional<PhaseEvents::Event> found = events.First(t_end, stop);
  if (!found) return std::nullopt;
  end.stop = found->stop;
  const Stop& arrival = hybrid_->GetStop(end.stop);
  const int c = arrival.Dof();
  end.state.t = found->t;
  flow.StateFrom(end.start.t, end.start.x, end.start.v, z0, found->t, &end.state.x, &end.state.v);
  end.state.x(c) = arrival.Position();
  const double speed = arrival.SpeedTowards(end.state.v(c));
  // The simulator's rule: an arrival whose height is unresolved is a
  // landing there, so no impact here.
  double acceleration;
  end.impact = speed > 0 && !events.IsLanding(end.stop, found->t, speed, &acceleration);
  const Eigen::VectorXd f = hybrid_->VectorField(found->t, end.state.x, end.state.v);
  end.pressed = arrival.SpeedTowards(f(GetSystem().Dof() + c)) > 0;
  return end;
}

bool ImpactMap::Step(const Eigen::VectorXd& eta, int stop, Eigen::VectorXd* next, int* next_stop,
                     Eigen::MatrixXd* jacobian, Termination* status) const {
  const System& system = GetSystem();
  const double t = eta(TimeIndex());
  const std::optional<FlightEnd> end =
      FirstArrival(eta, stop, t + options_.max_flight_periods * system.ForcingPeriod());
  if (!end) {
    *status = Termination::kNoImpact;
    return false;
  }
  if (!end->impact) {
    *status = end->pressed ? Termination::kSticking : Termination::kGrazing;
    return false;
  }
  *next_stop = end->stop;
  const double te = end->state.t;
  const Eigen::VectorXd &x = end->state.x, &v = end->state.v;
  *next = ToEta(te, x, v, *next_stop);
  if (jacobian)
    *jacobian = ArrivalJacobian(FlightJacobian(stop, end->start, te), *next_stop, end->state);
  return true;
}

Eigen::MatrixXd ImpactMap::ArrivalJacobian(const Eigen::MatrixXd& g, int stop,
                                           const HybridState& arrival) const {
  const int n = GetSystem().Dof(), c = hybrid_->GetStop(stop).Dof();
  // The gap's gradient over its slope: x_c(t') = xs, the sign of the
  // stop's side cancels.
  const EventDerivatives d = ThroughEvent(g, Eigen::RowVectorXd::Unit(2 * n, c), arrival.v(c),
                                          hybrid_->VectorField(arrival.t, arrival.x, arrival.v));
  Eigen::MatrixXd jacobian(2 * n, g.cols());
  jacobian.topRows(n - 1) = WithoutRow(d.state.topRows(n), c);
  jacobian.row(n - 1) = d.time;
  jacobian.bottomRows(n) = d.state.bottomRows(n);
  return jacobian;
}

MapResult ImpactMap::Apply(const Eigen::VectorXd& eta, int p, bool with_jacobian) const {
  MapResult result = Follow(eta, SectionStop(), p, with_jacobian);
  if (result.termination == Termination::kCompleted && result.stops.back() != SectionStop()) {
    result.termination = Termination::kOtherStop;
    result.jacobian.resize(0, 0);
    result.step_jacobians.clear();
  }
  return result;
}

MapResult ImpactMap::Follow(const Eigen::VectorXd& eta, int stop, int p, bool with_jacobian) const {
  if (p < 1) throw InvalidInput(fmt::format("p (impacts per period) must be >= 1, got {}", p));
  if (stop < 0 || stop >= hybrid_->StopCount()) {
    throw InvalidInput(
        fmt::format("stop index {} out of range 0..{}", stop, hybrid_->StopCount() - 1));
  }
  ValidateEta(eta, stop);
  MapResult result;
  result.eta = eta;
  if (with_jacobian) result.jacobian = Eigen::MatrixXd::Identity(eta.size(), eta.size());
  const bool keep_steps =
      with_jacobian && p * eta.size() * eta.size() <= MapResult::kKeptStepEntries;
  Eigen::VectorXd next;
  Eigen::MatrixXd step_jacobian;
  for (int k = 0, at = stop; k < p; ++k) {
    int next_stop = at;
    if (!Step(result.eta, at, &next, &next_stop, with_jacobian ? &step_jacobian : nullptr,
              &result.termination)) {
      result.jacobian.resize(0, 0);
      result.step_jacobians.clear();
      return result;
    }
    result.eta = next;
    if (with_jacobian) {
      result.jacobian = step_jacobian * result.jacobian;
      if (keep_steps) result.step_jacobians.push_back(std::move(step_jacobian));
    }
    result.path.push_back(next);
    result.stops.push_back(next_stop);
    ++result.impacts_done;
    at = next_stop;
  }
  return result;
}

Eigen::VectorXd ImpactMap::ParameterDerivative(const Eigen::VectorXd& eta, int p,
                                               const ImpactMap& below, const ImpactMap& above,
                                               double delta,
                                               std::span<const SectionStep> steps) const {
  const int n = GetSystem().Dof();
  const bool reuse = static_cast<int>(steps.size()) == p;
  Eigen::VectorXd derivative = Eigen::VectorXd::Zero(2 * n);
  Eigen::VectorXd at = eta;
  int stop = SectionStop();
  for (int k = 0; k < p; ++k) {
    // The same step as Follow(eta, ..., p, true) took (re-following one
    // was 13 % of a connected diagram's CPU time).
    SectionStep followed;
    const SectionStep* step = reuse ? &steps[k] : &followed;
    if (!reuse) {
      MapResult one = Follow(at, stop, 1, true);
      if (one.termination != Termination::kCompleted) return {};
      followed = {std::move(one.eta), one.stops.back(), std::move(one.jacobian)};
    }
    const int next_stop = step->stop, c = hybrid_->GetStop(next_stop).Dof();
    const double stop_rate = (above.hybrid_->GetStop(next_stop).Position() -
                              below.hybrid_->GetStop(next_stop).Position()) /
                             delta;
    const double t = step->state(TimeIndex());
    const HybridState high = above.FlightState(at, t, stop), low = below.FlightState(at, t, stop);
    Eigen::VectorXd rate(2 * n);  // ∂y(t)/∂μ at fixed t
    rate << (high.x - low.x) / delta, (high.v - low.v) / delta;
    // x_c is no coordinate of η: what the event sees is its rate relative
    // to the moving stop.
    rate(c) -= stop_rate;
    derivative = step->jacobian * derivative +
                 ArrivalJacobian(rate, next_stop, ToState(step->state, next_stop));
    at = step->state;
    stop = next_stop;
  }
  if (stop != SectionStop()) return {};
  return derivative;
}

SectionImage ImpactMap::ParameterRate(const Eigen::VectorXd& eta, int p, const SectionMap& below,
                                      const SectionMap& above, double delta,
                                      const SectionImage* at_eta) const {
  std::span<const SectionStep> steps;
  if (at_eta) steps = at_eta->steps;
  SectionImage rate;
  rate.state = ParameterDerivative(eta, p, dynamic_cast<const ImpactMap&>(below),
                                   dynamic_cast<const ImpactMap&>(above), delta, steps);
  if (rate.state.size() == 0) rate.failure = "the map fails beside the parameter's value";
  return rate;
}

SectionImage ImpactMap::Iterate(const Eigen::VectorXd& eta, int p, bool with_jacobian) const {
  SectionImage image;
  if (eta.size() != Size() || !eta.allFinite() || !(Speed(eta, SectionStop()) > 0)) {
    image.failure = "not an impact state at the section's stop";
    return image;
  }
  MapResult result = Apply(eta, p, with_jacobian);
  if (result.termination != Termination::kCompleted) {
    image.failure = fmt::format("after {} of {} impacts, {}", result.impacts_done, p,
                                Describe(result.termination));
    return image;
  }
  image.state = std::move(result.eta);
  image.jacobian = std::move(result.jacobian);
  for (std::size_t k = 0; k < result.step_jacobians.size(); ++k) {
    image.steps.push_back(
        {std::move(result.path[k]), result.stops[k], std::move(result.step_jacobians[k])});
  }
  return image;
}

}  // namespace impactkit
