// Systems with several stops: a mass in a clearance between two stops, stops
// on two masses of a chain. Checked against CVODE with one root function per
// stop, a closed form of the symmetric orbit of a clearance, and the mirror
// image of the seed's one-stop model.

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "cvode_impacts.hpp"
#include "impactkit/dynamics/events.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/impact_map.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::WithinAbs;
using namespace impactkit;

namespace {

/// One mass (m = k = 1, c = 0.1, A = 1) between stops at -d and +d.
System Clearance(double omega, double d, double restitution) {
  System s =
      UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 1.0), omega, d, restitution);
  s.stops = {{0, StopSide::kUpper, d, restitution}, {0, StopSide::kLower, -d, restitution}};
  Validate(s);
  return s;
}

std::vector<Impact> ImpactsOf(const System& s, double t_end) {
  ImpactRecorder recorder;
  HybridState state = RestState(s);
  Simulator(s).Run(state, t_end, recorder);
  return recorder.Impacts();
}

/// The symmetric period-1 orbit of Clearance(): an impact at +d at time t0
/// with speed v, one at -d at t0 + T/2 with speed v, and x(t + T/2) = -x(t)
/// between them (Shaw & Holmes 1983 for the one-sided case). With x_p the
/// forced response and Φ the free flow over T/2, the flight from (d, -r v)
/// must reach (-d, -v); both conditions are linear in v, so v follows from
/// the first and t0 is a root of the second. Returns (t0 mod T, v) of the
/// admissible root (v > 0, |x| < d in flight), or nothing.
struct SymmetricOrbit {
  double phase;
  double speed;
};
std::optional<SymmetricOrbit> SymmetricClosedForm(double omega, double d, double r) {
  const double a = 0.05, wd = std::sqrt(1.0 - a * a), period = 2 * std::numbers::pi / omega;
  const double tau = period / 2;
  const std::complex<double> amplitude =
      1.0 / std::complex<double>(1.0 - omega * omega, 0.1 * omega);
  auto forced = [&](double t, double* p, double* q) {
    const std::complex<double> e = amplitude * std::exp(std::complex<double>(0.0, omega * t));
    *p = e.real();
    *q = (std::complex<double>(0.0, omega) * e).real();
  };
  const double decay = std::exp(-a * tau), c = std::cos(wd * tau), s = std::sin(wd * tau);
  const double f11 = decay * (c + a / wd * s), f12 = decay * s / wd;
  const double f21 = -decay * s / wd, f22 = decay * (c - a / wd * s);
  auto speed = [&](double t0) {
    double p, q;
    forced(t0, &p, &q);
    return ((1 + f11) * (d - p) - f12 * q) / (f12 * r);
  };
  auto residual = [&](double t0) {
    double p, q;
    forced(t0, &p, &q);
    const double v = speed(t0);
    return -v + q - f21 * (d - p) - f22 * (-r * v - q);
  };
  auto admissible = [&](double t0) {
    double p, q;
    forced(t0, &p, &q);
    const double y0 = d - p, y1 = -r * speed(t0) - q;
    for (int k = 1; k < 1000; ++k) {
      const double t = tau * k / 1000.0, e = std::exp(-a * t);
      double pt, qt;
      forced(t0 + t, &pt, &qt);
      const double x = pt + e * (y0 * std::cos(wd * t) + (y1 + a * y0) / wd * std::sin(wd * t));
      if (std::abs(x) >= d) return false;
    }
    return speed(t0) > 0;
  };
  const int n = 2000;
  for (int k = 0; k < n; ++k) {
    double lo = period * k / n, hi = period * (k + 1) / n;
    if (residual(lo) * residual(hi) > 0) continue;
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
      const double mid = 0.5 * (lo + hi);
      (residual(lo) * residual(mid) <= 0 ? hi : lo) = mid;
    }
    const double t0 = 0.5 * (lo + hi);
    if (admissible(t0)) return SymmetricOrbit{t0, speed(t0)};
  }
  return std::nullopt;
}

/// The largest excursion of each stop's mass past that stop over every
/// free segment, from the segment's exact motion (the extrema of x_c where
/// its derivative changes sign): a missed impact shows as a positive one.
class Overshoot : public Observer {
 public:
  explicit Overshoot(const System& s) : s_(s) {}
  void OnSegment(const Segment& segment) override {
    if (segment.Mode() != SegmentMode::kFree) return;
    for (const StopParameters& stop : s_.stops) {
      const Signal x = segment.Position(stop.dof);
      const double sign = stop.Sign();
      std::vector<double> times =
          SignChanges(x.Derivative(), segment.Begin(), segment.End(), EventOptions{1e-13, 1.0});
      times.push_back(segment.End());
      for (double t : times) worst = std::max(worst, sign * (x.Value(t) - stop.position));
    }
  }
  double worst = -INFINITY;

