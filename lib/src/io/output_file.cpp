#include "impactkit/io/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

namespace impactkit {
namespace {

/// A name no other writer uses: hidden, beside the target (rename is atomic
/// only within one file system), unique per process and per call.
std::filesystem::path TemporaryPathFor(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  const std::string name =
      fmt::format(".{}.{}-{}.tmp", path.filename().string(), ::getpid(), counter++);
  return path.parent_path() / name;
}

}  // namespace

AtomicOutputFile::AtomicOutputFile(std::filesystem::path path) : path_(std::move(path)) {
  std::error_code ignored;
  if (path_.filename().empty() || std::filesystem::is_directory(path_, ignored)) {
    throw OutputError(
        fmt::format("cannot write {}: it names a directory, not a file", path_.string()));
  }
  // O_EXCL: never truncate someone else's file; 0666 lets the umask decide
  // the permissions, as for any file the user creates.
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temporary_path_ = TemporaryPathFor(path_);
    fd = ::open(temporary_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) Fail("create");
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    const int error = errno;
    ::close(fd);
    ::unlink(temporary_path_.c_str());
    errno = error;
    Fail("create");
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) Discard();
}

void AtomicOutputFile::Write(std::string_view bytes) {
  if (file_ == nullptr) throw OutputError(fmt::format("{} is already closed", path_.string()));
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) Fail("write");
}

void AtomicOutputFile::Commit() {
  if (file_ == nullptr) throw OutputError(fmt::format("{} is already closed", path_.string()));
  // fclose flushes: its result is the last word on whether every byte landed.
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (closed != 0) Fail("write");
  if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) Fail("write");
  committed_ = true;
}

void AtomicOutputFile::Discard() noexcept {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  ::unlink(temporary_path_.c_str());
}

void AtomicOutputFile::Fail(std::string_view action) const {
  throw OutputError(fmt::format("cannot {} {}: {}", action, path_.string(), std::strerror(errno)));
}

}  // namespace impactkit
