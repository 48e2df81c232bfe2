#include "impactkit/analysis/orbit_seed.hpp"

#include <fmt/format.h>

#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/orbits/impact_map.hpp"

namespace impactkit {

std::optional<OrbitSeed> SeedFromSimulation(const System& system, int transient, int max_q) {
  if (transient < 0 || max_q < 1) {
    throw InvalidInput(
        fmt::format("transient must be >= 0 and max_q >= 1, got {} and {}", transient, max_q));
  }
  // One decomposition for the simulation and the impact state's map.
  const auto hybrid = std::make_shared<const HybridSystem>(system);
  const Simulator simulator(hybrid);
  const double period = system.ForcingPeriod();
  HybridState state = RestState(system);
  simulator.Run(state, transient * period);
  SteadyWindowRecorder window(period);
  simulator.Run(state, (transient + 2 * max_q + 1) * period, window);
  if (window.Impacts().empty()) return std::nullopt;
  const ImpactView last = window.Impacts().back();
  ImpactMapOptions section;
  section.stop = last.stop;
  return OrbitSeed{window.Period(PeriodOptions{max_q, 1e-6}),
                   ImpactMap(hybrid, section).ToEta(last.t, last.x, last.v), last.stop};
}

}  // namespace impactkit
