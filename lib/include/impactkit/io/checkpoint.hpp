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
/// one; the unit being computed at the kill is computed again. Each file
/// ends in a line "crc32 XXXXXXXX", zlib's CRC-32 of the bytes before it:
/// a file cut, corrupted or edited after it was written (a shared cluster
/// file system does both) is known for what it is. A damaged unit is not
/// trusted but computed again (Damaged() lists them for the caller to say
/// so); a damaged run.txt, which says whose units these are, is refused, as
/// is a directory of another run (another identity): never mixed.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "impactkit/analysis/grid_cell.hpp"

namespace impactkit {

/// A unit file whose contents cannot be trusted.
struct DamagedUnit {
  int unit = 0;
  std::filesystem::path file;
  std::string reason;  ///< what is wrong with it: "empty", "its CRC-32 does not match", ...
};

class Checkpoint {
 public:
  /// Opens `directory` (creating it and its run.txt when new, or empty).
  /// Throws InvalidInput when it holds another run's checkpoint or a
  /// damaged run.txt, OutputError when it cannot be created.
  Checkpoint(std::filesystem::path directory, const std::string& identity, int units);

  /// The units recorded so far, with their cells (damaged ones left out).
  const std::map<int, std::vector<GridCell>>& Finished() const { return finished_; }
  /// The unit files found damaged on opening, by unit: to be computed again
  /// (Record replaces them).
  const std::vector<DamagedUnit>& Damaged() const { return damaged_; }

  /// Records a finished unit (whole or not at all). Throws OutputError.
  void Record(int unit, const std::vector<GridCell>& cells);

 private:
  /// Reads unit `unit`'s file into Finished(), or Damaged() when it cannot
  /// be trusted.
  void Open(int unit, const std::filesystem::path& file);

  std::filesystem::path directory_;
  std::map<int, std::vector<GridCell>> finished_;
  std::vector<DamagedUnit> damaged_;
};

}  // namespace impactkit
