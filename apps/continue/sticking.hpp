#pragma once
/// \file continue/sticking.hpp
/// `impactkit continue` for sticking orbits: the family of the start orbit
/// P(inf, q) followed in one parameter until the chatter stops ending in
/// sticking or a flight grazes the stop
/// (impactkit/continuation/sticking_branch.hpp).

#include <string>

#include "common/provenance.hpp"
#include "impactkit/continuation/sticking_branch.hpp"
#include "impactkit/io/output_set.hpp"

namespace impactkit::cli {

/// Follows the branch of `start`, prints it and its special points, and
/// adds its table to `out` and its JSON to `json` (either may be null),
/// all committed by the caller. Throws std::runtime_error if the branch
/// cannot leave its start.
void RunStickingContinue(const System& system, const PeriodicOrbit& start,
                         const StickingBranchOptions& options, OutputSet& outputs,
                         AtomicOutputFile* out, AtomicOutputFile* json,
                         const Provenance& provenance);

}  // namespace impactkit::cli
