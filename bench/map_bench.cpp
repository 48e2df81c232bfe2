/// Cells per CPU-second of a two-parameter map on the paper's (Ω, r) plane
/// (Ω 0.1-2.5, r 0.3-0.95, 500 transient + 100 recorded periods a cell,
/// rows from the previous value's final state), on 1 and 2 threads: the
/// parts of the 1000 x 1000 estimate in docs/performance.md. The grid is
/// coarse (every cell still a full run), so that the bench takes about a
/// minute; its rows sample the plane's mix of cheap and sticking cells.
///
///     map_bench [omega steps = 49] [r steps = 14]

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "cpu_time.hpp"
#include "impactkit/analysis/parameter_map.hpp"

using namespace impactkit;

namespace {

struct Timing {
  double wall = 0.0;
  double cpu = 0.0;
  std::int64_t events = 0;
};

Timing Run(const ParameterMapTask& task, int threads) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = bench::CpuSeconds();
  int next = 0;
  Timing timing;
  RunUnits(
      task, threads, [&] { return next < task.Units() ? next++ : -1; },
      [&](int, std::vector<GridCell>& cells) {
        for (const GridCell& cell : cells) timing.events += cell.events;
      });
  timing.cpu = bench::CpuSeconds() - cpu_start;
  timing.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return timing;
}

}  // namespace

int main(int argc, char** argv) {
  ParameterMapOptions options;
  options.row.from = 0.1;
  options.row.to = 2.5;
  options.row.steps = argc > 1 ? std::atoi(argv[1]) : 49;
  options.from2 = 0.3;
  options.to2 = 0.95;
  options.steps2 = argc > 2 ? std::atoi(argv[2]) : 14;
  const ParameterMapTask task(PaperSystem(), options);
  const auto cells = static_cast<double>(task.Cells());
  fmt::print("map {} x {} = {} cells, 500 + 100 periods each\n", options.row.steps, options.steps2,
             task.Cells());
  double one_thread_wall = 0.0;
  for (int threads : {1, 2}) {
    const Timing t = Run(task, threads);
    if (threads == 1) one_thread_wall = t.wall;
    fmt::print(
        "{} thread{}: {:.2f} s wall, {:.2f} s CPU, {:.1f} cells per CPU-second, {:.1f} cells per "
        "second, {:.0f} events per cell, speed-up {:.2f}\n",
        threads, threads == 1 ? "" : "s", t.wall, t.cpu, cells / t.cpu, cells / t.wall,
        static_cast<double>(t.events) / cells, one_thread_wall / t.wall);
  }
}
