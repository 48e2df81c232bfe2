// The simulator against a frozen copy of its own earlier results: the first
// 10^4 impacts of the paper system at Ω = 0.6 from rest, recorded before the
// speed work of the performance issue (tests/data/paper_omega0.6_impacts.csv
// says how). test_fingerprints.cpp checks the bits; this test states the
// tolerance an optimised event search must keep when it changes them: impact
// times to 1e-12 (relative to t, so a few ulps at t ~ 5e4), every flight time
// (between consecutive impacts) and impact velocity to 1e-12 absolute. The
// orbit is stable, so a change in the last bits does not grow along the run.

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

TEST_CASE("10^4 impacts agree with the frozen earlier results to 1e-12", "[simulate]") {
  const std::vector<FrozenImpact> frozen = ReadFrozenImpacts(
      std::string(IMPACTKIT_SOURCE_DIR) + "/tests/data/paper_omega0.6_impacts.csv");
  REQUIRE(frozen.size() == 10000);

  const System s = PaperSystem(0.6);
  ImpactRecorder recorder;
  HybridState state = RestState(s);
  // Just past the last frozen impact, so the run holds exactly those.
  Simulator(s).Run(state, frozen.back().t + 1e-3, recorder);
  const std::vector<Impact>& impacts = recorder.Impacts();
  REQUIRE(impacts.size() == frozen.size());

  double worst_time = 0.0, worst_flight = 0.0, worst_velocity = 0.0;
  for (std::size_t i = 0; i < frozen.size(); ++i) {
    worst_time =
        std::max(worst_time, std::abs(impacts[i].t - frozen[i].t) / std::max(1.0, frozen[i].t));
    worst_velocity = std::max(worst_velocity, std::abs(impacts[i].velocity - frozen[i].velocity));
    if (i > 0) {
      const double flight = impacts[i].t - impacts[i - 1].t;
      worst_flight = std::max(worst_flight, std::abs(flight - (frozen[i].t - frozen[i - 1].t)));
    }
  }
  INFO("relative time " << worst_time << ", flight " << worst_flight << ", velocity "
                        << worst_velocity);
  CHECK(worst_time <= 1e-12);
  CHECK(worst_flight <= 1e-12);
  CHECK(worst_velocity <= 1e-12);
}
