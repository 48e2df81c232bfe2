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

/// Continuation within paper-mass1-stop's sticking region, Ω in [0.12, 0.2].
ContinuationOptions StickingRegion(ContinuationDirection direction) {
  ContinuationOptions options;
  options.from = 0.12;
  options.to = 0.2;
  options.direction = direction;
  return options;
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
  options.from = 0.1;
  options.to = 0.6;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == Termination::kNoSticking);
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

namespace {

/// Every stuck phase the simulator begins and ends in the two periods
/// after `periods` - 1 from rest, as its releases report them: stop, start
/// and release (one under way at the window's start reports that start).
std::vector<Release> SimulatedReleases(const System& system, int periods) {
  const double period = system.ForcingPeriod();
  HybridState state = RestState(system);
  const Simulator simulator(system);
  simulator.Run(state, (periods - 1) * period);
  struct Releases : Observer {
    void OnRelease(const Release& release) override { all.push_back(release); }
    std::vector<Release> all;
  } releases;
  const double start = state.t;
  simulator.Run(state, (periods + 1) * period, releases);
  std::erase_if(releases.all, [&](const Release& r) { return r.t_begin <= start; });
  return releases.all;
}

/// Each of the orbit's stuck phases against the simulator's at the same
/// stop and phase 300 periods from rest: stick phase to 5e-8 (the chatter's
/// predicted accumulation point on both sides), release to 1e-9.
void CheckEveryStuckPhase(const System& system, const PeriodicOrbit& orbit) {
  const std::vector<Release> simulated = SimulatedReleases(system, 300);
  for (const StuckPhase& stuck : orbit.stuck) {
    const auto same = std::find_if(simulated.begin(), simulated.end(), [&](const Release& r) {
      return r.stop == stuck.stop &&
             std::abs(system.Phase(r.t_release) - stuck.release_phase) < 1e-6;
    });
    REQUIRE(same != simulated.end());
    CHECK_THAT(system.Phase(same->t_begin), WithinAbs(stuck.stick_phase, 5e-8));
    CHECK_THAT(system.Phase(same->t_release), WithinAbs(stuck.release_phase, 1e-9));
  }
}

}  // namespace

TEST_CASE("a mass that sticks at both stops of a clearance: one orbit of two releases",
          "[stops][sticking]") {
  SECTION("one mass (examples/systems/clearance-1dof.toml): the releases in closed form") {
    // x'' + c x' + x = cos Ωt between ±0.5: held at +0.5 the stop pushes
    // with Fs = cos Ωt − 0.5, released where it falls through 0 (Ωt = π/3);
    // at −0.5 with Fs = −(cos Ωt + 0.5), released at Ωt = 4π/3.
    const double omega = 0.2, pi = std::acos(-1.0);
    System system = UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Ones(1), omega, 0.5, 0.8);
    system.stops.push_back({0, StopSide::kLower, -0.5, 0.8});
    const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
    REQUIRE((orbit.releases == 2 && orbit.q == 1));
    REQUIRE(orbit.stuck.size() == 2);
    CHECK(orbit.stuck[0].stop != orbit.stuck[1].stop);
    for (const StuckPhase& stuck : orbit.stuck) {
      const double release = (stuck.stop == 0 ? 1.0 : 4.0) * pi / (3.0 * omega);
      CHECK_THAT(stuck.release_phase, WithinAbs(release, 1e-10));
    }
    CHECK(orbit.multipliers.size() == 0);  // 2N − 2 = 0: the section is a point per release
    CheckEveryStuckPhase(system, orbit);
  }
  SECTION("the paper's mass 2 in the clearance ±0.1: the simulator's phases, and the Jacobian") {
    System system = PaperSystem(0.2);
    system.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {1, StopSide::kLower, -0.1, 0.7}};
    Validate(system);
    const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
    REQUIRE((orbit.releases == 2 && orbit.q == 1));
    CHECK(orbit.stuck[0].stop != orbit.stuck[1].stop);
    CHECK(orbit.residual < 1e-11);
    CheckEveryStuckPhase(system, orbit);
    // The analytic Jacobian through both stops' stuck flows against central
    // differences of the map.
    StickingMapOptions map_options;
    map_options.stop = orbit.stop;
    const StickingMap map(system, map_options);
    const Eigen::MatrixXd fd = FiniteDifferenceJacobian(map, orbit.eta, 2);
    REQUIRE(fd.size() > 0);
    CHECK((orbit.jacobian - fd).cwiseAbs().maxCoeff() <
          1e-6 * orbit.jacobian.cwiseAbs().maxCoeff());
    // One release on, the mass leaves the other stop: P_R alone is no map
    // of this stop's section, as an impact map's impact at another stop.
    CHECK(map.Apply(orbit.eta, 1, false).termination == Termination::kOtherStop);
  }
}

