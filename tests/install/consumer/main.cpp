// Uses the installed impactkit: reads a system file through impactkit::io,
// checks it is the paper's system, and finds the paper's P(2,1) orbit at
// Ω = 0.6 through impactkit::impactkit.
//
//     consumer SYSTEM_FILE
//
// Prints one `impact PHASE VELOCITY` line per impact of the orbit, for the
// test to compare with the installed `impactkit orbit`.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/orbit.hpp"

int main(int argc, char** argv) {
  using namespace impactkit;
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer SYSTEM_FILE\n");
    return EXIT_FAILURE;
  }
  try {
    System system = ReadSystemFile(argv[1]);
    const System paper = PaperSystem();
    if (system.mass != paper.mass || system.damping != paper.damping ||
        system.stiffness != paper.stiffness || system.forcing != paper.forcing ||
        system.stops != paper.stops) {
      std::fprintf(stderr, "%s is not the paper's system:\n%s\n", argv[1],
                   SystemToJson(system).c_str());
      return EXIT_FAILURE;
    }
    SetParameter(system, "omega", 0.6);
    Validate(system);

    const std::optional<OrbitSeed> seed = SeedFromSimulation(system);
    if (!seed || !seed->motion.periodic) {
      std::fprintf(stderr, "no periodic motion at omega = 0.6\n");
      return EXIT_FAILURE;
    }
    OrbitOptions options;
    options.p = static_cast<int>(seed->motion.p);
    options.q = seed->motion.q;
    PeriodicOrbit orbit;
    const OrbitSummary summary = FindOrbit(system, seed->eta, options, &orbit);
    if (summary.termination != Termination::kConverged) {
      std::fprintf(stderr, "%s\n", summary.BriefReport().c_str());
      return EXIT_FAILURE;
    }
    std::printf("P(%d,%d) at omega = %g, %s\n", orbit.p, orbit.q, orbit.omega,
                orbit.stable ? "stable" : "unstable");
    for (const OrbitImpact& impact : orbit.impacts) {
      std::printf("impact %.12f %.12f\n", impact.phase, impact.velocity);
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "consumer: %s\n", error.what());
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
