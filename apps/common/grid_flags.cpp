#include "common/grid_flags.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "common/limits.hpp"
#include "impactkit/core/errors.hpp"

namespace impactkit::cli {
void AddGridRunOptions(CLI::App& command, std::optional<int>& threads, std::string& checkpoint) {
  const std::string group = "Run";
  command
      .add_option("--threads", threads,
                  "Worker threads of each process (default: all cores; one per rank under "
                  "mpirun); results do not depend on it")
      ->type_name("N")
      ->check(AtMost(kMaxThreads, "threads"))
      ->group(group);
  command
      .add_option("--checkpoint", checkpoint,
                  "Directory recording finished work units as they complete; rerun the same "
                  "command to resume (a directory of another run is refused)")
      ->type_name("DIR")
      ->check(OutputPath("folder"))
      ->group(group);
}

GridDriveOptions DriveOptionsOf(const std::string& label, std::optional<int> threads,
                                const std::string& checkpoint, const GridProcesses& processes) {
  Require(!threads || *threads >= 1,
          fmt::format("--threads must be >= 1, got {}", threads.value_or(0)));
  GridDriveOptions options;
  options.label = label;
  options.checkpoint = checkpoint;
  options.threads = threads ? *threads
                    : processes.Ranks() > 1
                        ? 1
                        : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return options;
}

std::string RunReport(const GridOutcome& outcome, const GridDriveOptions& options,
                      const GridProcesses& processes) {
  std::string text =
      fmt::format("{} cells in {:.2f} s on {} thread{} x {} rank{}", outcome.cells.size(),
                  outcome.seconds, options.threads, options.threads == 1 ? "" : "s",
                  processes.Ranks(), processes.Ranks() == 1 ? "" : "s");
  if (!options.checkpoint.empty()) {
    text += fmt::format(" ({} computed, {} resumed from the checkpoint)", outcome.computed,
                        outcome.resumed);
  }
  return text;
}

}  // namespace impactkit::cli
