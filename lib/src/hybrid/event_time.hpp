#pragma once
/// \file event_time.hpp (private)
/// How the state and the time at an event depend on what the flight to it
/// started from, when the event is where a witness w(y) crosses 0: the one
/// event-time correction (saltation) of the impact map, the release map,
/// the fixed-time orbit equations and the grazing limit.
///
/// A flight from (t0, y0), both depending on p, has at a fixed time t1
///
///     G = ∂y(t1)/∂p = Φ (dy0/dp − f0 dt0/dp),   Φ = e^{S (t1 − t0)},
///
/// f0 the vector field at its start (moving the start moves the whole
/// flight). With l = ∂w/∂y, ẇ the witness's slope at the event and f1 the
/// vector field there:
///
///     dt1/dp = −l G / ẇ,   dy1/dp = G + f1 dt1/dp.

#include <Eigen/Dense>

namespace impactkit {

struct EventDerivatives {
  Eigen::MatrixXd state;    ///< dy1/dp
  Eigen::RowVectorXd time;  ///< dt1/dp
};

inline Eigen::MatrixXd AtFixedTime(const Eigen::MatrixXd& transition, const Eigen::MatrixXd& start,
                                   const Eigen::RowVectorXd& start_time,
                                   const Eigen::VectorXd& start_field) {
  return transition * (start - start_field * start_time);
}

inline EventDerivatives ThroughEvent(const Eigen::MatrixXd& g, const Eigen::RowVectorXd& gradient,
                                     double slope, const Eigen::VectorXd& field) {
  EventDerivatives d;
  d.time = -(gradient * g) / slope;
  d.state = g + field * d.time;
  return d;
}

/// The saltation matrix of an event with reset Jacobian `reset`: how a
/// perturbation of the state at the event's time, just before it, is
/// carried to just after it at that same time,
///
///     S = R (I − f⁻ l / ẇ) + f⁺ l / ẇ = R + (f⁺ − R f⁻) l / ẇ,
///
/// f⁻ and f⁺ the vector fields before and after: ThroughEvent to the
/// perturbed event, the reset, and AtFixedTime back on the flow after it.
inline Eigen::MatrixXd Saltation(const Eigen::MatrixXd& reset, const Eigen::RowVectorXd& gradient,
                                 double slope, const Eigen::VectorXd& before,
                                 const Eigen::VectorXd& after) {
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(reset.rows(), reset.cols());
  const EventDerivatives event = ThroughEvent(identity, gradient, slope, before);
  return AtFixedTime(identity, reset * event.state, event.time, after);
}

}  // namespace impactkit
