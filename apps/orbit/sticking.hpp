#pragma once
/// \file orbit/sticking.hpp
/// `impactkit orbit` for sticking motions: a sticking steady state (or a
/// release-state guess with --sticking) refined into a sticking orbit
/// P(∞, q) of the release map (impactkit/orbits/sticking_orbit.hpp).

#include <string>

#include "common/sticking_seed.hpp"
#include "common/system_options.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::cli {

/// Refines the seed and prints the orbit: the impacts before each
/// accumulation faster than `min_speed`, and with `check_jacobian` the
/// analytic Jacobian's distance from finite differences. Writes it to
/// `json` if not empty, with the provenance of a run of the system that
/// `source` names. Throws std::runtime_error if Newton does not converge.
void RunStickingOrbit(const System& system, const StickingSeed& seed, double min_speed,
                      bool check_jacobian, const std::string& json, const SystemOptions& source);

}  // namespace impactkit::cli
