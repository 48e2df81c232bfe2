#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <limits>

#include "impactkit/analysis/classify.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/sweep.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using namespace impactkit;

namespace {

/// A short sweep of omega on the paper's system: 300 transient periods
/// (the slowest free mode decays as exp(-0.019 t), so 300 periods leave
/// less than 1e-6 of a start at Ω <= 2), 30 recorded.
SweepOptions ShortSweep(double from, double to, int steps) {
  SweepOptions options;
  options.from = from;
  options.to = to;
  options.steps = steps;
  options.transient_periods = 300;
  options.recorded_periods = 30;
  return options;
}

/// max - min of x_i(t) = Re(X_i e^{iΩt}) in the steady non-impacting
/// response, X = (K - Ω² M + iΩ C)^{-1} A: 2 |X_i|.
double LinearRange(const System& s, int i) {
  const std::complex<double> j(0.0, 1.0);
  const Eigen::MatrixXcd z = s.stiffness.cast<std::complex<double>>() -
                             s.omega * s.omega * s.mass.cast<std::complex<double>>() +
                             j * s.omega * s.damping.cast<std::complex<double>>();
  const Eigen::VectorXcd x = z.partialPivLu().solve(s.forcing.cast<std::complex<double>>());
  return 2.0 * std::abs(x(i));
}

/// Largest distance of the two trajectories' states at t = periods T, from
/// rest and from rest with x_1 moved by `offset`, after 300 periods.
double Separation(double omega, double offset, int periods) {
  const System s = PaperSystem(omega);
  const Simulator simulator(s);
  HybridState a = RestState(s);
  simulator.Run(a, 300 * s.ForcingPeriod());
  HybridState b = a;
  b.x(0) += offset;
  simulator.Run(a, (300 + periods) * s.ForcingPeriod());
  simulator.Run(b, (300 + periods) * s.ForcingPeriod());
  return std::max((a.x - b.x).cwiseAbs().maxCoeff(), (a.v - b.v).cwiseAbs().maxCoeff());
}

void RequireIdentical(const SweepResult& a, const SweepResult& b) {
  REQUIRE(a.points.size() == b.points.size());
  for (std::size_t k = 0; k < a.points.size(); ++k) {
    const SweepPoint &p = a.points[k], &q = b.points[k];
    INFO("value " << p.value);
    REQUIRE(p.value == q.value);
    REQUIRE(p.classification.kind == q.classification.kind);
    REQUIRE(p.classification.period.p == q.classification.period.p);
    REQUIRE(p.classification.period.q == q.classification.period.q);
    REQUIRE(p.classification.lyapunov.largest == q.classification.lyapunov.largest);
    REQUIRE(p.range_contact == q.range_contact);
    REQUIRE(p.range_first == q.range_first);
    REQUIRE(p.restarted == q.restarted);
    REQUIRE(p.impacts.size() == q.impacts.size());
    for (std::size_t i = 0; i < p.impacts.size(); ++i) {
      REQUIRE(p.impacts[i].t == q.impacts[i].t);
      REQUIRE(p.impacts[i].velocity == q.impacts[i].velocity);
    }
  }
}

/// One value of a sweep run twice: with the early end of its transient
/// (the default) and with its whole transient.
struct BothWays {
  SweepPoint early, full;
};

BothWays RunBothWays(const System& system, SweepOptions options) {
  options.full_transient = false;
  BothWays both{RunSweep(system, options).points.front(), {}};
  options.full_transient = true;
  both.full = RunSweep(system, options).points.front();
  return both;
}

/// The early cell records what the whole run does: the same class, the
/// same impacts and per-period ranges to `tolerance` (both runs end their
/// transient within ~1e-10 of the same orbit, sweep.hpp).
void RequireSameRecord(const SweepPoint& early, const SweepPoint& full, double tolerance) {
  REQUIRE(early.classification.ToString() == full.classification.ToString());
  REQUIRE(early.impacts.size() == full.impacts.size());
  for (std::size_t i = 0; i < early.impacts.size(); ++i) {
    INFO("impact " << i);
    CHECK_THAT(early.impacts[i].t, WithinAbs(full.impacts[i].t, tolerance));
    CHECK_THAT(early.impacts[i].velocity, WithinAbs(full.impacts[i].velocity, tolerance));
  }
  REQUIRE(early.range_contact.size() == full.range_contact.size());
  for (std::size_t k = 0; k < early.range_contact.size(); ++k) {
    CHECK_THAT(early.range_contact[k], WithinAbs(full.range_contact[k], tolerance));
    CHECK_THAT(early.range_first[k], WithinAbs(full.range_first[k], tolerance));
  }
}

}  // namespace

