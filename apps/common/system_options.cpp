#include "common/system_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <string_view>

#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/io/system_file.hpp"

namespace impactkit::cli {
namespace {

/// One parameter change, with the flag it came from for error messages.
struct Assignment {
  std::string name;
  double value = 0.0;
  std::string origin;  ///< "--set c=0.05", "--omega 1.4", ...
};

double ParseNumber(std::string_view text, std::string_view origin) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end) {
    throw InvalidInput(fmt::format("{}: '{}' is not a number", origin, text));
  }
  return value;
}

Assignment ParseSet(const std::string& text) {
  const std::string origin = "--set " + text;
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw InvalidInput(
        fmt::format("{}: expected name=value (e.g. --set c=0.05), got '{}'", origin, text));
  }
  return {text.substr(0, equals), ParseNumber(std::string_view(text).substr(equals + 1), origin),
          origin};
}

/// All changes the flags ask for, `n` first. A parameter named twice is an
/// error: which one was meant cannot be guessed.
std::vector<Assignment> Assignments(const SystemOptions& options) {
  std::vector<Assignment> all;
  for (const std::string& text : options.sets) all.push_back(ParseSet(text));
  if (options.dof) all.push_back({"n", static_cast<double>(*options.dof), "--dof"});
  if (options.omega) all.push_back({"omega", *options.omega, "--omega"});
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (all[i].name != all[j].name) continue;
      throw InvalidInput(fmt::format("parameter '{}' is given twice ({} and {})", all[i].name,
                                     all[j].origin, all[i].origin));
    }
  }
  std::stable_partition(all.begin(), all.end(), [](const Assignment& a) { return a.name == "n"; });
  return all;
}

void Apply(const Assignment& assignment, System& system) {
  if (assignment.name == "n" && !system.chain) {
    throw InvalidInput(fmt::format(
        "{}: the number of masses can be changed only for a uniform chain; this system has "
        "general matrices",
        assignment.origin));
  }
  try {
    SetParameter(system, assignment.name, assignment.value);
  } catch (const InvalidInput& error) {
    throw InvalidInput(fmt::format("{}: {}", assignment.origin, error.what()));
  }
}

/// "omega (forcing frequency, > 0), ..., and for chains m (mass, > 0), ...",
/// from the model's parameter table.
std::string ParameterHelp() {
  std::vector<std::string> any, chain;
  for (const ParameterSpec& spec : ParameterTable()) {
    const std::string name = spec.PerMass() ? fmt::format("{0}1..{0}N", spec.name)
                             : spec.stop    ? fmt::format("{0}, {0}2, ...", spec.name)
                                            : std::string(spec.name);
    (spec.chain_only ? chain : any)
        .push_back(fmt::format("{} ({}, {})", name, spec.meaning, spec.range));
  }
  return fmt::format("{}; for chains {}", fmt::join(any, ", "), fmt::join(chain, ", "));
}

}  // namespace

void AddSystemOptions(CLI::App& command, SystemOptions& options) {
  const System paper = PaperSystem();
  const std::string group = fmt::format("System (default: the paper's, {})", ParameterList(paper));
  command
      .add_option("--system", options.file,
                  "System file, .json or .toml (docs/system-files.md); default: the paper's "
                  "uniform chain")
      ->type_name("FILE")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return text.empty() ? "an empty path names no system file (leave --system out for "
                                  "the paper's system)"
                                : "";
          },
          ""))
      ->group(group);
  command
      .add_option("--set", options.sets,
                  fmt::format("Change a parameter, name=value; repeatable (e.g. --set c=0.05 "
                              "--set A2=0.1). Names: {}",
                              ParameterHelp()))
      ->type_name("NAME=VALUE")
      ->group(group);
  command
      .add_option("--omega", options.omega,
                  fmt::format("Forcing frequency; short for --set omega=W (default {}, or "
                              "the file's)",
                              paper.omega))
      ->type_name("W")
      ->group(group);
  command
      .add_option("--dof", options.dof,
                  fmt::format("Number of masses of a uniform chain; short for --set n=N "
                              "(default {}, or the file's)",
                              paper.Dof()))
      ->type_name("N")
      ->group(group);
}

System ResolveSystem(const SystemOptions& options) {
  System system = options.file.empty() ? PaperSystem() : ReadSystemFile(options.file);
  for (const Assignment& assignment : Assignments(options)) Apply(assignment, system);
  Validate(system);
  return system;
}

std::optional<std::string> FlagSetting(const SystemOptions& options, const std::string& parameter) {
  for (const Assignment& assignment : Assignments(options)) {
    if (assignment.name == parameter) return assignment.origin;
  }
  return std::nullopt;
}

void RequireNotSet(const SystemOptions& options, const std::string& parameter,
                   const std::string& flag, const std::string& source) {
  if (const std::optional<std::string> origin = FlagSetting(options, parameter)) {
    throw InvalidInput(fmt::format("{} conflicts with {} {}: the values of {} come from {}",
                                   *origin, flag, parameter, parameter, source));
  }
}

std::string ParameterList(const System& system) {
  std::vector<std::string> items;
  for (const std::string& name : ParameterNames(system)) {
    items.push_back(fmt::format("{}={}", name, GetParameter(system, name)));
  }
  return fmt::format("{}", fmt::join(items, " "));
}

namespace {

/// The stops as "xs=0.1, r=0.7" for the one upper stop of the seed's
/// model, else one "x2 <= 0.1 (r=0.7)" per stop.
std::string DescribeStops(const System& system) {
  const StopParameters& first = system.stops[0];
  if (system.StopCount() == 1 && first.side == StopSide::kUpper) {
    return fmt::format("xs={:.6g}, r={:.6g}", first.position, first.restitution);
  }
  std::vector<std::string> stops;
  for (const StopParameters& stop : system.stops) {
    stops.push_back(fmt::format("x{} {} {:.6g} (r={:.6g})", stop.dof + 1,
                                stop.side == StopSide::kUpper ? "<=" : ">=", stop.position,
                                stop.restitution));
  }
  return fmt::format("stops {}", fmt::join(stops, ", "));
}

}  // namespace

std::string ImpactSpeedLabel(const System& system) {
  if (system.StopCount() > 1) return "impact speed (every stop)";
  return fmt::format("impact velocity v{}(t-)", system.stops[0].dof + 1);
}

std::string DescribeSystem(const System& system) {
  const std::string common =
      fmt::format("A=({:.6g}), omega={:.6g}, {}", fmt::join(system.forcing, ", "), system.omega,
                  DescribeStops(system));
  if (system.chain) {
    const ChainParameters& chain = *system.chain;
    return fmt::format("uniform chain n={} m={:.6g} k={:.6g} c={:.6g}, {}", chain.dof, chain.mass,
                       chain.stiffness, chain.damping, common);
  }
  if (system.StopCount() > 1) return fmt::format("general N={}, {}", system.Dof(), common);
  return fmt::format("general N={} (contact mass {}), {}", system.Dof(), system.stops[0].dof + 1,
                     common);
}

}  // namespace impactkit::cli
