#include "impactkit/analysis/grid_task.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "impactkit/core/errors.hpp"

namespace impactkit {

void RunUnits(const GridTask& task, int threads, const NextUnit& next, const UnitDone& done) {
  Require(threads >= 1, fmt::format("threads must be >= 1, got {}", threads));
  std::mutex mutex;
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  auto take = [&] {
    const std::lock_guard<std::mutex> lock(mutex);
    return failed ? -1 : next();
  };
  auto worker = [&] {
    for (int unit = take(); unit >= 0; unit = take()) {
      try {
        std::vector<GridCell> cells = task.RunUnit(unit);
        const std::lock_guard<std::mutex> lock(mutex);
        done(unit, cells);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

GridResult RunGrid(const GridTask& task, int threads, const RunControl& control) {
  const auto start = std::chrono::steady_clock::now();
  GridResult result;
  int next = 0;  // RunUnits calls `next` and `done` one at a time
  RunUnits(
      task, threads, [&] { return next < task.Units() && !control.Cancelled() ? next++ : -1; },
      [&](int, std::vector<GridCell>& cells) {
        result.cells.insert(result.cells.end(), cells.begin(), cells.end());
        ++result.iterations;
        control.Report({.stage = "grid",
                        .done = static_cast<std::int64_t>(result.cells.size()),
                        .total = task.Cells()});
      });
  if (result.iterations == task.Units()) {
    result.cells = InIndexOrder(std::move(result.cells), task.Cells());
    result.termination = Termination::kCompleted;
  } else {
    std::sort(result.cells.begin(), result.cells.end(),
              [](const GridCell& a, const GridCell& b) { return a.index < b.index; });
    result.termination = Termination::kStopped;
    result.message = fmt::format("{} after {} of {} units", Describe(result.termination),
                                 result.iterations, task.Units());
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

namespace {

std::string Numbers(const Eigen::MatrixXd& matrix) {
  return fmt::format("{}", fmt::join(matrix.reshaped(), ","));
}

}  // namespace

std::string SystemIdentity(const System& system) {
  const std::string matrices =
      fmt::format("M={} C={} K={} A={} omega={}", Numbers(system.mass), Numbers(system.damping),
                  Numbers(system.stiffness), Numbers(system.forcing), system.omega);
  const StopParameters& first = system.stops[0];
  // One upper stop keeps the identity it had before stop lists, so that
  // its checkpoints stay valid.
  if (system.StopCount() == 1 && first.side == StopSide::kUpper) {
    std::string identity = matrices;
    for (const StopParameterRow& row : kStopParameterRows) {
      identity += fmt::format(" {}={}", row.name, first.*row.member);
    }
    return identity + fmt::format(" contact={}", first.dof);
  }
  std::string stops;
  for (const StopParameters& stop : system.stops) {
    stops +=
        fmt::format(" stop={}:{}", stop.dof, stop.side == StopSide::kUpper ? "upper" : "lower");
    for (const StopParameterRow& row : kStopParameterRows)
      stops += fmt::format(":{}", stop.*row.member);
  }
  return matrices + stops;
}

std::string SweepIdentity(const SweepOptions& o) {
  std::string text = fmt::format(
      "param={} from={} to={} steps={} transient={} record={} start={} direction={} chunk={} "
      "warmup={} max_q={}",
      o.parameter, o.from, o.to, o.steps, o.transient_periods, o.recorded_periods,
      ToString(o.start), ToString(o.direction), o.chunk_values, o.warmup_values,
      o.classify.period.max_q);
  if (o.fixed_state) {
    text += fmt::format(" x0={} v0={}", Numbers(o.fixed_state->x), Numbers(o.fixed_state->v));
  }
  if (o.full_transient) text += " full_transient";
  return text;
}

std::vector<GridCell> InIndexOrder(std::vector<GridCell> cells, std::int64_t total) {
  std::sort(cells.begin(), cells.end(),
            [](const GridCell& a, const GridCell& b) { return a.index < b.index; });
  Require(static_cast<std::int64_t>(cells.size()) == total,
          fmt::format("grid has {} cells, expected {}", cells.size(), total));
  for (std::int64_t k = 0; k < total; ++k) {
    Require(cells[k].index == k, fmt::format("grid cell {} missing or repeated", k));
  }
  return cells;
}

}  // namespace impactkit
