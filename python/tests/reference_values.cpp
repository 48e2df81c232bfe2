// The C++ library's results for the computations test_bit_for_bit.py makes
// through the Python module, printed as hexadecimal floats (exact):
//   orbit <p> <q> <omega> <eta...> <multipliers re im ...>
//   branch <n> <values...>
//   special <type> <parameter>
// for the paper's P(1,1) orbit at omega = 1.65 (seeded by simulation) and
// its branch continued over [1.5, 1.8].
#include <fmt/format.h>

#include <cstdlib>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/continuation/continuation.hpp"

int main() {
  using namespace impactkit;
  const System system = PaperSystem(1.65);
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system, 500);
  if (!seed) return EXIT_FAILURE;
  OrbitOptions options;  // p = q = 1
  PeriodicOrbit orbit;
  if (FindOrbit(system, seed->eta, options, &orbit).termination != Termination::kConverged) {
    return EXIT_FAILURE;
  }
  fmt::print("orbit {} {} {:a}", orbit.p, orbit.q, orbit.omega);
  for (double e : orbit.eta) fmt::print(" {:a}", e);
  for (const std::complex<double>& m : orbit.multipliers) {
    fmt::print(" {:a} {:a}", m.real(), m.imag());
  }
  fmt::print("\n");

  ContinuationOptions continuation;
  continuation.from = 1.5;
  continuation.to = 1.8;
  continuation.direction = ContinuationDirection::kBoth;
  const Branch branch = ContinueBranch({system, orbit, {}}, continuation);
  fmt::print("branch {}", branch.points.size());
  for (const BranchPoint& point : branch.points) fmt::print(" {:a}", point.parameter);
  fmt::print("\n");
  for (const SpecialPoint& special : branch.special_points) {
    fmt::print("special {} {:a}\n", ToString(special.type), special.parameter);
  }
}
