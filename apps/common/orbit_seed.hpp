#pragma once
/// \file common/orbit_seed.hpp
/// The flags that choose a starting orbit, shared by `orbit`, `continue`,
/// `diagram` and `curve`: p and q (or --sticking and --releases), and
/// either a guess or a steady simulation. The rule that picks the orbit is
/// the library's (analysis/start_orbit.hpp).

#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/analysis/start_orbit.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::cli {

struct OrbitSeedOptions {
  std::optional<int> p, q;
  std::vector<double> guess;
  std::optional<int> stop;  ///< 1-based: the stop the guess's impact is at
  int transient = 500;
  std::string jacobian = "analytic";
  bool no_fallback = false;
};

struct StickingSeedOptions {
  bool sticking = false;  ///< --sticking: the start must be a sticking orbit
  int releases = 1;       ///< --releases: sticking phases per orbit, with --guess
};

/// Adds --p, --q, --guess, --stop, --transient, --jacobian, --no-fallback in `group`.
void AddOrbitSeedOptions(CLI::App& command, OrbitSeedOptions& options, const std::string& group);

/// Adds --sticking and --releases in `group`.
void AddStickingSeedOptions(CLI::App& command, StickingSeedOptions& options,
                            const std::string& group);

/// The library's request (analysis/start_orbit.hpp) from the flags: of
/// `kind`, or a sticking orbit where --sticking asks for one. Throws
/// InvalidInput for a --stop without --guess or one the system lacks.
StartOrbitRequest StartRequest(const System& system, const OrbitSeedOptions& seed,
                               const StickingSeedOptions& sticking, StartOrbitKind kind);

/// FindStartOrbit; throws std::runtime_error, with what to try, when no
/// orbit was seeded or found.
StartOrbit SolveStartOrbit(const System& system, const StartOrbitRequest& request);

}  // namespace impactkit::cli
