// The simulator against a frozen copy of its own earlier results: the first
// 10^4 impacts of the paper system at Ω = 0.6 from rest (a period-2 motion),
// recorded before the speed work of the performance issue
// (tests/data/paper_omega0.6_impacts.csv says how). test_fingerprints.cpp
// checks the bits; this test states the tolerance an event search that
// changes them must keep: impact times, flight times (between consecutive
// impacts) and impact velocities within 1e-12 max(1, t). Relative to t
// because an impact time t is only known to a few ulps of t (the forcing
// phase Ω t is rounded): at t = 5e4 an ulp is 7e-12, and two correct
// searches differ there by up to ~2e-10 in a flight time and ~2e-11 in a
// velocity, while the first impacts agree to ~1e-14.

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"

using namespace impactkit;

namespace {

struct FrozenImpact {
  double t;
  double velocity;
};

std::vector<FrozenImpact> ReadFrozenImpacts(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<FrozenImpact> impacts;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;  // comments and header
    std::istringstream fields(line);
    FrozenImpact impact{};
    char comma = 0;
    fields >> impact.t >> comma >> impact.velocity;
    REQUIRE((fields && comma == ','));
    impacts.push_back(impact);
  }
  return impacts;
}

}  // namespace

TEST_CASE("10^4 impacts agree with the frozen earlier results to 1e-12 max(1, t)", "[simulate]") {
  const std::vector<FrozenImpact> frozen = ReadFrozenImpacts(
      std::string(IMPACTKIT_SOURCE_DIR) + "/tests/data/paper_omega0.6_impacts.csv");
  REQUIRE(frozen.size() == 10000);

  const System s = PaperSystem(0.6);
  ImpactRecorder recorder;
  HybridState state = RestState(s);
  // Just past the last frozen impact, so the run holds exactly those.
  Simulator(s).Run(state, frozen.back().t + 1e-3, recorder);
  const ImpactLog& impacts = recorder.Impacts();
  REQUIRE(impacts.size() == frozen.size());

  // Each difference divided by max(1, t), t the later impact's time.
  double worst_time = 0.0, worst_flight = 0.0, worst_velocity = 0.0;
  for (std::size_t i = 0; i < frozen.size(); ++i) {
    const double scale = std::max(1.0, frozen[i].t);
    worst_time = std::max(worst_time, std::abs(impacts[i].t - frozen[i].t) / scale);
    worst_velocity =
        std::max(worst_velocity, std::abs(impacts[i].velocity - frozen[i].velocity) / scale);
    if (i > 0) {
      const double flight = impacts[i].t - impacts[i - 1].t;
      worst_flight =
          std::max(worst_flight, std::abs(flight - (frozen[i].t - frozen[i - 1].t)) / scale);
    }
  }
  INFO("relative time " << worst_time << ", flight " << worst_flight << ", velocity "
                        << worst_velocity);
  CHECK(worst_time <= 1e-12);
  CHECK(worst_flight <= 1e-12);
  CHECK(worst_velocity <= 1e-12);
}
