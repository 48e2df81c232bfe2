#pragma once
/// \file common/orbit_seed.hpp
/// The flags that choose a starting orbit, shared by `orbit` and
/// `continue` (and the starts of `paper`'s branches): p and q, and either a
/// guess or a steady simulation.

#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::cli {

struct OrbitSeedOptions {
  std::optional<int> p, q;
  std::vector<double> guess;
  std::optional<int> stop;  ///< 1-based: the stop the guess's impact is at
  int transient = 500;
  std::string jacobian = "analytic";
  bool no_fallback = false;
};

/// Adds --p, --q, --guess, --stop, --transient, --jacobian, --no-fallback in `group`.
void AddOrbitSeedOptions(CLI::App& command, OrbitSeedOptions& options, const std::string& group);

/// The orbit options and the seed η: the user's guess, or the last impact
/// of a steady simulation (whose P(p, q) is used unless p and q are given).
/// Throws InvalidInput for inconsistent flags, std::runtime_error when the
/// simulated motion offers no orbit.
OrbitOptions ChooseSeed(const System& system, const OrbitSeedOptions& options,
                        Eigen::VectorXd* eta);

/// The 0-based stop of a --guess: --stop K, or the first. Throws
/// InvalidInput for a --stop without --guess or one the system lacks.
int GuessStop(const System& system, const OrbitSeedOptions& options);

/// FindOrbit from the chosen seed; throws std::runtime_error if it fails.
PeriodicOrbit FindStartOrbit(const System& system, const OrbitSeedOptions& seed,
                             OrbitOptions* options, OrbitSummary* summary = nullptr);

}  // namespace impactkit::cli
