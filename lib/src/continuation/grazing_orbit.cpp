// The grazing orbit at a located grazing of a branch (continuation.hpp),
// whose normal form (grazing_normal_form.hpp) says what the grazing does.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "continuation/branch_problem.hpp"
#include "continuation/vanishing_impact.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/sticking_map.hpp"
#include "orbits/orbit_shooting.hpp"

namespace impactkit {
namespace {

/// Newton steps on the touch time: v_c = 0 is quadratic convergence from a
/// guess O(v_k / a) away, v_k the vanishing impact's speed.
constexpr int kTouchTimeSteps = 8;

/// The impacts η_0 … η_{p−1} of the orbit through `eta` (p impacts) and
/// their stops.
std::vector<StopContact> OrbitImpacts(const ImpactMap& map, const Eigen::VectorXd& eta, int p) {
  const MapResult path = map.Apply(eta, p, false);
  Require(path.termination == Termination::kCompleted,
          "the branch's last orbit cannot be followed round: " + ToString(path.termination));
  std::vector<StopContact> impacts = {{map.ToState(eta), map.SectionStop()}};
  for (int k = 0; k + 1 < p; ++k) {
    impacts.push_back({map.ToState(path.path[k], path.stops[k]), path.stops[k]});
  }
  return impacts;
}

/// The time in the free flight after `from` (at stop `from_stop`) where
/// stop `touched`'s mass turns (v_c = 0), from the guess t.
double TouchTime(const ImpactMap& map, const HybridSystem& hybrid, const Eigen::VectorXd& from,
                 int from_stop, int touched, double t) {
  const int c = hybrid.GetStop(touched).Dof(), n = hybrid.GetSystem().Dof();
  for (int step = 0; step < kTouchTimeSteps; ++step) {
    const HybridState at = map.FlightState(from, t, from_stop);
    const double acceleration = hybrid.VectorField(at.t, at.x, at.v)(n + c);
    t -= at.v(c) / acceleration;
  }
  return t;
}

/// Where impact k of the branch's last orbit (through `eta` at `map`, p
/// impacts) vanishes at `system`: the orbit without it, p − 1 impacts at
/// the other impacts' stops (solved at fixed times, orbit_shooting.hpp,
/// which the touch does not disturb), touching impact k's stop at the turn
/// of the flight that held impact k.
GrazingOrbit ReducedGrazingOrbit(const System& system, const ImpactMap& map,
                                 const Eigen::VectorXd& eta, int p, int q, int k) {
  const std::vector<StopContact> impacts = OrbitImpacts(map, eta, p);
  const double period = q * system.ForcingPeriod();
  // The others in time order from the one after impact k.
  std::vector<StopContact> others;
  for (int j = 1; j < p; ++j) {
    StopContact impact = impacts[(k + j) % p];
    if (k + j >= p) impact.state.t += period;
    others.push_back(impact);
  }
  const auto hybrid = std::make_shared<const HybridSystem>(system);
  ImpactMapOptions options;
  options.stop = others.front().stop;
  const ImpactMap reduced_map(hybrid, options);
  std::vector<int> stops;
  std::vector<Eigen::VectorXd> etas;
  for (const StopContact& impact : others) {
    stops.push_back(impact.stop);
    etas.push_back(reduced_map.ToEta(impact.state.t, impact.state.x, impact.state.v, impact.stop));
  }
  const ShootingProblem problem(*hybrid, reduced_map, stops, q);
  Eigen::VectorXd z = problem.Pack(etas);
  const SolveSummary solve = problem.Solve(NewtonOptions{}, &z);
  Require(solve.termination == Termination::kConverged,
          "the orbit without the vanishing impact could not be found: " + solve.message);
  // Impact k lay in the flight after the last of the others, a period
  // before the first: the touch is that flight's turn, shifted to precede
  // the first.
  const int last = problem.Impacts() - 1;
  const int touched = impacts[k].stop;
  const double t = TouchTime(reduced_map, *hybrid, problem.Eta(z, last), problem.Stop(last),
                             touched, impacts[k].state.t + period);
  GrazingOrbit orbit{system, q, {}};
  HybridState touch = reduced_map.FlightState(problem.Eta(z, last), t, problem.Stop(last));
  touch.t -= period;
  orbit.contacts.push_back({touch, touched});
  for (int j = 0; j < problem.Impacts(); ++j) {
    orbit.contacts.push_back({reduced_map.ToState(problem.Eta(z, j), stops[j]), stops[j]});
  }
  return orbit;
}

/// The sticking orbit `orbit` (of `system`, on `map`'s section, k
/// releases in q periods) as a grazing orbit touching at its clearance's
/// turn, its family keeping off the stop on `smooth_side`.
GrazingOrbit TouchingStickingOrbit(const System& system, const StickingMapOptions& map_options,
                                   const PeriodicOrbit& orbit, double smooth_side) {
  Require(orbit.contacts.clearance.has_value(), "the grazing orbit has no flight maximum");
  StickingGrazing sticking{map_options, orbit.releases, orbit.eta, 0.0, smooth_side};
  const StickingMap map(system, map_options);
  const HybridState release = map.ToState(orbit.eta);
  const StickingFlight to_touch =
      map.Follow(release, orbit.contacts.clearance_time, false, map_options.stop);
  Require(to_touch.termination == Termination::kCompleted,
          "the grazing orbit cannot be followed to its touch: " + Describe(to_touch.termination));
  sticking.previous_event = release.t;
  for (const StickingCycle& cycle : to_touch.cycles) {
    sticking.previous_event = std::max(sticking.previous_event, cycle.release);
    for (const StickingImpact& impact : cycle.impacts) {
      sticking.previous_event = std::max(sticking.previous_event, impact.t);
    }
  }
  GrazingOrbit grazing{system, orbit.q, {{to_touch.state, orbit.contacts.clearance_stop}}};
  grazing.sticking = std::move(sticking);
  return grazing;
}

/// Where a sticking family's approach impact vanishes, the neighbouring
/// family (without it, past the branch's end on `side`) touches: its
/// clearance, linear in the parameter there, is solved at two distances
/// 1e-6 and 2e-6 past and extrapolated to its zero p*, and the orbit taken
/// 1e-10 short of it on its side (its gap ~1e-10, where the orbit at p*
/// itself may come out with the impact at a speed of rounding's square
/// root). The extrapolation errs by c'' Δ² ~ 1e-12.
GrazingOrbit NeighbouringTouch(const System& system, const Branch& branch,
                               const SpecialPoint& graze, const StickingMapOptions& map_options,
                               double side) {
  OrbitOptions options;
  options.q = branch.q;
  options.releases = branch.releases;
  options.release_map = map_options;
  const double scale = std::max(1.0, std::abs(graze.parameter));
  auto orbit_at = [&](double value) {
    System at = system;
    SetParameter(at, branch.parameter, value);
    PeriodicOrbit orbit;
    const OrbitSummary solved = FindOrbit(at, graze.point.orbit.eta, options, &orbit);
    Require(solved.termination == Termination::kConverged && orbit.contacts.clearance,
            "the neighbouring sticking family, without the vanishing impact, could not be found: " +
                solved.message);
    return std::make_pair(at, orbit);
  };
  const double p1 = graze.parameter + side * 1e-6 * scale,
               p2 = graze.parameter + side * 2e-6 * scale;
  const double c1 = *orbit_at(p1).second.contacts.clearance;
  const double c2 = *orbit_at(p2).second.contacts.clearance;
  Require(c2 > c1 && c1 > 0, "the neighbouring sticking family's clearance does not open past it");
  const double touch = p1 - c1 * (p2 - p1) / (c2 - c1) + side * 1e-10 * scale;
  const auto [at, orbit] = orbit_at(touch);
  return TouchingStickingOrbit(at, map_options, orbit, side);
}

/// A sticking family's grazing orbit: at a new contact the located point's
/// orbit (its clearance 0 to end_tolerance), its family keeping off the
/// stop on the branch's side; where an approach impact vanishes, the
/// neighbouring family's touch (NeighbouringTouch).
GrazingOrbit StickingGrazingOrbit(const System& system, const Branch& branch,
                                  const SpecialPoint& graze, const ContinuationOptions& options) {
  StickingMapOptions map_options = options.orbit.release_map;
  map_options.stop = branch.stop;
  // The branch's points all lie on the side it was followed from.
  const double from = branch.points.front().parameter, to = branch.points.back().parameter;
  const double away = std::abs(from - graze.parameter) > std::abs(to - graze.parameter) ? from : to;
  const double branch_side = away < graze.parameter ? -1.0 : 1.0;
  if (graze.vanishing_impact >= 0) {
    return NeighbouringTouch(system, branch, graze, map_options, -branch_side);
  }
  System on_branch = system;
  SetParameter(on_branch, branch.parameter, graze.point.parameter);
  return TouchingStickingOrbit(on_branch, map_options, graze.point.orbit, branch_side);
}

}  // namespace

GrazingOrbit GrazingOrbitAt(const System& system, const Branch& branch, const SpecialPoint& graze,
                            const ContinuationOptions& options) {
  Require(graze.type == SpecialPointType::kGrazing,
          "a grazing orbit needs a located grazing point, got " + ToString(graze.type));
  if (branch.section == OrbitSection::kRelease) {
    return StickingGrazingOrbit(system, branch, graze, options);
  }
  System at = system;
  SetParameter(at, branch.parameter, graze.parameter);
  if (graze.vanishing_impact >= 0 && branch.p == 1) {
    return ShortestPeriod({at, branch.q, {ResponseTouch(at, detail::NonImpactingTouchStop(at))}});
  }
  System on_branch = system;
  SetParameter(on_branch, branch.parameter, graze.point.parameter);
  ImpactMapOptions map_options = options.orbit.map;
  map_options.stop = branch.stop;
  const ImpactMap map(on_branch, map_options);
  const PeriodicOrbit& orbit = graze.point.orbit;
  if (graze.vanishing_impact >= 0) {
    return ShortestPeriod(
        ReducedGrazingOrbit(at, map, orbit.eta, branch.p, branch.q, graze.vanishing_impact));
  }
  const OrbitContacts& contacts = orbit.contacts;
  Require(contacts.clearance.has_value(), "the grazing orbit has no flight maximum");
  const std::optional<std::vector<StopContact>> touch =
      TouchContacts(map, orbit.eta, branch.p, branch.q, contacts.clearance_flight,
                    contacts.clearance_time, contacts.clearance_stop);
  Require(touch.has_value(), "the grazing orbit cannot be followed round");
  return {on_branch, branch.q, *touch};
}

}  // namespace impactkit
