// The special points of the paper's P(1,1), P(2,1) and P(1,2) branches over
// the paper's range 0.1..2.5 computed directly by the library
// (ContinueBranch, no CLI code and no diagram), one SpecialPoint::Describe
// line each: check_paper.sh expects `impactkit paper`, whose connected
// diagram is seeded with these orbits, to print the same lines.
#include <cstdio>
#include <cstdlib>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/continuation/continuation.hpp"

int main() {
  using namespace impactkit;
  for (double omega : {1.0, 0.6, 2.0}) {
    const System system = PaperSystem(omega);
    const std::optional<OrbitSeed> seed = SeedFromSimulation(system, 200);
    if (!seed || !seed->motion.periodic) return EXIT_FAILURE;
    ContinuationOptions options;
    options.from = 0.1;
    options.to = 2.5;
    options.direction = ContinuationDirection::kBoth;
    options.orbit.p = static_cast<int>(seed->motion.p);
    options.orbit.q = seed->motion.q;
    PeriodicOrbit start;
    if (FindOrbit(system, seed->eta, options.orbit, &start).termination !=
        Termination::kConverged) {
      return EXIT_FAILURE;
    }
    for (const SpecialPoint& s : ContinueBranch({system, start, {}}, options).special_points) {
      std::printf("%s\n", s.Describe("omega").c_str());
    }
  }
  return EXIT_SUCCESS;
}
