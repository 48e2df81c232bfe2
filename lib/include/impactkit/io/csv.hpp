#pragma once
/// \file csv.hpp
/// Numeric tables for plotting tools and scripts:
///
///     t,x1,x2,v1,v2,stuck                            (header)
///     # impactkit 0.6.0                              (provenance: comment
///     # command: impactkit simulate --omega 1.4 ...   lines, as the caller
///     # ...                                           gives them)
///     897.59992760, ...                              (rows)
///
/// The header comes first because numpy.genfromtxt(names=True) takes its
/// names from the first line, comment or not; pandas (comment="#"), numpy
/// (comments="#") and gnuplot skip the comment lines wherever they are.
/// Numbers are written in the shortest form that reads back to the same
/// double, so a table loses nothing of what the simulator computed. The file
/// appears only on Commit() (output_file.hpp), or with the other files of
/// its OutputSet (output_set.hpp).

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "impactkit/io/output_file.hpp"

namespace impactkit {

/// The start of every table, before its rows: `columns` as the header row,
/// then `provenance` as comment lines, each of its lines after "# " (a final
/// line break in `provenance` adds no empty comment). For tables with text
/// columns anywhere, written row by row by their callers. Throws
/// std::invalid_argument for a carriage return in `provenance` or no columns.
std::string CsvHead(const std::vector<std::string>& columns, std::string_view provenance);

/// A number as a text field of a table: the shortest form that reads back
/// to the same double; an undefined value (NaN) is an empty field, which
/// gnuplot and pandas read as missing, so that no NaN reaches a file.
std::string CsvField(double value);

class CsvWriter {
 public:
  /// `columns` are the header names; `provenance` is what produced the
  /// table, written as comment lines after them (CsvHead). Throws OutputError if
  /// the file cannot be created, std::invalid_argument for a carriage
  /// return in the provenance or no columns.
  CsvWriter(const std::filesystem::path& path, std::string_view provenance,
            const std::vector<std::string>& columns);
  /// A table written into `file`, which outlives the writer and is
  /// committed by its owner (an OutputSet) after Finish().
  CsvWriter(AtomicOutputFile& file, std::string_view provenance,
            const std::vector<std::string>& columns);

  /// One row: exactly as many values as there are columns (else
  /// std::invalid_argument). Throws OutputError if writing fails.
  void WriteRow(std::span<const double> values);
  /// A row whose last columns are text: `values`, then `labels` (names
  /// without commas or line breaks; empty for none), as many in all as
  /// there are columns (else std::invalid_argument).
  void WriteRow(std::span<const double> values, std::span<const std::string> labels);
  /// Writes what is buffered to the (temporary) file. Throws OutputError.
  void Finish();
  /// Finish(), then moves the file into place.
  void Commit();

  std::size_t Columns() const { return columns_; }
  const std::filesystem::path& Path() const { return file_->Path(); }

 private:
  std::optional<AtomicOutputFile> owned_;  ///< the file, unless an OutputSet owns it
  AtomicOutputFile* file_;
  std::size_t columns_;
  std::string buffer_;  ///< rows not yet written: one write per ~64 KiB, not per row
};

}  // namespace impactkit
