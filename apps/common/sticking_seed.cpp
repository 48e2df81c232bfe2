#include "common/sticking_seed.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "common/limits.hpp"

namespace impactkit::cli {

void AddStickingSeedOptions(CLI::App& command, StickingSeedOptions& options,
                            const std::string& group) {
  command
      .add_flag("--sticking", options.sticking,
                "Start from a sticking orbit P(inf,q): from the steady simulation, or from "
                "--guess (a release state: x and v of the other masses, then t) with --q")
      ->group(group);
  command
      .add_option("--releases", options.releases,
                  "With --sticking --guess: sticking phases per orbit")
      ->type_name("K")
      ->check(CLI::Range(1, static_cast<int>(kMaxOrbitPeriod)))
      ->capture_default_str()
      ->group(group);
}

std::optional<StickingSeed> ChooseStickingSeed(const System& system, const OrbitSeedOptions& seed,
                                               const StickingSeedOptions& request) {
  if (!request.sticking) {
    if (seed.p || seed.q || !seed.guess.empty()) return std::nullopt;
    return SeedStickingFromSimulation(system, seed.transient);
  }
  if (seed.p) throw InvalidInput("--sticking orbits have no --p (the chatter has no end count)");
  const int stop = GuessStop(system, seed);
  if (!seed.guess.empty()) {
    if (!seed.q) throw InvalidInput("--sticking --guess needs --q");
    return StickingSeed{stop, request.releases, *seed.q,
                        Eigen::Map<const Eigen::VectorXd>(
                            seed.guess.data(), static_cast<Eigen::Index>(seed.guess.size()))};
  }
  std::optional<StickingSeed> found = SeedStickingFromSimulation(system, seed.transient);
  if (!found) {
    throw std::runtime_error(
        "the simulated motion does not stick periodically: no sticking orbit to refine");
  }
  return found;
}

PeriodicOrbit FindAnyStartOrbit(const System& system, const OrbitSeedOptions& seed,
                                const StickingSeedOptions& sticking, OrbitOptions* orbit_options) {
  if (const std::optional<StickingSeed> found = ChooseStickingSeed(system, seed, sticking)) {
    *orbit_options = OrbitOptionsFor(*found);
    return RefineStickingOrbit(system, *found);
  }
  return FindStartOrbit(system, seed, orbit_options);
}

PeriodicOrbit RefineStickingOrbit(const System& system, const StickingSeed& seed,
                                  OrbitSummary* summary) {
  const OrbitOptions options = OrbitOptionsFor(seed);
  PeriodicOrbit orbit;
  const OrbitSummary result = FindOrbit(system, seed.state, options, &orbit);
  if (result.termination != Termination::kConverged) {
    throw std::runtime_error(
        fmt::format("no sticking P(inf,{}) orbit found: {}", options.q, result.BriefReport()));
  }
  if (summary) *summary = result;
  return orbit;
}

}  // namespace impactkit::cli
