#include "common/sweep_flags.hpp"

#include <fmt/format.h>

#include "common/limits.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit::cli {

void AddRunFlags(CLI::App& command, RunFlags& flags, const std::string& group) {
  command.add_option("--transient", flags.transient, "Forcing periods discarded at each value")
      ->type_name("P")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command.add_option("--record", flags.record, "Forcing periods recorded at each value")
      ->type_name("P")
      ->check(AtMost(kMaxPeriods, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command.add_option("--max-q", flags.max_q, "Longest period searched, in forcing periods")
      ->type_name("Q")
      ->check(AtMost(kMaxOrbitPeriod, "forcing periods"))
      ->capture_default_str()
      ->group(group);
  command
      .add_flag("--full-transient", flags.full_transient,
                "Run every value's whole transient: no early end at an orbit confirmed by a "
                "Newton solve (the same class from the same start; docs/grids.md)")
      ->group(group);
  command.add_option("--x0", flags.x0, "Fixed state positions x1,...,xN (default 0)")
      ->type_name("X1,...,XN")
      ->delimiter(',')
      ->group(group);
  command.add_option("--v0", flags.v0, "Fixed state velocities v1,...,vN (default 0)")
      ->type_name("V1,...,VN")
      ->delimiter(',')
      ->group(group);
}

void AddRangeFlags(CLI::App& command, RangeFlags& flags, const std::string& group,
                   const std::string& suffix) {
  const std::string which = suffix.empty() ? "" : " (second axis)";
  command
      .add_option("--param" + suffix, flags.param,
                  "Parameter to sweep" + which + ": omega, xs, r, A1..AN, m, k, c")
      ->type_name("NAME")
      ->capture_default_str()
      ->group(group);
  command.add_option("--from" + suffix, flags.from, "One end of the range" + which)
      ->type_name("A")
      ->required()
      ->group(group);
  command.add_option("--to" + suffix, flags.to, "The other end of the range" + which)
      ->type_name("B")
      ->required()
      ->group(group);
  command
      .add_option("--steps" + suffix, flags.steps,
                  "Number of values" + which + ", both ends included")
      ->type_name("K")
      ->check(AtMost(kMaxSteps, "values"))
      ->required()
      ->group(group);
  if (!suffix.empty()) return;
  command
      .add_option("--start", flags.start,
                  "'previous': each value from the previous value's final state; 'fixed': each "
                  "from the fixed state (--x0/--v0, default rest)")
      ->check(CLI::IsMember({"previous", "fixed"}))
      ->capture_default_str()
      ->group(group);
  command.add_option("--direction", flags.direction, "'up' or 'down' through the range")
      ->check(CLI::IsMember({"up", "down"}))
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--chunk", flags.chunk,
                  "With --start previous: values per independently computed chunk (0: one "
                  "chunk, strictly sequential); part of the result, unlike --threads")
      ->type_name("N")
      ->check(AtMost(kMaxSteps, "values"))
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--warmup", flags.warmup,
                  "With --start previous: values before each chunk whose transients it runs "
                  "first, from the fixed state")
      ->type_name("N")
      ->check(AtMost(kMaxSteps, "values"))
      ->capture_default_str()
      ->group(group);
}

std::optional<HybridState> FixedStateOf(const RunFlags& flags, const System& system) {
  if (flags.x0.empty() && flags.v0.empty()) return std::nullopt;
  HybridState state = RestState(system);
  auto fill = [&](const std::vector<double>& given, Eigen::VectorXd& target, const char* flag) {
    if (given.empty()) return;
    if (static_cast<int>(given.size()) != system.Dof()) {
      throw InvalidInput(fmt::format("{} needs {} values (one per mass), got {}", flag,
                                     system.Dof(), given.size()));
    }
    target = Eigen::Map<const Eigen::VectorXd>(given.data(), system.Dof());
  };
  fill(flags.x0, state.x, "--x0");
  fill(flags.v0, state.v, "--v0");
  return state;
}

std::string RunFlagsProvenance(const RunFlags& flags) {
  std::string text;
  if (!flags.x0.empty()) text += fmt::format(" x0={}", fmt::join(flags.x0, ","));
  if (!flags.v0.empty()) text += fmt::format(" v0={}", fmt::join(flags.v0, ","));
  if (flags.full_transient) text += " full_transient";
  return text;
}

void ApplyRunFlags(const RunFlags& flags, const System& system, SweepOptions& options) {
  if (flags.transient < 0) {
    throw InvalidInput(fmt::format("--transient must be >= 0, got {}", flags.transient));
  }
  if (flags.record < 1)
    throw InvalidInput(fmt::format("--record must be >= 1, got {}", flags.record));
  if (flags.max_q < 1) throw InvalidInput(fmt::format("--max-q must be >= 1, got {}", flags.max_q));
  options.transient_periods = flags.transient;
  options.recorded_periods = flags.record;
  options.classify.period.max_q = flags.max_q;
  options.fixed_state = FixedStateOf(flags, system);
  options.full_transient = flags.full_transient;
}

void ApplyRangeFlags(const RangeFlags& flags, const SystemOptions& system_flags,
                     const System& system, const std::string& suffix, SweepOptions& options) {
  const std::string from = "--from" + suffix, to = "--to" + suffix, steps = "--steps" + suffix;
  if (flags.steps < 1)
    throw InvalidInput(fmt::format("{} must be >= 1, got {}", steps, flags.steps));
  if (flags.steps > 1 && flags.from == flags.to) {
    throw InvalidInput(fmt::format("{} and {} are both {}: {} steps need a range (or {} 1)", from,
                                   to, flags.from, flags.steps, steps));
  }
  if (flags.chunk < 0) throw InvalidInput(fmt::format("--chunk must be >= 0, got {}", flags.chunk));
  if (flags.warmup < 0) {
    throw InvalidInput(fmt::format("--warmup must be >= 0, got {}", flags.warmup));
  }
  GetParameter(system, flags.param);  // "unknown parameter 'x'; allowed: ..."
  RequireNotSet(system_flags, flags.param, "--param" + suffix, from + " and " + to);
  options.parameter = flags.param;
  options.from = flags.from;
  options.to = flags.to;
  options.steps = flags.steps;
  options.start = flags.start == "fixed" ? SweepStart::kFixed : SweepStart::kPrevious;
  options.direction = flags.direction == "down" ? SweepDirection::kDown : SweepDirection::kUp;
  options.chunk_values = flags.chunk;
  options.warmup_values = flags.warmup;
}

}  // namespace impactkit::cli
