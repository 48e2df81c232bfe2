#pragma once
/// \file seeded_orbit.hpp
/// The converged orbit P(p, q), or sticking orbit, that a steady simulation
/// from rest seeds, as several test files need them (a test fails at once
/// if the seed or the solve fails).

#include <catch2/catch.hpp>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
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

/// The sticking orbit seeded by 200 periods from rest (periods up to 4).
inline StickingOrbit SeededStickingOrbit(const System& system) {
  const std::optional<StickingSeed> seed = SeedStickingFromSimulation(system, 200, 4);
  REQUIRE(seed);
  StickingOrbitOptions options;
  options.releases = seed->releases;
  options.q = seed->q;
  StickingOrbit orbit;
  REQUIRE(FindStickingOrbit(system, seed->state, options, &orbit).termination ==
          Termination::kConverged);
  return orbit;
}

}  // namespace impactkit::testing
