#include "common/grid_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>

#include "common/limits.hpp"
#include "impactkit/core/errors.hpp"

namespace impactkit::cli {
namespace {

/// Shortest round-trip form; NaN (undefined) as an empty field.
std::string Number(double value) { return std::isnan(value) ? "" : fmt::format("{}", value); }

}  // namespace

PeriodLabels LabelsOf(const GridCell& cell) {
  PeriodLabels labels{ToString(cell.kind), "", ""};
  if (cell.q > 0) {
    labels.p = cell.kind == MotionKind::kSticking ? "inf" : std::to_string(cell.p);
    labels.q = std::to_string(cell.q);
  }
  return labels;
}

std::string CellFields(const GridCell& cell) {
  const PeriodLabels labels = LabelsOf(cell);
  return fmt::format("{},{},{},{},{},{}", labels.kind, labels.p, labels.q, Number(cell.max_v),
                     Number(cell.range_xN), Number(cell.lyapunov));
}

std::string MotionLabel(const GridCell& cell) {
  switch (cell.kind) {
    case MotionKind::kPeriodic:
      return fmt::format("P({},{})", cell.p, cell.q);
    case MotionKind::kSticking:
      return fmt::format("P(inf,{})", cell.q);
    case MotionKind::kNonImpacting:
      return "non-impacting";
    case MotionKind::kChaotic:
      return "chaotic";
    case MotionKind::kUnresolved:
      return "unresolved";
  }
  return "unresolved";
}

std::vector<std::string> ClassColors(int count) {
  // Paul Tol's "muted" and "light" qualitative schemes: distinct for most
  // readers, colour-blind ones included.
  static constexpr std::array<const char*, 18> kFixed = {
      "#332288", "#88ccee", "#44aa99", "#117733", "#999933", "#ddcc77",
      "#cc6677", "#882255", "#aa4499", "#77aadd", "#ee8866", "#eedd88",
      "#ffaabb", "#99ddff", "#e7298a", "#bbcc33", "#aaaa00", "#d95f02"};
  std::vector<std::string> colors;
  for (int i = 0; i < count; ++i) {
    if (i < static_cast<int>(kFixed.size())) {
      colors.emplace_back(kFixed[i]);
      continue;
    }
    // Hues a golden angle apart never repeat; lightness alternates so that
    // neighbours in the legend differ in two ways.
    const double hue = std::fmod(0.618033988749895 * i, 1.0) * 6.0;
    const double light = i % 2 == 0 ? 0.45 : 0.7;
    const double chroma = 0.6, x = chroma * (1.0 - std::abs(std::fmod(hue, 2.0) - 1.0));
    const int sector = static_cast<int>(hue);
    const std::array<std::array<double, 3>, 6> rgb = {{{chroma, x, 0},
                                                       {x, chroma, 0},
                                                       {0, chroma, x},
                                                       {0, x, chroma},
                                                       {x, 0, chroma},
                                                       {chroma, 0, x}}};
    auto channel = [&](double c) {
      return static_cast<int>(std::lround(255.0 * std::clamp(c + light - chroma / 2, 0.0, 1.0)));
    };
    colors.push_back(fmt::format("#{:02x}{:02x}{:02x}", channel(rgb[sector][0]),
                                 channel(rgb[sector][1]), channel(rgb[sector][2])));
  }
  return colors;
}

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
