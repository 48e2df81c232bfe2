#include "impactkit/orbits/grazing_limit.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "hybrid/event_time.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"

namespace impactkit {
namespace {

/// S(u) = regular + d0 n / u at one contact: the saltation matrix as the
/// mass arrives at speed u, with its 1/u part split off. f⁺ − R f⁻ is
/// affine in u (the arrival velocity enters the vector field linearly), so
/// S(u) = A + B / u exactly, and two speeds give A and B = d0 n.
SpeedSplitMonodromy SplitSaltation(const HybridSystem& hybrid, const StopContact& at) {
  const Stop& stop = hybrid.GetStop(at.stop);
  const HybridState& contact = at.state;
  const int n = hybrid.GetSystem().Dof(), c = stop.Dof();
  const Eigen::MatrixXd reset = stop.ResetJacobian(n);
  Eigen::RowVectorXd normal = Eigen::RowVectorXd::Zero(2 * n);
  normal(c) = stop.Sign();  // the gap's gradient: its slope is the speed
  auto saltation = [&](double speed) {
    Eigen::VectorXd before = contact.v;
    before(c) = stop.Sign() * speed;
    Eigen::VectorXd after = before;
    stop.Reset(after);
    return Saltation(reset, normal, speed, hybrid.VectorField(contact.t, contact.x, before),
                     hybrid.VectorField(contact.t, contact.x, after));
  };
  const Eigen::MatrixXd at_1 = saltation(1.0), at_2 = saltation(2.0);
  const Eigen::MatrixXd singular = 2.0 * (at_1 - at_2);
  const Eigen::VectorXd jump = singular * normal.transpose();  // d0 (|n| = 1)
  return {at_1 - singular, jump, normal, Eigen::MatrixXd::Identity(2 * n, 2 * n), jump};
}

}  // namespace

Eigen::MatrixXd SpeedSplitMonodromy::At(double speed) const {
  return regular + singular * normal / speed;
}

double SpeedSplitMonodromy::GrazingLimit(double lambda) const {
  const Eigen::Index n = regular.rows();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n + 1, n + 1);
  k.topLeftCorner(n, n) = regular - lambda * Eigen::MatrixXd::Identity(n, n);
  k.topRightCorner(n, 1) = singular.normalized();
  k.bottomLeftCorner(1, n) = normal.normalized();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(k);
  const double least = svd.singularValues()(n);
  return k.partialPivLu().determinant() < 0 ? -least : least;
}

SpeedSplitMonodromy SplitMonodromy(const System& system, const std::vector<StopContact>& contacts,
                                   int q) {
  const double end = contacts.empty() ? 0.0 : contacts.front().state.t + q * system.ForcingPeriod();
  Require(
      !contacts.empty() && contacts.back().state.t < end,
      fmt::format("the contacts of an orbit's monodromy must lie within its q = {} forcing periods",
                  q));
  for (const StopContact& contact : contacts) {
    Require(contact.stop >= 0 && contact.stop < system.StopCount(),
            fmt::format("a contact's stop must be one of the system's {} stops (0 to {}), got {}",
                        system.StopCount(), system.StopCount() - 1, contact.stop));
  }
  const HybridSystem hybrid(system);
  const LinearFlow& flow = hybrid.FreeFlow();
  const SpeedSplitMonodromy split = SplitSaltation(hybrid, contacts.front());
  // G: the flights and the other impacts, from the split contact round.
  Eigen::MatrixXd rest = Eigen::MatrixXd::Identity(2 * system.Dof(), 2 * system.Dof());
  double t = contacts.front().state.t;
  for (std::size_t k = 1; k < contacts.size(); ++k) {
    const HybridState& state = contacts[k].state;
    const SpeedSplitMonodromy impact = SplitSaltation(hybrid, contacts[k]);
    // n · f⁻ = s v_c: the position part of n on the velocities.
    const double speed = impact.normal.head(system.Dof()).dot(state.v);
    rest = impact.At(speed) * flow.Transition(state.t - t) * rest;
    t = state.t;
  }
  rest = flow.Transition(end - t) * rest;
  return {rest * split.regular, rest * split.singular, split.normal, rest, split.jump};
}

StopContact ResponseTouch(const System& system, int stop_index) {
  Require(stop_index >= 0 && stop_index < system.StopCount(),
          fmt::format("the stop touched must be one of the system's {} stops (0 to {}), got {}",
                      system.StopCount(), system.StopCount() - 1, stop_index));
  const HybridSystem hybrid(system);
  const Stop& stop = hybrid.GetStop(stop_index);
  const LinearFlow& flow = hybrid.FreeFlow();
  // x_c(t) = a cos Ωt + b sin Ωt: the stop's side of it is largest at
  // Ωt = atan2(s b, s a).
  const double period = system.ForcingPeriod();
  HybridState touch;
  flow.SteadyState(0.0, &touch.x, &touch.v);
  const double a = stop.Sign() * touch.x(stop.Dof());
  flow.SteadyState(0.25 * period, &touch.x, &touch.v);
  const double b = stop.Sign() * touch.x(stop.Dof());
  touch.t = std::atan2(b, a) / (2.0 * std::numbers::pi) * period;
  flow.SteadyState(touch.t, &touch.x, &touch.v);
  return {touch, stop_index};
}

std::optional<std::vector<StopContact>> TouchContacts(const ImpactMap& map,
                                                      const Eigen::VectorXd& eta, int p, int q,
                                                      int flight, double t, int stop) {
  const MapResult path = map.Apply(eta, p, false);
  if (path.termination != Termination::kCompleted) return std::nullopt;
  // The impact that starts the flight, and its stop.
  const auto k0 = static_cast<std::size_t>(flight - 1);
  const Eigen::VectorXd& start = flight == 0 ? eta : path.path[k0];
  const int start_stop = flight == 0 ? map.SectionStop() : path.stops[k0];
  std::vector<StopContact> contacts = {{map.FlightState(start, t, start_stop), stop}};
  // The impacts after the touch, the orbit's first ones shifted a period on.
  const double shift = q * map.GetSystem().ForcingPeriod();
  for (int k = flight; k < flight + p; ++k) {
    const auto at = static_cast<std::size_t>(k % p);
    HybridState impact = map.ToState(path.path[at], path.stops[at]);
    if (k >= p) impact.t += shift;
    contacts.push_back({impact, path.stops[at]});
  }
  return contacts;
}

}  // namespace impactkit
