#pragma once
/// \file common/sweep_flags.hpp
/// The flags of a brute-force run as `sweep`, `map` and `basins` share them:
/// how each value is run and classified (--transient, --record, --max-q,
/// the fixed state --x0/--v0, --full-transient), and the swept range (--param, --from, --to,
/// --steps, --start, --direction, --chunk, --warmup).

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "common/system_options.hpp"
#include "impactkit/analysis/sweep.hpp"

namespace impactkit::cli {

/// How each value is run: periods, period search, the fixed state.
struct RunFlags {
  int transient = SweepOptions{}.transient_periods;
  int record = SweepOptions{}.recorded_periods;
  int max_q = PeriodOptions{}.max_q;
  std::vector<double> x0, v0;
  bool full_transient = SweepOptions{}.full_transient;
};

/// The swept range and its start rule.
struct RangeFlags {
  std::string param = "omega";
  double from = 0.0;
  double to = 0.0;
  int steps = 0;
  std::string start = "previous";
  std::string direction = "up";
  int chunk = SweepOptions{}.chunk_values;
  int warmup = SweepOptions{}.warmup_values;
};

void AddRunFlags(CLI::App& command, RunFlags& flags, const std::string& group);
/// `suffix` names a second range ("2": --param2, --from2, --to2, --steps2);
/// only the first has --start, --direction, --chunk and --warmup.
void AddRangeFlags(CLI::App& command, RangeFlags& flags, const std::string& group,
                   const std::string& suffix = "");

/// `options` with the run flags applied (periods, max_q, fixed state,
/// full transient), the
/// flag names in the messages. Throws InvalidInput.
void ApplyRunFlags(const RunFlags& flags, const System& system, SweepOptions& options);

/// `options` with the range flags applied (`suffix` as for AddRangeFlags;
/// `system` names the flags that set the parameter). Throws InvalidInput.
void ApplyRangeFlags(const RangeFlags& flags, const SystemOptions& system_flags,
                     const System& system, const std::string& suffix, SweepOptions& options);

/// The fixed state of --x0/--v0 (rest for what is not given); none if neither.
std::optional<HybridState> FixedStateOf(const RunFlags& flags, const System& system);

/// " x0=... v0=... full_transient" of the fixed state's flags and
/// --full-transient (what is given), as the provenance lines write them.
std::string RunFlagsProvenance(const RunFlags& flags);

}  // namespace impactkit::cli
