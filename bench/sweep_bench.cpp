/// The paper's Fig. 3 sweep (Ω from 0.1 to 2.5, 2401 values, 500 transient
/// and 100 recorded forcing periods each, every value from the previous
/// one's final state) on 2 threads, with its transients ended early at
/// confirmed orbits (the default) and whole (full_transient): the ratio,
/// values per CPU-second, and whether every value's class is the same;
/// beside the whole-transient sweep's cost with the fastest peer of
/// simulate_bench: the plain Boost.Odeint dense-output Dormand–Prince with
/// TOMS 748 on the dense output (odeint_peer.hpp).
///
/// The peer's full-sweep cost is extrapolated from a subset measured in the
/// same run: every `stride`-th value, simulated from rest for the same 600
/// periods. Where the peer cannot go on (chatter: it stops when impacts
/// accumulate, at Ω <= 0.3), its cost is estimated as the number of impacts
/// we simulate there times its CPU time per impact at the nearest value it
/// completes; that underestimates it, since its steps shrink with the
/// flights of a chatter sequence. Our own single-thread cost on the same
/// subset, whole transients, is measured too, so the subset ratio compares
/// like with like.
///
///   ./build/bench/sweep_bench [threads] [stride]      (default 2 and 100)

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "cpu_time.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "odeint_peer.hpp"

namespace {

using namespace impactkit;

using bench::CpuSeconds;

/// The tolerance (rtol = atol) simulate_bench found necessary for the
/// Odeint peer's first 50 impact times to agree with ours within 1e-8
/// across the paper's Ω (1e-9 at 0.6 and 1.4, 1e-11 at 1.75): the tightest.
constexpr double kPeerTolerance = 1e-11;

SweepOptions Figure3(int threads) {
  SweepOptions options;  // the defaults are Fig. 3's range and periods
  options.threads = threads;
  return options;
}

struct PeerCost {
  double seconds = 0.0;  ///< CPU seconds
  long impacts = 0;
  bool stopped = false;  ///< stopped early at chatter
};

struct SubsetRow {
  double omega = 0.0;
  PeerCost peer;
  double peer_estimate = 0.0;  ///< CPU seconds of the whole run (= peer.seconds unless stopped)
  std::int64_t our_events = 0;
  double ours = 0.0;  ///< our CPU seconds
};

struct SweepCost {
  SweepResult result;
  double cpu = 0.0;  ///< CPU seconds
};

SweepCost MeasureSweep(const SweepOptions& options) {
  const double cpu_start = CpuSeconds();
  SweepCost cost{RunSweep(PaperSystem(), options), 0.0};
  cost.cpu = CpuSeconds() - cpu_start;
  fmt::print("  {}: {}\n", options.full_transient ? "whole transients" : "early ends",
             cost.result.BriefReport());
  fmt::print("    wall {:.2f} s, CPU {:.2f} s, {:.1f} values per CPU-second\n", cost.result.seconds,
             cost.cpu, cost.result.points.size() / cost.cpu);
  return cost;
}

/// Values whose class (kind, p, q) differs between the two sweeps.
int Differences(const SweepResult& a, const SweepResult& b) {
  int differ = 0;
  for (std::size_t k = 0; k < a.points.size(); ++k) {
    const Classification &x = a.points[k].classification, &y = b.points[k].classification;
    differ += x.kind != y.kind || x.period.p != y.period.p || x.period.q != y.period.q;
  }
  return differ;
}

PeerCost Peer(double omega, int periods) {
  const System s = PaperSystem(omega);
  const double start = CpuSeconds();
  const bench::PlainOdeintRun run =
      bench::PlainOdeintImpacts(s, periods * s.ForcingPeriod(), kPeerTolerance);
  return {CpuSeconds() - start, static_cast<long>(run.times.size()), run.stopped};
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int stride = argc > 2 ? std::atoi(argv[2]) : 100;
  if (threads < 1 || stride < 1) {
    fmt::print(stderr, "usage: sweep_bench [threads >= 1] [stride >= 1]\n");
    return 2;
  }
  SweepOptions options = Figure3(threads);
  const int periods = options.transient_periods + options.recorded_periods;

  // The sweep both ways, wall clock and CPU.
  fmt::print("Fig. 3 sweep on {} threads\n", threads);
  const SweepCost early = MeasureSweep(options);
  options.full_transient = true;
  const SweepCost whole = MeasureSweep(options);
  fmt::print("  whole / early, CPU: {:.2f}x; values classed differently: {}\n\n",
             whole.cpu / early.cpu, Differences(early.result, whole.result));
  const SweepResult& full = whole.result;
  const double full_cpu = whole.cpu;

  // The subset, by both, whole transients (the peer runs all 600 periods).
  const std::vector<double> values = SweepValues(options);
  std::vector<SubsetRow> rows;
  for (std::size_t k = 0; k < values.size(); k += stride) {
    SweepOptions one = options;
    one.from = one.to = values[k];
    one.steps = 1;
    one.threads = 1;
    SubsetRow row;
    row.omega = values[k];
    const double start = CpuSeconds();
    row.our_events = RunSweep(PaperSystem(), one).points[0].events;
    row.ours = CpuSeconds() - start;
    row.peer = Peer(values[k], periods);
    row.peer_estimate = row.peer.seconds;
    rows.push_back(row);
  }
  // Stopped runs: our impact count at the peer's cost per impact at the
  // nearest completed value with impacts.
  for (SubsetRow& row : rows) {
    if (!row.peer.stopped) continue;
    const SubsetRow* nearest = nullptr;
    for (const SubsetRow& other : rows) {
      if (other.peer.stopped || other.peer.impacts == 0) continue;
      if (!nearest || std::abs(other.omega - row.omega) < std::abs(nearest->omega - row.omega)) {
        nearest = &other;
      }
    }
    if (nearest) row.peer_estimate = row.our_events * nearest->peer.seconds / nearest->peer.impacts;
  }
  fmt::print("| Ω | peer impacts | peer CPU s | impactkit events | impactkit CPU s |\n");
  fmt::print("|---|---|---|---|---|\n");
  double ours_subset = 0.0, peer_subset = 0.0;
  int stopped = 0;
  for (const SubsetRow& row : rows) {
    fmt::print("| {:.3f} | {} | {} | {} | {:.4f} |\n", row.omega, row.peer.impacts,
               row.peer.stopped ? fmt::format("{:.4f}, stopped at chatter; estimate {:.4f}",
                                              row.peer.seconds, row.peer_estimate)
                                : fmt::format("{:.4f}", row.peer.seconds),
               row.our_events, row.ours);
    ours_subset += row.ours;
    peer_subset += row.peer_estimate;
    stopped += row.peer.stopped;
  }
  const double scale = static_cast<double>(values.size()) / rows.size();
  const double peer_full = peer_subset * scale;
  fmt::print("\nsubset: {} values ({} estimated where the peer stopped at chatter)\n", rows.size(),
             stopped);
  fmt::print("  impactkit {:.3f} CPU s, Odeint {:.3f} CPU s: {:.1f}x\n", ours_subset, peer_subset,
             peer_subset / ours_subset);
  fmt::print("Odeint full sweep, extrapolated: {:.1f} CPU s, {:.1f} s on {} threads at best\n",
             peer_full, peer_full / threads, threads);
  fmt::print(
      "impactkit whole-transient sweep: {:.2f} s wall on {} threads ({:.2f} CPU s): {:.1f}x "
      "faster than "
      "the peer's best wall time (CPU: {:.1f}x)\n",
      full.seconds, threads, full_cpu, peer_full / threads / full.seconds, peer_full / full_cpu);
  return 0;
}
