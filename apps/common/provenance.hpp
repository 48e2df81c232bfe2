#pragma once
/// \file common/provenance.hpp
/// What produced an output, at the head of every output file (comment lines
/// of a CSV, a "provenance" object of a JSON): the version, the command as
/// typed, the system (its file with a checksum of the file's bytes, and every
/// named parameter resolved) and the run's resolved settings. Enough to
/// repeat the run from the output alone, and to notice when the system file
/// has changed since.

#include <nlohmann/json.hpp>
#include <string>

#include "common/system_options.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::cli {

/// Keeps the command line for the outputs' provenance; main() calls it once.
void RecordCommandLine(int argc, const char* const* argv);

/// "impactkit VERSION\ncommand: ...": what a figure records of its run (the
/// data files beside it carry the whole provenance).
std::string CommandLineProvenance();

struct Provenance {
  std::string version;      ///< impactkit's version
  std::string command;      ///< the command line, quoted for a POSIX shell
  std::string system_file;  ///< --system FILE as given; empty for the paper's system
  std::string system_hash;  ///< zlib's CRC-32 of the file's bytes, 8 hex digits
  std::string parameters;   ///< every named parameter, as --set takes them
  std::string run;          ///< the command's settings, every default resolved

  /// Lines "impactkit VERSION", "command: ...", "system: ...",
  /// "parameters: ...", "run: ..." (a CSV's comment lines).
  std::string Text() const;
  /// {impactkit_version, command, system_file, system_crc32, parameters, run}.
  nlohmann::json Json() const;
};

/// The provenance of a run of `system`, named by `options`, with settings `run`.
/// Throws InvalidInput if the system file can no longer be read.
Provenance MakeProvenance(const SystemOptions& options, const System& system, std::string run);

}  // namespace impactkit::cli
