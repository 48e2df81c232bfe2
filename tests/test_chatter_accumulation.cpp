// Sticking from the true accumulation point (issue 41, item 2): complete
// chatter of a single mass near the end of its sticking family, where the
// acceleration at the stop is small and the bounces' tail long. Expected
// values from tests/reference/sdof_chatter_mp.py, a 50-digit computation
// written from the model alone (every bounce found on the closed-form
// flight until its speed is below 1e-25):
//
//     sdof_chatter_mp.py 1 0.1 1 1.2 0.3 0.6 0.4615 0.4618 0.46181 0.4618117 0.461812
#include <catch2/catch.hpp>
#include <cmath>

#include "impactkit/continuation/continuation.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"
#include "seeded_orbit.hpp"
#include "single_mass.hpp"

using namespace impactkit;
using Catch::Matchers::WithinAbs;
using testing::SingleMass;

namespace {

struct Reference {
  double omega, accumulation_phase, stuck_duration;
};

}  // namespace

TEST_CASE("sticking begins at the accumulation point of its chatter, near the family's end too",
          "[sticking][chatter-accumulation]") {
  const Reference references[] = {
      {0.4615, 2.7737142191864462157, 0.082441949075347859594},
      {0.4618, 2.8427030160751137219, 0.011597702099026524362},
      {0.46181, 2.8502546921771492174, 0.0039842191777758940984},
      {0.4618117, 2.8528737203333183499, 0.0013546841285390819498},
      {0.461812, 2.8538550161420706058, 0.00037153417021657108423},
  };
  for (const Reference& expected : references) {
    INFO("omega " << expected.omega);
    const System system = SingleMass(1.0, 0.1, 1.2, expected.omega, 0.3, 0.6);
    const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
    CHECK_THAT(orbit.stuck[0].stick_phase, WithinAbs(expected.accumulation_phase, 1e-9));
    // The bound, 1e-8 relative. Near the end the accumulation point
    // moves by ~10⁴ times an impact's time error: at Ω = 0.461812 (4e-8
    // from the end) the rounding of the absolute impact times alone (half
    // an ulp of t ≈ 16 each) spreads it by 3e-9 relative rms
    // (`sdof_chatter_mp.py 1 0.1 1 1.2 0.3 0.6 --rounding 6 0.461812`),
    // the floor of any double computation; ours is within 6e-10 there
    // (docs/theory.md §4).
    const double relative_error =
        std::abs(orbit.stuck[0].Duration() - expected.stuck_duration) / expected.stuck_duration;
    CAPTURE(relative_error);
    CHECK(relative_error <= 1e-8);
  }
}

TEST_CASE("the single mass's sticking family ends where its chatter stops accumulating",
          "[sticking][continuation][chatter-accumulation]") {
  // The 50-digit computation's bisection on whether the chatter after the
  // release accumulates before the next one:
  //     sdof_chatter_mp.py 1 0.1 1 1.2 0.3 0.6 --end 0.46181203 0.4618121
  //     family end between 0.4618120395456123 and 0.4618120395456791
  // Near the end the last bounces rise ~1e-14, the landing rule's
  // resolution (64 ulps of the gap's scale): the family runs on by the Ω
  // over which such a bounce decides the end, 7e-9 here (docs/theory.md §5a).
  constexpr double kEnd = 0.46181203954564;
  const System system = SingleMass(1.0, 0.1, 1.2, 0.45, 0.3, 0.6);
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  ContinuationOptions options;
  options.from = 0.44;
  options.to = 0.47;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == Termination::kNoSticking);
  CHECK_THAT(branch.points.back().parameter, WithinAbs(kEnd, 1e-8));
  CHECK(branch.special_points.back().point.parameter == branch.points.back().parameter);
  // A tolerance below the rounding of Ω ends the bisection there.
  options.end_tolerance = 1e-300;
  const Branch finest = ContinueBranch({system, start, {}}, options);
  CHECK_THAT(finest.points.back().parameter, WithinAbs(branch.points.back().parameter, 1e-9));
}

TEST_CASE("the stuck time per period of a sticking single mass is the exact one",
          "[simulate][chatter-accumulation]") {
  // The second system: stuck 7.4563728878455695 per period (the
  // 50-digit computation above: release where 0.9 cos Ωt = 1.3 xs, the
  // accumulation point of the chatter before it).
  const System system = SingleMass(1.3, 0.06, 0.9, 0.25, 0.2, 0.6);
  HybridState state = RestState(system);
  const Simulator simulator(system);
  simulator.Run(state, 50 * system.ForcingPeriod());
  const SimulationSummary summary = simulator.Run(state, 52 * system.ForcingPeriod());
  CHECK_THAT(summary.stuck_time / 2, WithinAbs(7.4563728878455695, 1e-9));
  CHECK(summary.chatter_cuts == 0);
}
