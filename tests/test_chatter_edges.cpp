// The edges of chatter (docs/theory.md §4): elastic and near-elastic
// chatter that never accumulates, arrivals at the stop at zero speed, and
// the per-period work bound.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "hybrid/chatter_rule.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/parameters.hpp"
#include "single_mass.hpp"

using Catch::Matchers::WithinAbs;
using namespace impactkit;
using testing::SingleMass;

namespace {

/// The 3-mass system with r = 1 that logged 2.5 million impacts in
/// two forcing periods.
System ElasticChain() {
  Eigen::MatrixXd m(3, 3), k(3, 3), c(3, 3);
  m << 0.7212, 0, 0, 0, 0.3845, 0, 0, 0, 2.672;
  k << 7.618, -3.867, 0, -3.867, 7.166, -3.300, 0, -3.300, 3.300;
  c << 2.085, -1.811, 0, -1.811, 2.332, -0.520, 0, -0.520, 0.520;
  return GeneralSystem(m, c, k, Eigen::Vector3d(-0.3644, 0.1057, 0.2527), 0.06768, 0.05923, 1.0, 1);
}

struct Releases : Observer {
  std::vector<double> times;
  void OnRelease(const Release& release) override { times.push_back(release.t_release); }
};

/// The first time after `from` where the closed form x(t) reaches 0 from
/// below, by bisection on a fine grid: independent of the event search.
template <class F>
double FirstUpwardZero(const F& x, double from, double to) {
  const int steps = 200000;
  const double h = (to - from) / steps;
  double a = from + h;
  for (int i = 1; i < steps; ++i, a += h) {
    if (x(a) < 0 && x(a + h) >= 0) {
      double lo = a, hi = a + h;
      for (int j = 0; j < 200 && hi - lo > 1e-15 * hi; ++j) {
        const double mid = 0.5 * (lo + hi);
        (x(mid) < 0 ? lo : hi) = mid;
      }
      return hi;
    }
  }
  return std::nan("");
}

}  // namespace

TEST_CASE("elastic chatter (r = 1) of a damped mass ends as contact and releases where Fs = 0",
          "[simulate][chatter]") {
  // Pressed into the stop for part of each period, the mass bounces
  // elastically; only damping in flight takes energy, so the bounces never
  // accumulate. The micro-bounce rule ends them; the release is where the
  // held mass's contact force A cos Ωt − k xs falls through 0, whatever
  // the rule's resolution: Ωt = arccos(k xs / A) mod 2π.
  const System s = SingleMass(1.0, 2.0, 1.0, 0.05, 0.2, 1.0);
  const double release_phase = std::acos(0.2) / 0.05;
  for (const double resolution : {1.0, 0.25}) {
    INFO("resolution x " << resolution);
    SimulationOptions options;
    options.chatter_span *= resolution;
    options.bounce_height_resolution *= resolution;
    HybridState state = RestState(s);
    Releases releases;
    const SimulationSummary summary = Simulate(s, options, state, 4 * s.ForcingPeriod(), releases);
    CHECK(summary.termination == Termination::kCompleted);
    CHECK(summary.chatter_jumps >= 3);
    // The bounces decay as 1/k (damping takes ~u³ per bounce), so their
    // number grows as the rule's bounce speed falls: ~2800 per period here.
    CHECK(summary.impacts < 4 * 40000 / resolution);
    REQUIRE(releases.times.size() >= 3);
    for (const double t : releases.times) {
      CHECK_THAT(s.Phase(t), WithinAbs(release_phase, 1e-9));
    }
  }
}

TEST_CASE("the issue's elastic 3-mass chatter runs in bounded work, to the same state",
          "[simulate][chatter]") {
  const System s = ElasticChain();
  const double t_end = 2 * s.ForcingPeriod();
  HybridState state = RestState(s);
  const SimulationSummary summary = Simulator(s).Run(state, t_end);
  CHECK(summary.termination == Termination::kCompleted);
  CHECK(summary.impacts < 100000);
  CHECK(state.Stuck());
  // A 100 times finer cut (ended at a bounce height of 1e-12 of the gap's
  // scale where that comes first) moves the end state by no more than the
  // coarse cut's bounce speed (~1e-5 here) and its consequences.
  SimulationOptions finer;
  finer.chatter_span = 1e-6;
  finer.bounce_height_resolution = 1e-12;
  HybridState reference = RestState(s);
  const SimulationSummary fine = Simulate(s, finer, reference, t_end);
  CHECK(fine.termination == Termination::kCompleted);
  CHECK((state.x - reference.x).lpNorm<Eigen::Infinity>() < 1e-4);
  CHECK((state.v - reference.v).lpNorm<Eigen::Infinity>() < 1e-4);
}

