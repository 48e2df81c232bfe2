#pragma once
/// \file stuck_subsystem.hpp (private)
/// The equations of the masses that move while a set H of stops holds
/// theirs: rows and columns of the held DOFs removed, their coupling to the
/// held positions becoming a constant force,
///
///     M' x'' + C' x' + K' x = A' cos(Ω t) − K_{·H} xs_H.
///
/// Validation and the hybrid system build their held flows from this one
/// place (dynamics/held_flow.hpp).

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
