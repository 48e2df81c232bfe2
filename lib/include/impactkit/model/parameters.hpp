#pragma once
/// \file parameters.hpp
/// The named scalar parameters of a system, in one table: the model gets and
/// sets them by name, system files take their chain keys from it, and the
/// command line lists them in `--set`'s help and in every provenance line.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "impactkit/model/system.hpp"

namespace impactkit {

struct ParameterSpec {
  /// The name; "A" stands for A1 … AN, one per mass; a stop parameter's
  /// name is the first stop's, name<k> stop k's (xs, xs2, …).
  std::string_view name;
  std::string_view meaning;  ///< e.g. "forcing frequency"
  std::string_view range;    ///< the values Validate() accepts, e.g. "> 0"
  bool chain_only;           ///< only a uniform chain has it (m, k, c, n)
  /// Value and assignment of a single parameter; null for the indexed ones
  /// ("A", the stop parameters: see Get/SetParameter).
  double (*get)(const System& system);
  void (*set)(System& system, double value);
  /// A parameter of each stop: its row in hybrid/stop_parameters.hpp,
  /// whose name, meaning and range this entry repeats.
  const StopParameterRow* stop = nullptr;
  bool PerMass() const { return !get && !stop; }
};

/// omega, the stop parameters (xs, r), A, m, k, c, n: the order of
/// ParameterNames.
std::span<const ParameterSpec> ParameterTable();

/// The entry for a name (A1 … AN map to "A", xs2 … to "xs", r2 … to "r");
/// null if the system lacks it.
const ParameterSpec* FindParameter(const System& system, std::string_view name);

/// Names accepted by GetParameter / SetParameter for this system:
/// omega, xs, r (of the first stop), xs2, r2, ... (of each further stop),
/// A1..AN, and for chains m, k, c, n.
std::vector<std::string> ParameterNames(const System& system);

/// A named parameter resolved once against a system: its table entry and,
/// for A<i> or a stop's parameter, which mass or stop. Get and Set then
/// parse nothing, so a driver that sets its parameter at every step
/// (continuation, sweeps, maps) resolves the name when it starts.
class NamedParameter {
 public:
  /// Throws InvalidInput for a name `system` lacks (as GetParameter).
  NamedParameter(const System& system, std::string_view name);

  const std::string& Name() const { return name_; }
  double Get(const System& system) const;
  /// As SetParameter. Throws InvalidInput where `system` no longer has the
  /// mass or stop the name was resolved to (n changed under A<i>).
  void Set(System& system, double value) const;

 private:
  std::string name_;
  const ParameterSpec* spec_;
  int index_ = -1;  ///< the mass of A<i> or the stop of a stop parameter; -1 for the others
};

/// Value of a named scalar parameter; throws InvalidInput for unknown names.
double GetParameter(const System& system, std::string_view name);

/// Sets a named scalar parameter (rebuilding chain matrices for m, k, c, n;
/// n must be a whole number and resizes A, keeping given entries). Throws
/// InvalidInput for unknown names; does not validate ranges (call Validate).
void SetParameter(System& system, std::string_view name, double value);

}  // namespace impactkit
