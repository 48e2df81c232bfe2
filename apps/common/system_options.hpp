#pragma once
/// \file common/system_options.hpp
/// The flags every subcommand shares to name its system: a file or the
/// paper's default, then changes by parameter name, the names of
/// impactkit::ParameterNames (omega, xs, r, A1..AN; m, k, c, n for chains).

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "impactkit/model/parameters.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit::cli {

struct SystemOptions {
  std::string file;               ///< --system FILE (.json/.toml); empty: the paper's system
  std::vector<std::string> sets;  ///< --set name=value, in the order given
  std::optional<double> omega;    ///< --omega W, short for --set omega=W
  std::optional<int> dof;         ///< --dof N, short for --set n=N (chains only)
};

/// Adds --system, --set, --omega and --dof to `command`, in the group "System".
void AddSystemOptions(CLI::App& command, SystemOptions& options);

/// The system the options name, validated. `n` is applied first, whatever
/// its place on the command line, since it decides which A_i exist.
/// Throws InvalidInput naming the flag or parameter at fault.
System ResolveSystem(const SystemOptions& options);

/// The flag that sets `parameter` ("--omega", "--set omega=1.2"), if any.
/// Throws InvalidInput for a malformed --set.
std::optional<std::string> FlagSetting(const SystemOptions& options, const std::string& parameter);

/// Throws InvalidInput when a flag sets `parameter`, which `flag` (e.g.
/// "--param") makes the varied one: the fixed value would be silently
/// overridden by those of `source` (e.g. "--from and --to").
void RequireNotSet(const SystemOptions& options, const std::string& parameter,
                   const std::string& flag, const std::string& source);

/// Every named parameter as --set would take it, at full precision:
/// "omega=1.4 xs=0.1 r=0.7 A1=0.5 A2=0 m=1 k=1 c=0.1 n=2".
std::string ParameterList(const System& system);

/// One readable line: "uniform chain n=2 m=1 k=1 c=0.1, A=(0.5, 0), omega=1.4,
/// xs=0.1, r=0.7", or for general matrices their size and contact mass.
std::string DescribeSystem(const System& system);

/// The axis label of impact speeds: "impact velocity v2(t-)" for one stop,
/// "impact speed (every stop)" for several.
std::string ImpactSpeedLabel(const System& system);

}  // namespace impactkit::cli
