/// The paper's P(1,1) branch from Ω = 1.0 down to its grazing (≈ 0.856) and
/// up to its period doubling (≈ 1.613, the branch stopped at Ω = 1.62),
/// special points located — beside the way it is done by hand (the paper's
/// method): FindOrbit with the finite-difference Jacobian at each of the
/// same Ω values (natural-parameter stepping, no location), in the same run.
///
///   ./build/bench/continuation_bench

#include <fmt/format.h>

#include "cpu_time.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/continuation/continuation.hpp"

namespace {

using namespace impactkit;
using bench::CpuSeconds;

/// Mean CPU seconds of `job` over at least one second of repeats.
template <typename Job>
double Time(Job job) {
  int repeats = 0;
  const double start = CpuSeconds();
  do {
    job();
    ++repeats;
  } while (CpuSeconds() - start < 1.0);
  return (CpuSeconds() - start) / repeats;
}

}  // namespace

int main() {
  const System system = PaperSystem(1.0);
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system);
  if (!seed) return 1;
  OrbitOptions orbit_options;
  PeriodicOrbit start;
  if (FindOrbit(system, seed->eta, orbit_options, &start).termination != Termination::kConverged) {
    return 1;
  }
  ContinuationOptions options;
  options.from = 0.5;
  options.to = 1.62;
  options.direction = ContinuationDirection::kBoth;
  Branch branch;
  const double continuation = Time([&] { branch = ContinueBranch({system, start, {}}, options); });

  // The peer: a converged orbit at every branch point's Ω from the previous
  // one, finite-difference Jacobian, natural-parameter steps.
  OrbitOptions by_hand;
  by_hand.jacobian = JacobianMethod::kFiniteDifference;
  int failures = 0;
  const double peer = Time([&] {
    failures = 0;
    Eigen::VectorXd eta = branch.points.front().orbit.eta;
    for (const BranchPoint& point : branch.points) {
      System at = system;
      at.omega = point.parameter;
      PeriodicOrbit orbit;
      if (FindOrbit(at, eta, by_hand, &orbit).termination == Termination::kConverged) {
        eta = orbit.eta;
      } else {
        ++failures;
      }
    }
  });
  fmt::print("| job | points | special points | CPU seconds |\n|---|---|---|---|\n");
  fmt::print("| ContinueBranch, Ω 0.856 (grazing) to 1.62 (PD located) | {} | {} | {:.4f} |\n",
             branch.points.size(), branch.special_points.size(), continuation);
  fmt::print(
      "| FindOrbit (FD Jacobian) at the same Ω values, no location | {} ({} failed) | 0 | "
      "{:.4f} |\n",
      branch.points.size(), failures, peer);
  for (const SpecialPoint& s : branch.special_points) fmt::print("  {}\n", s.Describe("omega"));
  return 0;
}
