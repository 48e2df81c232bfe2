#pragma once
/// \file sticking_end.hpp (private)
/// What ends a family of sticking orbits (continuation.hpp follows it on the
/// release map), watched at every point:
///   - the chatter no longer ends in sticking: the least Fs(t*) of the
///     orbit's stuck phases reaches 0 (beyond, the mass is not held), or, as
///     the acceleration towards the stop at the chatter vanishes with Fs,
///     the simulator's chatter rule stops predicting an accumulation
///     (beyond, the map finds impacts without end); the located end's
///     Fs(t*) is then small but not 0;
///   - a new impact (a grazing): a free flight's turn reaches the stop.
///     Beyond, the release map has the extra impact and stays continuous,
///     and the flight's turn is gone rather than past the stop: the event
///     shows as the first impact after a release jumping to an earlier time
///     between two points, or one more impact at another stop than the
///     cycle's;
///   - an early release: an interior minimum of Fs in a stuck phase reaches
///     0 (beyond, the mass leaves the stop there: one more sticking phase);
///   - a vanishing impact (a grazing): the same graze met from the side
///     where the impact exists — an approach impact (orbit_contacts.hpp)
///     slows to 0, and beyond it the first impact after a release jumps to
///     a later time or an impact at another stop is gone.
/// Past each the map still converges, onto another motion: a point beyond
/// is recognised (Violation, ImpactChange) and refused; the end is named by
/// the monitor whose linear extrapolation reaches 0 first (NearestEnd),
/// else by what the refused trials showed, and located by bisection in μ
/// (LocateStickingEnd).

#include <Eigen/Dense>
#include <optional>

#include "continuation/branch_problem.hpp"
#include "impactkit/continuation/branch_point.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/solvers/nonlinear_solve.hpp"

namespace impactkit::detail {

/// The four ends, in the order of their monitors.
enum class StickingEnd { kNoSticking, kNewImpact, kEarlyRelease, kVanishingImpact };

/// Why a sticking orbit cannot be on its family, if it cannot: a monitor
/// at or below 0.
std::optional<StickingEnd> Violation(const PeriodicOrbit& orbit);

/// Where the impacts before the chatter changed between two neighbouring
/// orbits of a family: the first impact after some release jumped to an
/// earlier time (an impact appeared before it) or to a later one (it
/// vanished), or a cycle has an impact more or fewer at the other stops.
/// Along the family that delay moves continuously; a jump of a quarter of
/// it between two points is none of that motion.
std::optional<StickingEnd> ImpactChange(const PeriodicOrbit& a, const PeriodicOrbit& b);

/// An end ahead of a family's last point, by its monitors' extrapolation,
/// and a μ past it (twice as far as the extrapolated zero).
struct ExtrapolatedEnd {
  StickingEnd end;
  double beyond;
};

/// The end whose monitor, extrapolated linearly in arclength from a to b,
/// reaches 0 first within `reach` beyond b; none if none does.
std::optional<ExtrapolatedEnd> NearestEnd(const BranchPoint& a, const BranchPoint& b, double reach);

/// The family's point nearest its end between `last` (on the family) and
/// μ = `beyond` (past the end): bisection in μ to `tolerance`, each μ
/// solved at fixed μ from the last point inside and judged as above, to
/// the residual's rounding floor. Empty when μ = `beyond` still holds a
/// point of the family (no bracket) or no bisection point does.
std::optional<BranchPoint> LocateStickingEnd(const BranchProblem& problem, const BranchPoint& last,
                                             double beyond, double tolerance,
                                             const NewtonOptions& newton);

/// The special point `end` at `point`, a located end: a new or vanishing
/// impact is a grazing (for a vanishing one, of the slowest approach
/// impact); its monitor is the one that reached 0.
SpecialPoint EndPoint(const BranchPoint& point, StickingEnd end);
/// The branch's end there.
Termination TerminationOf(StickingEnd end);

}  // namespace impactkit::detail
