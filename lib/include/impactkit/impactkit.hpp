#pragma once
/// \file impactkit.hpp
/// Everything of the impactkit numerics library (the io area has its own
/// headers: system_file.hpp, csv.hpp, output_file.hpp).

#include "impactkit/classify.hpp"
#include "impactkit/continuation.hpp"
#include "impactkit/events.hpp"
#include "impactkit/flow.hpp"
#include "impactkit/impact_map.hpp"
#include "impactkit/lyapunov.hpp"
#include "impactkit/map_fit.hpp"
#include "impactkit/modal.hpp"
#include "impactkit/model.hpp"
#include "impactkit/nonlinear_solve.hpp"
#include "impactkit/orbit.hpp"
#include "impactkit/orbit_contacts.hpp"
#include "impactkit/periodicity.hpp"
#include "impactkit/recorders.hpp"
#include "impactkit/resonance.hpp"
#include "impactkit/segment.hpp"
#include "impactkit/simulate.hpp"
#include "impactkit/sweep.hpp"
