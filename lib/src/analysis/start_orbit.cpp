#include "impactkit/analysis/start_orbit.hpp"

#include <fmt/format.h>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/sticking_seed.hpp"

namespace impactkit {
namespace {

bool AsksForSticking(const StartOrbitRequest& request) {
  return request.releases.has_value() || request.kind == StartOrbitKind::kSticking;
}

void CheckRequest(const System& system, const StartOrbitRequest& request) {
  Require(request.transient >= 0, fmt::format("transient must be >= 0, got {}", request.transient));
  Require(!(request.p && request.releases),
          "give p (an impacting orbit) or releases (a sticking orbit, whose impacts are counted, "
          "not asked for), not both");
  Require(!(request.p && request.kind == StartOrbitKind::kSticking),
          "a sticking orbit has no p (the chatter has no end count)");
  Require(!(request.releases && request.kind == StartOrbitKind::kImpacting),
          "an impacting orbit has no releases");
  Require(!request.releases || *request.releases >= 1,
          fmt::format("releases must be >= 1, got {}", request.releases.value_or(0)));
  if (request.guess) {
    Require(request.stop >= 0 && request.stop < system.StopCount(),
            fmt::format("stop must be in [0, {}] (0-based), got {}", system.StopCount() - 1,
                        request.stop));
  } else if (!AsksForSticking(request)) {
    // A simulated motion's p belongs to its q: one of them alone names no orbit.
    Require(request.p.has_value() == request.q.has_value(),
            "p and q go together: give both, or neither to take them from the simulated motion");
  }
}

/// A seeded start on the section `sticking` names, at `stop`: the
/// request's solver settings, the counts yet to be set.
StartOrbit Seeded(const StartOrbitRequest& request, bool sticking, int stop) {
  StartOrbit start;
  start.seeded = true;
  start.options = request.solver;
  start.options.p = 1;
  start.options.releases = sticking ? 1 : 0;
  start.options.q = 1;
  (sticking ? start.options.release_map.stop : start.options.map.stop) = stop;
  return start;
}

/// The start where nothing was seeded: why, in FindOrbit's report.
StartOrbit NoSeed(std::string why) {
  StartOrbit start;
  start.summary.termination = Termination::kFailure;
  start.summary.message = std::move(why);
  return start;
}

/// The seed of a sticking orbit: the simulated motion's last release, with
/// the releases and q after which it repeats unless the request gives them.
std::optional<StartOrbit> SimulatedStickingSeed(const System& system,
                                                const StartOrbitRequest& request,
                                                Eigen::VectorXd* guess) {
  const std::optional<StickingSeed> seed = SeedStickingFromSimulation(system, request.transient);
  if (!seed) return std::nullopt;
  StartOrbit start = Seeded(request, true, seed->stop);
  start.options.releases = request.releases.value_or(seed->releases);
  start.options.q = request.q.value_or(seed->q);
  *guess = seed->state;
  return start;
}

/// The seed from a steady simulation (the request has no guess).
StartOrbit SimulatedSeed(const System& system, const StartOrbitRequest& request,
                         Eigen::VectorXd* guess) {
  if (AsksForSticking(request)) {
    if (std::optional<StartOrbit> found = SimulatedStickingSeed(system, request, guess)) {
      return *found;
    }
    return NoSeed("the simulated motion does not stick periodically: no sticking orbit to refine");
  }
  // The impacting seed first: its simulation says whether the motion
  // sticks, so a motion that does not is simulated once.
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system, request.transient);
  if (!seed) return NoSeed("the simulated motion has no impacts: no orbit to refine");
  if (!request.p && seed->motion.sticking && request.kind == StartOrbitKind::kAny) {
    if (std::optional<StartOrbit> found = SimulatedStickingSeed(system, request, guess)) {
      return *found;
    }
  }
  if (!request.p && (!seed->motion.periodic || seed->motion.sticking)) {
    return NoSeed(
        fmt::format("the simulated motion is {}; give p and q (and a guess) to look for an orbit",
                    seed->motion.sticking ? "sticking (an impact map orbit cannot stick)"
                                          : seed->motion.ToString()));
  }
  StartOrbit start = Seeded(request, false, seed->stop);
  start.options.p = request.p.value_or(static_cast<int>(seed->motion.p));
  start.options.q = request.q.value_or(seed->motion.q);
  *guess = seed->eta;
  return start;
}

}  // namespace

StartOrbit FindStartOrbit(const System& system, const StartOrbitRequest& request) {
  CheckRequest(system, request);
  Eigen::VectorXd guess;
  StartOrbit start;
  if (request.guess) {
    const bool sticking = AsksForSticking(request);
    start = Seeded(request, sticking, request.stop);
    if (sticking) start.options.releases = request.releases.value_or(1);
    start.options.p = request.p.value_or(1);
    start.options.q = request.q.value_or(1);
    guess = *request.guess;
  } else {
    start = SimulatedSeed(system, request, &guess);
    if (!start.seeded) return start;
  }
  start.summary = FindOrbit(system, guess, start.options, &start.orbit);
  return start;
}

}  // namespace impactkit
