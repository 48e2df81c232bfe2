#pragma once
/// \file seeded_orbit.hpp
/// The converged orbit P(p, q), or sticking orbit, that a steady simulation
/// from rest seeds, as several test files need them (a test fails at once
/// if the seed or the solve fails).

#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"

namespace impactkit::testing {

inline PeriodicOrbit SeededOrbit(const System& system, int p, int q) {
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system, 500);
  REQUIRE(seed.has_value());
  OrbitOptions options;
  options.p = p;
  options.q = q;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, seed->eta, options, &orbit).termination == Termination::kConverged);
  return orbit;
}

/// FindOrbit's options for a sticking orbit with one release per q = 1
/// period at the first stop, everything else at its default.
inline OrbitOptions OneRelease() {
  OrbitOptions options;
  options.releases = 1;
  return options;
}

/// The sticking orbit seeded by 200 periods from rest (periods up to 4).
inline PeriodicOrbit SeededStickingOrbit(const System& system) {
  const std::optional<StickingSeed> seed = SeedStickingFromSimulation(system, 200, 4);
  REQUIRE(seed);
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, seed->state, OrbitOptionsFor(*seed), &orbit).termination ==
          Termination::kConverged);
  return orbit;
}

/// The simulator's exact extrema of each coordinate over one steady period
/// (its interior turns found like events, recorders.hpp): the first whole
/// period after 300 from rest.
inline PeriodExtrema SteadyPeriodExtrema(const System& system) {
  HybridState state = RestState(system);
  const Simulator simulator(system);
  simulator.Run(state, 300 * system.ForcingPeriod());
  ExtremaRecorder extrema(system.ForcingPeriod());
  simulator.Run(state, 303 * system.ForcingPeriod(), extrema);
  const std::vector<PeriodExtrema> periods = extrema.CompletePeriods();
  REQUIRE(!periods.empty());
  return periods.front();
}

/// A stuck phase of a steady simulation as the simulator's recorders see
/// it: from its chatter's accumulation point (begin) to the release (end),
/// and the stop it was at: the first whole one in the two periods after
/// `periods` - 1 from rest.
struct SimulatedStuckPhase {
  StickingInterval interval;
  int stop = 0;
};

inline SimulatedStuckPhase SimulateStuckPhase(const System& system, int periods) {
  const double period = system.ForcingPeriod();
  HybridState state = RestState(system);
  const Simulator simulator(system);
  simulator.Run(state, (periods - 1) * period);
  struct Releases : Observer {
    void OnRelease(const Release& release) override { stops.push_back(release.stop); }
    std::vector<int> stops;
  } releases;
  ChatterRecorder chatter;
  StickingRecorder sticking;
  ObserverList all;
  all.Add(chatter);
  all.Add(sticking);
  all.Add(releases);
  simulator.Run(state, (periods + 1) * period, all);
  REQUIRE(!chatter.EndTimes().empty());
  REQUIRE(sticking.Intervals().size() >= 2);
  // The window may open during a stuck phase: the first whole one is the second.
  const StickingInterval stuck = sticking.Intervals()[1];
  REQUIRE(std::find(chatter.EndTimes().begin(), chatter.EndTimes().end(), stuck.begin) !=
          chatter.EndTimes().end());
  REQUIRE(releases.stops.size() >= 2);
  return {stuck, releases.stops[1]};
}

}  // namespace impactkit::testing
