#include "impactkit/io/checkpoint.hpp"

#include <fmt/format.h>

#include <charconv>
#include <fstream>
#include <sstream>

#include "impactkit/core/errors.hpp"
#include "impactkit/io/output_file.hpp"

namespace impactkit {
namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(fmt::format("cannot read checkpoint file {}", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteWhole(const fs::path& path, const std::string& text) {
  AtomicOutputFile file(path);
  file.Write(text);
  file.Commit();
}

/// N of "unit-N.txt", or -1 for any other name.
int UnitOfName(const std::string& name) {
  const std::string prefix = "unit-", suffix = ".txt";
  if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) ||
      !name.ends_with(suffix)) {
    return -1;
  }
  int unit = -1;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size() - suffix.size();
  const auto [end, error] = std::from_chars(first, last, unit);
  return error == std::errc() && end == last ? unit : -1;
}

}  // namespace

Checkpoint::Checkpoint(fs::path directory, const std::string& identity, int units)
    : directory_(std::move(directory)) {
  const std::string run = fmt::format("{}\nunits={}\n", identity, units);
  std::error_code error;
  fs::create_directories(directory_, error);
  if (error || !fs::is_directory(directory_)) {
    throw OutputError(fmt::format("cannot create checkpoint directory {}: {}", directory_.string(),
                                  error ? error.message() : "not a directory"));
  }
  const fs::path run_file = directory_ / "run.txt";
  if (!fs::exists(run_file)) {
    for (const fs::directory_entry& entry : fs::directory_iterator(directory_)) {
      Require(UnitOfName(entry.path().filename().string()) < 0,
              fmt::format("checkpoint {} has unit files but no run.txt: not a checkpoint of "
                          "this run; use another directory",
                          directory_.string()));
    }
    WriteWhole(run_file, run);
    return;
  }
  Require(ReadAll(run_file) == run,
          fmt::format("checkpoint {} belongs to another run (another grid, system or options); "
                      "use another directory or remove it",
                      directory_.string()));
  for (const fs::directory_entry& entry : fs::directory_iterator(directory_)) {
    const int unit = UnitOfName(entry.path().filename().string());
    if (unit < 0) continue;
    Require(unit < units, fmt::format("checkpoint {}: unit {} beyond the run's {} units",
                                      directory_.string(), unit, units));
    std::istringstream lines(ReadAll(entry.path()));
    std::vector<GridCell>& cells = finished_[unit];
    for (std::string line; std::getline(lines, line);) cells.push_back(CellFromText(line));
  }
}

void Checkpoint::Record(int unit, const std::vector<GridCell>& cells) {
  std::string text;
  for (const GridCell& cell : cells) text += CellToText(cell) + "\n";
  WriteWhole(directory_ / fmt::format("unit-{}.txt", unit), text);
  finished_[unit] = cells;
}

}  // namespace impactkit