TEST_CASE("masses that stick in turn at stops of their own: one orbit through both stuck flows",
          "[stops][sticking]") {
  // paper-mass1-stop.toml with mass 1's stop raised to -0.3: mass 1 is held
  // at it, then mass 2 at the paper's stop, each once per period. Between
  // the two the section's coordinates leave out another mass, and while
  // mass 1 is held mass 2 moves: its extent is measured on that stuck flow.
  System system = PaperWithMass1Stop();
  system.stops[0].position = -0.3;
  Validate(system);
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  REQUIRE((orbit.releases == 2 && orbit.q == 1));
  CHECK(orbit.stuck[0].stop != orbit.stuck[1].stop);
  CheckEveryStuckPhase(system, orbit);
  StickingMapOptions map_options;
  map_options.stop = orbit.stop;
  const Eigen::MatrixXd fd =
      FiniteDifferenceJacobian(StickingMap(system, map_options), orbit.eta, 2);
  REQUIRE(fd.size() > 0);
  CHECK((orbit.jacobian - fd).cwiseAbs().maxCoeff() < 1e-6 * orbit.jacobian.cwiseAbs().maxCoeff());
  // The section stop's mass's extent against the simulator's exact
  // extrema of a steady period.
  const PeriodExtrema period = testing::SteadyPeriodExtrema(system);
  const int dof = system.stops[orbit.stop].dof;
  CHECK_THAT(orbit.contacts.contact_max, WithinAbs(period.max(dof), 1e-9));
  CHECK_THAT(orbit.contacts.contact_min, WithinAbs(period.min(dof), 1e-9));
}

TEST_CASE(
    "a family that sticks at both stops of a clearance ends where the simulator stops sticking",
    "[stops][sticking][continuation]") {
  System system = UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Ones(1), 0.2, 0.5, 0.8);
  system.stops.push_back({0, StopSide::kLower, -0.5, 0.8});
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  ContinuationOptions options;
  options.from = 0.15;
  options.to = 0.6;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == Termination::kNoSticking);
  for (const BranchPoint& point : branch.points) {
    REQUIRE(point.orbit.stuck.size() == 2);
    CHECK(point.orbit.stuck[0].stop != point.orbit.stuck[1].stop);
  }
  const double omega_end = branch.special_points.back().point.parameter;
  auto sticks = [&](double omega) {
    System s = system;
    s.omega = omega;
    return SeedStickingFromSimulation(s, 300, 4).has_value();
  };
  CHECK(sticks(omega_end - 1e-3));
  CHECK(!sticks(omega_end + 1e-3));
}

