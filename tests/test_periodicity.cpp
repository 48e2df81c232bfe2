#include <catch2/catch.hpp>

#include "impactkit/analysis/periodicity.hpp"
#include "impactkit/hybrid/simulator.hpp"

using namespace impactkit;

namespace {

/// Records stroboscopic points, impact times and chatter ends.
class PeriodProbe : public Observer {
 public:
  explicit PeriodProbe(double period) : strobe(period) {}
  void OnSegment(const Segment& segment) override { strobe.OnSegment(segment); }
  void OnImpact(const Impact& impact) override { impacts.push_back(impact.t); }
  void OnChatter(const ChatterEnd& chatter) override { chatter_ends.push_back(chatter.t_end); }
  StroboscopicRecorder strobe;
  std::vector<double> impacts, chatter_ends;
};

MotionPeriod SteadyPeriod(double omega) {
  const System s = PaperSystem(omega);
  Simulator simulator(s);
  HybridState state = RestState(s);
  simulator.Run(state, 500 * s.ForcingPeriod());
  PeriodProbe probe(s.ForcingPeriod());
  simulator.Run(state, 564 * s.ForcingPeriod(), probe);
  return DetectPeriod(probe.strobe.Points(), probe.impacts, probe.chatter_ends);
}

}  // namespace

// The paper's Sec. 3.1 and Fig. 4: the motion at each sample frequency.
TEST_CASE("the paper's periodic motions are recognised", "[periodicity]") {
  struct Expected {
    double omega;
    const char* motion;
  };
  for (const Expected& e :
       {Expected{0.2, "P(inf,1)"}, Expected{0.4, "P(4,1)"}, Expected{0.6, "P(2,1)"},
        Expected{0.9, "P(1,1)"}, Expected{1.4, "P(1,1)"}, Expected{1.7, "P(4,4)"},
        Expected{2.0, "P(1,2)"}}) {
    INFO("omega = " << e.omega);
    CHECK(SteadyPeriod(e.omega).ToString() == e.motion);
  }
}

TEST_CASE("a non-repeating window is not called periodic", "[periodicity]") {
  SampleLog strobe;
  for (int k = 0; k < 20; ++k) {
    strobe.push_back(
        Sample{double(k), Eigen::Vector2d(std::sin(k * 1.0), 0.0), Eigen::Vector2d::Zero(), false});
  }
  CHECK_FALSE(DetectPeriod(strobe, {}, {}).periodic);
}
