#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/core/large_buffer_allocator.hpp"
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
      for (const SampleView s : dense.Samples()) {
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
    void OnRelease(const Release& release) override { times.push_back(release.t_release); }
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
  for (const SampleView s : series.Samples()) {
    if (s.stuck) CHECK(s.x(1) == 0.1);
  }
  CHECK(sticking.TotalTime() > 0.0);
}

TEST_CASE("a series with events has each impact before and after, and every stick and release",
          "[recorders]") {
  for (double omega : {1.4, 0.2}) {
    INFO("omega = " << omega);
    const System s = PaperSystem(omega);
    const double period = s.ForcingPeriod();
    const int c = s.stops[0].dof;
    TimeSeriesRecorder plain(100 * period, period / 50),
        with_events(100 * period, period / 50, true);
    ImpactRecorder impacts;
    ChatterRecorder chatter;
    struct Releases : Observer {
      std::vector<double> times;
      void OnRelease(const Release& release) override { times.push_back(release.t_release); }
    } releases;
    ObserverList all;
    for (Observer* o :
         std::initializer_list<Observer*>{&plain, &with_events, &impacts, &chatter, &releases}) {
      all.Add(*o);
    }
    RecordSteady(omega, 3, all);
    std::vector<Sample> grid, before, after, sticks, release_samples;
    for (const SampleView sample : with_events.Samples()) {
      switch (sample.kind) {
        case SampleKind::kGrid:
          grid.push_back(sample.Owned());
          break;
        case SampleKind::kBeforeImpact:
          before.push_back(sample.Owned());
          break;
        case SampleKind::kAfterImpact:
          after.push_back(sample.Owned());
          break;
        case SampleKind::kStick:
          sticks.push_back(sample.Owned());
          break;
        case SampleKind::kRelease:
          release_samples.push_back(sample.Owned());
          break;
      }
    }
    // The grid is the plain recorder's, sample for sample.
    REQUIRE(grid.size() == plain.Samples().size());
    for (std::size_t i = 0; i < grid.size(); ++i) {
      CHECK(grid[i].t == plain.Samples()[i].t);
      CHECK(grid[i].v == plain.Samples()[i].v);
    }
    // Time order throughout.
    for (std::size_t i = 1; i < with_events.Samples().size(); ++i) {
      CHECK(with_events.Samples()[i].t >= with_events.Samples()[i - 1].t);
    }
    // Each impact twice; after it, v_c = -r v_c (the impact law), the rest unchanged.
    REQUIRE(before.size() == impacts.Impacts().size());
    REQUIRE(after.size() == before.size());
    REQUIRE_FALSE(before.empty());
    for (std::size_t k = 0; k < before.size(); ++k) {
      const ImpactView impact = impacts.Impacts()[k];
      CHECK(before[k].t == impact.t);
      CHECK(after[k].t == impact.t);
      CHECK(before[k].x(c) == s.stops[0].position);
      CHECK(before[k].v(c) == impact.velocity);
      CHECK_THAT(after[k].v(c), WithinAbs(-s.stops[0].restitution * impact.velocity, 1e-15));
      CHECK(after[k].v(0) == before[k].v(0));
    }
    // Sticking at chatter ends where the mass is held, released at the releases.
    if (omega == 0.2) {
      REQUIRE(sticks.size() >= 3);
      REQUIRE(release_samples.size() == releases.times.size());
      for (const Sample& stick : sticks) {
        CHECK(stick.stuck);
        CHECK(stick.x(c) == s.stops[0].position);
        CHECK(stick.v(c) == 0.0);
        CHECK(std::count(chatter.EndTimes().begin(), chatter.EndTimes().end(), stick.t) == 1);
        // The state there, by a separate run to that instant.
        HybridState state = RestState(s);
        Simulator simulator(s);
        simulator.Run(state, stick.t);
        CHECK((state.x - stick.x).cwiseAbs().maxCoeff() < 1e-12);
      }
      for (std::size_t k = 0; k < releases.times.size(); ++k) {
        CHECK(release_samples[k].t == releases.times[k]);
        CHECK_FALSE(release_samples[k].stuck);
      }
    } else {
      CHECK(sticks.empty());
      CHECK(release_samples.empty());
    }
  }
}

