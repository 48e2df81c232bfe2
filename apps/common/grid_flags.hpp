#pragma once
/// \file common/grid_flags.hpp
/// The flags that run a grid (threads, checkpoint) and the run's report, so
/// that `map` and `basins` run identically (their cells' columns and labels
/// are the library's: impactkit/io/grid_output.hpp).

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/grid_driver.hpp"

namespace impactkit::cli {

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
