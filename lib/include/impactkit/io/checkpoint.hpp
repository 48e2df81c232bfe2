#pragma once
/// \file checkpoint.hpp
/// The finished work units of a grid run (analysis/grid_task.hpp) in a
/// directory, so that a run killed at any moment and restarted with the same
/// command resumes where it stopped:
///
///     DIR/run.txt        the run's identity (GridTask::Identity) and unit count
///     DIR/unit-N.txt     the cells of unit N, one CellToText line each
///
/// Every file is written whole or not at all (a temporary renamed into
/// place, output_file.hpp), so a kill leaves finished units and no partial
/// one; the unit being computed at the kill is computed again. A directory
/// of another run (another identity) is refused, never mixed.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "impactkit/analysis/grid_cell.hpp"

namespace impactkit {

class Checkpoint {
 public:
  /// Opens `directory` (creating it and its run.txt when new, or empty).
  /// Throws InvalidInput when it holds another run's checkpoint or a
  /// damaged unit file, OutputError when it cannot be created.
  Checkpoint(std::filesystem::path directory, const std::string& identity, int units);

  /// The units recorded so far, with their cells.
  const std::map<int, std::vector<GridCell>>& Finished() const { return finished_; }

  /// Records a finished unit (whole or not at all). Throws OutputError.
  void Record(int unit, const std::vector<GridCell>& cells);

 private:
  std::filesystem::path directory_;
  std::map<int, std::vector<GridCell>> finished_;
};

}  // namespace impactkit
