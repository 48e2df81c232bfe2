#pragma once
/// \file sticking_seed.hpp
/// A starting point for a sticking orbit (FindOrbit on the release section,
/// orbits/sticking_orbit.hpp) from a
/// steady simulation: the last release of the recorded window, with the
/// number of releases and forcing periods after which the releases repeat.

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit {

struct StickingSeed {
  int stop = 0;           ///< the stop released from (System::stops), the section's
  int releases = 0;       ///< k: releases per repetition, from any stop
  int q = 0;              ///< forcing periods per repetition
  Eigen::VectorXd state;  ///< the last release of the window, a section state of sticking_map.hpp
};

/// Records, at every release after a stuck segment, the stop and the
/// section state there (x, v without that stop's DOF, t): the releases of
/// a window from which a sticking orbit is seeded.
class ReleaseRecorder : public Observer {
 public:
  explicit ReleaseRecorder(const System& system) : system_(system) {}
  void OnSegment(const Segment& segment) override;
  void OnRelease(const Release& release) override;

  /// The window's last release with the least (k, q) for which the release
  /// k releases earlier (counting every stop's) is from the same stop and
  /// the same state q forcing periods (of length `period`) before, q <=
  /// max_q, to 1e-6 relative; nothing if there is none.
  std::optional<StickingSeed> Seed(double period, int max_q) const;

 private:
  struct Recorded {
    int stop;
    Eigen::VectorXd state;
  };
  const System& system_;
  Eigen::VectorXd x_, v_;
  double stuck_end_ = -1.0;
  std::vector<Recorded> releases_;
};

/// Simulates `transient` periods from rest, then 2 max_q + 1 more, and
/// returns ReleaseRecorder::Seed of that window. Throws InvalidInput for
/// transient < 0, max_q < 1 or invalid options.
std::optional<StickingSeed> SeedStickingFromSimulation(const System& system, int transient = 500,
                                                       int max_q = 32,
                                                       const SimulationOptions& options = {});

/// The options FindOrbit needs from a seed: the release section at its
/// stop, its releases and q; everything else at its default.
OrbitOptions OrbitOptionsFor(const StickingSeed& seed);

}  // namespace impactkit
