#pragma once
/// \file system_flows.hpp
/// The flows of a system (model/system.hpp is data, dynamics/flow.hpp knows
/// no system): its free flow and the flows of its stuck subsystems, which
/// exist only where each has a bounded steady response — the one check on a
/// system that needs them decomposed.

#include "impactkit/dynamics/flow.hpp"
#include "impactkit/model/system.hpp"

namespace impactkit {

/// ValidateParameters (every field and the scales derived from them,
/// docs/bad-input.md), then the resonances: throws InvalidInput for an
/// undamped system, or a stuck subsystem of it, forced at one of its
/// natural frequencies (no bounded steady response exists).
void Validate(const System& system);

/// The exact flow of the masses that move while the stops in `held` hold
/// theirs (model's StuckSubsystem). Throws InvalidInput "stuck subsystem
/// (mass 2 held at the stop): <why>" when it has no bounded steady response.
LinearFlow HeldFlow(const System& system, StopSet held);

}  // namespace impactkit