TEST_CASE("the paper's threshold rule with a tiny threshold ends its chatter in bounded work",
          "[simulate][chatter]") {
  // `--chatter threshold --chatter-threshold 1e-8` logged 5.4 million
  // impacts in 10 periods: the intervals shrink geometrically, but below
  // 1e-4 of the time scale the micro-bounce rule ends the sequence.
  const System s = PaperSystem(0.2);
  SimulationOptions threshold;
  threshold.chatter = ChatterMethod::kThreshold;
  threshold.chatter_threshold = 1e-8;
  HybridState state = RestState(s);
  const SimulationSummary summary = Simulate(s, threshold, state, 10 * s.ForcingPeriod());
  CHECK(summary.termination == Termination::kCompleted);
  CHECK(summary.impacts < 40 * 10);
  CHECK(summary.releases >= 9);
  // The same sticking as the default rule's (Budd & Dux), per period.
  HybridState other = RestState(s);
  const SimulationSummary accumulation = Simulator(s).Run(other, 10 * s.ForcingPeriod());
  CHECK_THAT(summary.stuck_time, WithinAbs(accumulation.stuck_time, 1e-5));
}

TEST_CASE("a mass at rest on the stop lands: no impact at zero speed (closed form, N = 1)",
          "[simulate][chatter]") {
  // m = k = 1, c = 0, A = 1, Ω = 1.3, xs = 0, r = 1, from rest at the stop:
  // pushed into it, it sticks (no impact) until cos Ωt falls through 0 at
  // t_r = π / (2Ω), then flies from rest: x = X cos Ωt + a cos t + b sin t
  // with X = A / (k − Ω²) and x(t_r) = v(t_r) = 0.
  const double omega = 1.3;
  const System s = SingleMass(1.0, 0.0, 1.0, omega, 0.0, 1.0);
  const double t_r = std::numbers::pi / (2 * omega);
  const double big_x = 1.0 / (1.0 - omega * omega);
  const double a = -std::sin(t_r) * big_x * omega, b = std::cos(t_r) * big_x * omega;
  auto x = [&](double t) {
    return big_x * std::cos(omega * t) + a * std::cos(t) + b * std::sin(t);
  };
  auto v = [&](double t) {
    return -big_x * omega * std::sin(omega * t) - a * std::sin(t) + b * std::cos(t);
  };
  const double t1 = FirstUpwardZero(x, t_r, t_r + 40.0);
  REQUIRE(std::isfinite(t1));

  HybridState state = RestState(s);
  ImpactRecorder impacts;
  Releases releases;
  struct Landings : Observer {
    void OnLanding(const Landing& landing) override { all.push_back(landing); }
    std::vector<Landing> all;
  } landings;
  ObserverList observers;
  observers.Add(impacts);
  observers.Add(releases);
  observers.Add(landings);
  const SimulationSummary summary = Simulator(s).Run(state, 20 * s.ForcingPeriod(), observers);
  CHECK(summary.termination == Termination::kCompleted);
  CHECK(summary.landings >= 1);
  // The observer hears each landing, with its stop: the mass at rest on
  // the stop (x = 0) and pushed into it lands at once, at t = 0 to the
  // event search's time tolerance (1e-13).
  REQUIRE(landings.all.size() == static_cast<std::size_t>(summary.landings));
  CHECK(landings.all.front().stop == 0);
  CHECK_THAT(landings.all.front().t, WithinAbs(0.0, 1e-13));
  REQUIRE(!releases.times.empty());
  CHECK_THAT(releases.times.front(), WithinAbs(t_r, 1e-12));
  REQUIRE(!impacts.Impacts().empty());
  CHECK_THAT(impacts.Impacts().front().t, WithinAbs(t1, 1e-10));
  CHECK_THAT(impacts.Impacts().front().velocity, WithinAbs(v(t1), 1e-10));
  for (const ImpactView impact : impacts.Impacts()) CHECK(impact.velocity > 1e-8);
}

TEST_CASE("the issue's zero-speed impacts are landings: every impact has a resolved speed",
          "[simulate][chatter]") {
  struct Case {
    const char* name;
    double omega, xs, c, r;
    int periods;
  };
  for (const Case& k : {Case{"r=1 xs=0 c=0 Ω=1.3", 1.3, 0.0, 0.0, 1.0, 20},
                        Case{"c=0 xs=0 Ω=1", 1.0, 0.0, 0.0, 0.7, 2},
                        Case{"Ω=0.001 xs=0.1", 0.001, 0.1, 0.1, 0.7, 2}}) {
    INFO(k.name);
    System s = PaperSystem(k.omega);
    SetParameter(s, "xs", k.xs);
    SetParameter(s, "c", k.c);
    SetParameter(s, "r", k.r);
    HybridState state = RestState(s);
    ImpactRecorder impacts;
    const SimulationSummary summary =
        Simulator(s).Run(state, k.periods * s.ForcingPeriod(), impacts);
    CHECK(summary.termination == Termination::kCompleted);
    CHECK(summary.impacts < 100L * k.periods);
    for (const ImpactView impact : impacts.Impacts()) CHECK(impact.velocity > 1e-8);
  }
}

