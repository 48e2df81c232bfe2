/// The C++ side of bench/python_bench.py: the same computations the Python
/// module is timed on, called directly, so that the difference is the
/// binding's cost.
///
///   python_peer orbit OMEGA SEED...   FindOrbit P(1,1) from SEED (hex
///                                     floats), repeated for 1 CPU second:
///                                     prints the CPU microseconds per call
///                                     and the orbit's η in hex
///   python_peer impacts OMEGA T_END   Simulate the paper's system from rest
///                                     to T_END with an ImpactRecorder:
///                                     prints the CPU seconds and the count
#include <fmt/format.h>

#include <cstdlib>
#include <string>

#include "cpu_time.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace {

using namespace impactkit;
using bench::CpuSeconds;

int Orbit(double omega, const Eigen::VectorXd& seed) {
  const System system = PaperSystem(omega);
  OrbitOptions options;  // p = q = 1, as find_orbit(system, p=1, q=1, seed=...)
  PeriodicOrbit orbit;
  int repeats = 0;
  const double start = CpuSeconds();
  do {
    if (FindOrbit(system, seed, options, &orbit).termination != Termination::kConverged) {
      return EXIT_FAILURE;
    }
    ++repeats;
  } while (CpuSeconds() - start < 1.0);
  fmt::print("microseconds {:.3f}\neta", 1e6 * (CpuSeconds() - start) / repeats);
  for (double e : orbit.eta) fmt::print(" {:a}", e);
  fmt::print("\n");
  return EXIT_SUCCESS;
}

int Impacts(double omega, double t_end) {
  const System system = PaperSystem(omega);
  HybridState state = RestState(system);
  ImpactRecorder impacts;
  const double start = CpuSeconds();
  Simulate(system, {}, state, t_end, impacts);
  fmt::print("seconds {:.4f}\nimpacts {}\n", CpuSeconds() - start, impacts.Impacts().size());
  return EXIT_SUCCESS;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 2 ? argv[1] : "";
  if (mode == "orbit" && argc > 3) {
    Eigen::VectorXd seed(argc - 3);
    for (int i = 3; i < argc; ++i) seed(i - 3) = std::strtod(argv[i], nullptr);
    return Orbit(std::strtod(argv[2], nullptr), seed);
  }
  if (mode == "impacts" && argc == 4) {
    return Impacts(std::strtod(argv[2], nullptr), std::strtod(argv[3], nullptr));
  }
  fmt::print(stderr, "usage: python_peer orbit OMEGA SEED... | python_peer impacts OMEGA T_END\n");
  return 2;
}
