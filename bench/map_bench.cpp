/// Cells per CPU-second of a two-parameter map on the paper's (Ω, r) plane
/// (Ω 0.1-2.5, r 0.3-0.95, 500 transient + 100 recorded periods a cell,
/// rows from the previous value's final state) and of a basin picture (the
/// paper's system at Ω = 1.7, starts over (x1, v1) in [-2, 2]², the P(4,4)
/// and P(12,8) of docs/grids.md), on 1 and 2 threads, each with its
/// transients ended early at confirmed orbits (the default) and whole
/// (--full-transient): the ratio, and whether every cell's class is the
/// same. The parts of the 1000 x 1000 estimate in docs/performance.md. The
/// grids are coarse so that the bench takes about a minute; the map's rows
/// sample the plane's mix of cheap and sticking cells.
///
///     map_bench [omega steps = 49] [r steps = 14] [basin steps = 20]

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>

#include "cpu_time.hpp"
#include "impactkit/analysis/basins.hpp"
#include "impactkit/analysis/parameter_map.hpp"

using namespace impactkit;

namespace {

struct Timing {
  double wall = 0.0;
  double cpu = 0.0;
  std::vector<GridCell> cells;  ///< in index order
};

Timing Run(const GridTask& task, int threads) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = bench::CpuSeconds();
  int next = 0;
  Timing timing;
  RunUnits(
      task, threads, [&] { return next < task.Units() ? next++ : -1; },
      [&](int, std::vector<GridCell>& cells) {
        timing.cells.insert(timing.cells.end(), cells.begin(), cells.end());
      });
  timing.cpu = bench::CpuSeconds() - cpu_start;
  timing.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  timing.cells = InIndexOrder(std::move(timing.cells), task.Cells());
  return timing;
}

/// Cells whose class (kind, p, q) differs between the two runs.
std::int64_t Differences(const std::vector<GridCell>& a, const std::vector<GridCell>& b) {
  std::int64_t differ = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    differ += a[k].kind != b[k].kind || a[k].p != b[k].p || a[k].q != b[k].q;
  }
  return differ;
}

/// The task built with whole or early-ended transients.
using TaskOf = std::function<std::unique_ptr<GridTask>(bool full_transient)>;

void Compare(const std::string& name, const TaskOf& task_of) {
  const auto cells = static_cast<double>(task_of(false)->Cells());
  fmt::print("{}: {} cells, 500 + 100 periods each\n", name, cells);
  double cpu[2] = {0.0, 0.0};
  std::vector<GridCell> classes[2];
  for (const bool full : {true, false}) {
    const std::unique_ptr<GridTask> task = task_of(full);
    double one_thread_wall = 0.0;
    for (int threads : {1, 2}) {
      const Timing t = Run(*task, threads);
      std::int64_t events = 0;
      for (const GridCell& cell : t.cells) events += cell.events;
      if (threads == 1) {
        one_thread_wall = t.wall;
        cpu[full] = t.cpu;
        classes[full] = t.cells;
      }
      fmt::print(
          "  {}, {} thread{}: {:.2f} s wall, {:.2f} s CPU, {:.1f} cells per CPU-second, {:.1f} "
          "cells per second, {:.0f} events per cell, speed-up {:.2f}\n",
          full ? "whole transients" : "early ends", threads, threads == 1 ? "" : "s", t.wall, t.cpu,
          cells / t.cpu, cells / t.wall, static_cast<double>(events) / cells,
          one_thread_wall / t.wall);
    }
  }
  fmt::print("  whole / early, CPU on 1 thread: {:.2f}x; cells classed differently: {}\n\n",
             cpu[1] / cpu[0], Differences(classes[0], classes[1]));
}

}  // namespace

int main(int argc, char** argv) {
  const int steps = argc > 1 ? std::atoi(argv[1]) : 49;
  const int steps2 = argc > 2 ? std::atoi(argv[2]) : 14;
  const int basin_steps = argc > 3 ? std::atoi(argv[3]) : 20;
  Compare(fmt::format("map {} x {}", steps, steps2), [&](bool full_transient) {
    ParameterMapOptions options;
    options.row.from = 0.1;
    options.row.to = 2.5;
    options.row.steps = steps;
    options.row.full_transient = full_transient;
    options.from2 = 0.3;
    options.to2 = 0.95;
    options.steps2 = steps2;
    return std::make_unique<ParameterMapTask>(PaperSystem(), options);
  });
  Compare(fmt::format("basins at omega = 1.7, {0} x {0}", basin_steps), [&](bool full_transient) {
    BasinsOptions options;
    options.run.full_transient = full_transient;
    options.from1 = options.from2 = -2.0;
    options.to1 = options.to2 = 2.0;
    options.steps1 = options.steps2 = basin_steps;
    return std::make_unique<BasinsTask>(PaperSystem(1.7), options);
  });
}
