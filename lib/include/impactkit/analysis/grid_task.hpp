#pragma once
/// \file grid_task.hpp
/// A brute-force grid (parameter_map.hpp, basins.hpp) cut into work units:
/// each unit is a fixed set of cells, computed the same way whatever thread,
/// process or run computes it, so a grid's result does not depend on how its
/// units are shared out. RunUnits shares them among threads; an MPI driver
/// (apps/common/grid_driver) among processes, a checkpoint (io/checkpoint.hpp)
/// across runs: all three only hand out unit numbers and collect cells.

#include <functional>
#include <string>
#include <vector>

#include "impactkit/analysis/grid_cell.hpp"
#include "impactkit/core/run_control.hpp"
#include "impactkit/core/termination.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

class GridTask {
 public:
  virtual ~GridTask() = default;
  virtual int Units() const = 0;
  virtual std::int64_t Cells() const = 0;
  /// The cells of `unit` in [0, Units()), each with its index. Thread-safe.
  virtual std::vector<GridCell> RunUnit(int unit) const = 0;
  /// Everything that decides the result, on one line: two runs with the same
  /// identity compute the same cells (checkpoints compare it).
  virtual std::string Identity() const = 0;
};

/// The next unit to compute, or -1 when there is none; called from any worker
/// thread, one call at a time.
using NextUnit = std::function<int()>;

/// Receives each finished unit's cells; calls are serialised (never
/// concurrent) but may come from any worker thread.
using UnitDone = std::function<void(int unit, std::vector<GridCell>& cells)>;

/// Computes units taken from `next` on `threads` threads (the caller's
/// among them) until it returns -1. The first exception of any unit stops
/// the others at their next unit and is rethrown here.
void RunUnits(const GridTask& task, int threads, const NextUnit& next, const UnitDone& done);

/// Summary::termination kCompleted (`cells` holds every cell, in index
/// order) or kStopped (cancelled: the units running finished, no other
/// started; `cells` holds theirs, in index order); iterations counts the
/// units done.
struct GridResult : Summary {
  std::vector<GridCell> cells;
};

/// The whole grid on `threads` threads, its units in order. Progress: stage
/// "grid", cells done of the task's. Throws InvalidInput for threads < 1,
/// and what a unit throws.
GridResult RunGrid(const GridTask& task, int threads, const RunControl& control = {});

/// Every number of `system` (M, C, K, A, omega, xs, r, the contact mass) in
/// shortest round-trip form, for identities.
std::string SystemIdentity(const System& system);

/// The options of a sweep that decide its result (not `threads`), on one line.
std::string SweepIdentity(const SweepOptions& options);

/// The cells of all units in index order. Throws InvalidInput unless every
/// index of [0, task cells) is there exactly once.
std::vector<GridCell> InIndexOrder(std::vector<GridCell> cells, std::int64_t total);

}  // namespace impactkit
