/// Time to one converged orbit: P(1,1) at Ω = 0.9 from a seed 1e-2 away in
/// every entry of η, with the analytic and with the finite-difference
/// Jacobian (the paper's method), side by side in the same run.
///
///   ./build/bench/orbit_bench

#include <fmt/format.h>

#include "cpu_time.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace {

using namespace impactkit;

using bench::CpuSeconds;

void Measure(const System& system, const Eigen::VectorXd& seed, int p, int q,
             JacobianMethod method) {
  OrbitOptions options;
  options.p = p;
  options.q = q;
  options.jacobian = method;
  PeriodicOrbit orbit;
  OrbitSummary summary;
  int repeats = 0;
  const double start = CpuSeconds();
  do {
    summary = FindOrbit(system, seed, options, &orbit);
    ++repeats;
  } while (CpuSeconds() - start < 1.0);
  const double seconds = (CpuSeconds() - start) / repeats;
  fmt::print("| P({},{}) at Ω = {} | {} | {} | {:.2e} | {:.1f} |\n", p, q, system.omega,
             ToString(method), summary.iterations, summary.residual, 1e6 * seconds);
}

}  // namespace

int main() {
  fmt::print("| orbit | Jacobian | Newton iterations | residual | microseconds per solve |\n");
  fmt::print("|---|---|---|---|---|\n");
  struct Case {
    double omega;
    int p, q;
  };
  for (const Case& c : {Case{0.9, 1, 1}, Case{0.6, 2, 1}, Case{1.7, 4, 4}}) {
    const System system = PaperSystem(c.omega);
    const std::optional<OrbitSeed> seed = SeedFromSimulation(system);
    if (!seed) return 1;
    const Eigen::VectorXd guess = seed->eta.array() + 1e-2;
    for (JacobianMethod method : {JacobianMethod::kAnalytic, JacobianMethod::kFiniteDifference}) {
      Measure(system, guess, c.p, c.q, method);
    }
  }
  return 0;
}
