#pragma once
/// \file output_file.hpp
/// Output files that appear whole or not at all. The bytes go to a hidden
/// temporary file beside the target, which Commit() renames over it (atomic
/// on POSIX file systems): a run that fails, or is interrupted, never leaves
/// a half-written table behind for a plotting script to read as if complete.

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace impactkit {

/// An output file could not be created, written or moved into place. The
/// message names the file and the system's reason, on one line.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class AtomicOutputFile {
 public:
  /// Creates the temporary file at once, so that an unwritable target (a
  /// missing directory, no permission) fails before any work is done.
  /// Throws OutputError.
  explicit AtomicOutputFile(std::filesystem::path path);
  /// Removes the temporary file unless Commit() succeeded.
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  /// Appends bytes. Throws OutputError (disk full, ...).
  void Write(std::string_view bytes);
  /// Closes the temporary file and renames it onto the target, replacing
  /// any file there. Throws OutputError; the target is then untouched.
  void Commit();

  const std::filesystem::path& Path() const { return path_; }

 private:
  void Discard() noexcept;
  [[noreturn]] void Fail(std::string_view action) const;

  std::filesystem::path path_;
  std::filesystem::path temporary_path_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

}  // namespace impactkit
