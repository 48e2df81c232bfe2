#include "common/provenance.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <fstream>
#include <iterator>
#include <vector>

#include "impactkit/core/errors.hpp"

namespace impactkit::cli {
namespace {

std::string& CommandLine() {
  static std::string line = "impactkit";
  return line;
}

/// `word` as a POSIX shell reads it back: bare when it has only characters
/// no shell treats specially, else in single quotes.
std::string ShellQuoted(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of(
                                          "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                          "0123456789_-+=.,/:@%") == std::string::npos;
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// zlib's CRC-32 of the file's bytes: it identifies a version of a system
/// file (not a security hash).
std::string Crc32OfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(fmt::format("{}: cannot read the system file again", path));
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto crc =
      ::crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size()));
  return fmt::format("{:08x}", crc);
}

}  // namespace

void RecordCommandLine(int argc, const char* const* argv) {
  std::vector<std::string> words = {"impactkit"};
  for (int i = 1; i < argc; ++i) words.push_back(ShellQuoted(argv[i]));
  CommandLine() = fmt::format("{}", fmt::join(words, " "));
}

std::string CommandLineProvenance() {
  return fmt::format("impactkit {}\ncommand: {}", IMPACTKIT_VERSION, CommandLine());
}

std::string Provenance::Text() const {
  const std::string system = system_file.empty()
                                 ? "the paper's system (built in)"
                                 : fmt::format("{} (CRC-32 {})", system_file, system_hash);
  return fmt::format("impactkit {}\ncommand: {}\nsystem: {}\nparameters: {}\nrun: {}", version,
                     command, system, parameters, run);
}

nlohmann::json Provenance::Json() const {
  return {{"impactkit_version", version},
          {"command", command},
          {"system_file", system_file.empty() ? nlohmann::json() : nlohmann::json(system_file)},
          {"system_crc32", system_hash.empty() ? nlohmann::json() : nlohmann::json(system_hash)},
          {"parameters", parameters},
          {"run", run}};
}

Provenance MakeProvenance(const SystemOptions& options, const System& system, std::string run) {
  Provenance p;
  p.version = IMPACTKIT_VERSION;
  p.command = CommandLine();
  p.system_file = options.file;
  if (!options.file.empty()) p.system_hash = Crc32OfFile(options.file);
  p.parameters = ParameterList(system);
  p.run = std::move(run);
  return p;
}

}  // namespace impactkit::cli
