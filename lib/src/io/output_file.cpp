#include "impactkit/io/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <mutex>
#include <set>
#include <string>

namespace impactkit {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kPrefix = ".impactkit.";
constexpr std::string_view kSuffix = ".tmp";

/// This host's name as it appears in temporary names: at most 64 bytes of
/// letters, digits, '-' and '.', so that the name stays short and safe.
const std::string& HostTag() {
  static const std::string tag = [] {
    std::array<char, 256> buffer{};
    if (::gethostname(buffer.data(), buffer.size() - 1) != 0) buffer[0] = '\0';
    std::string host(buffer.data());
    if (host.size() > 64) host.resize(64);
    for (char& c : host) {
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
    }
    return host.empty() ? std::string("localhost") : host;
  }();
  return tag;
}

// --- Temporaries the signal handler removes -------------------------------
//
// A fixed table, so that the handler touches no allocator and no lock: a
// slot is free (0), being filled or emptied (1), or holds the absolute path
// of a live temporary (2). The handler reads only slots in state 2, through
// lock-free atomics. A temporary that finds no free slot is not registered;
// the stale cleanup of a later run still removes it.

constexpr int kFree = 0, kBusy = 1, kRegistered = 2;
constexpr std::size_t kSlots = 128;
constexpr std::size_t kSlotPath = 4096;

struct Slot {
  std::atomic<int> state{kFree};
  char path[kSlotPath];
};
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

constexpr int kCleanedSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void RemoveTemporariesAndReraise(int signal) {
  const int saved_errno = errno;
  for (Slot& slot : g_slots) {
    if (slot.state.load(std::memory_order_acquire) == kRegistered) ::unlink(slot.path);
  }
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  ::sigaction(signal, &action, nullptr);
  errno = saved_errno;
  // Pending until this handler returns (the signal is blocked inside it),
  // then delivered with the default action: the process ends as it would
  // have without us.
  ::raise(signal);
}

/// Installs the handler for the signals at their default action; a program
/// that chose its own handling (or to ignore them) keeps it. Asked at every
/// registration (one system call per signal and output file), so that a
/// disposition reset to the default later, or in a forked child, is covered.
void InstallSignalCleanup() {
  for (int signal : kCleanedSignals) {
    struct sigaction current {};
    if (::sigaction(signal, nullptr, &current) != 0) continue;
    if ((current.sa_flags & SA_SIGINFO) != 0 || current.sa_handler != SIG_DFL) continue;
    struct sigaction action {};
    action.sa_handler = RemoveTemporariesAndReraise;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    ::sigaction(signal, &action, nullptr);
  }
}

int Register(const fs::path& temporary) {
  std::error_code error;
  const std::string path = fs::absolute(temporary, error).string();
  if (error || path.size() >= kSlotPath) return -1;
  InstallSignalCleanup();
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kBusy)) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    g_slots[i].state.store(kRegistered, std::memory_order_release);
    return static_cast<int>(i);
  }
  return -1;
}

void Unregister(int slot) noexcept {
  if (slot >= 0) g_slots[slot].state.store(kFree, std::memory_order_release);
}

// --- Stale temporaries ------------------------------------------------------

/// The PID of a temporary of this host named as TemporaryFileName names
/// them, or -1.
long StalePid(std::string_view name) {
  if (name.size() <= kPrefix.size() + kSuffix.size() || !name.starts_with(kPrefix) ||
      !name.ends_with(kSuffix)) {
    return -1;
  }
  name.remove_prefix(kPrefix.size());
  name.remove_suffix(kSuffix.size());
  long pid = 0;
  unsigned long serial = 0;
  auto [after_pid, pid_error] = std::from_chars(name.data(), name.data() + name.size(), pid);
  if (pid_error != std::errc() || after_pid == name.data() + name.size() || *after_pid != '.') {
    return -1;
  }
  const char* serial_begin = after_pid + 1;
  auto [after_serial, serial_error] =
      std::from_chars(serial_begin, name.data() + name.size(), serial);
  if (serial_error != std::errc() || after_serial == name.data() + name.size() ||
      *after_serial != '.') {
    return -1;
  }
  const std::string_view host(after_serial + 1, name.data() + name.size() - (after_serial + 1));
  return host == HostTag() && pid > 0 ? pid : -1;
}

bool Running(long pid) {
  if (pid == static_cast<long>(::getpid())) return true;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH;
}

void RemoveStaleTemporariesOnce(const fs::path& directory) {
  static std::mutex mutex;
  static std::set<std::string> cleaned;
  std::error_code error;
  const std::string key = fs::absolute(directory, error).lexically_normal().string();
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (error || !cleaned.insert(key).second) return;
  }
  RemoveStaleTemporaries(directory);
}

}  // namespace

std::string TemporaryFileName(long pid, unsigned long serial) {
  return fmt::format("{}{}.{}.{}{}", kPrefix, pid, serial, HostTag(), kSuffix);
}

std::size_t RemoveStaleTemporaries(const fs::path& directory) noexcept {
  std::size_t removed = 0;
  try {
    std::error_code error;
    for (fs::directory_iterator it(directory, error), end; !error && it != end;
         it.increment(error)) {
      const long pid = StalePid(it->path().filename().string());
      if (pid < 0 || Running(pid)) continue;
      std::error_code ignored;
      if (fs::remove(it->path(), ignored)) ++removed;
    }
  } catch (...) {
    // Out of memory while listing: leave the rest for another run.
  }
  return removed;
}

AtomicOutputFile::AtomicOutputFile(fs::path path) : path_(std::move(path)) {
  if (path_.empty()) throw OutputError("cannot write a file with an empty name");
  std::error_code ignored;
  if (path_.filename().empty() || path_.filename() == "." || path_.filename() == ".." ||
      fs::is_directory(path_, ignored)) {
    throw OutputError(
        fmt::format("cannot write {}: it names a directory, not a file", path_.string()));
  }
  const fs::path directory = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
  RemoveStaleTemporariesOnce(directory);
  // O_EXCL: never truncate someone else's file; 0666 lets the umask decide
  // the permissions, as for any file the user creates.
  static std::atomic<unsigned long> serial{0};
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temporary_path_ = directory / TemporaryFileName(::getpid(), serial++);
    fd = ::open(temporary_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) Fail("create");
  slot_ = Register(temporary_path_);
  file_ = ::fdopen(fd, "wb");
  if (file_ == nullptr) {
    const int error = errno;
    ::close(fd);
    Discard();
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

void AtomicOutputFile::Close() {
  if (file_ == nullptr) throw OutputError(fmt::format("{} is already closed", path_.string()));
  // fclose flushes: its result is the last word on whether every byte landed.
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (closed != 0) Fail("write");
  closed_ = true;
}

void AtomicOutputFile::Commit() {
  if (committed_ || (file_ == nullptr && !closed_)) {
    throw OutputError(fmt::format("{} is already closed", path_.string()));
  }
  if (file_ != nullptr) Close();
  if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) Fail("write");
  committed_ = true;
  Unregister(slot_);
  slot_ = -1;
}

void AtomicOutputFile::Discard() noexcept {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  ::unlink(temporary_path_.c_str());
  Unregister(slot_);
  slot_ = -1;
}

void AtomicOutputFile::Fail(std::string_view action) const {
  throw OutputError(fmt::format("cannot {} {}: {}", action, path_.string(), std::strerror(errno)));
}

}  // namespace impactkit
