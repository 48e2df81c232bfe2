#pragma once
/// \file event_time.hpp (private)
/// How the state and the time at an event depend on what the flight to it
/// started from, when the event is where a witness w(y) crosses 0: the one
/// event-time correction (saltation) of the impact map, the release map and
/// the fixed-time orbit equations.
///
/// With G = ∂y(t1)/∂p at the event's time held fixed, l = ∂w/∂y, ẇ the
/// witness's slope at the event and f1 the vector field there:
///
///     dt1/dp = −l G / ẇ,   dy1/dp = G + f1 dt1/dp.

#include <Eigen/Dense>

namespace impactkit {

struct EventDerivatives {
  Eigen::MatrixXd state;    ///< dy1/dp
  Eigen::RowVectorXd time;  ///< dt1/dp
};

inline EventDerivatives ThroughEvent(const Eigen::MatrixXd& g, const Eigen::RowVectorXd& gradient,
                                     double slope, const Eigen::VectorXd& field) {
  EventDerivatives d;
  d.time = -(gradient * g) / slope;
  d.state = g + field * d.time;
  return d;
}

}  // namespace impactkit
