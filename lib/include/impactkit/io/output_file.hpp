#pragma once
/// \file output_file.hpp
/// Output files that appear whole or not at all. The bytes go to a hidden
/// temporary file beside the target, which Commit() renames over it (atomic
/// on POSIX file systems): a run that fails, or is interrupted, never leaves
/// a half-written table behind for a plotting script to read as if complete.
///
/// Temporaries are named `.impactkit.PID.SERIAL.HOST.tmp`: short, so that
/// any target name the file system accepts (up to NAME_MAX bytes) works, and
/// recognisable, so that they are removed
///  - on SIGINT, SIGTERM and SIGHUP: creating a temporary installs a
///    handler for each of these signals still at its default action; the
///    handler unlinks every temporary not yet committed (unlink is
///    async-signal-safe), restores the default action and re-raises, so the
///    process ends as it would have;
///  - after SIGKILL, a crash or a power cut: the first temporary created in a
///    directory removes the temporaries there of processes of this host that
///    no longer run.

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
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
  /// missing directory, no permission, an empty path, a directory) fails
  /// before any work is done. Throws OutputError.
  explicit AtomicOutputFile(std::filesystem::path path);
  /// Removes the temporary file unless Commit() succeeded.
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  /// Appends bytes. Throws OutputError (disk full, ...).
  void Write(std::string_view bytes);
  /// Flushes and closes the temporary file, leaving it to be renamed: the
  /// last point at which writing can fail (a full disk shows here). Throws
  /// OutputError. Commit() closes too; OutputSet closes every file of a set
  /// before renaming any.
  void Close();
  /// Closes the temporary file (if still open) and renames it onto the
  /// target, replacing any file there. Throws OutputError; the target is
  /// then untouched.
  void Commit();

  const std::filesystem::path& Path() const { return path_; }
  const std::filesystem::path& TemporaryPath() const { return temporary_path_; }

 private:
  void Discard() noexcept;
  [[noreturn]] void Fail(std::string_view action) const;

  std::filesystem::path path_;
  std::filesystem::path temporary_path_;
  std::FILE* file_ = nullptr;
  bool closed_ = false;
  bool committed_ = false;
  int slot_ = -1;  ///< in the registry the signal handler cleans; -1: not registered
};

/// The name of the `serial`-th temporary of process `pid` on this host:
/// ".impactkit.PID.SERIAL.HOST.tmp".
std::string TemporaryFileName(long pid, unsigned long serial);

/// Removes the temporaries in `directory` left by processes of this host
/// that no longer run (a PID in use by another user's process counts as
/// running); returns how many. Never throws: cleaning is a courtesy.
/// AtomicOutputFile calls it once per directory and process.
std::size_t RemoveStaleTemporaries(const std::filesystem::path& directory) noexcept;

}  // namespace impactkit
