#pragma once
/// \file common/grid_output.hpp
/// What `map` and `basins` write alike: a cell's columns, its motion's label,
/// the colours of a class map, and the flags that run a grid (threads,
/// checkpoint), so the two commands format and run identically.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/grid_driver.hpp"
#include "impactkit/analysis/grid_cell.hpp"

namespace impactkit::cli {

/// The one schema of a motion's kind and period in every output (sweep,
/// map, basins, paper): the kind by name ("periodic", "sticking", ...), p
/// the impacts per q forcing periods, "inf" when sticking, both empty where
/// the motion does not repeat (docs/cli.md, "Motion kinds").
struct PeriodLabels {
  std::string kind, p, q;
};
PeriodLabels LabelsOf(const GridCell& cell);

/// "kind,p,q,max_v,range_xN,lyapunov": the CSV columns of a cell after its
/// coordinates (kind, p and q as LabelsOf).
inline constexpr const char* kCellColumns = "kind,p,q,max_v,range_xN,lyapunov";
std::string CellFields(const GridCell& cell);

/// "P(2,1)", "P(inf,1)", "non-impacting", "chaotic", "unresolved".
std::string MotionLabel(const GridCell& cell);

/// --threads and --checkpoint, into `threads` (unset: automatic) and `checkpoint`.
void AddGridRunOptions(CLI::App& command, std::optional<int>& threads, std::string& checkpoint);

/// The run's driver options: threads unset means all cores of one process, one
/// thread per rank under mpirun (run one rank per core there).
GridDriveOptions DriveOptionsOf(const std::string& label, std::optional<int> threads,
                                const std::string& checkpoint, const GridProcesses& processes);

/// "2400 cells in 14.2 s on 2 threads x 1 rank (40 resumed from the checkpoint)".
std::string RunReport(const GridOutcome& outcome, const GridDriveOptions& options,
                      const GridProcesses& processes);

}  // namespace impactkit::cli
