#pragma once
/// \file orbit/sticking.hpp
/// `impactkit orbit` for sticking motions: the output of a sticking orbit
/// P(∞, q) of the release map (impactkit/orbits/sticking_orbit.hpp).

#include <string>

#include "common/system_options.hpp"
#include "impactkit/io/output_file.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::cli {

/// Prints the sticking orbit found, with its solver's summary: the impacts
/// before each accumulation faster than `min_speed`, and with
/// `check_jacobian` the analytic Jacobian's distance from finite
/// differences. Writes it to `json` (at `json_path`) if given, with the
/// provenance of a run of the system that `source` names.
void ReportStickingOrbit(const System& system, const PeriodicOrbit& orbit,
                         const OrbitSummary& summary, double min_speed, bool check_jacobian,
                         AtomicOutputFile* json, const std::string& json_path,
                         const SystemOptions& source);

}  // namespace impactkit::cli
