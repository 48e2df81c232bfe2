#pragma once
/// \file sticking_grazing.hpp
/// The sticking family of examples/systems/paper-mass1-stop.toml from
/// Ω = 0.2 followed down to its new contact at Ω ≈ 0.1901614: mass 2
/// sticks at its stop every period while mass 1 strikes its own three
/// times between releases, until a fourth turn of mass 1 touches its stop
/// (tests/test_sticking_stops.cpp).

#include <catch2/catch.hpp>

#include "impactkit/continuation/continuation.hpp"
#include "impactkit/io/system_file.hpp"
#include "seeded_orbit.hpp"

namespace impactkit::testing {

inline System PaperWithMass1StopFile() {
  return ReadSystemFile(IMPACTKIT_SOURCE_DIR "/examples/systems/paper-mass1-stop.toml");
}

/// The continuation from Ω = 0.2 down towards 0.18.
inline ContinuationOptions DownToNewContact() {
  ContinuationOptions options;
  options.from = 0.2;
  options.to = 0.18;
  options.direction = ContinuationDirection::kDecreasing;
  return options;
}

/// The family from Ω = 0.2, ended at its new contact.
inline Branch StickingBranchToNewContact(const System& system) {
  const Branch branch =
      ContinueBranch({system, SeededStickingOrbit(system), {}}, DownToNewContact());
  REQUIRE(branch.end == Termination::kGrazing);
  return branch;
}

}  // namespace impactkit::testing