TEST_CASE("default sweep and classification options are valid", "[sweep]") {
  std::string error;
  CHECK(SweepOptions{}.IsValid(&error));
  CHECK(ClassifyOptions{}.IsValid(&error));
  CHECK(error.empty());
}

TEST_CASE("sweep options whose period counts would overflow an int are refused", "[sweep]") {
  std::string error;
  SweepOptions options;
  options.transient_periods = std::numeric_limits<int>::max();
  options.recorded_periods = 1;
  CHECK_FALSE(options.IsValid(&error));
  CHECK_THAT(error, Contains("transient + recorded periods must be at most"));
  options = SweepOptions{};
  options.classify.period.max_q = std::numeric_limits<int>::max();
  CHECK_FALSE(options.IsValid(&error));
  CHECK_THAT(error, Contains("max_q must be at most"));
}

TEST_CASE("sweep values: both ends exact, evenly spaced, reversed downwards", "[sweep]") {
  SweepOptions options = ShortSweep(2.5, 0.1, 2401);
  const std::vector<double> up = SweepValues(options);
  REQUIRE(up.size() == 2401);
  CHECK(up.front() == 0.1);
  CHECK(up.back() == 2.5);
  CHECK_THAT(up[500], WithinAbs(0.6, 1e-15));
  options.direction = SweepDirection::kDown;
  const std::vector<double> down = SweepValues(options);
  CHECK(down.front() == 2.5);
  CHECK(down[1900] == up[500]);
  options.steps = 1;
  CHECK(SweepValues(options) == std::vector<double>{2.5});
}

TEST_CASE("sweep classification agrees with the orbits Newton finds", "[sweep]") {
  // Ω = 0.6, 1.3, 2.0: the paper's P(2,1), P(1,1) and P(1,2) (its §3.1).
  const SweepResult result = RunSweep(PaperSystem(), ShortSweep(0.6, 2.0, 3));
  struct Expected {
    int p, q;
  };
  const Expected expected[] = {{2, 1}, {1, 1}, {1, 2}};
  REQUIRE(result.points.size() == 3);
  for (int k = 0; k < 3; ++k) {
    const SweepPoint& point = result.points[k];
    INFO("omega = " << point.value);
    // The orbit: Newton on the impact map from a seed simulated from rest
    // (not from the sweep's state), with the paper's p and q.
    const System s = PaperSystem(point.value);
    const std::optional<OrbitSeed> seed = SeedFromSimulation(s);
    REQUIRE(seed);
    OrbitOptions orbit_options;
    orbit_options.p = expected[k].p;
    orbit_options.q = expected[k].q;
    PeriodicOrbit orbit;
    REQUIRE(FindOrbit(s, seed->eta, orbit_options, &orbit).termination == Termination::kConverged);
    REQUIRE(orbit.stable);
    CHECK(point.classification.kind == MotionKind::kPeriodic);
    CHECK(point.classification.period.p == orbit.p);
    CHECK(point.classification.period.q == orbit.q);
    // Every recorded impact is one of the orbit's, within 1e-6 in speed and
    // phase, and each of the orbit's impacts is recorded.
    REQUIRE(point.impacts.size() == static_cast<std::size_t>(30 / orbit.q * orbit.p));
    std::vector<bool> seen(orbit.impacts.size(), false);
    for (const SweepImpact& i : point.impacts) {
      bool matched = false;
      for (std::size_t j = 0; j < orbit.impacts.size(); ++j) {
        if (std::abs(i.velocity - orbit.impacts[j].velocity) <= 1e-6 &&
            std::abs(i.phase - orbit.impacts[j].phase) <= 1e-6) {
          matched = seen[j] = true;
        }
      }
      INFO("impact at t = " << i.t << ", v = " << i.velocity);
      CHECK(matched);
    }
    for (bool s : seen) CHECK(s);
  }
}

