#include "continuation/sticking_end.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace impactkit::detail {
namespace {

/// The relative jump of the first impact's delay after a release that
/// marks an impact appearing or vanishing before it (ImpactChange).
constexpr double kDelayJump = 0.25;

/// The ending monitors of an orbit, in StickingEnd order: each positive on
/// the family and 0 at its end (infinity where it watches nothing).
std::array<double, 4> Monitors(const PeriodicOrbit& orbit) {
  const OrbitContacts& c = orbit.contacts;
  return {c.contact_margin, c.clearance.value_or(std::numeric_limits<double>::infinity()),
          c.hold_margin, c.approach_impact_speed};
}

/// The delay from each release to the first impact after it (NaN for a
/// cycle without impacts), in the order of the orbit's stuck phases.
std::vector<double> FirstImpactDelays(const PeriodicOrbit& orbit) {
  std::vector<double> delays;
  for (std::size_t k = 0; k < orbit.stuck.size(); ++k) {
    // The cycle starts at the release of the section state, or the last.
    const double release = k == 0 ? orbit.eta(orbit.eta.size() - 1) : orbit.stuck[k - 1].release;
    const std::span<const OrbitImpact> cycle = CycleImpacts(orbit, k);
    delays.push_back(cycle.empty() ? std::numeric_limits<double>::quiet_NaN()
                                   : cycle.front().t - release);
  }
  return delays;
}

/// The impacts of each cycle at other stops than the one holding it at the
/// cycle's end, in the order of the orbit's stuck phases: approach impacts
/// (orbit_contacts.hpp) whose number changes only where one appears or
/// vanishes.
std::vector<std::ptrdiff_t> OtherStopImpacts(const PeriodicOrbit& orbit) {
  std::vector<std::ptrdiff_t> counts;
  for (std::size_t k = 0; k < orbit.stuck.size(); ++k) {
    const std::span<const OrbitImpact> cycle = CycleImpacts(orbit, k);
    counts.push_back(std::count_if(cycle.begin(), cycle.end(), [&](const OrbitImpact& impact) {
      return impact.stop != orbit.stuck[k].stop;
    }));
  }
  return counts;
}

}  // namespace

std::optional<StickingEnd> Violation(const PeriodicOrbit& orbit) {
  const std::array<double, 4> monitors = Monitors(orbit);
  for (std::size_t i = 0; i < 3; ++i) {  // an impact's speed is > 0 by definition
    if (!(monitors[i] > 0)) return static_cast<StickingEnd>(i);
  }
  return std::nullopt;
}

std::optional<StickingEnd> ImpactChange(const PeriodicOrbit& a, const PeriodicOrbit& b) {
  if (a.stuck.size() != b.stuck.size()) return std::nullopt;
  const std::vector<double> from = FirstImpactDelays(a), to = FirstImpactDelays(b);
  const std::vector<std::ptrdiff_t> others_from = OtherStopImpacts(a),
                                    others_to = OtherStopImpacts(b);
  for (std::size_t k = 0; k < from.size(); ++k) {
    if (to[k] < (1.0 - kDelayJump) * from[k] || others_to[k] > others_from[k]) {
      return StickingEnd::kNewImpact;
    }
    if (to[k] > (1.0 + kDelayJump) * from[k] || others_to[k] < others_from[k]) {
      return StickingEnd::kVanishingImpact;
    }
  }
  return std::nullopt;
}

std::optional<ExtrapolatedEnd> NearestEnd(const BranchPoint& a, const BranchPoint& b,
                                          double reach) {
  const double step = (BranchProblem::PointX(b) - BranchProblem::PointX(a)).norm();
  const std::array<double, 4> before = Monitors(a.orbit), after = Monitors(b.orbit);
  std::optional<ExtrapolatedEnd> nearest;
  double best = reach;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const double fall = (before[i] - after[i]) / step;  // per unit arclength
    if (!std::isfinite(after[i]) || !(fall > 0)) continue;
    if (const double distance = after[i] / fall; distance < best) {
      best = distance;
      const double mu_rate = (b.parameter - a.parameter) / step;
      nearest = {static_cast<StickingEnd>(i), b.parameter + 2.0 * distance * mu_rate};
    }
  }
  return nearest;
}

std::optional<BranchPoint> LocateStickingEnd(const BranchProblem& problem, const BranchPoint& last,
                                             double beyond, double tolerance,
                                             const NewtonOptions& newton) {
  const Eigen::VectorXd e_mu = Eigen::VectorXd::Unit(problem.Size(), problem.Size() - 1);
  // The family's point at μ, from the last point inside, or none if μ is
  // past its end.
  auto point_at = [&](const BranchPoint& inside, double mu) -> std::optional<BranchPoint> {
    // Near a vanishing impact of speed v, D P ~ 1/v and so does the
    // rounding of U: Newton is asked for no less than that floor (as
    // FindOrbit is), or it fails at every μ next to the end.
    NewtonOptions at_floor = newton;
    at_floor.residual_tolerance =
        std::max(newton.residual_tolerance, ResidualFloor(inside.orbit.jacobian, inside.orbit.eta));
    int iterations = 0;
    const std::optional<Eigen::VectorXd> x =
        problem.Correct(BranchProblem::Join(inside.orbit.eta, mu), e_mu, mu, at_floor, &iterations);
    problem.TakeStoppedSticking();
    if (!x) return std::nullopt;
    std::optional<BranchPoint> point = problem.Describe(*x, inside.tangent);
    if (!point || Violation(point->orbit) || ImpactChange(inside.orbit, point->orbit)) {
      return std::nullopt;
    }
    point->arclength = inside.arclength + inside.tangent.dot(*x - BranchProblem::PointX(inside));
    return point;
  };
  if (!std::isfinite(beyond) || point_at(last, beyond)) return std::nullopt;
  double inside = last.parameter, outside = beyond;
  std::optional<BranchPoint> located;
  while (std::abs(outside - inside) > tolerance) {
    const double mid = 0.5 * (inside + outside);
    if (mid == inside || mid == outside) break;  // a tolerance below μ's rounding
    if (std::optional<BranchPoint> point = point_at(located ? *located : last, mid)) {
      inside = mid;
      located = std::move(point);
    } else {
      outside = mid;
    }
  }
  return located;
}

SpecialPoint EndPoint(const BranchPoint& point, StickingEnd end) {
  SpecialPoint special;
  special.point = point;
  special.parameter = point.parameter;
  special.monitor = Monitors(point.orbit)[static_cast<std::size_t>(end)];
  switch (end) {
    case StickingEnd::kNoSticking:
      special.type = SpecialPointType::kNoSticking;
      break;
    case StickingEnd::kEarlyRelease:
      special.type = SpecialPointType::kEarlyRelease;
      break;
    case StickingEnd::kNewImpact:
      special.type = SpecialPointType::kGrazing;
      break;
    case StickingEnd::kVanishingImpact: {
      special.type = SpecialPointType::kGrazing;
      const std::vector<OrbitImpact>& impacts = point.orbit.impacts;
      for (std::size_t i = 0; i < impacts.size(); ++i) {
        if (impacts[i].velocity == point.orbit.contacts.approach_impact_speed) {
          special.vanishing_impact = static_cast<int>(i);
          break;
        }
      }
      break;
    }
  }
  return special;
}

Termination TerminationOf(StickingEnd end) {
  switch (end) {
    case StickingEnd::kNoSticking:
      return Termination::kNoSticking;
    case StickingEnd::kEarlyRelease:
      return Termination::kEarlyRelease;
    default:
      return Termination::kGrazing;
  }
}

}  // namespace impactkit::detail
