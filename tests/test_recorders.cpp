#include <catch2/catch.hpp>
#include <cmath>

#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"

using Catch::Matchers::WithinAbs;
using namespace impactkit;

namespace {

/// Runs the paper's system for a transient, then records `periods` periods.
void RecordSteady(double omega, int periods, Observer& observer) {
  const System s = PaperSystem(omega);
  Simulator simulator(s);
  HybridState state = RestState(s);
  simulator.Run(state, 100 * s.ForcingPeriod());
  simulator.Run(state, (100 + periods) * s.ForcingPeriod(), observer);
}

}  // namespace

TEST_CASE("exact per-period extrema bound dense samples tightly", "[recorders]") {
  for (double omega : {0.2, 0.6, 1.7}) {
    INFO("omega = " << omega);
    const double period = PaperSystem(omega).ForcingPeriod();
    ExtremaRecorder extrema(period);
    TimeSeriesRecorder dense(0.0, period / 20000);
    ObserverList both;
    both.Add(extrema);
    both.Add(dense);
    RecordSteady(omega, 4, both);
    const auto periods = extrema.CompletePeriods();
    REQUIRE(periods.size() >= 3);
    for (const PeriodExtrema& e : periods) {
      Eigen::Vector2d max = Eigen::Vector2d::Constant(-INFINITY), min = -max;
      double speed = 0.0;
      for (const Sample& s : dense.Samples()) {
        if (s.t < e.period * period || s.t > (e.period + 1) * period) continue;
        max = max.cwiseMax(s.x);
        min = min.cwiseMin(s.x);
        speed = std::max(speed, s.v.cwiseAbs().maxCoeff());
      }
      // Exact extrema are never inside the samples' range, and the samples
      // (spacing dt = T/20000) come within speed * dt of them: an extremum
      // at an impact is a corner, not a smooth maximum.
      const double dt = period / 20000;
      CHECK((e.max - max).minCoeff() >= -1e-13);
      CHECK((min - e.min).minCoeff() >= -1e-13);
      CHECK((e.max - max).maxCoeff() <= speed * dt);
      CHECK((min - e.min).maxCoeff() <= speed * dt);
    }
  }
}

TEST_CASE("stroboscopic points are the state at t = kT", "[recorders]") {
  const System s = PaperSystem(1.4);
  StroboscopicRecorder strobe(s.ForcingPeriod());
  HybridState state = RestState(s);
  Simulator simulator(s);
  simulator.Run(state, 10.5 * s.ForcingPeriod(), strobe);
  REQUIRE(strobe.Points().size() == 11);
  for (int k : {0, 3, 10}) {
    HybridState at = RestState(s);
    simulator.Run(at, k * s.ForcingPeriod());
    CHECK((strobe.Points()[k].x - at.x).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(strobe.Points()[k].t == k * s.ForcingPeriod());
  }
}

TEST_CASE("time series samples lie on the grid, once each", "[recorders]") {
  TimeSeriesRecorder series(0.0, 0.05);
  RecordSteady(0.2, 2, series);
  const auto& samples = series.Samples();
  REQUIRE(samples.size() > 100);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    CHECK_THAT(samples[i].t - samples[i - 1].t, WithinAbs(0.05, 1e-9));
  }
}

TEST_CASE("sticking intervals end at releases and hold the mass at the stop", "[recorders]") {
  StickingRecorder sticking;
  TimeSeriesRecorder series(0.0, 0.01);
  struct Releases : Observer {
    std::vector<double> times;
    void OnRelease(double, double t) override { times.push_back(t); }
  } releases;
  ObserverList all;
  all.Add(sticking);
  all.Add(series);
  all.Add(releases);
  RecordSteady(0.2, 3, all);
  REQUIRE(sticking.Intervals().size() >= 3);
  REQUIRE(releases.times.size() >= 3);
  for (std::size_t i = 0; i < releases.times.size(); ++i) {
    CHECK(sticking.Intervals()[i].end == releases.times[i]);
  }
  for (const Sample& s : series.Samples()) {
    if (s.stuck) CHECK(s.x(1) == 0.1);
  }
  CHECK(sticking.TotalTime() > 0.0);
}
