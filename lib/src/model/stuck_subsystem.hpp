#pragma once
/// \file stuck_subsystem.hpp (private)
/// The equations of the other masses while the contact mass is held at the
/// stop: rows and columns of the contact DOF c removed, its coupling to
/// x_c = xs becoming a constant force,
///
///     M' x'' + C' x' + K' x = A' cos(Ω t) − K_{·c} xs.
///
/// Validation and the simulator build their stuck flow from this one place.

#include <Eigen/Dense>

#include "impactkit/model/system.hpp"

namespace impactkit::detail {

struct StuckSubsystem {
  Eigen::MatrixXd mass, damping, stiffness;
  Eigen::VectorXd forcing;
  Eigen::VectorXd constant_force;  ///< −K_{·c} xs without row c
};

StuckSubsystem StuckSubsystemOf(const System& system);

/// The message of a stuck subsystem that has no bounded steady response:
/// "stuck subsystem (mass 2 held at the stop): <why>".
std::string StuckSubsystemError(const System& system, const std::string& why);

}  // namespace impactkit::detail
