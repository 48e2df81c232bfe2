#pragma once
/// \file stuck_subsystem.hpp (private)
/// The equations of the masses that move while a set H of stops holds
/// theirs: rows and columns of the held DOFs removed, their coupling to the
/// held positions becoming a constant force,
///
///     M' x'' + C' x' + K' x = A' cos(Ω t) − K_{·H} xs_H.
///
/// A rigid stop holds its mass at xs: this is the held phase of the stop's
/// law (hybrid/stop.hpp), beside it. The held modes (hybrid/mode.hpp) and
/// their flows (hybrid/system_flows.hpp) are built from this one place.

#include <Eigen/Dense>
#include <vector>

#include "impactkit/model/system.hpp"

namespace impactkit::detail {

struct StuckSubsystem {
  Eigen::MatrixXd mass, damping, stiffness;
  Eigen::VectorXd forcing;
  Eigen::VectorXd constant_force;  ///< −K_{·H} xs_H on the moving DOFs
};

/// The DOFs that move while the stops in `held` hold theirs, in order.
std::vector<int> MovingDofs(const System& system, StopSet held);

StuckSubsystem StuckSubsystemOf(const System& system, StopSet held);

}  // namespace impactkit::detail
