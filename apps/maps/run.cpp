/// The run shared by `impactkit impactmap` and `impactkit returnmap`
/// (maps/run.hpp); the commands are maps/impactmap.cpp, maps/returnmap.cpp
/// and maps/lyapunov.cpp.

#include "maps/run.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "common/limits.hpp"
#include "common/progress.hpp"
#include "common/system_options.hpp"
#include "impactkit/core/errors.hpp"

namespace impactkit::cli {

void AddRunOptions(CLI::App& command, RunOptions& run, int default_periods) {
  run.periods = default_periods;
  command.add_option("--transient", run.transient, "Forcing periods run from rest and discarded")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group("Run");
  command.add_option("--periods", run.periods, "Forcing periods recorded after the transient")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group("Run");
}

void ValidateRun(const RunOptions& run) {
  Require(run.transient >= 0, fmt::format("--transient must be >= 0, got {}", run.transient));
  Require(run.periods >= 1, fmt::format("--periods must be >= 1, got {}", run.periods));
}

RecordedRun RecordImpacts(const System& system, const RunOptions& run) {
  const Simulator simulator(system);
  const double period = system.ForcingPeriod();
  HybridState state = RestState(system);
  {
    ProgressLine progress("transient", 0.0, run.transient * period, period);
    simulator.Run(state, run.transient * period, progress);
  }
  ImpactRecorder recorder;
  ProgressLine progress("recording", state.t, state.t + run.periods * period, period);
  ObserverList observers;
  observers.Add(recorder);
  observers.Add(progress);
  RecordedRun result;
  result.summary = simulator.Run(state, state.t + run.periods * period, observers);
  if (result.summary.termination != Termination::kCompleted) {
    throw std::runtime_error(
        fmt::format("the simulation stopped early: {}", result.summary.BriefReport()));
  }
  result.impacts = recorder.Impacts();
  result.end = state;
  return result;
}

Provenance RunProvenance(const std::string& settings, const RunOptions& run,
                         const SystemOptions& source, const System& system) {
  return MakeProvenance(
      source, system,
      fmt::format("{} --transient {} --periods {}", settings, run.transient, run.periods));
}

void PrintRun(const System& system, const RunOptions& run, const RecordedRun& recorded) {
  fmt::print("system:      {}\n", DescribeSystem(system));
  fmt::print("run:         from rest, {} periods discarded, {} recorded: {}\n", run.transient,
             run.periods, recorded.summary.BriefReport());
}

}  // namespace impactkit::cli