TEST_CASE("the work bound ends a run that needs too many events per period", "[simulate]") {
  const System s = ElasticChain();
  SimulationOptions options;
  options.max_events_per_period = 50;
  HybridState state = RestState(s);
  const double t_end = 2 * s.ForcingPeriod();
  const SimulationSummary summary = Simulate(s, options, state, t_end);
  CHECK(summary.termination == Termination::kWorkLimit);
  CHECK(state.t < t_end);
  CHECK(summary.impacts + summary.landings + summary.releases + summary.chatter_jumps <= 51 + 1);

  SimulationOptions bad;
  bad.max_events_per_period = 0;
  CHECK_FALSE(bad.IsValid(nullptr));
  bad = {};
  bad.bounce_height_resolution = 1e-2;
  CHECK_FALSE(bad.IsValid(nullptr));
}

TEST_CASE("the paper's chain undamped with the stop on mass 1 at xs = 0 runs in bounded work",
          "[simulate][chatter]") {
  // The hang. At Ω = 1 mass 1 is at an antiresonance (its forced
  // amplitude is 0 = xs), so it rests on the stop with a contact force that
  // is 0 to rounding for long stretches: landings and releases at noise
  // level, and a release search that had to certify a force of 1e-12
  // negative piece by piece.
  System s = GeneralSystem(Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Zero(),
                           (Eigen::Matrix2d() << 2, -1, -1, 1).finished(),
                           Eigen::Vector2d(0.5, 0.0), 1.0, 0.0, 0.01, 0);
  HybridState state = RestState(s);
  struct Gap : Observer {
    double worst = -INFINITY;
    void OnSegment(const Segment& segment) override {
      Eigen::VectorXd x, v;
      segment.StateAt(segment.End(), &x, &v);
      worst = std::max(worst, x(0));
    }
  } gap;
  const SimulationSummary summary = Simulator(s).Run(state, 220 * s.ForcingPeriod(), gap);
  CHECK(summary.termination == Termination::kCompleted);
  CHECK(summary.impacts + summary.landings + summary.releases < 1000L * 220);
  CHECK(gap.worst <= 1e-12);
}

TEST_CASE("the chatter rule's gate never skips an impact whose chatter it would end",
          "[simulate][chatter]") {
  // Wherever Decide ends chatter with acceleration a, it must end it with
  // any larger acceleration too (MayEnd asks with a bound >= a): the
  // simulator skips the acceleration only where MayEnd says no. Random
  // impacts over twelve decades of speed and acceleration, both methods, r
  // from 0 to 1; and the gate must say no to most impacts that end
  // nothing, or it saves nothing.
  std::mt19937 random(20261123);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto decades = [&](double low, double high) {
    return std::pow(10.0, low + (high - low) * unit(random));
  };
  long ended = 0, kept_going = 0, skipped = 0;
  for (const ChatterMethod method : {ChatterMethod::kAccumulation, ChatterMethod::kThreshold}) {
    SimulationOptions options;
    options.chatter = method;
    for (const double r : {0.0, 0.5, 0.8, 0.99, 1.0}) {
      const ChatterRule rule(options, r, 2 * std::numbers::pi);
      for (int trial = 0; trial < 20000; ++trial) {
        // Accelerations away from the stop too: the bound is then 0.
        const double speed = decades(-12.0, 0.0);
        const double acceleration = (unit(random) < 0.9 ? 1.0 : -1.0) * decades(-6.0, 6.0);
        const double bound = std::max(acceleration, 0.0), length = decades(-3.0, 0.0);
        const double te = 10.0, previous = te - decades(-10.0, 0.0);
        const double rebound = r * speed;
        CAPTURE(r, speed, acceleration, length, te - previous);
        if (rule.Decide(te, previous, rebound, acceleration, length) != ChatterDecision::kGoesOn) {
          ++ended;
          CHECK(rule.MayEnd(te, previous, rebound, bound, length));
          CHECK(rule.MayEnd(te, previous, rebound, 2.0 * bound, length));
        } else {
          ++kept_going;
          skipped += !rule.MayEnd(te, previous, rebound, bound, length);
        }
      }
    }
  }
  CHECK(ended > 20000);
  CHECK(skipped > kept_going / 2);
}