 private:
  const System& s_;
};

}  // namespace

TEST_CASE("a stop given as a list is the seed's one stop", "[stops]") {
  const System keys = ParseSystem("xs = 0.2\nr = 0.6\n", SystemFileFormat::kToml, "keys.toml");
  const System list = ParseSystem("[[stops]]\ndof = 2\nposition = 0.2\nrestitution = 0.6\n",
                                  SystemFileFormat::kToml, "list.toml");
  REQUIRE(list.stops == keys.stops);
  // The same system, so the same numbers to the bit (test_fingerprints.cpp
  // holds the simulator to the values recorded before stop lists).
  const std::vector<Impact> a = ImpactsOf(keys, 100 * keys.ForcingPeriod()),
                            b = ImpactsOf(list, 100 * list.ForcingPeriod());
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].t == b[i].t);
    CHECK(a[i].velocity == b[i].velocity);
  }
  // Written back in the one-stop form; a two-stop system as a list.
  CHECK_THAT(SystemToJson(list), Contains("\"xs\": 0.2"));
  const System two = Clearance(1.0, 0.5, 0.8);
  const System again = ParseSystem(SystemToJson(two), SystemFileFormat::kJson, "two.json");
  CHECK(again.stops == two.stops);
}

TEST_CASE("a lower stop is the mirror image of an upper one, sticking included", "[stops]") {
  // x -> -x maps the paper's system onto one with forcing -A and a lower
  // stop at -xs: the same impacts, chatter and sticking at the same times.
  for (double omega : {0.2, 1.3, 1.8}) {
    INFO("omega = " << omega);
    const System upper = PaperSystem(omega);
    System lower = upper;
    lower.forcing = -upper.forcing;
    lower.stops = {{1, StopSide::kLower, -0.1, 0.7}};
    ImpactRecorder a, b;
    StickingRecorder stuck_a, stuck_b;
    ObserverList both_a, both_b;
    both_a.Add(a);
    both_a.Add(stuck_a);
    both_b.Add(b);
    both_b.Add(stuck_b);
    HybridState state_a = RestState(upper), state_b = RestState(lower);
    const SimulationSummary sa = Simulator(upper).Run(state_a, 60 * upper.ForcingPeriod(), both_a);
    const SimulationSummary sb = Simulator(lower).Run(state_b, 60 * lower.ForcingPeriod(), both_b);
    REQUIRE(a.Impacts().size() == b.Impacts().size());
    REQUIRE(a.Impacts().size() > 30);
    for (std::size_t i = 0; i < a.Impacts().size(); ++i) {
      CHECK_THAT(b.Impacts()[i].t, WithinAbs(a.Impacts()[i].t, 1e-12 * a.Impacts()[i].t));
      CHECK_THAT(b.Impacts()[i].velocity, WithinAbs(a.Impacts()[i].velocity, 1e-12));
      CHECK(b.Impacts()[i].stop == 0);
    }
    CHECK(sb.releases == sa.releases);
    CHECK(stuck_b.Intervals().size() == stuck_a.Intervals().size());
    CHECK_THAT(sb.stuck_time, WithinAbs(sa.stuck_time, 1e-9));
    CHECK(((state_b.x + state_a.x).cwiseAbs().maxCoeff() < 1e-9));
    if (omega == 0.2) CHECK(sa.releases > 10);  // this one sticks
  }
}

TEST_CASE("a chain with stops on two masses: the first 50 impacts as CVODE finds them", "[stops]") {
  // Mass 2 below an upper stop at 0.1, mass 1 above a lower stop at -0.4;
  // CVODE watches one root function per stop (reference/cvode_impacts.cpp).
  System s = PaperSystem(0.8);
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {0, StopSide::kLower, -0.4, 0.6}};
  Validate(s);
  const double t_end = 40 * s.ForcingPeriod();
  const std::vector<Impact> ours = ImpactsOf(s, t_end);
  const reference::ReferenceRun cvode =
      reference::CvodeImpacts(s, RestState(s).x, RestState(s).v, 0.0, t_end, {});
  REQUIRE(ours.size() >= 50);
  REQUIRE(cvode.impacts.size() >= 50);
  int at_lower = 0;
  for (int i = 0; i < 50; ++i) {
    INFO("impact " << i);
    CHECK(ours[i].stop == cvode.impacts[i].stop);
    CHECK_THAT(ours[i].t, WithinAbs(cvode.impacts[i].t, 1e-7));
    CHECK_THAT(ours[i].velocity, WithinAbs(cvode.impacts[i].velocity, 1e-7));
    at_lower += ours[i].stop == 1;
  }
  CHECK(at_lower >= 20);  // both stops are hit, many times
}

