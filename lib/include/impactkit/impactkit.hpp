#pragma once
/// \file impactkit.hpp
/// Everything of the impactkit numerics library, area by area from the
/// bottom layer up (docs/architecture.md). The io area (system files, CSV
/// and JSON output) is its own target, impactkit::io, with its own headers.

#include "impactkit/analysis/classify.hpp"
#include "impactkit/analysis/lyapunov.hpp"
#include "impactkit/analysis/map_fit.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/periodicity.hpp"
#include "impactkit/analysis/resonance.hpp"
#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/continuation/sticking_branch.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/dynamics/segment.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/modal.hpp"
#include "impactkit/model/system.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/orbit_contacts.hpp"
#include "impactkit/orbits/sticking_map.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"
