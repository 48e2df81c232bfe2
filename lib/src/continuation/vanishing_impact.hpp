#pragma once
/// \file vanishing_impact.hpp (private)
/// Where an impact of a P(p, q) branch vanishes, by its defining equation.
///
/// As the speed v_k of impact k falls to zero along a branch, the orbit
/// tends to the reduced orbit P(p − 1, q) — the same motion without impact
/// k — whose flight through t_k just touches the stop. Locating the end by
/// the branch's own monitor (v_k², the depth) leaves an error of order
/// v_k / (dv_k/dμ) in μ, unbounded where the slope is small, and the
/// branch's multipliers grow like 1/v_k, so the corrector cannot go much
/// closer. The reduced orbit is regular there: its clearance (xs minus the
/// highest interior maximum of x_c) is smooth and crosses zero linearly at
/// the grazing. So the end is located on the reduced orbit, from the side
/// where it exists as a P(p − 1, q) orbit (clearance > 0); for p = 1 the
/// reduced orbit is the non-impacting response, whose maximum of x_c is
/// |X_c| for X = (K − Ω²M + iΩC)⁻¹ A, a closed form defined on both sides.

#include <optional>

#include "continuation/branch_problem.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::detail {

struct VanishingImpactPoint {
  double parameter = 0.0;
  double clearance = 0.0;  ///< the defining function there (0 at the grazing)
};

/// xs − max_t x_c(t) of the non-impacting steady response X cos(Ωt − φ):
/// xs − |X_c| with X = (K − Ω²M + iΩC)⁻¹ A, the least over the stops.
double NonImpactingClearance(const System& system);
/// The same for one stop: s xs − |X_c| at stop `stop` (c its mass, s its
/// Sign()).
double NonImpactingClearance(const System& system, int stop);
/// The stop the non-impacting response comes closest to (least clearance):
/// the one it touches where P(1, q)'s impact vanishes.
int NonImpactingTouchStop(const System& system);

/// The grazing beyond the branch's last two points `a`, `b`, where impact
/// `impact` (an index among the p impacts of b) vanishes. Empty when the
/// reduced orbit cannot be found there or its clearance has no zero nearby.
std::optional<VanishingImpactPoint> LocateVanishingImpact(const BranchProblem& problem,
                                                          const BranchPoint& a,
                                                          const BranchPoint& b, int impact,
                                                          const OrbitOptions& orbit_options);

}  // namespace impactkit::detail
