#pragma once
/// \file seeded_orbit.hpp
/// The converged orbit P(p, q) that a steady simulation from rest seeds, as
/// several test files need it (a test fails at once if it does not converge).

#include <catch2/catch.hpp>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/orbits/orbit.hpp"

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

}  // namespace impactkit::testing
