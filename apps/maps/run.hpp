#pragma once
/// \file maps/run.hpp
/// The run `impactkit impactmap` and `impactkit returnmap` start with: from
/// rest, `transient` forcing periods discarded, then `periods` recorded,
/// every impact of the recorded window kept. (`lyapunov` starts from the
/// last impact of its transient instead.)

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "common/provenance.hpp"
#include "common/system_options.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit::cli {

struct RunOptions {
  int transient = 500;
  int periods = 5000;
};

/// Adds --transient and --periods (default `default_periods`) in the group "Run".
void AddRunOptions(CLI::App& command, RunOptions& run, int default_periods);

/// Throws InvalidInput for a negative transient or no recorded period.
void ValidateRun(const RunOptions& run);

struct RecordedRun {
  ImpactLog impacts;
  SimulationSummary summary;  ///< of the recorded window
  HybridState end;
};

/// The run, with a progress line; throws std::runtime_error if the
/// simulation cannot reach the end of the window.
RecordedRun RecordImpacts(const System& system, const RunOptions& run);

/// What produced a file: the system `source` names and the settings
/// "SETTINGS --transient N --periods M".
Provenance RunProvenance(const std::string& settings, const RunOptions& run,
                         const SystemOptions& source, const System& system);

/// The "system:" and "run:" lines of the printed summary.
void PrintRun(const System& system, const RunOptions& run, const RecordedRun& recorded);

}  // namespace impactkit::cli
