// Follow the paper's P(1,1) orbit in Ω from Ω = 1 both ways through the
// library API: where it ends (grazing), where it period-doubles, and the
// first point of the period-doubled P(2,2) branch.
#include <cstdio>
#include <cstdlib>

#include "impactkit/impactkit.hpp"

int main() {
  using namespace impactkit;
  const System system = PaperSystem(/*omega=*/1.0);
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system);
  if (!seed) return EXIT_FAILURE;
  PeriodicOrbit start;
  if (FindOrbit(system, seed->eta, OrbitOptions{}, &start).termination != Termination::kConverged) {
    return EXIT_FAILURE;
  }

  ContinuationOptions options;  // Ω, p = q = 1
  options.from = 0.5;
  options.to = 2.0;
  options.direction = ContinuationDirection::kBoth;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  std::printf("P(1,1): %zu points, from %s to %s\n", branch.points.size(),
              ToString(*branch.begin).c_str(), ToString(branch.end).c_str());
  for (const SpecialPoint& s : branch.special_points) {
    std::printf("  %s\n", s.Describe("omega").c_str());
    if (s.type != SpecialPointType::kPeriodDoubling) continue;
    const std::optional<BranchStart> doubled = DoubledBranchStart(system, branch, s, options);
    if (doubled) {
      std::printf("  -> P(%d,%d) branch starts at omega = %.8f\n", doubled->orbit.p,
                  doubled->orbit.q, doubled->system.omega);
    }
  }
  return EXIT_SUCCESS;
}