TEST_CASE("a clearance's symmetric P(2,1) orbit against its closed form", "[stops]") {
  for (double omega : {1.0, 2.0}) {
    INFO("omega = " << omega);
    const System s = Clearance(omega, 0.5, 0.8);
    const std::optional<SymmetricOrbit> exact = SymmetricClosedForm(omega, 0.5, 0.8);
    REQUIRE(exact);
    const std::vector<Impact> impacts = ImpactsOf(s, 400 * s.ForcingPeriod());
    REQUIRE(impacts.size() > 10);
    // The last impacts alternate between the stops, half a period apart.
    const Impact& last = impacts.back();
    const Impact& before = impacts[impacts.size() - 2];
    CHECK(last.stop != before.stop);
    CHECK_THAT(last.t - before.t, WithinAbs(s.ForcingPeriod() / 2, 1e-9));
    const Impact& upper = last.stop == 0 ? last : before;
    const Impact& lower = last.stop == 0 ? before : last;
    CHECK_THAT(upper.velocity, WithinAbs(exact->speed, 1e-9));
    CHECK_THAT(lower.velocity, WithinAbs(exact->speed, 1e-9));
    CHECK_THAT(upper.phase, WithinAbs(exact->phase, 1e-9));
    CHECK(lower.x(0) == -0.5);
    CHECK(lower.v(0) < 0);
  }
}

TEST_CASE("grazing families at each stop of a clearance: no impact missed", "[stops]") {
  // The forced response of Clearance() has amplitude |X| = 1 / |1 - Ω² +
  // 0.1 i Ω|; stops just inside and just outside it make flights that
  // barely reach, or barely miss, either stop.
  for (double omega : {0.7, 1.3, 1.9}) {
    const double amplitude = 1.0 / std::abs(std::complex<double>(1.0 - omega * omega, 0.1 * omega));
    for (double ratio : {0.999, 0.99999, 0.9999999, 1.0000001}) {
      const System s = Clearance(omega, ratio * amplitude, 0.8);
      Overshoot overshoot(s);
      HybridState state = RestState(s);
      Simulator(s).Run(state, 300 * s.ForcingPeriod(), overshoot);
      INFO("omega = " << omega << ", d / |X| = " << ratio);
      CHECK(overshoot.worst <= 1e-12);
    }
  }
}

TEST_CASE("stops: validation and their parameters", "[stops]") {
  System s = PaperSystem();
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {1, StopSide::kUpper, 0.2, 0.7}};
  CHECK_THROWS_WITH(Validate(s), Contains("both limit mass 2 from above"));
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {1, StopSide::kLower, 0.2, 0.7}};
  CHECK_THROWS_WITH(Validate(s), Contains("leave it no room"));
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {0, StopSide::kLower, -0.3, 1.5}};
  CHECK_THROWS_WITH(Validate(s), Contains("r2 (restitution of stop 2) must be in [0, 1]"));
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {2, StopSide::kLower, -0.3, 0.5}};
  CHECK_THROWS_WITH(Validate(s), Contains("the mass of stop 2 must be in [1, 2], got 3"));
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {0, StopSide::kLower, -0.3, 0.5}};
  REQUIRE_NOTHROW(Validate(s));
  // Parameters: xs and r of stop 1, xs2 and r2 of stop 2.
  CHECK(ParameterNames(s) ==
        std::vector<std::string>{"omega", "xs", "xs2", "r", "r2", "A1", "A2", "m", "k", "c", "n"});
  SetParameter(s, "xs2", -0.35);
  SetParameter(s, "r2", 0.4);
  CHECK(s.stops[1].position == -0.35);
  CHECK(GetParameter(s, "r2") == 0.4);
  CHECK(GetParameter(s, "xs") == 0.1);
  CHECK_THROWS_WITH(GetParameter(s, "xs3"), Contains("unknown parameter 'xs3'"));
  // n keeps stops given on masses by number.
  SetParameter(s, "n", 3);
  CHECK(s.stops[0].dof == 1);
  // The initial state inside every stop.
  HybridState state = RestState(s);
  state.x(0) = -0.5;
  CHECK_THROWS_WITH(ValidateState(s, state), Contains("beyond the stop xs2 = -0.35"));
  state.x(0) = -0.35;
  state.held = StopBit(1);
  REQUIRE_NOTHROW(ValidateState(s, state));
  state.held = StopBit(0);
  CHECK_THROWS_WITH(ValidateState(s, state), Contains("needs x2 = xs"));
}

TEST_CASE("the impact map says it handles one stop so far", "[stops]") {
  CHECK_THROWS_WITH(
      ImpactMap(Clearance(1.0, 0.5, 0.8)),
      Contains("the impact map handles systems with one stop so far; this one has 2"));
}
