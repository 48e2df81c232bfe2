#pragma once
/// \file orbit_seed.hpp
/// A starting point for FindOrbit (orbit.hpp) from a steady simulation: the
/// last impact of the recorded window, with the period the window showed.

#include <Eigen/Dense>
#include <optional>

#include "impactkit/analysis/periodicity.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

struct OrbitSeed {
  MotionPeriod motion;  ///< what the recorded window showed (periodic? P(p, q)? sticking?)
  Eigen::VectorXd eta;  ///< the last impact of the recorded window
  int stop = 0;         ///< the stop it is at: the section of its orbit (ImpactMapOptions::stop)
};

/// Simulates `transient` periods from rest, then 2 max_q + 1 more, and
/// returns the last impact state with the motion found; nothing if the
/// recorded window has no impact.
std::optional<OrbitSeed> SeedFromSimulation(const System& system, int transient = 500,
                                            int max_q = 32);

}  // namespace impactkit
