#pragma once
/// \file output_set.hpp
/// All the output files of one run, written all or none. Every file is
/// created (as its temporary, output_file.hpp) when added, so that a path
/// that cannot be written fails before any work; Commit() writes out every
/// buffer and closes every temporary (where a full disk shows) before it
/// renames the first onto its target. A run that fails or is interrupted
/// before Commit() changes no file; the set's destructor removes the
/// temporaries.
///
/// What remains: the renames themselves are one per file, so a file system
/// that refuses a rename of a complete temporary beside its target (the
/// directory removed or made read-only meanwhile) can leave the files
/// renamed before it in place. Commit() then throws OutputError naming it.

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "impactkit/io/csv.hpp"
#include "impactkit/io/output_file.hpp"

namespace impactkit {

class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// A whole-file output (PNG, JSON), its temporary created now. Throws
  /// OutputError, or InvalidInput when the set already has a file of this
  /// path (one would silently overwrite the other).
  AtomicOutputFile& AddFile(const std::filesystem::path& path);
  /// A CSV table (csv.hpp), its temporary created now. Throws as AddFile,
  /// and std::invalid_argument as CsvWriter.
  CsvWriter& AddCsv(const std::filesystem::path& path, std::string_view provenance,
                    const std::vector<std::string>& columns);

  /// A CSV table in `file`, a file of this set added before the table's
  /// columns were known (they may depend on the result).
  CsvWriter& AddCsv(AtomicOutputFile& file, std::string_view provenance,
                    const std::vector<std::string>& columns);

  /// Finishes every table, closes every file, then moves them all into
  /// place. Throws OutputError.
  void Commit();

  std::size_t Size() const { return files_.size(); }

 private:
  // Tables are declared after the files, so destroyed first: they point into them.
  std::vector<std::unique_ptr<AtomicOutputFile>> files_;
  std::vector<std::unique_ptr<CsvWriter>> tables_;
};

}  // namespace impactkit
