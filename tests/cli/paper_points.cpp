// The special points of the paper's P(1,1), P(2,1) and P(1,2) branches
// computed directly by the library (ContinueBranch, no CLI code), one
// SpecialPoint::Describe line each: check_paper.sh expects `impactkit paper`
// to print the same lines.
#include <cstdio>
#include <cstdlib>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/continuation/continuation.hpp"

int main() {
  using namespace impactkit;
  struct Plan {
    double start, lower, upper;
  };
  for (const Plan& plan : {Plan{1.0, 0.5, 2.0}, Plan{0.6, 0.4, 1.0}, Plan{2.0, 1.0, 3.0}}) {
    const System system = PaperSystem(plan.start);
    const std::optional<OrbitSeed> seed = SeedFromSimulation(system, 200);
    if (!seed || !seed->motion.periodic) return EXIT_FAILURE;
    ContinuationOptions options;
    options.lower = plan.lower;
    options.upper = plan.upper;
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
