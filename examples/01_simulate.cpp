// Simulate the paper's system at Ω = 0.6 through the library API: discard a
// transient, record impacts and stroboscopic points, and name the motion.
#include <cstdio>

#include "impactkit/impactkit.hpp"

int main() {
  using namespace impactkit;
  const System system = PaperSystem(/*omega=*/0.6);
  const Simulator simulator(system);
  HybridState state = RestState(system);               // x = v = 0 at t = 0
  simulator.Run(state, 200 * system.ForcingPeriod());  // transient

  ImpactRecorder impacts;
  StroboscopicRecorder strobe(system.ForcingPeriod());
  ObserverList recorders;
  recorders.Add(impacts);
  recorders.Add(strobe);
  simulator.Run(state, 210 * system.ForcingPeriod(), recorders);

  std::vector<double> times;
  for (const ImpactView impact : impacts.Impacts()) {
    std::printf("impact at t = %.12f, phase %.6f, speed %.9f\n", impact.t, impact.phase,
                impact.velocity);
    times.push_back(impact.t);
  }
  std::printf("motion: %s\n", DetectPeriod(strobe.Points(), times, {}).ToString().c_str());
  return 0;
}
