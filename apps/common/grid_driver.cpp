#include "common/grid_driver.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "impactkit/core/errors.hpp"
#include "impactkit/io/checkpoint.hpp"
#if IMPACTKIT_HAVE_MPI
#include "common/grid_mpi.hpp"
#endif

namespace impactkit::cli {
namespace {

using Clock = std::chrono::steady_clock;

/// The world size an MPI launcher gave this process (Open MPI, then the
/// PMI variables of MPICH's and Slurm's launchers); 1 when none did.
int LaunchedRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
  }
  return 1;
}

/// Cells done of all, with the time left, on stderr rewritten in place;
/// like ProgressLine (progress.hpp), only on a terminal and after a second.
class GridProgress {
 public:
  GridProgress(std::string label, std::int64_t total, std::int64_t resumed)
      : enabled_(::isatty(STDERR_FILENO) == 1),
        label_(std::move(label)),
        total_(total),
        done_(resumed),
        resumed_(resumed) {}
  ~GridProgress() {
    if (drawn_) fmt::print(stderr, "\r\033[K");
  }
  GridProgress(const GridProgress&) = delete;
  GridProgress& operator=(const GridProgress&) = delete;

  void Add(std::int64_t cells) {
    done_ += cells;
    const Clock::time_point now = Clock::now();
    if (!enabled_ || now - start_ < std::chrono::seconds(1) ||
        now - last_drawn_ < std::chrono::milliseconds(200)) {
      return;
    }
    // The rate of this run's cells only: resumed ones cost nothing.
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double left =
        elapsed / static_cast<double>(done_ - resumed_) * static_cast<double>(total_ - done_);
    fmt::print(stderr, "\r\033[Kimpactkit: {} {:3.0f}% ({} of {} cells), about {} left", label_,
               100.0 * static_cast<double>(done_) / static_cast<double>(total_), done_, total_,
               Duration(left));
    last_drawn_ = now;
    drawn_ = true;
  }

 private:
  static std::string Duration(double seconds) {
    if (seconds < 120) return fmt::format("{:.0f} s", seconds);
    if (seconds < 7200) return fmt::format("{:.0f} min", seconds / 60);
    return fmt::format("{:.1f} h", seconds / 3600);
  }

  const bool enabled_;
  const std::string label_;
  const std::int64_t total_;
  std::int64_t done_;
  const std::int64_t resumed_;
  const Clock::time_point start_ = Clock::now();
  Clock::time_point last_drawn_{};
  bool drawn_ = false;
};

/// The line ResumeHintOnSignal writes, prepared before any signal: a
/// handler may only write(2) bytes that already exist.
std::array<char, 1024> resume_hint{};
std::size_t resume_hint_length = 0;

extern "C" void SayResumeAndDie(int signal) {
  [[maybe_unused]] const ssize_t written =
      ::write(STDERR_FILENO, resume_hint.data(), resume_hint_length);
  // SA_RESETHAND restored the default action: the signal, delivered when
  // this handler returns, ends the process as it would have (status 128 +
  // signal for the shell and the batch system).
  ::raise(signal);
}

/// While a checkpoint is being written: Ctrl-C (SIGINT) or SIGTERM (a batch
/// system's time limit) says on stderr that the finished units are kept
/// and that the same command resumes, then ends the process as the signal
/// would have. A signal the process was started ignoring (SIGINT of a
/// background job) stays ignored.
class ResumeHintOnSignal {
 public:
  explicit ResumeHintOnSignal(const std::string& directory) {
    const std::string hint = fmt::format(
        "{}impactkit: interrupted; the units finished so far are saved in {}: run the same "
        "command again to resume from them\n",
        ::isatty(STDERR_FILENO) == 1 ? "\r\033[K" : "", directory);
    resume_hint_length = std::min(hint.size(), resume_hint.size());
    std::copy_n(hint.begin(), resume_hint_length, resume_hint.begin());
    struct sigaction action {};
    action.sa_handler = SayResumeAndDie;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    for (std::size_t i = 0; i < kSignals.size(); ++i) {
      ::sigaction(kSignals[i], nullptr, &previous_[i]);
      if (previous_[i].sa_handler != SIG_IGN) ::sigaction(kSignals[i], &action, nullptr);
    }
  }
  ~ResumeHintOnSignal() {
    for (std::size_t i = 0; i < kSignals.size(); ++i)
      ::sigaction(kSignals[i], &previous_[i], nullptr);
  }
  ResumeHintOnSignal(const ResumeHintOnSignal&) = delete;
  ResumeHintOnSignal& operator=(const ResumeHintOnSignal&) = delete;

 private:
  static constexpr std::array<int, 2> kSignals = {SIGINT, SIGTERM};
  std::array<struct sigaction, 2> previous_{};
};

