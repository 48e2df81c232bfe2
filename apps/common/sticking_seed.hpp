#pragma once
/// \file common/sticking_seed.hpp
/// The flags that choose a starting sticking orbit, shared by `orbit` and
/// `continue`: --sticking and --releases beside the orbit-seed flags (a
/// release-state --guess, --q, --transient).

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "common/orbit_seed.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::cli {

struct StickingSeedOptions {
  bool sticking = false;  ///< --sticking: the start must be a sticking orbit
  int releases = 1;       ///< --releases: sticking phases per orbit, with --guess
};

/// Adds --sticking and --releases in `group`.
void AddStickingSeedOptions(CLI::App& command, StickingSeedOptions& options,
                            const std::string& group);

/// The seed of a sticking orbit: the --guess (with --sticking, --q and
/// --releases) or the releases of the steady simulation. Nothing when the
/// simulated motion does not stick periodically and --sticking was not
/// given (the impact map's turn); throws InvalidInput for inconsistent flags
/// and std::runtime_error when --sticking asks for what the motion lacks.
std::optional<StickingSeed> ChooseStickingSeed(const System& system, const OrbitSeedOptions& seed,
                                               const StickingSeedOptions& request);

/// The start orbit of `continue` and `diagram`: the sticking orbit where the
/// simulated motion sticks (or --sticking asks for one), else the impacting
/// one of FindStartOrbit; its options in *orbit_options.
PeriodicOrbit FindAnyStartOrbit(const System& system, const OrbitSeedOptions& seed,
                                const StickingSeedOptions& sticking, OrbitOptions* orbit_options);

/// FindOrbit from the seed; throws std::runtime_error if it fails.
PeriodicOrbit RefineStickingOrbit(const System& system, const StickingSeed& seed,
                                  OrbitSummary* summary = nullptr);

}  // namespace impactkit::cli