TEST_CASE("a record log gives back every record it was given, field by field", "[recorders]") {
  // Impacts of a 3-DOF system, as an ImpactRecorder's vector of records
  // would have held them; every view's fields and vectors are the record's.
  // 10^5 of them: both of the log's buffers grow past 2 MiB, into huge
  // pages (core/large_buffer_allocator.hpp), copied there as they grow;
  // from no room, and from room for fewer (it grows past it) or more.
  const std::size_t room = GENERATE(0, 60000, 200000);
  INFO("reserved " << room);
  std::vector<Impact> given;
  ImpactLog log;
  log.reserve(room);
  for (int k = 0; k < 100000; ++k) {
    const double s = k;
    const Eigen::Vector3d x(s, 0.5 * s, -1.0), v(0.1 * s, -2.0, s * s), after(-0.1 * s, 2.0, 1.0);
    given.push_back(Impact{0.25 * s, k % 2, 0.01 * s, 1.0 / (1 + s), x, v, after});
    log.push_back(given.back());
  }
  REQUIRE(log.size() == given.size());
  std::size_t k = 0, differing = 0;
  for (const ImpactView view : log) {
    const Impact& expected = given[k++];
    const bool same = view.t == expected.t && view.stop == expected.stop &&
                      view.phase == expected.phase && view.velocity == expected.velocity &&
                      view.x == expected.x && view.v == expected.v &&
                      view.v_after == expected.v_after;
    if (!same) ++differing;
  }
  CHECK(differing == 0);
  CHECK(k == given.size());
  const Impact last = log.back().Owned();
  CHECK(last.v_after == given.back().v_after);
  CHECK(log.front().x == given.front().x);

  // A record of another length would be read back wrongly: refused.
  const Eigen::Vector3d x = given.back().x;
  const Eigen::Vector2d short_vector(1.0, 2.0);
  CHECK_THROWS_AS(log.push_back(Impact{1.0, 0, 0.0, 1.0, x, short_vector, x}), InvalidInput);
  REQUIRE(log.size() == given.size());
  CHECK(log.back().v_after == given.back().v_after);
  log.push_back(given.front());
  CHECK(log.back().x == given.front().x);
  // Room asked for once records exist keeps them and takes more.
  log.reserve(2 * given.size());
  log.push_back(given[1]);
  CHECK(log.back().x == given[1].x);
  CHECK(log[given.size() / 2].v == given[given.size() / 2].v);
}

TEST_CASE("a steady window given room records what one without room does", "[recorders]") {
  // Room for the whole window, for too few periods (it grows past it) and
  // for a negative count (none): the same impacts, points and period P(2,1)
  // as the window recorded without room, value for value.
  const double omega = 0.6;
  const int periods = 300;
  const double period = PaperSystem(omega).ForcingPeriod();
  SteadyWindowRecorder plain(period);
  RecordSteady(omega, periods, plain);
  for (const long room : {long{periods}, 10L, -5L}) {
    INFO("room for " << room << " periods");
    SteadyWindowRecorder reserved(period);
    reserved.Reserve(room);
    RecordSteady(omega, periods, reserved);
    REQUIRE(reserved.Impacts().size() == plain.Impacts().size());
    REQUIRE(reserved.Strobe().size() == plain.Strobe().size());
    for (std::size_t k = 0; k < plain.Impacts().size(); ++k) {
      CHECK(reserved.Impacts()[k].t == plain.Impacts()[k].t);
      CHECK(reserved.Impacts()[k].x == plain.Impacts()[k].x);
    }
    for (std::size_t k = 0; k < plain.Strobe().size(); ++k) {
      CHECK(reserved.Strobe()[k].x == plain.Strobe()[k].x);
    }
    const MotionPeriod motion = reserved.Period();
    CHECK(motion.periodic);
    CHECK(motion.p == 2);
    CHECK(motion.q == 1);
  }
}

TEST_CASE("the record logs' allocator aligns large buffers to 2 MiB and keeps every value",
          "[recorders]") {
  using Allocator = LargeBufferAllocator<double>;
  std::vector<double, Allocator> small(100, 1.5), large;
  const int count = 1 << 20;  // 8 MiB, grown through small and large buffers
  for (int i = 0; i < count; ++i) large.push_back(0.5 * i);
  CHECK(reinterpret_cast<std::uintptr_t>(large.data()) % Allocator::kHugePage == 0);
  int differing = 0;
  for (int i = 0; i < count; ++i) differing += large[i] != 0.5 * i;
  CHECK(differing == 0);
  CHECK(small.back() == 1.5);
}
