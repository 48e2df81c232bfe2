/// Long chains (issue 38): CPU time of the paper's chain (m = k = 1,
/// c = 0.1, A_1 = 0.5, the stop on mass N at 0.1, r = 0.7, Ω = 1, what
/// `impactkit simulate --set n=N` builds) at N = 100, 200, 400, 1000, in one
/// run:
///
/// - set-up: what the command does before its first step, Validate (the
///   parameters and the flows' resonances) then the Simulator (the free
///   and the stuck flows, decomposed again);
/// - one forcing period from rest;
/// - the cost per event: the same chain forced on its contact mass
///   (A_N = 0.5, Ω = 0.5, xs = 0.01: about one impact per period, where
///   the paper's forcing at Ω = 1.4 leaves a long chain's end almost
///   still); CPU time of the run alone over its impacts, releases and
///   chatter jumps.
///
/// The growth of set-up plus one period from N = 100 to 1000 is printed
/// beside the N² bound (a factor 100).
///
///   ./build/bench/chain_bench [periods for the per-event cost]   (default 20)

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "cpu_time.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/hybrid/system_flows.hpp"

namespace {

using namespace impactkit;
using bench::CpuSeconds;

System Chain(int n, bool on_contact, double omega, double stop) {
  Eigen::VectorXd forcing = Eigen::VectorXd::Zero(n);
  forcing(on_contact ? n - 1 : 0) = 0.5;
  return UniformChain({n, 1.0, 1.0, 0.1}, forcing, omega, stop, 0.7);
}

/// CPU seconds of `job`, repeated until 0.3 s and averaged (once where one
/// run takes longer).
template <typename Job>
double Seconds(Job job) {
  int repeats = 0;
  const double start = CpuSeconds();
  do {
    job();
    ++repeats;
  } while (CpuSeconds() - start < 0.3);
  return (CpuSeconds() - start) / repeats;
}

struct Row {
  int n;
  double validate, simulator, period;
  std::int64_t events;
  double per_event;
  double SetUpAndPeriod() const { return validate + simulator + period; }
};

Row Measure(int n, int periods) {
  const System paper = Chain(n, false, 1.0, 0.1);
  Row row{n, 0, 0, 0, 0, 0};
  row.validate = Seconds([&] { Validate(paper); });
  row.simulator = Seconds([&] { const Simulator simulator(paper); });
  const Simulator simulator(paper);
  row.period = Seconds([&] {
    HybridState state = RestState(paper);
    simulator.Run(state, paper.ForcingPeriod());
  });
  const System impacting = Chain(n, true, 0.5, 0.01);
  const Simulator run(impacting);
  SimulationSummary summary;
  const double seconds = Seconds([&] {
    HybridState state = RestState(impacting);
    summary = run.Run(state, periods * impacting.ForcingPeriod());
  });
  row.events = summary.impacts + summary.releases + summary.chatter_jumps;
  row.per_event = seconds / static_cast<double>(row.events);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const int periods = argc > 1 ? std::atoi(argv[1]) : 20;
  if (periods < 1) {
    fmt::print(stderr, "usage: chain_bench [periods >= 1]\n");
    return 2;
  }
  fmt::print(
      "| N | Validate ms | Simulator ms | one period ms | set-up + period ms | events in {} "
      "periods (A_N, Ω = 0.5, xs = 0.01) | µs per event |\n|---|---|---|---|---|---|---|\n",
      periods);
  std::vector<Row> rows;
  for (int n : {100, 200, 400, 1000}) {
    rows.push_back(Measure(n, periods));
    const Row& r = rows.back();
    fmt::print("| {} | {:.2f} | {:.2f} | {:.3f} | {:.2f} | {} | {:.1f} |\n", r.n, 1e3 * r.validate,
               1e3 * r.simulator, 1e3 * r.period, 1e3 * r.SetUpAndPeriod(), r.events,
               1e6 * r.per_event);
  }
  const double growth = rows.back().SetUpAndPeriod() / rows.front().SetUpAndPeriod();
  fmt::print(
      "\nset-up + one period, N = 100 to 1000: x{:.1f} (N² bound: x100; exponent {:.2f})\n"
      "µs per event, N = 100 to 1000: x{:.1f} (exponent {:.2f})\n",
      growth, std::log10(growth), rows.back().per_event / rows.front().per_event,
      std::log10(rows.back().per_event / rows.front().per_event));
  return 0;
}
