/// Impacts per CPU-second of the exact simulator beside two peers that
/// integrate the same system at equal accuracy: SUNDIALS CVODE with
/// rootfinding and Boost.Odeint's dense-output Dormand–Prince with crossing
/// location (reference/). Each peer's tolerance is the loosest of a ladder
/// whose first impacts are within 1e-8 in time of ours; our own accuracy is
/// checked against CVODE at its tightest. Then the cost growth with N.
///
///   ./build/bench/simulate_bench [periods]      (default 10000)

#include <fmt/format.h>

#include <cstdlib>
#include <functional>
#include <vector>

#include "cpu_time.hpp"
#include "cvode_impacts.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "odeint_impacts.hpp"

namespace {

using namespace impactkit;

using bench::CpuSeconds;

struct Timed {
  std::vector<double> times;  ///< impact times
  double seconds = 0.0;
};

/// Times `run` (which returns impact times), repeating short runs.
Timed Measure(const std::function<std::vector<double>()>& run) {
  Timed result;
  int repeats = 0;
  const double start = CpuSeconds();
  do {
    result.times = run();
    ++repeats;
  } while (CpuSeconds() - start < 0.5);
  result.seconds = (CpuSeconds() - start) / repeats;
  return result;
}

std::vector<double> OurImpacts(const System& s, double t_end) {
  ImpactRecorder recorder;
  HybridState state = RestState(s);
  Simulator(s).Run(state, t_end, recorder);
  std::vector<double> times;
  for (const Impact& i : recorder.Impacts()) times.push_back(i.t);
  return times;
}

template <typename Options, typename Integrate>
std::vector<double> PeerImpacts(const System& s, double t_end, const Options& options,
                                Integrate integrate) {
  const reference::ReferenceRun run =
      integrate(s, RestState(s).x, RestState(s).v, 0.0, t_end, options);
  std::vector<double> times;
  for (const auto& i : run.impacts) times.push_back(i.t);
  return times;
}

/// Largest |difference| over the first `count` impact times.
double MaxDifference(const std::vector<double>& a, const std::vector<double>& b,
                     std::size_t count) {
  if (a.size() < count || b.size() < count) return INFINITY;
  double worst = 0.0;
  for (std::size_t i = 0; i < count; ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

/// The loosest tolerance whose first impacts agree with `exact` to 1e-8.
template <typename Make>
double LoosestAccurateTolerance(const std::vector<double>& exact, Make impacts_at) {
  for (double tol : {1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13}) {
    if (MaxDifference(impacts_at(tol), exact, 50) <= 1e-8) return tol;
  }
  return 1e-13;
}

void CompareWithPeers(double omega, int periods) {
  const System s = PaperSystem(omega);
  const double t_end = periods * s.ForcingPeriod();
  const double t_check = 100 * s.ForcingPeriod();
  const std::vector<double> exact = OurImpacts(s, t_check);

  auto cvode_at = [&](double tol, double t) {
    reference::CvodeOptions o;
    o.rtol = tol;
    o.atol = tol * 1e-2;
    return PeerImpacts(s, t, o, reference::CvodeImpacts);
  };
  auto odeint_at = [&](double tol, double t) {
    reference::OdeintOptions o;
    o.rel_tol = tol;
    o.abs_tol = tol * 1e-2;
    return PeerImpacts(s, t, o, reference::OdeintImpacts);
  };
  const double our_error = MaxDifference(exact, cvode_at(1e-13, t_check), 50);
  const double cvode_tol =
      LoosestAccurateTolerance(exact, [&](double tol) { return cvode_at(tol, t_check); });
  const double odeint_tol =
      LoosestAccurateTolerance(exact, [&](double tol) { return odeint_at(tol, t_check); });

  const Timed ours = Measure([&] { return OurImpacts(s, t_end); });
  const Timed cvode = Measure([&] { return cvode_at(cvode_tol, t_end); });
  const Timed odeint = Measure([&] { return odeint_at(odeint_tol, t_end); });
  auto rate = [](const Timed& t) { return t.times.size() / t.seconds; };
  fmt::print(
      "| {:4} | {:8} | {:>10.0f} | {:>10.0f} (tol {:.0e}) | {:>10.0f} (tol {:.0e}) | {:>5.1f}x | "
      "{:.1e} |\n",
      omega, ours.times.size(), rate(ours), rate(cvode), cvode_tol, rate(odeint), odeint_tol,
      rate(ours) / std::max(rate(cvode), rate(odeint)), our_error);
}

void ScalingWithDof(int periods) {
  fmt::print("\n| N | impacts | impacts per CPU-second | microseconds per forcing period |\n");
  fmt::print("|---|---|---|---|\n");
  for (int n : {2, 5, 10, 50}) {
    Eigen::VectorXd forcing = Eigen::VectorXd::Zero(n);
    forcing(n - 1) = 0.5;  // on the contact mass, so every N impacts
    const System s = UniformChain({n, 1.0, 1.0, 0.1}, forcing, 1.4, 0.1, 0.7);
    const Timed ours = Measure([&] { return OurImpacts(s, periods * s.ForcingPeriod()); });
    fmt::print("| {} | {} | {:.0f} | {:.2f} |\n", n, ours.times.size(),
               ours.times.size() / ours.seconds, 1e6 * ours.seconds / periods);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int periods = argc > 1 ? std::atoi(argv[1]) : 10000;
  if (periods < 1) {
    fmt::print(stderr, "usage: simulate_bench [periods >= 1]\n");
    return 2;
  }
  fmt::print("{} forcing periods from rest, paper system; rates in impacts per CPU-second\n\n",
             periods);
  fmt::print(
      "| Ω | impacts | impactkit | CVODE | Odeint DOPRI5 | speed-up vs faster peer | our max |Δt| "
      "vs CVODE 1e-13 (first 50) |\n");
  fmt::print("|---|---|---|---|---|---|---|\n");
  for (double omega : {1.4, 0.6, 1.75}) CompareWithPeers(omega, periods);
  ScalingWithDof(periods / 10);
  return 0;
}
