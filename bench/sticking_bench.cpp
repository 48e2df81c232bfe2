/// Sticking orbits and their branch, each beside the peer a user would
/// write, in the same run:
///  - the paper's sticking orbit at Ω = 0.2 by FindOrbit (releases = 1) from the
///    last release of a steady simulation, against simulating on from that
///    release until the release phase repeats to 1e-9 (the simulator's own
///    convergence to the attractor);
///  - the sticking branch from Ω = 0.1 up to its end, against
///    FindOrbit at the same Ω values by natural-parameter stepping
///    (nothing located).
///
///   ./build/bench/sticking_bench

#include <fmt/format.h>

#include <cmath>

#include "cpu_time.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/hybrid/recorders.hpp"

namespace {

using namespace impactkit;
using bench::CpuSeconds;

/// Calls `job` until a second of CPU has passed; CPU seconds per call.
template <typename Job>
double PerCall(const Job& job) {
  int repeats = 0;
  const double start = CpuSeconds();
  do {
    job();
    ++repeats;
  } while (CpuSeconds() - start < 1.0);
  return (CpuSeconds() - start) / repeats;
}

/// Releases, recorded.
class Releases : public Observer {
 public:
  void OnRelease(const Release& release) override { times.push_back(release.t_release); }
  std::vector<double> times;
};

/// Simulates on from the release state until two successive release phases
/// agree to 1e-9; the number of periods simulated.
int SimulateToRepeat(const Simulator& simulator, const StickingMap& map, const Eigen::VectorXd& s) {
  HybridState state = map.ToState(s);
  const double period = simulator.GetSystem().ForcingPeriod();
  Releases releases;
  for (int periods = 1; periods <= 200; ++periods) {
    simulator.Run(state, state.t + period, releases);
    const std::vector<double>& t = releases.times;
    if (t.size() >= 2 && std::abs(t[t.size() - 1] - t[t.size() - 2] - period) < 1e-9) {
      return periods;
    }
  }
  return -1;
}

}  // namespace

int main() {
  const System system = PaperSystem(0.2);
  const std::optional<StickingSeed> seed = SeedStickingFromSimulation(system, 20, 2);
  if (!seed) return 1;
  OrbitOptions options;
  options.releases = 1;
  PeriodicOrbit orbit;
  const double solve = PerCall([&] { FindOrbit(system, seed->state, options, &orbit); });
  const Simulator simulator(system);
  const StickingMap map(system);
  int periods = 0;
  const double simulate = PerCall([&] { periods = SimulateToRepeat(simulator, map, seed->state); });
  fmt::print("| job | CPU milliseconds |\n|---|---|\n");
  fmt::print(
      "| FindOrbit (release section) at Ω = 0.2 from a 20-period seed (residual {:.1e}) | {:.3f} "
      "|\n",
      orbit.residual, 1e3 * solve);
  fmt::print("| simulating on until the release repeats to 1e-9 ({} periods) | {:.3f} |\n\n",
             periods, 1e3 * simulate);

  const System low = PaperSystem(0.1);
  const std::optional<StickingSeed> low_seed = SeedStickingFromSimulation(low, 200, 2);
  if (!low_seed) return 1;
  PeriodicOrbit start;
  FindOrbit(low, low_seed->state, options, &start);
  ContinuationOptions branch_options;
  branch_options.from = 0.1;
  branch_options.to = 0.6;
  Branch branch;
  double begin = CpuSeconds();
  branch = ContinueBranch({low, start, {}}, branch_options);
  const double continuation = CpuSeconds() - begin;
  begin = CpuSeconds();
  int failed = 0;
  Eigen::VectorXd guess = start.eta;
  for (const BranchPoint& p : branch.points) {
    PeriodicOrbit natural;
    try {
      const OrbitSummary s = FindOrbit(PaperSystem(p.parameter), guess, options, &natural);
      if (s.termination == Termination::kConverged) {
        guess = natural.eta;
      } else {
        ++failed;
      }
    } catch (const InvalidInput&) {
      ++failed;
    }
  }
  const double peer = CpuSeconds() - begin;
  fmt::print("| job | points | end | CPU seconds |\n|---|---|---|---|\n");
  fmt::print(
      "| ContinueBranch of the sticking family, Ω 0.1 to its end | {} | {} at {:.8f} | {:.3f} |\n",
      branch.points.size(), ToString(branch.end), branch.points.back().parameter, continuation);
  fmt::print("| FindOrbit at the same Ω values, no location | {} ({} failed) | - | {:.3f} |\n",
             branch.points.size(), failed, peer);
  return 0;
}