/// The writer's side: which units are left, and every cell received.
class Collector {
 public:
  Collector(const GridTask& task, const GridDriveOptions& options)
      : task_(task), label_(options.label) {
    if (!options.checkpoint.empty()) {
      checkpoint_ = std::make_unique<Checkpoint>(options.checkpoint, task.Identity(), task.Units());
      resume_hint_ = std::make_unique<ResumeHintOnSignal>(options.checkpoint);
      for (const DamagedUnit& damaged : checkpoint_->Damaged()) {
        fmt::print(
            stderr,
            "impactkit: warning: checkpoint unit {} is damaged ({}: {}); computing it again\n",
            damaged.unit, damaged.file.string(), damaged.reason);
      }
    }
    std::vector<bool> finished(task.Units(), false);
    if (checkpoint_) {
      for (const auto& [unit, cells] : checkpoint_->Finished()) {
        finished[unit] = true;
        cells_.insert(cells_.end(), cells.begin(), cells.end());
      }
    }
    resumed_ = static_cast<std::int64_t>(cells_.size());
    for (int unit = 0; unit < task.Units(); ++unit) {
      if (!finished[unit]) pending_.push_back(unit);
    }
  }

  void StartProgress() {
    progress_ = std::make_unique<GridProgress>(label_, task_.Cells(), resumed_);
  }

  /// Thread-safe.
  int Take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return next_ < pending_.size() ? pending_[next_++] : -1;
  }

  /// Thread-safe.
  void Receive(int unit, std::vector<GridCell>& cells) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (checkpoint_) checkpoint_->Record(unit, cells);
    computed_ += static_cast<std::int64_t>(cells.size());
    progress_->Add(static_cast<std::int64_t>(cells.size()));
    cells_.insert(cells_.end(), cells.begin(), cells.end());
  }

  GridOutcome Outcome(double seconds) {
    progress_.reset();
    return GridOutcome{InIndexOrder(std::move(cells_), task_.Cells()), resumed_, computed_,
                       seconds};
  }

 private:
  const GridTask& task_;
  const std::string label_;
  std::unique_ptr<Checkpoint> checkpoint_;
  std::unique_ptr<ResumeHintOnSignal> resume_hint_;
  std::unique_ptr<GridProgress> progress_;
  std::vector<int> pending_;
  std::size_t next_ = 0;
  std::vector<GridCell> cells_;
  std::int64_t resumed_ = 0;
  std::int64_t computed_ = 0;
  std::mutex mutex_;
};

#if IMPACTKIT_HAVE_MPI
/// Rank 0 computes on its own threads while its main thread serves the
/// other ranks.
void RunWriterWithRanks(const GridTask& task, int threads, int ranks, Collector& collector) {
  std::exception_ptr error;
  std::thread local([&] {
    try {
      RunUnits(
          task, threads, [&] { return collector.Take(); },
          [&](int unit, std::vector<GridCell>& cells) { collector.Receive(unit, cells); });
    } catch (...) {
      error = std::current_exception();
    }
  });
  try {
    mpi::Serve(
        ranks, [&] { return collector.Take(); },
        [&](int unit, std::vector<GridCell>& cells) { collector.Receive(unit, cells); });
  } catch (const std::exception& e) {
    mpi::Abort(e.what());
  }
  local.join();
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      mpi::Abort(e.what());
    }
  }
}

void RunWorker(const GridTask& task, int threads) {
  try {
    RunUnits(task, threads, mpi::Request,
             [](int unit, std::vector<GridCell>& cells) { mpi::Send(unit, cells); });
  } catch (const std::exception& e) {
    mpi::Abort(e.what());
  }
}
#endif

}  // namespace

GridProcesses::GridProcesses() {
  const int launched = LaunchedRanks();
#if IMPACTKIT_HAVE_MPI
  if (launched > 1) {
    std::tie(rank_, ranks_) = mpi::Start();
    started_mpi_ = true;
  }
#else
  Require(launched == 1,
          fmt::format("launched as one of {} MPI processes, but this impactkit was built "
                      "without MPI (install libopenmpi-dev, scripts/setup.sh, and rebuild)",
                      launched));
#endif
}

GridProcesses::~GridProcesses() {
#if IMPACTKIT_HAVE_MPI
  // Unwinding from an error of this rank alone (an output it could not
  // open), the others may wait for it in a collective call: finalising
  // could wait with them. Without it, the process ends with its error,
  // and mpirun ends the others.
  if (started_mpi_ && std::uncaught_exceptions() == 0) mpi::Finish();
#endif
}

std::optional<GridOutcome> DriveGrid(const GridTask& task, const GridDriveOptions& options,
                                     const GridProcesses& processes) {
  const Clock::time_point start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  if (processes.Ranks() == 1) {
    Collector collector(task, options);
    collector.StartProgress();
    RunUnits(
        task, options.threads, [&] { return collector.Take(); },
        [&](int unit, std::vector<GridCell>& cells) { collector.Receive(unit, cells); });
    return collector.Outcome(seconds());
  }
#if IMPACTKIT_HAVE_MPI
  if (!processes.Writer()) {
    // The writer opens the checkpoint first; a refusal ends every rank.
    if (!mpi::Agree(true)) return std::nullopt;
    RunWorker(task, options.threads);
    return std::nullopt;
  }
  std::unique_ptr<Collector> collector;
  try {
    collector = std::make_unique<Collector>(task, options);
  } catch (...) {
    mpi::Agree(false);
    throw;
  }
  mpi::Agree(true);
  collector->StartProgress();
  RunWriterWithRanks(task, options.threads, processes.Ranks(), *collector);
  return collector->Outcome(seconds());
#else
  return std::nullopt;  // unreachable: GridProcesses refuses more than one rank
#endif
}

}  // namespace impactkit::cli
