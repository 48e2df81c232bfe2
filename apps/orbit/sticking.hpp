#pragma once
/// \file orbit/sticking.hpp
/// `impactkit orbit` for sticking motions: a sticking steady state (or a
/// release-state guess with --sticking) refined into a sticking orbit
/// P(∞, q) of the release map (impactkit/orbits/sticking_orbit.hpp).

#include <Eigen/Dense>
#include <optional>
#include <string>

#include "common/orbit_seed.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::cli {

struct StickingRequest {
  bool sticking = false;    ///< --sticking: the motion must be a sticking one
  int releases = 1;         ///< --releases: sticking phases per orbit, with --guess
  double min_speed = 1e-3;  ///< --min-speed: impacts listed are faster than this
};

/// The seed of a sticking orbit: the --guess (with --sticking, --q and
/// --releases) or the releases of the steady simulation. Nothing when the
/// simulated motion does not stick periodically and --sticking was not
/// given (the impact map's turn); throws InvalidInput for inconsistent flags
/// and std::runtime_error when --sticking asks for what the motion lacks.
std::optional<StickingSeed> ChooseStickingSeed(const System& system, const OrbitSeedOptions& seed,
                                               const StickingRequest& request);

/// Refines the seed, prints the orbit (with the analytic Jacobian's distance
/// from finite differences if `check_jacobian`), and writes it to `json` if
/// not empty. Throws std::runtime_error if Newton does not converge.
void RunStickingOrbit(const System& system, const StickingSeed& seed,
                      const StickingRequest& request, bool check_jacobian, const std::string& json);

}  // namespace impactkit::cli
