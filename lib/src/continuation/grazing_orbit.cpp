// The grazing orbit at a located grazing of a branch (continuation.hpp),
// whose normal form (grazing_normal_form.hpp) says what the grazing does.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
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

/// The touch found must lie this close (relative to max(1, |p|)) to the
/// located grazing, or it is another one. A vanishing impact's located
/// parameter errs by more than end_tolerance, its Newton floor growing
/// like 1/v: on paper-mass1-stop's sticking chain the touches lie 5e-10
/// to 1e-7 from it.
constexpr double kTouchAgreement = 1e-6;
/// The touching orbit's clearance: ~1e-10 (RequireTouch allows 1e-8).
constexpr double kTouchClearance = 1e-10;
/// Secant steps towards it, each a tenth of the way closer.
constexpr int kTouchSteps = 8;

/// Where a sticking family's approach impact vanishes, the neighbouring
/// family (without it) touches, on the side `side` of the grazing: its
/// clearance c, solved 1e-6 and 2e-6 away, is followed by secant steps
/// towards its zero, each to a tenth of the nearer point's distance from
/// the zero estimate (so always on the family's side: at the zero itself
/// Newton may land on the side with the impact, at a speed of rounding's
/// square root), until c <= 1e-10. The clearance is not linear enough to
/// extrapolate at once: on paper-mass1-stop's sticking chain its
/// curvature moves the first estimate by up to 1e-7. None where no such
/// family opens on that side with its zero near the grazing.
std::optional<GrazingOrbit> NeighbouringTouch(const System& system, const Branch& branch,
                                              const SpecialPoint& graze,
                                              const StickingMapOptions& map_options, double side) {
  OrbitOptions options;
  options.q = branch.q;
  options.releases = branch.releases;
  options.release_map = map_options;
  const double scale = std::max(1.0, std::abs(graze.parameter));
  struct Sample {
    double p, c;
    System system;
    PeriodicOrbit orbit;
  };
  auto sample = [&](double value) -> std::optional<Sample> {
    Sample at{value, 0.0, system, {}};
    SetParameter(at.system, branch.parameter, value);
    const OrbitSummary solved = FindOrbit(at.system, graze.point.orbit.eta, options, &at.orbit);
    if (solved.termination != Termination::kConverged || !at.orbit.contacts.clearance) return {};
    at.c = *at.orbit.contacts.clearance;
    if (!(at.c > 0)) return {};
    return at;
  };
  auto far = sample(graze.parameter + side * 2e-6 * scale);
  auto near = sample(graze.parameter + side * 1e-6 * scale);
  for (int step = 0; step < kTouchSteps && far && near && near->c < far->c; ++step) {
    if (near->c <= kTouchClearance) {
      if (!(std::abs(near->p - graze.parameter) <= kTouchAgreement * scale)) return std::nullopt;
      return TouchingStickingOrbit(near->system, map_options, near->orbit, side);
    }
    const double zero = near->p - near->c * (far->p - near->p) / (far->c - near->c);
    far = std::move(near);
    near = sample(zero + 0.1 * (far->p - zero));
  }
  return std::nullopt;
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
    // Past the branch's end (the impact persists across the grazing as
    // the family without it), or on its own side (the two families fold
    // into each other there).
    for (const double side : {-branch_side, branch_side}) {
      if (auto orbit = NeighbouringTouch(system, branch, graze, map_options, side)) return *orbit;
    }
    throw InvalidInput(
        "no sticking family without the vanishing impact touches the stop at this grazing on "
        "either side of it (its clearance solved 1e-6 and 2e-6 away does not open to a zero "
        "here)");
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
