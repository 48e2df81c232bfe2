#pragma once
/// \file common/grid_driver.hpp
/// How `map` and `basins` run a grid (impactkit/analysis/grid_task.hpp): its
/// units shared among threads, and under `mpirun` among processes too, with
/// dynamic load balancing (a unit is handed out when a worker asks, so
/// expensive sticking units do not hold up cheap ones); finished units
/// recorded in a checkpoint directory when asked (a damaged unit there is
/// computed again, with a warning line on stderr naming it); a progress line
/// with the time left. Rank 0 collects every cell and alone writes; the cells do not
/// depend on the number of threads or ranks, so neither do the files.
///
/// MPI is only transport here (grid_mpi.hpp); no MPI type leaves the apps.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/analysis/grid_task.hpp"

namespace impactkit::cli {

/// The processes of this run: one, or the ranks of an `mpirun` launch.
/// Starts MPI when the program was launched by mpirun (and built with MPI:
/// otherwise throws InvalidInput saying so); ends it on destruction.
class GridProcesses {
 public:
  GridProcesses();
  ~GridProcesses();
  GridProcesses(const GridProcesses&) = delete;
  GridProcesses& operator=(const GridProcesses&) = delete;
  int Rank() const { return rank_; }
  int Ranks() const { return ranks_; }
  bool Writer() const { return rank_ == 0; }

 private:
  int rank_ = 0;
  int ranks_ = 1;
  bool started_mpi_ = false;
};

struct GridDriveOptions {
  std::string label;       ///< "map", "basins": the progress line's
  int threads = 1;         ///< worker threads of this process
  std::string checkpoint;  ///< directory; empty: none
};

struct GridOutcome {
  std::vector<GridCell> cells;  ///< in index order
  std::int64_t resumed = 0;     ///< cells read from the checkpoint
  std::int64_t computed = 0;    ///< cells computed by this run
  double seconds = 0.0;         ///< wall-clock time
};

/// Runs `task`. On the writer (rank 0): every cell; elsewhere nothing.
/// Throws InvalidInput (a checkpoint of another run, a damaged run.txt),
/// OutputError.
std::optional<GridOutcome> DriveGrid(const GridTask& task, const GridDriveOptions& options,
                                     const GridProcesses& processes);

}  // namespace impactkit::cli