TEST_CASE("sticking, non-impacting and chaotic motions are told apart", "[sweep]") {
  SECTION("Ω = 0.2: sticking P(inf,1), held at the stop in every recorded period") {
    const SweepResult result = RunSweep(PaperSystem(), ShortSweep(0.2, 0.2, 1));
    const Classification& c = result.points[0].classification;
    CHECK(c.kind == MotionKind::kSticking);
    CHECK(c.period.q == 1);
    CHECK(c.ToString() == "P(inf,1)");
    const System s = PaperSystem(0.2);
    HybridState state = RestState(s);
    const Simulator simulator(s);
    simulator.Run(state, 300 * s.ForcingPeriod());
    StickingRecorder sticking;
    simulator.Run(state, 330 * s.ForcingPeriod(), sticking);
    CHECK(sticking.Intervals().size() >= 29);
  }
  SECTION("Ω = 2.4: non-impacting, ranges of the linear steady response") {
    SweepOptions options = ShortSweep(2.4, 2.4, 1);
    options.transient_periods = 600;  // exp(-0.019 * 600 T) ~ 1e-13
    const SweepResult result = RunSweep(PaperSystem(), options);
    const SweepPoint& point = result.points[0];
    CHECK(point.classification.kind == MotionKind::kNonImpacting);
    CHECK(point.impacts.empty());
    REQUIRE(point.range_contact.size() == 30);
    const System s = PaperSystem(2.4);
    for (double r : point.range_contact) CHECK_THAT(r, WithinAbs(LinearRange(s, 1), 1e-9));
    for (double r : point.range_first) CHECK_THAT(r, WithinAbs(LinearRange(s, 0), 1e-9));
  }
  SECTION("Ω = 1.76: chaotic; nearby trajectories separate, unlike at Ω = 1.3") {
    const SweepResult result = RunSweep(PaperSystem(), ShortSweep(1.76, 1.76, 1));
    const Classification& c = result.points[0].classification;
    CHECK(c.kind == MotionKind::kChaotic);
    CHECK_FALSE(c.period.periodic);
    REQUIRE(c.lyapunov_computed);
    CHECK(c.lyapunov.largest > 0.01);
    // Independent of the Jacobians: a 1e-10 offset grows by more than 1e6
    // in 200 periods where the exponent is positive, and dies out at the
    // stable P(1,1) orbit of Ω = 1.3.
    CHECK(Separation(1.76, 1e-10, 200) > 1e-4);
    CHECK(Separation(1.3, 1e-10, 200) < 1e-10);
  }
}

TEST_CASE("sweeps are bit-identical on 1 and 2 threads", "[sweep]") {
  // Across the period doublings and the chaotic range, 5 chunks.
  SweepOptions options = ShortSweep(1.6, 1.8, 17);
  options.transient_periods = 150;
  options.chunk_values = 4;
  options.warmup_values = 2;
  options.threads = 1;
  const SweepResult one = RunSweep(PaperSystem(), options);
  options.threads = 2;
  const SweepResult two = RunSweep(PaperSystem(), options);
  CHECK(one.chunks == 5);
  RequireIdentical(one, two);
  // Chunk starts after a warm-up are not restarts; with no warm-up they are.
  CHECK_FALSE(one.points[4].restarted);
  options.warmup_values = 0;
  CHECK(RunSweep(PaperSystem(), options).points[4].restarted);
}

TEST_CASE("fixed starts do not depend on direction; warm-ups join the sequential branch",
          "[sweep]") {
  SweepOptions options = ShortSweep(0.9, 1.5, 7);
  options.start = SweepStart::kFixed;
  const SweepResult up = RunSweep(PaperSystem(), options);
  options.direction = SweepDirection::kDown;
  SweepResult down = RunSweep(PaperSystem(), options);
  std::reverse(down.points.begin(), down.points.end());
  RequireIdentical(up, down);

  // P(1,1) throughout: a chunked sweep from the previous state reaches the
  // same attractor as the strictly sequential one, to the decay of its
  // (different) transient.
  options = ShortSweep(0.9, 1.5, 7);
  options.chunk_values = 0;
  const SweepResult sequential = RunSweep(PaperSystem(), options);
  options.chunk_values = 2;
  options.warmup_values = 1;
  const SweepResult chunked = RunSweep(PaperSystem(), options);
  for (std::size_t k = 0; k < sequential.points.size(); ++k) {
    const SweepPoint &a = sequential.points[k], &b = chunked.points[k];
    INFO("omega = " << a.value);
    CHECK(a.classification.ToString() == "P(1,1)");
    CHECK(b.classification.ToString() == "P(1,1)");
    REQUIRE(a.impacts.size() == b.impacts.size());
    CHECK_THAT(a.impacts.back().velocity, WithinAbs(b.impacts.back().velocity, 1e-8));
  }
}

