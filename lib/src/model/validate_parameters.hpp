#pragma once
/// \file validate_parameters.hpp
/// Validate() without the flows: for callers that build the free flow
/// themselves (its constructor rejects an undamped resonance) and never use
/// the stuck subsystem, such as the impact map.

#include "impactkit/model/system.hpp"

namespace impactkit {

/// Every check of Validate() except those that need a flow (resonances).
void ValidateParameters(const System& system);

}  // namespace impactkit
