// Find the paper's P(2,1) orbit at Ω = 0.6 through the library API: seed it
// from a steady simulation, refine it as a fixed point of the impact map,
// and print its impacts and multipliers.
#include <cstdio>
#include <cstdlib>

#include "impactkit/impactkit.hpp"

int main() {
  using namespace impactkit;
  const System system = PaperSystem(/*omega=*/0.6);
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system);
  if (!seed || !seed->motion.periodic) {
    std::puts("no periodic motion to refine");
    return EXIT_FAILURE;
  }
  OrbitOptions options;
  options.p = static_cast<int>(seed->motion.p);
  options.q = seed->motion.q;
  PeriodicOrbit orbit;
  const OrbitSummary summary = FindOrbit(system, seed->eta, options, &orbit);
  std::printf("%s\n", summary.BriefReport().c_str());
  if (summary.termination != Termination::kConverged) return EXIT_FAILURE;

  std::printf("P(%d,%d), %s\n", orbit.p, orbit.q, orbit.stable ? "stable" : "unstable");
  for (const OrbitImpact& impact : orbit.impacts) {
    std::printf("  impact at phase %.10f with speed %.10f\n", impact.phase, impact.velocity);
  }
  for (const auto& m : orbit.multipliers) {
    std::printf("  multiplier %+.10f %+.10fi  |%.10f|\n", m.real(), m.imag(), std::abs(m));
  }
  return EXIT_SUCCESS;
}