TEST_CASE(
    "a sticking family ends where an impact at another stop appears, and both sides meet there",
    "[stops][sticking][continuation]") {
  // On paper-mass1-stop.toml the family from Ω = 0.2 (mass 2 sticking at
  // its stop, mass 1 hitting its own stop 3 times per period) ends, going
  // down, where mass 1's next turn reaches its stop (Ω ≈ 0.1901614). The
  // release map is continuous there: the grazing orbit's release state,
  // refined just below, is the sticking orbit with that impact more, it is
  // the one the simulator settles on there, and its own family, followed
  // back up, ends where that impact vanishes at the same Ω.
  const System system = PaperWithMass1Stop();
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  const ContinuationOptions options = StickingRegion(ContinuationDirection::kDecreasing);
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == Termination::kGrazing);
  const SpecialPoint& graze = branch.special_points.back();
  REQUIRE(graze.type == SpecialPointType::kGrazing);
  CHECK(graze.monitor < 1e-9);  // the new impact's clearance
  // Fixed-Ω solves 1e-5 either side (FindOrbit, not the march): mass 1's
  // impacts per period are 3 above and 4 below.
  auto impacts_at_mass_1 = [&](double omega) {
    System s = system;
    s.omega = omega;
    OrbitOptions on_family;
    on_family.releases = start.releases;
    on_family.q = start.q;
    on_family.release_map.stop = start.stop;
    PeriodicOrbit orbit;
    REQUIRE(FindOrbit(s, start.eta, on_family, &orbit).termination == Termination::kConverged);
    return std::count_if(orbit.impacts.begin(), orbit.impacts.end(),
                         [](const OrbitImpact& impact) { return impact.stop == 0; });
  };
  CHECK(impacts_at_mass_1(graze.parameter + 1e-5) == 3);
  CHECK(impacts_at_mass_1(graze.parameter - 1e-5) == 4);

  const std::vector<GrazingSeed> seeds = SeedsAtGrazing(system, branch, graze, options);
  REQUIRE(seeds.size() == 2);
  const GrazingSeed& below = seeds[0];
  REQUIRE(below.system.omega < graze.parameter);
  PeriodicOrbit past;
  REQUIRE(FindOrbit(below.system, below.eta, below.orbit, &past).termination ==
          Termination::kConverged);
  CHECK(past.p == graze.point.orbit.p + 1);
  const PeriodicOrbit simulated = testing::SeededStickingOrbit(below.system);
  CHECK(simulated.p == past.p);
  CHECK_THAT(past.stuck[0].stick_phase, WithinAbs(simulated.stuck[0].stick_phase, 1e-8));
  CHECK_THAT(past.stuck[0].release_phase, WithinAbs(simulated.stuck[0].release_phase, 1e-9));

  ContinuationOptions back = options;
  back.direction = ContinuationDirection::kIncreasing;
  const Branch returning = ContinueBranch({below.system, past, {}}, back);
  REQUIRE(returning.end == Termination::kGrazing);
  const SpecialPoint& vanishing = returning.special_points.back();
  REQUIRE(vanishing.vanishing_impact >= 0);
  const auto which = static_cast<std::size_t>(vanishing.vanishing_impact);
  CHECK(returning.points.back().orbit.impacts[which].stop == 0);
  CHECK(vanishing.monitor < 1e-5);  // its speed
  CHECK_THAT(vanishing.parameter, WithinAbs(graze.parameter, 1e-8));
}

TEST_CASE("a sticking family between two grazings has one period doubling, listed once",
          "[stops][sticking][continuation]") {
  // paper-mass1-stop's family through Ω = 0.148 runs between a new impact
  // of mass 1 (Ω ≈ 0.1448346) and one vanishing (Ω ≈ 0.1486756). Just above
  // its period doubling (Ω ≈ 0.148449) a multiplier passes through
  // infinity from −2.9 to −0.11: a sign change of det(D P + I) that no
  // multiplier −1 explains, and no second period doubling.
  System system = PaperWithMass1Stop();
  system.omega = 0.148;
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  const Branch branch =
      ContinueBranch({system, start, {}}, StickingRegion(ContinuationDirection::kBoth));
  CHECK(branch.begin == Termination::kGrazing);
  CHECK(branch.end == Termination::kGrazing);
  const auto doublings = std::count_if(
      branch.special_points.begin(), branch.special_points.end(),
      [](const SpecialPoint& s) { return s.type == SpecialPointType::kPeriodDoubling; });
  CHECK(doublings == 1);
  const auto [lowest, highest] = std::minmax_element(
      branch.points.begin(), branch.points.end(),
      [](const BranchPoint& a, const BranchPoint& b) { return a.parameter < b.parameter; });
  CHECK_THAT(lowest->parameter, WithinAbs(0.1448346, 1e-6));
  CHECK_THAT(highest->parameter, WithinAbs(0.1486756, 1e-6));
}
