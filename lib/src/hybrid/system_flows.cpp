#include "impactkit/hybrid/system_flows.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <string>
#include <vector>

#include "hybrid/stuck_subsystem.hpp"

namespace impactkit {

LinearFlow HeldFlow(const System& s, StopSet held) {
  const detail::StuckSubsystem stuck = detail::StuckSubsystemOf(s, held);
  try {
    return LinearFlow(stuck.mass, stuck.damping, stuck.stiffness, stuck.forcing,
                      stuck.constant_force, s.omega);
  } catch (const InvalidInput& e) {
    std::vector<std::string> masses;
    for (int k = 0; k < s.StopCount(); ++k) {
      if ((held & StopBit(k)) != 0) masses.push_back(std::to_string(s.stops[k].dof + 1));
    }
    throw InvalidInput(fmt::format("stuck subsystem (mass {} held at {}): {}",
                                   fmt::join(masses, ", "),
                                   s.StopCount() == 1 ? "the stop" : "its stop", e.what()));
  }
}

void Validate(const System& s) {
  ValidateParameters(s);
  // Constructing the flows rejects an undamped resonance (no bounded
  // steady response): the same test the simulator relies on.
  LinearFlow(s.mass, s.damping, s.stiffness, s.forcing, Eigen::VectorXd::Zero(s.Dof()), s.omega);
  if (s.Dof() > 1) {
    for (int k = 0; k < s.StopCount(); ++k) HeldFlow(s, StopBit(k));
  }
}

}  // namespace impactkit
