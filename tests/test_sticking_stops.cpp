// Sticking orbits at any stop of a system with several: the release map's
// section at the stop the motion sticks at, impacts at the others followed
// through the cycle, and what it cannot follow refused with the reason.
// Checked against the simulator's own stuck phases (a different code path:
// the hybrid run, not the release map and its Newton solve).

#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/sticking_map.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"
#include "seeded_orbit.hpp"

using namespace impactkit;
using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;

namespace {

/// The orbit's stick and release phases against the simulator's stuck
/// phase 300 periods from rest, at the same stop. The stick phase is the
/// chatter's predicted accumulation point on both sides, to 5e-8 (as in
/// test_sticking_orbit.cpp); the release, a root of the contact force, to
/// 1e-9.
void CheckAgainstSimulation(const System& system, const PeriodicOrbit& orbit) {
  const testing::SimulatedStuckPhase simulated = testing::SimulateStuckPhase(system, 300);
  CHECK(orbit.stop == simulated.stop);
  CHECK_THAT(orbit.stuck[0].stick_phase, WithinAbs(system.Phase(simulated.interval.begin), 5e-8));
  CHECK_THAT(orbit.stuck[0].release_phase, WithinAbs(system.Phase(simulated.interval.end), 1e-9));
}

/// examples/systems/paper-mass1-stop.toml: the paper's system at Ω = 0.2
/// with a lower stop under mass 1 at -0.45, inside its free swing (down to
/// -0.63), as stop 1 and the paper's stop as stop 2.
System PaperWithMass1Stop() {
  System system = PaperSystem(0.2);
  system.stops = {{0, StopSide::kLower, -0.45, 0.8}, system.stops[0]};
  Validate(system);
  return system;
}

}  // namespace

TEST_CASE("a sticking orbit at the second stop of a system: its section is that stop's",
          "[stops][sticking]") {
  // The paper's stop as stop 2, after one on mass 1 far below its motion:
  // nothing but the index changes, so the orbit is the paper system's.
  System system = PaperSystem(0.2);
  system.stops = {{0, StopSide::kLower, -10.0, 0.5}, system.stops[0]};
  Validate(system);
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  CHECK(orbit.stop == 1);
  CheckAgainstSimulation(system, orbit);
  CHECK_THAT(orbit.stuck[0].stick_phase, WithinAbs(30.464633012, 1e-8));  // docs/cli.md's sample
  CHECK_THAT(orbit.stuck[0].release_phase, WithinAbs(6.633818118, 1e-8));
  // A map at a stop the system lacks is refused.
  StickingMapOptions options;
  options.stop = 2;
  CHECK_THROWS_AS(StickingMap(system, options), InvalidInput);
  options.stop = -1;
  CHECK_THROWS_AS(StickingMap(system, options), InvalidInput);
}

TEST_CASE("a sticking orbit whose flights impact another stop: the simulator's impacts and phases",
          "[stops][sticking]") {
  // It sticks at mass 2's stop each period and mass 1 strikes its own
  // three times between releases.
  const System system = PaperWithMass1Stop();
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  REQUIRE(orbit.stop == 1);
  CheckAgainstSimulation(system, orbit);
  std::vector<OrbitImpact> at_mass_1;
  for (const OrbitImpact& impact : orbit.impacts) {
    if (impact.stop == 0) at_mass_1.push_back(impact);
  }
  // The simulator's impacts at stop 1 in one steady period, by phase.
  HybridState state = RestState(system);
  const Simulator simulator(system);
  simulator.Run(state, 300 * system.ForcingPeriod());
  ImpactRecorder impacts;
  simulator.Run(state, 301 * system.ForcingPeriod(), impacts);
  std::vector<Impact> simulated;
  for (const ImpactView impact : impacts.Impacts()) {
    if (impact.stop == 0) simulated.push_back(impact.Owned());
  }
  REQUIRE(simulated.size() == 3);
  REQUIRE(at_mass_1.size() == simulated.size());
  for (std::size_t i = 0; i < simulated.size(); ++i) {
    CHECK_THAT(system.Phase(at_mass_1[i].t), WithinAbs(simulated[i].phase, 1e-8));
    CHECK_THAT(at_mass_1[i].velocity, WithinAbs(simulated[i].velocity, 1e-8));
  }
  // The analytic Jacobian through those impacts' resets against central
  // differences of the map (steps 1e-6: their error ~1e-10 of its entries).
  StickingMapOptions options;
  options.stop = orbit.stop;
  const Eigen::MatrixXd fd = FiniteDifferenceJacobian(StickingMap(system, options), orbit.eta, 1);
  REQUIRE(fd.size() > 0);
  CHECK((orbit.jacobian - fd).cwiseAbs().maxCoeff() <=
        1e-6 * std::max(1.0, orbit.jacobian.cwiseAbs().maxCoeff()));
}

TEST_CASE("a sticking family at the second stop ends where simulation stops sticking there",
          "[stops][sticking][continuation]") {
  // paper-mass1-stop.toml's family continued in Ω from 0.2: its maps stay
  // at the start's stop, and where it ends (the chatter no longer ends in
  // sticking) the simulator from rest, independently, sticks at that stop
  // periodically 1e-3 below and not at all 1e-3 above.
  const System system = PaperWithMass1Stop();
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  ContinuationOptions options;
  options.lower = 0.1;
  options.upper = 0.6;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == BranchEnd::kNoSticking);
  for (const BranchPoint& point : branch.points) {
    CHECK(point.orbit.stop == 1);
    CHECK(point.orbit.residual < 1e-9);
  }
  const double omega_end = branch.special_points.back().point.parameter;
  auto at = [&](double omega) {
    System s = system;
    s.omega = omega;
    return SeedStickingFromSimulation(s, 300, 4);
  };
  const std::optional<StickingSeed> below = at(omega_end - 1e-3);
  REQUIRE(below);
  CHECK(below->stop == 1);
  CHECK(!at(omega_end + 1e-3));
}

TEST_CASE("a motion that sticks at both stops of a clearance is refused by the release map",
          "[stops][sticking]") {
  // Mass 2 in the clearance ±0.1 sticks at both stops every period at
  // Ω = 0.2 (test_several_stops.cpp): one cycle of the release map follows
  // one stop's sticking phase, so it says so instead of an orbit.
  System system = PaperSystem(0.2);
  system.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {1, StopSide::kLower, -0.1, 0.7}};
  Validate(system);
  const std::optional<StickingSeed> seed = SeedStickingFromSimulation(system, 200, 4);
  REQUIRE(seed);
  PeriodicOrbit orbit;
  const OrbitSummary summary = FindOrbit(system, seed->state, OrbitOptionsFor(*seed), &orbit);
  CHECK(summary.termination == Termination::kFailure);
  CHECK_THAT(summary.message, Contains("another stop holds a mass"));
}
