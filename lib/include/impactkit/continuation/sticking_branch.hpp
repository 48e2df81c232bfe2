#pragma once
/// \file sticking_branch.hpp
/// Pseudo-arclength continuation of sticking orbits P(∞, q) in one named
/// parameter μ (any of ParameterNames). The unknowns are X = (s, μ), size
/// 2N, on the curve
///
///     U(s, μ) = P_R^k(s; μ) − s − q T(μ) e_t = 0          (sticking_orbit.hpp)
///
/// with the same predictor, bordered KINSOL corrector and tangent as
/// continuation.hpp (U_s the release map's analytic Jacobian, U_μ a
/// central difference of its images, one-sided within a step of the end).
///
/// What ends a sticking family, watched at every point:
///   - the chatter no longer ends in sticking: the least Fs(t*) of the
///     orbit's cycles reaches 0 (beyond, the mass is not held), or, as the
///     acceleration towards the stop at the chatter vanishes with Fs, the
///     simulator's chatter rule stops predicting an accumulation (beyond,
///     the map finds impacts without end: kNoChatter); the located end's
///     Fs(t*) is then small but not 0;
///   - a new impact: a free flight's interior maximum of x_c reaches the
///     stop. Beyond, the release map has the extra impact and stays
///     continuous, and the flight's maximum is gone rather than past the
///     stop: the event shows as the first impact after a release jumping to
///     an earlier time between two points;
///   - an early release: an interior minimum of Fs in a stuck phase reaches
///     0 (beyond, the mass leaves the stop there and the orbit has one more
///     sticking phase);
///   - a vanishing impact: the same graze met from the side where the
///     impact exists — the first impact after a release slows to 0, and
///     beyond it jumps to a later time;
/// each approached from the branch side by halving the step until it falls
/// below min_step, named by the monitor (Fs(t*), clearance, hold margin,
/// first impact speed) whose linear extrapolation from the last two points
/// reaches 0 first, within 1e-3 in arclength, or else by what the failed
/// trials beyond it showed; then located by bisection in μ between the last
/// point and the failed trial beyond it, each μ solved at fixed μ, to
/// locate_tolerance: the last point is the located end.
/// Fold and period doubling of the release map (a section multiplier
/// through +1 or −1; test functions Π(λ_i − 1), Π(λ_i + 1)) are located by
/// bisection in arclength and reported; the branch goes on through them.

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

#include "impactkit/model/system.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"

namespace impactkit {

struct StickingBranchOptions {
  std::string parameter = "omega";
  /// The branch stays within [lower, upper] (it ends on reaching a bound).
  double lower = 0.0;
  double upper = 0.0;
  /// Follow μ upwards from the start (else downwards).
  bool increasing = true;
  /// Arclength steps in (s, μ): start, floor (the resolution of a located
  /// end) and ceiling.
  double initial_step = 0.005;
  double min_step = 1e-8;
  double max_step = 0.02;
  int max_points = 10000;
  /// A bifurcation's parameter (bisection in arclength) and the family's
  /// end (bisection in μ) are located to this.
  double locate_tolerance = 1e-9;
  /// Releases k, q, Newton tolerances and the map's options.
  StickingOrbitOptions orbit;
  bool IsValid(std::string* error) const;
};

enum class StickingEvent {
  kNoSticking,       ///< Fs(t*) = 0: the chatter stops ending in sticking (ends the branch)
  kNewImpact,        ///< a free flight grazes the stop (ends the branch)
  kEarlyRelease,     ///< Fs touches 0 inside a stuck phase (ends the branch)
  kVanishingImpact,  ///< the first impact after a release slows to a graze (ends the branch)
  kFold,             ///< a section multiplier through +1
  kPeriodDoubling,   ///< a section multiplier through −1
};

/// "no_sticking", "new_impact", "early_release", "vanishing_impact", "fold",
/// "period_doubling".
std::string ToString(StickingEvent event);

struct StickingBranchPoint {
  double parameter = 0.0;
  PeriodicOrbit orbit;
};

struct StickingSpecialPoint {
  StickingEvent type = StickingEvent::kFold;
  StickingBranchPoint point;
  /// One line: "fold at omega = 0.2345 (stick phase ..., release phase ...)".
  std::string Describe(const std::string& parameter_name) const;
};

enum class StickingBranchEnd {
  kParameterBound,   ///< reached lower or upper
  kNoSticking,       ///< ended where the chatter stops ending in sticking
  kNewImpact,        ///< ended where a free flight grazes the stop
  kEarlyRelease,     ///< ended where Fs touches 0 inside a stuck phase
  kVanishingImpact,  ///< ended where the first impact after a release slows to a graze
  kMaxPoints,        ///< max_points reached
  kCorrectorFailed,  ///< no convergence even with the smallest step, no monitor near 0
};

/// "parameter_bound", "no_sticking", "new_impact", "early_release",
/// "vanishing_impact", "max_points", "corrector_failed".
std::string ToString(StickingBranchEnd end);

struct StickingBranch {
  std::string parameter;
  int releases = 0;
  int q = 0;
  std::vector<StickingBranchPoint> points;           ///< in order along the branch
  std::vector<StickingSpecialPoint> special_points;  ///< in order; an end event last
  StickingBranchEnd end = StickingBranchEnd::kMaxPoints;
  std::string end_message;
  double seconds = 0.0;
};

/// Follows the sticking family through `start`, an orbit of `system`.
/// Throws InvalidInput for bad options, a parameter the system lacks,
/// bounds not holding the start, or a start that is not an orbit.
StickingBranch ContinueStickingBranch(
    const System& system, const PeriodicOrbit& start, const StickingBranchOptions& options,
    const std::function<void(const StickingBranchPoint&)>& progress = {});

}  // namespace impactkit
