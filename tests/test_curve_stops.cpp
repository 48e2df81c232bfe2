// Two-parameter curves at any stop: the grazing of one mass's symmetric
// P(2,1) in a clearance (examples/systems/clearance-1dof.toml,
// docs/several-stops.md), followed in (omega, A1) and checked point by
// point against fresh one-parameter branches.

#include <catch2/catch.hpp>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <string>

#include "curve_plane.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"

using Catch::Matchers::WithinAbs;
using namespace impactkit;

namespace {

System ClearanceFile() {
  return ReadSystemFile(IMPACTKIT_SOURCE_DIR "/examples/systems/clearance-1dof.toml");
}

/// The symmetric P(2,1) of `system` at `omega`, seeded by simulation from
/// rest (its section the stop of the seed's last impact); empty where the
/// motion simulated is not that orbit.
std::optional<PeriodicOrbit> SymmetricOrbit(System system, double omega) {
  system.omega = omega;
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system, 500);
  if (!seed) return std::nullopt;
  OrbitOptions options;
  options.p = 2;
  options.q = 1;
  options.map.stop = seed->stop;
  PeriodicOrbit orbit;
  if (FindOrbit(system, seed->eta, options, &orbit).termination != Termination::kConverged ||
      orbit.impacts.size() != 2 || orbit.impacts[0].stop == orbit.impacts[1].stop) {
    return std::nullopt;  // not one impact at each stop
  }
  return orbit;
}

/// The grazing of the symmetric P(2,1) branch of `system` (at its A1)
/// continued in omega down from where simulation finds that orbit first
/// among `omegas`: a fresh one-parameter run.
SpecialPoint BranchGrazing(const System& system, std::initializer_list<double> omegas) {
  std::optional<PeriodicOrbit> orbit;
  double omega = 0.0;
  for (double w : omegas) {
    omega = w;
    orbit = SymmetricOrbit(system, w);
    if (orbit) break;
  }
  REQUIRE(orbit.has_value());
  System start = system;
  start.omega = omega;
  ContinuationOptions options;
  options.from = 0.5;
  options.to = omega;
  options.direction = ContinuationDirection::kDecreasing;
  options.orbit.p = 2;
  options.orbit.q = 1;
  options.orbit.map.stop = orbit->stop;
  const Branch branch = ContinueBranch({start, *orbit, {}}, options);
  REQUIRE(!branch.special_points.empty());
  const SpecialPoint& end = branch.special_points.back();
  INFO("the branch from omega = " << omega << " ends: " << branch.end_message);
  REQUIRE(end.type == SpecialPointType::kGrazing);
  return end;
}

}  // namespace