TEST_CASE("bad sweep input is rejected before any work", "[sweep]") {
  const System s = PaperSystem();
  auto rejects = [&](SweepOptions options, const std::string& message) {
    INFO(message);
    CHECK_THROWS_AS(RunSweep(s, options), InvalidInput);
    CHECK_THROWS_WITH(RunSweep(s, options), Contains(message));
  };
  SweepOptions o = ShortSweep(0.5, 1.0, 0);
  rejects(o, "steps must be >= 1, got 0");
  o = ShortSweep(0.5, 0.5, 3);
  rejects(o, "from and to are both 0.5");
  o = ShortSweep(0.5, 1.0, 3);
  o.transient_periods = -1;
  rejects(o, "transient periods must be >= 0, got -1");
  o.transient_periods = 10;
  o.recorded_periods = 0;
  rejects(o, "recorded periods must be >= 1, got 0");
  o.recorded_periods = 10;
  o.threads = 0;
  rejects(o, "threads must be >= 1, got 0");
  o.threads = 1;
  o.parameter = std::string("q");  // (a literal trips GCC 12's false -Wrestrict)
  rejects(o, "unknown parameter 'q'");
  o = ShortSweep(0.5, 1.5, 3);
  o.parameter = std::string("r");
  rejects(o, "sweep of r at 1.5");
  o = ShortSweep(0.5, 1.0, 3);
  o.fixed_state = RestState(PaperSystem());
  o.fixed_state->x(1) = 0.2;  // beyond the stop xs = 0.1
  rejects(o, "beyond the stop");
}

TEST_CASE("a long transient ends early only once its orbit is confirmed, as the whole run ends",
          "[sweep][early]") {
  // Damping c = 0.03 instead of 0.1: the start from x1 = 2 decays over
  // hundreds of periods before the P(1,1) of Omega = 1.3 shows.
  System s = PaperSystem(1.3);
  SetParameter(s, "c", 0.03);
  SweepOptions options = ShortSweep(1.3, 1.3, 1);
  options.start = SweepStart::kFixed;
  options.fixed_state = RestState(s);
  options.fixed_state->x(0) = 2.0;
  const BothWays both = RunBothWays(s, options);
  CHECK(both.full.periods_run == 330);
  CHECK(both.early.periods_run < both.full.periods_run);
  CHECK(both.early.periods_run > 100);
  CHECK(both.early.classification.ToString() == "P(1,1)");
  RequireSameRecord(both.early, both.full, 1e-8);
}

TEST_CASE("near a period doubling, where periodicity is slow to show, the class is the whole run's",
          "[sweep][early]") {
  // P(1,1) doubles at Omega = 1.6130 (docs/continuation.md): its multiplier
  // near -1 contracts the transient slowly, by about 0.99 a period at 1.61.
  SECTION("Omega = 1.61: confirmed late, once the periods left suffice") {
    SweepOptions options = ShortSweep(1.61, 1.61, 1);
    options.transient_periods = 500;
    options.recorded_periods = 100;
    const BothWays both = RunBothWays(PaperSystem(), options);
    CHECK(both.full.classification.ToString() == "P(1,1)");
    CHECK(both.early.periods_run > 300);
    CHECK(both.early.periods_run < both.full.periods_run);
    RequireSameRecord(both.early, both.full, 1e-8);
  }
  SECTION("Omega = 1.612: not settled in 300 periods, run whole, unresolved both ways") {
    const BothWays both = RunBothWays(PaperSystem(), ShortSweep(1.612, 1.612, 1));
    CHECK(both.full.classification.kind == MotionKind::kUnresolved);
    CHECK(both.early.periods_run == both.full.periods_run);
    RequireSameRecord(both.early, both.full, 0.0);
  }
}

TEST_CASE("a chaotic cell runs its whole transient", "[sweep][early]") {
  const BothWays both = RunBothWays(PaperSystem(), ShortSweep(1.76, 1.76, 1));
  CHECK(both.early.classification.kind == MotionKind::kChaotic);
  CHECK(both.full.classification.kind == MotionKind::kChaotic);
  CHECK(both.early.periods_run == both.full.periods_run);
}

TEST_CASE("a sticking cell ends early on its release map's orbit, as the whole run ends",
          "[sweep][early]") {
  const BothWays both = RunBothWays(PaperSystem(), ShortSweep(0.2, 0.2, 1));
  CHECK(both.full.classification.ToString() == "P(inf,1)");
  CHECK(both.early.periods_run < both.full.periods_run);
  RequireSameRecord(both.early, both.full, 1e-8);
}
