#include "common/provenance.hpp"

#include <fmt/format.h>

#include <cstdint>
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

/// FNV-1a, 64 bits, of the file's bytes: it identifies a version of a
/// system file (not a security hash); no library of the stack has a hash.
std::string Fnv1a64OfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(fmt::format("{}: cannot read the system file again", path));
  std::uint64_t hash = 14695981039346656037ull;
  for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
    hash ^= static_cast<unsigned char>(*it);
    hash *= 1099511628211ull;
  }
  return fmt::format("{:016x}", hash);
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
                                 : fmt::format("{} (FNV-1a 64 {})", system_file, system_hash);
  return fmt::format("impactkit {}\ncommand: {}\nsystem: {}\nparameters: {}\nrun: {}", version,
                     command, system, parameters, run);
}

nlohmann::json Provenance::Json() const {
  return {{"impactkit_version", version},
          {"command", command},
          {"system_file", system_file.empty() ? nlohmann::json() : nlohmann::json(system_file)},
          {"system_fnv1a64", system_hash.empty() ? nlohmann::json() : nlohmann::json(system_hash)},
          {"parameters", parameters},
          {"run", run}};
}

Provenance MakeProvenance(const SystemOptions& options, const System& system, std::string run) {
  Provenance p;
  p.version = IMPACTKIT_VERSION;
  p.command = CommandLine();
  p.system_file = options.file;
  if (!options.file.empty()) p.system_hash = Fnv1a64OfFile(options.file);
  p.parameters = ParameterList(system);
  p.run = std::move(run);
  return p;
}

}  // namespace impactkit::cli
