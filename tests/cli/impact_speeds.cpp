/// The reference for the CLI test of `impactkit simulate --impacts`: the
/// impact speeds the library itself gives for the paper's system at Ω, from
/// rest at t = 0, over the window [transient T, (transient + periods) T],
/// one per line in the shortest form that round-trips (as the CSV has them),
/// so the test can compare the two as text, bit for bit.
///
///     impactkit_impact_speeds OMEGA TRANSIENT PERIODS

#include <fmt/format.h>

#include <cstdlib>
#include <string>

#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    fmt::print(stderr, "usage: {} OMEGA TRANSIENT PERIODS\n", argv[0]);
    return 2;
  }
  const double omega = std::stod(argv[1]);
  const long transient = std::stol(argv[2]), periods = std::stol(argv[3]);

  const impactkit::System system = impactkit::PaperSystem(omega);
  const impactkit::Simulator simulator(system);
  impactkit::HybridState state = impactkit::RestState(system);
  const double period = system.ForcingPeriod();
  simulator.Run(state, static_cast<double>(transient) * period);
  impactkit::ImpactRecorder impacts;
  simulator.Run(state, static_cast<double>(transient + periods) * period, impacts);
  for (const impactkit::ImpactView impact : impacts.Impacts()) fmt::print("{}\n", impact.velocity);
  return 0;
}
