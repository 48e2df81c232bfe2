/// impactkit: the command-line tool. Subcommands register themselves
/// (commands.hpp); this file turns every failure into one line on stderr and
/// an exit status a script can act on:
///
///     0  success
///     1  the run failed or could not produce what was asked: an output
///        could not be written, gnuplot failed, the simulation could not
///        reach its end, an orbit did not converge, a branch could not leave
///        its start, a fit failed, the Lyapunov exponents were not computed
///     2  bad input: unknown flags, values out of range, a bad system file

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "impactkit/model/system.hpp"

#if IMPACTKIT_HAVE_MIMALLOC
#include <mimalloc.h>
#endif

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

int ReportError(std::string message, int status) {
  // Messages are one line by contract; make sure of it, since a multi-line
  // message from a dependency would break scripts that read stderr.
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  fmt::print(stderr, "impactkit: error: {}\n", message);
  return status;
}

/// The subcommands, in the order --help lists them.
std::string KnownCommands(const CLI::App& app) {
  std::vector<std::string> names;
  const auto all = [](const CLI::App*) { return true; };
  for (const CLI::App* command : app.get_subcommands(all)) names.push_back(command->get_name());
  return fmt::format("{}", fmt::join(names, ", "));
}

/// The message for a command line that chose no subcommand: CLI11 says only
/// "A subcommand is required", even when the first word is a misspelt one.
std::string NoCommandMessage(const CLI::App& app, int argc, char** argv) {
  if (argc > 1) {
    const std::string word = argv[1];
    const std::string problem = word.starts_with('-')
                                    ? fmt::format("unknown option '{}' before the subcommand", word)
                                    : fmt::format("unknown subcommand '{}'", word);
    return fmt::format("{}; known: {} (see 'impactkit --help')", problem, KnownCommands(app));
  }
  return fmt::format("a subcommand is required; known: {} (see 'impactkit --help')",
                     KnownCommands(app));
}

/// The allocator that serves this process's malloc, as --version reports
/// it: mimalloc where the build links it and it took malloc over (it must
/// come before the C library in the link), else the C library's.
std::string AllocatorName() {
#if IMPACTKIT_HAVE_MIMALLOC
  void* probe = std::malloc(1);
  const bool from_mimalloc = mi_is_in_heap_region(probe);
  std::free(probe);
  if (from_mimalloc) {
    const int version = mi_version();  // 209 for 2.0.9
    return fmt::format("mimalloc {}.{}.{}", version / 100, version / 10 % 10, version % 10);
  }
#endif
  return "the C library's";
}

/// Where to look after a command-line syntax error.
std::string HelpHint(const CLI::App& app) {
  const auto chosen = app.get_subcommands();
  return chosen.empty() ? "impactkit --help"
                        : fmt::format("impactkit {} --help", chosen.front()->get_name());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{fmt::format(
      "impactkit: exact simulation and analysis of impact oscillators (N masses in a chain, "
      "one of them limited by a rigid stop; Wagg & Bishop 2001).\n"
      "Without --system every command uses the paper's system: {}.",
      impactkit::cli::ParameterList(impactkit::PaperSystem()))};
  app.name("impactkit");
  app.set_version_flag(
      "--version", fmt::format("impactkit {} (malloc: {})", IMPACTKIT_VERSION, AllocatorName()));
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 the run failed or produced no result (output, gnuplot, "
      "simulation, no convergence), 2 bad input.\n"
      "Docs: docs/guide.md (tasks), docs/cli.md (commands), docs/system-files.md (system files).");
  impactkit::cli::AddSimulateCommand(app);
  impactkit::cli::AddOrbitCommand(app);
  impactkit::cli::AddContinueCommand(app);
  impactkit::cli::AddCurveCommand(app);
  impactkit::cli::AddDiagramCommand(app);
  impactkit::cli::AddPaperCommand(app);
  impactkit::cli::AddSweepCommand(app);
  impactkit::cli::AddImpactMapCommand(app);
  impactkit::cli::AddReturnMapCommand(app);
  impactkit::cli::AddLyapunovCommand(app);
  impactkit::cli::AddResonanceCommand(app);
  impactkit::cli::AddMapCommand(app);
  impactkit::cli::AddBasinsCommand(app);

  impactkit::cli::RecordCommandLine(argc, argv);
  try {
    app.parse(argc, argv);
    return 0;
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) return app.exit(error);  // --help, --version
    if (app.get_subcommands().empty() && error.get_name() == "RequiredError") {
      return ReportError(NoCommandMessage(app, argc, argv), kExitBadInput);
    }
    return ReportError(fmt::format("{} (see '{}')", error.what(), HelpHint(app)), kExitBadInput);
  } catch (const impactkit::InvalidInput& error) {
    return ReportError(error.what(), kExitBadInput);
  } catch (const std::exception& error) {
    return ReportError(error.what(), kExitFailure);
  } catch (...) {
    return ReportError("unexpected failure of unknown type", kExitFailure);
  }
}
