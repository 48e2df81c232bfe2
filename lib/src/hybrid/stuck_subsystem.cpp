#include "hybrid/stuck_subsystem.hpp"

namespace impactkit {
namespace detail {

std::vector<int> MovingDofs(const System& s, StopSet held) {
  std::vector<int> moving;
  for (int i = 0; i < s.Dof(); ++i) {
    bool is_held = false;
    for (int k = 0; k < s.StopCount(); ++k) {
      is_held = is_held || ((held & StopBit(k)) != 0 && s.stops[k].dof == i);
    }
    if (!is_held) moving.push_back(i);
  }
  return moving;
}

StuckSubsystem StuckSubsystemOf(const System& s, StopSet held) {
  const std::vector<int> moving = MovingDofs(s, held);
  Eigen::VectorXd held_positions = Eigen::VectorXd::Zero(s.Dof());
  for (int k = 0; k < s.StopCount(); ++k) {
    if ((held & StopBit(k)) != 0) held_positions(s.stops[k].dof) = s.stops[k].position;
  }
  return {s.mass(moving, moving), s.damping(moving, moving), s.stiffness(moving, moving),
          s.forcing(moving), -(s.stiffness(moving, Eigen::all) * held_positions)};
}

}  // namespace detail
}  // namespace impactkit
