// The start orbit's rule (analysis/start_orbit.hpp): which orbit a steady
// simulation or a guess gives, and the requests it refuses.
#include <catch2/catch.hpp>
#include <cmath>

#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/start_orbit.hpp"

namespace impactkit {
namespace {

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;

/// The distance of two phases on the circle of period `period`.
double PhaseDistance(double a, double b, double period) {
  const double d = std::fmod(std::abs(a - b), period);
  return std::min(d, period - d);
}

}  // namespace

TEST_CASE(
    "where the motion sticks the start is its sticking orbit, unless an impacting one is asked for",
    "[start][sticking]") {
  const System system = PaperSystem(0.2);
  const StartOrbit any = FindStartOrbit(system, {});
  REQUIRE(any.seeded);
  REQUIRE(any.summary.termination == Termination::kConverged);
  CHECK(any.orbit.Sticks());
  CHECK(any.options.releases == 1);
  CHECK(any.orbit.q == 1);
  // The simulator's accumulation and release (docs/cli.md's sample, checked
  // against the simulation in test_sticking_stops.cpp).
  CHECK_THAT(any.orbit.stuck[0].stick_phase, WithinAbs(30.464633012, 1e-8));
  CHECK_THAT(any.orbit.stuck[0].release_phase, WithinAbs(6.633818118, 1e-8));

  StartOrbitRequest impacting;
  impacting.kind = StartOrbitKind::kImpacting;
  const StartOrbit none = FindStartOrbit(system, impacting);
  CHECK_FALSE(none.seeded);
  CHECK(none.summary.termination == Termination::kFailure);
  CHECK_THAT(none.summary.message, Contains("an impact map orbit cannot stick"));
}

TEST_CASE("where the motion does not stick the start is the impacting orbit it settles on",
          "[start]") {
  const System system = PaperSystem(0.6);
  const StartOrbit any = FindStartOrbit(system, {});
  REQUIRE(any.summary.termination == Termination::kConverged);
  CHECK_FALSE(any.orbit.Sticks());
  // The simulated motion's period and, to the settling of 500 periods, its
  // last impact's phase.
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system, 500);
  REQUIRE(seed);
  CHECK(any.orbit.p == static_cast<int>(seed->motion.p));
  CHECK(any.orbit.q == seed->motion.q);
  const double period = system.ForcingPeriod();
  double nearest = period;
  for (const OrbitImpact& impact : any.orbit.impacts) {
    nearest = std::min(nearest, PhaseDistance(impact.t, seed->eta(1), period));
  }
  CHECK(nearest < 1e-6);

  StartOrbitRequest sticking;
  sticking.kind = StartOrbitKind::kSticking;
  const StartOrbit none = FindStartOrbit(system, sticking);
  CHECK_FALSE(none.seeded);
  CHECK_THAT(none.summary.message, Contains("does not stick periodically"));

  // The orbit found again from its own impact state as a guess: p and q
  // given, the same orbit to the solver's tolerance.
  StartOrbitRequest again;
  again.guess = any.orbit.eta;
  again.p = any.orbit.p;
  again.q = any.orbit.q;
  const StartOrbit refound = FindStartOrbit(system, again);
  REQUIRE(refound.summary.termination == Termination::kConverged);
  CHECK((refound.orbit.eta - any.orbit.eta).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("a start request that names no orbit is refused before any simulation", "[start]") {
  const System system = PaperSystem(0.6);
  auto refused = [&](StartOrbitRequest request, const char* message) {
    CHECK_THROWS_WITH(FindStartOrbit(system, request), Contains(message));
  };
  StartOrbitRequest request;
  request.p = 1;
  refused(request, "p and q go together");
  request.releases = 1;
  refused(request, "give p (an impacting orbit) or releases");
  request = {};
  request.kind = StartOrbitKind::kSticking;
  request.p = 1;
  request.q = 1;
  refused(request, "a sticking orbit has no p");
  request = {};
  request.kind = StartOrbitKind::kImpacting;
  request.releases = 1;
  refused(request, "an impacting orbit has no releases");
  request = {};
  request.releases = 0;
  refused(request, "releases must be >= 1");
  request = {};
  request.transient = -1;
  refused(request, "transient must be >= 0");
  request = {};
  request.guess = Eigen::Vector4d(0.1, 1.0, 0.2, 0.5);
  request.stop = 1;
  refused(request, "stop must be in [0, 0]");
}

}  // namespace impactkit
