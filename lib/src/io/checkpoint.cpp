#include "impactkit/io/checkpoint.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string_view>

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

constexpr std::string_view kSealTag = "crc32 ";
constexpr std::size_t kSealSize = kSealTag.size() + 8 + 1;  // tag, 8 hex digits, line break

std::uint32_t Crc32(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      ::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

/// `body`, then the line that seals it: its CRC-32.
std::string Sealed(const std::string& body) {
  return fmt::format("{}{}{:08x}\n", body, kSealTag, Crc32(body));
}

/// What a sealed file holds: its body, or why it cannot be trusted.
struct Unsealed {
  std::string body;
  std::string damage;  ///< empty: whole, as written
};

Unsealed Unseal(const std::string& text) {
  if (text.empty()) return {"", "empty"};
  // The seal is the last kSealSize bytes, a line of its own.
  const std::size_t seal = text.size() - std::min(text.size(), kSealSize);
  const bool sealed = text.size() >= kSealSize && text.back() == '\n' &&
                      text.compare(seal, kSealTag.size(), kSealTag) == 0 &&
                      (seal == 0 || text[seal - 1] == '\n');
  if (!sealed) return {"", "its last line is no CRC-32: cut short or added to"};
  std::uint32_t recorded = 0;
  const char* digits = text.data() + seal + kSealTag.size();
  const auto [end, error] = std::from_chars(digits, digits + 8, recorded, 16);
  if (error != std::errc() || end != digits + 8) return {"", "its CRC-32 line is unreadable"};
  std::string body = text.substr(0, seal);
  if (Crc32(body) != recorded) return {"", "its CRC-32 does not match its contents"};
  return {std::move(body), ""};
}

void WriteWhole(const fs::path& path, const std::string& body) {
  AtomicOutputFile file(path);
  file.Write(Sealed(body));
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
  const Unsealed recorded = Unseal(ReadAll(run_file));
  Require(recorded.damage.empty(),
          fmt::format("checkpoint {}: run.txt is damaged ({}), so its units cannot be told "
                      "to be this run's; remove the directory or use another one",
                      directory_.string(), recorded.damage));
  Require(recorded.body == run,
          fmt::format("checkpoint {} belongs to another run (another grid, system or options); "
                      "use another directory or remove it",
                      directory_.string()));
  for (const fs::directory_entry& entry : fs::directory_iterator(directory_)) {
    const int unit = UnitOfName(entry.path().filename().string());
    if (unit < 0) continue;
    Require(unit < units, fmt::format("checkpoint {}: unit {} beyond the run's {} units",
                                      directory_.string(), unit, units));
    Open(unit, entry.path());
  }
  std::sort(damaged_.begin(), damaged_.end(),
            [](const DamagedUnit& a, const DamagedUnit& b) { return a.unit < b.unit; });
}

void Checkpoint::Open(int unit, const fs::path& file) {
  Unsealed contents = Unseal(ReadAll(file));
  std::vector<GridCell> cells;
  if (contents.damage.empty()) {
    // A matching checksum over a line that does not parse: written so (by
    // hand, or by another version), and not trusted either.
    try {
      std::istringstream lines(contents.body);
      for (std::string line; std::getline(lines, line);) cells.push_back(CellFromText(line));
    } catch (const InvalidInput& error) {
      contents.damage = error.what();
    }
  }
  if (contents.damage.empty()) {
    finished_[unit] = std::move(cells);
  } else {
    damaged_.push_back({unit, file, std::move(contents.damage)});
  }
}

void Checkpoint::Record(int unit, const std::vector<GridCell>& cells) {
  std::string text;
  for (const GridCell& cell : cells) text += CellToText(cell) + "\n";
  WriteWhole(directory_ / fmt::format("unit-{}.txt", unit), text);
  finished_[unit] = cells;
}

}  // namespace impactkit