TEST_CASE(
    "a clearance's symmetric P(2,1) grazing followed in (omega, A1): each point is where a "
    "fresh branch in omega grazes",
    "[curve][stops]") {
  const System clearance = ClearanceFile();
  REQUIRE(clearance.StopCount() == 2);
  // The branch from omega = 1 down (at 0.8 a symmetric P(4,1) attracts
  // instead) grazes where the flight after each impact turns back to touch
  // the stop it left (both stops at once: the orbit is symmetric).
  const SpecialPoint graze = BranchGrazing(clearance, {1.0});
  CHECK_THAT(graze.parameter, WithinAbs(0.7010019931, 1e-9));
  CHECK(graze.vanishing_impact < 0);  // a new contact, not a vanishing impact

  // A1 scales the forcing and keeps the symmetry (x, t) → (−x, t + T/2):
  // the orbit stays symmetric along the curve and the branch grazes both
  // stops at once, so each point of the curve is the branch's grazing.
  // (xs alone would move one stop: the curve would follow that stop's
  // touch, beyond the other stop's on one side.)
  // Up to A1 = 1.15: at 1.2 the motion simulated at omega = 1 is P(8,3),
  // no seed for the fresh branches.
  CurveOptions options = testing::Plane("A1", 0.8, 1.15, 2, 1);
  options.to = 1.2;
  System at = clearance;
  at.omega = graze.parameter;
  const Curve curve = ContinueCurve({at, graze}, options);
  INFO("curve: begins " << ToString(curve.begin) << " (" << curve.begin_message << "), ends "
                        << ToString(curve.end) << " (" << curve.end_message << ")");
  REQUIRE(curve.points.size() > 10);
  CHECK(curve.begin == Termination::kParameterBound);
  CHECK(curve.end == Termination::kParameterBound);
  CHECK(curve.points.front().parameter2 == 0.8);
  CHECK(curve.points.back().parameter2 == 1.15);

  // Along the curve: the orbit grazes (defining rows zero, the flight's
  // turning point at a stop to kGrazingMargin) and stays symmetric (both
  // impacts at the same speed, one at each stop).
  for (const CurvePoint& point : curve.points) {
    INFO("omega = " << point.parameter << ", A1 = " << point.parameter2);
    CHECK(point.defining.cwiseAbs().maxCoeff() < 1e-9);
    REQUIRE(point.orbit.impacts.size() == 2);
    CHECK(point.orbit.impacts[0].stop != point.orbit.impacts[1].stop);
    CHECK_THAT(point.orbit.impacts[0].velocity, WithinAbs(point.orbit.impacts[1].velocity, 1e-9));
    REQUIRE(point.orbit.contacts.clearance.has_value());
    CHECK(std::abs(*point.orbit.contacts.clearance) < 1e-9);
  }

  // Points spread along the curve, each against a fresh branch in omega at
  // its A1, from the symmetric orbit seeded by simulation at omega = 1 (or
  // nearer the grazing where another motion attracts at 1).
  const std::size_t n = curve.points.size();
  for (const std::size_t k : {std::size_t{0}, n / 4, n / 2, 3 * n / 4, n - 1}) {
    const CurvePoint& point = curve.points[k];
    INFO("curve point " << k << ": omega = " << point.parameter << ", A1 = " << point.parameter2);
    System fresh = clearance;
    SetParameter(fresh, "A1", point.parameter2);
    const SpecialPoint branch = BranchGrazing(fresh, {1.0, 0.9, point.parameter + 0.05});
    CHECK_THAT(branch.parameter, WithinAbs(point.parameter, 1e-7));
  }
}

TEST_CASE("a grazing curve of a two-stop system starts from either stop's section",
          "[curve][stops]") {
  // The same grazing, its orbit described from the upper stop's impact and
  // from the lower one's: the same curve point at A1 = 1.1.
  const System clearance = ClearanceFile();
  const SpecialPoint graze = BranchGrazing(clearance, {1.0});
  System at = clearance;
  at.omega = graze.parameter;
  CurveOptions options = testing::Plane("A1", 1.0, 1.1, 2, 1);
  options.to = 1.2;
  SpecialPoint other = graze;
  const ImpactMap map(at, [&] {
    ImpactMapOptions section;
    section.stop = graze.point.orbit.stop;
    return section;
  }());
  const MapResult path = map.Apply(graze.point.orbit.eta, 1, false);
  REQUIRE(path.termination == Termination::kOtherStop);  // the next impact is at the other stop
  REQUIRE(!path.path.empty());
  OrbitOptions orbit;
  orbit.p = 2;
  orbit.q = 1;
  orbit.map.stop = path.stops.front();
  REQUIRE(FindOrbit(at, path.path.front(), orbit, &other.point.orbit).termination ==
          Termination::kConverged);
  REQUIRE(other.point.orbit.stop != graze.point.orbit.stop);
  const Curve a = ContinueCurve({at, graze}, options);
  const Curve b = ContinueCurve({at, other}, options);
  REQUIRE(a.end == Termination::kParameterBound);
  REQUIRE(b.end == Termination::kParameterBound);
  CHECK(a.points.back().parameter2 == 1.1);
  CHECK(b.points.back().parameter2 == 1.1);
  CHECK_THAT(b.points.back().parameter, WithinAbs(a.points.back().parameter, 1e-9));
}
