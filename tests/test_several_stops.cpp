// Systems with several stops: a mass in a clearance between two stops, stops
// on two masses of a chain. Checked against CVODE with one root function per
// stop, a closed form of the symmetric orbit of a clearance, and the mirror
// image of the seed's one-stop model.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "cvode_impacts.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/dynamics/events.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/hybrid/stop.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "seeded_orbit.hpp"

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

ImpactLog ImpactsOf(const System& s, double t_end) {
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

/// The eigenvalues of S·DH for the symmetric orbit: H the half map from
/// the impact at +d to the one at -d, S the reflection (τ, v) -> (τ - T/2,
/// -v) that maps the latter onto the former. P(2,1) = (S∘H)², so its
/// multipliers are the squares; a multiplier -1 of S·DH is the
/// symmetry-breaking pitchfork (+1 of P(2,1)). DH by the implicit function
/// theorem on the closed-form flight: ∂y/∂τ = -Φ f(τ, y+), ∂y/∂v = Φ (0, -r),
/// then dτ' = -e_xᵀ G / v' and dv' = e_vᵀ G + a' dτ'.
Eigen::Vector2cd HalfMapMultipliers(double omega, double d, double r, const SymmetricOrbit& orbit) {
  const double a = 0.05, wd = std::sqrt(1.0 - a * a), tau = std::numbers::pi / omega;
  const double decay = std::exp(-a * tau), c = std::cos(wd * tau), s = std::sin(wd * tau);
  Eigen::Matrix2d phi;
  phi << decay * (c + a / wd * s), decay * s / wd, -decay * s / wd, decay * (c - a / wd * s);
  const double v = orbit.speed, t0 = orbit.phase;
  const Eigen::Vector2d f0(-r * v, std::cos(omega * t0) - 0.1 * (-r * v) - d);
  Eigen::Matrix2d g;
  g.col(0) = -phi * f0;
  g.col(1) = phi * Eigen::Vector2d(0.0, -r);
  const double v_arrival = -v;
  const double a_arrival = std::cos(omega * (t0 + tau)) - 0.1 * v_arrival + d;
  const Eigen::RowVector2d dt = -g.row(0) / v_arrival;
  Eigen::Matrix2d dh;
  dh.row(0) = dt;
  dh.row(1) = g.row(1) + a_arrival * dt;
  const Eigen::Matrix2d reflected = Eigen::Vector2d(1.0, -1.0).asDiagonal() * dh;
  return reflected.eigenvalues();
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
  const ImpactLog a = ImpactsOf(keys, 100 * keys.ForcingPeriod()),
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

TEST_CASE("a lower stop's sticking orbit is the mirror image of the upper one's", "[stops]") {
  // The release map used to take the stop for an upper one: the mirrored
  // paper system's orbit at Ω = 0.2 came out with no impact before its
  // accumulation and a stick phase 4.9 off. The upper one's orbit is
  // checked against the simulator in test_sticking_orbit.cpp.
  const System upper = PaperSystem(0.2);
  System lower = upper;
  lower.forcing = -upper.forcing;
  lower.stops = {{1, StopSide::kLower, -0.1, 0.7}};
  const PeriodicOrbit a = testing::SeededStickingOrbit(upper);
  const PeriodicOrbit b = testing::SeededStickingOrbit(lower);
  REQUIRE(b.stuck.size() == a.stuck.size());
  CHECK_THAT(b.stuck[0].stick_phase, WithinAbs(a.stuck[0].stick_phase, 1e-9));
  CHECK_THAT(b.stuck[0].release_phase, WithinAbs(a.stuck[0].release_phase, 1e-9));
  CHECK_THAT(a.stuck[0].stick_phase, WithinAbs(30.464633012, 1e-8));  // docs/cli.md's sample
  REQUIRE(b.stuck.size() == a.stuck.size());
  CHECK(b.stuck[0].impacts == a.stuck[0].impacts);
  CHECK(a.stuck[0].impacts == 27);
  CHECK_THAT(b.contacts.contact_margin, WithinAbs(a.contacts.contact_margin, 1e-9));
  // Neither flight turns back towards the stop before the chatter.
  CHECK_FALSE(a.contacts.clearance);
  CHECK_FALSE(b.contacts.clearance);
  // The mirror image's extent in x2 is the paper system's negated.
  CHECK_THAT(b.contacts.contact_min, WithinAbs(-a.contacts.contact_max, 1e-9));
  CHECK_THAT(b.contacts.contact_max, WithinAbs(-a.contacts.contact_min, 1e-9));
  CHECK(((b.eta.head(2) + a.eta.head(2)).cwiseAbs().maxCoeff() < 1e-9));
  REQUIRE(b.multipliers.size() == a.multipliers.size());
  for (Eigen::Index i = 0; i < a.multipliers.size(); ++i) {
    CHECK(std::abs(b.multipliers(i) - a.multipliers(i)) < 1e-9);
  }
}

TEST_CASE("the observer hears which stop released and ended each chatter", "[stops]") {
  // The paper's system with mass 2 in the clearance ±0.1 sticks at both
  // stops at Ω = 0.2 (docs/several-stops.md). Independently of the index
  // the events carry: at a release the mass sits on the stop it names, and
  // a chatter's first impact was recorded at that stop.
  System s = PaperSystem(0.2);
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {1, StopSide::kLower, -0.1, 0.7}};
  Validate(s);
  struct Events : Observer {
    void OnSegment(const Segment& segment) override { segment.StateAt(segment.End(), &x, &v); }
    void OnImpact(const Impact& impact) override { impacts.push_back(impact); }
    void OnChatter(const ChatterEnd& chatter) override { chatters.push_back(chatter); }
    void OnRelease(const Release& release) override {
      releases.push_back(release);
      positions.push_back(x(1));
    }
    Eigen::VectorXd x, v;
    std::vector<Impact> impacts;
    std::vector<ChatterEnd> chatters;
    std::vector<Release> releases;
    std::vector<double> positions;
  } events;
  HybridState state = RestState(s);
  Simulator(s).Run(state, 10 * s.ForcingPeriod(), events);
  int per_stop[2] = {0, 0};
  REQUIRE(!events.releases.empty());
  for (std::size_t i = 0; i < events.releases.size(); ++i) {
    const Release& release = events.releases[i];
    REQUIRE((release.stop == 0 || release.stop == 1));
    ++per_stop[release.stop];
    CHECK(events.positions[i] == s.stops[release.stop].position);
    CHECK(release.t_begin < release.t_release);
  }
  CHECK(per_stop[0] > 0);
  CHECK(per_stop[1] > 0);
  for (const ChatterEnd& chatter : events.chatters) {
    const auto first = std::find_if(events.impacts.begin(), events.impacts.end(),
                                    [&](const Impact& i) { return i.t == chatter.t_first; });
    REQUIRE(first != events.impacts.end());
    CHECK(first->stop == chatter.stop);
  }
}

TEST_CASE("a chain with stops on two masses: the first 50 impacts as CVODE finds them", "[stops]") {
  // Mass 2 below an upper stop at 0.1, mass 1 above a lower stop at -0.4;
  // CVODE watches one root function per stop (reference/cvode_impacts.cpp).
  System s = PaperSystem(0.8);
  s.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {0, StopSide::kLower, -0.4, 0.6}};
  Validate(s);
  const double t_end = 40 * s.ForcingPeriod();
  const ImpactLog ours = ImpactsOf(s, t_end);
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
    const ImpactLog impacts = ImpactsOf(s, 400 * s.ForcingPeriod());
    REQUIRE(impacts.size() > 10);
    // The last impacts alternate between the stops, half a period apart.
    const ImpactView last = impacts.back();
    const ImpactView before = impacts[impacts.size() - 2];
    CHECK(last.stop != before.stop);
    CHECK_THAT(last.t - before.t, WithinAbs(s.ForcingPeriod() / 2, 1e-9));
    const ImpactView& upper = last.stop == 0 ? last : before;
    const ImpactView& lower = last.stop == 0 ? before : last;
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

TEST_CASE("a clearance's symmetric P(2,1): multipliers and the pitchfork against closed forms",
          "[stops]") {
  const double d = 0.5, r = 0.8;
  auto symmetric_orbit = [&](double omega) {
    const std::optional<SymmetricOrbit> exact = SymmetricClosedForm(omega, d, r);
    REQUIRE(exact);
    const System s = Clearance(omega, d, r);
    OrbitOptions options;
    options.p = 2;
    options.q = 1;
    HybridState state = RestState(s);
    state.t = exact->phase;
    state.x(0) = d;
    state.v(0) = exact->speed * (1 + 1e-3);  // a nearby guess
    PeriodicOrbit orbit;
    REQUIRE(
        FindOrbit(s, ImpactMap(s).ToEta(state.t, state.x, state.v), options, &orbit).termination ==
        Termination::kConverged);
    return std::pair{*exact, orbit};
  };
  for (double omega : {0.9, 1.0, 1.2, 2.0}) {
    INFO("omega = " << omega);
    const auto [exact, orbit] = symmetric_orbit(omega);
    // Two impacts, one at each stop, with the closed form's speed.
    REQUIRE(orbit.impacts.size() == 2);
    CHECK(orbit.impacts[0].stop == 0);
    CHECK(orbit.impacts[1].stop == 1);
    for (const OrbitImpact& impact : orbit.impacts) {
      CHECK_THAT(impact.velocity, WithinAbs(exact.speed, 1e-10));
    }
    const Eigen::Vector2cd half = HalfMapMultipliers(omega, d, r, exact);
    std::vector<double> expected = {std::abs(half(0) * half(0)), std::abs(half(1) * half(1))};
    std::sort(expected.rbegin(), expected.rend());
    CHECK_THAT(std::abs(orbit.multipliers(0)), WithinAbs(expected[0], 1e-8));
    CHECK_THAT(std::abs(orbit.multipliers(1)), WithinAbs(expected[1], 1e-8));
  }
  // The pitchfork: S·DH has the multiplier -1. Bisection on the closed form.
  auto flip = [&](double omega) {
    const std::optional<SymmetricOrbit> exact = SymmetricClosedForm(omega, d, r);
    const Eigen::Vector2cd half = HalfMapMultipliers(omega, d, r, *exact);
    return ((half(0) + 1.0) * (half(1) + 1.0)).real();
  };
  double lo = 1.0, hi = 1.1;
  REQUIRE(flip(lo) * flip(hi) < 0);
  while (hi - lo > 1e-13) ((flip(lo) * flip(0.5 * (lo + hi)) <= 0) ? hi : lo) = 0.5 * (lo + hi);
  const double pitchfork = 0.5 * (lo + hi);

  const auto [exact, start] = symmetric_orbit(1.0);
  ContinuationOptions options;
  options.orbit.p = 2;
  options.orbit.q = 1;
  options.from = 0.9;
  options.to = 1.2;
  const Branch branch = ContinueBranch({Clearance(1.0, d, r), start, {}}, options);
  const auto found =
      std::find_if(branch.special_points.begin(), branch.special_points.end(),
                   [](const SpecialPoint& p) { return p.type == SpecialPointType::kPitchfork; });
  REQUIRE(found != branch.special_points.end());
  CHECK_THAT(found->parameter, WithinAbs(pitchfork, 1e-8));
  // Not a fold: the branch goes on past it.
  CHECK(branch.points.back().parameter == 1.2);
  // The crossing branch: asymmetric orbits, one on each half. The halves
  // are mirror images, so the asymmetry v_upper − v_lower changes sign
  // across the pitchfork; the located point may sit a little way along the
  // crossing branch (the corrector slides where the branches meet), so the
  // two starts lie on either side of its asymmetry.
  auto asymmetry = [](const PeriodicOrbit& orbit) {
    const std::vector<OrbitImpact>& impacts = orbit.impacts;
    const double sign = impacts[0].stop == 0 ? 1.0 : -1.0;
    return sign * (impacts[0].velocity - impacts[1].velocity);
  };
  const double at_pitchfork = asymmetry(found->point.orbit);
  std::vector<double> sides;
  for (double offset : {1e-3, -1e-3}) {
    const std::optional<BranchStart> crossing =
        PitchforkBranchStart(Clearance(1.0, d, r), branch, *found, options, offset);
    REQUIRE(crossing);
    CHECK_THAT(crossing->system.omega, WithinAbs(found->parameter, 1e-6));
    CHECK(std::abs(asymmetry(crossing->orbit)) > 1e-4);
    sides.push_back(asymmetry(crossing->orbit) - at_pitchfork);
    // Heading away from the pitchfork on either half: the start's tangent
    // (in (η, Ω)) points from the pitchfork to the start, so each half is
    // followed outwards and not back across the pitchfork onto the other.
    Eigen::VectorXd from_pitchfork(crossing->direction.size());
    from_pitchfork << crossing->orbit.eta - found->point.orbit.eta,
        crossing->system.omega - found->parameter;
    CAPTURE(offset);
    CHECK(crossing->direction.dot(from_pitchfork) > 0);
  }
  CHECK(sides[0] * sides[1] < 0);
}

TEST_CASE("impact map with two stops: the analytic Jacobian against finite differences",
          "[stops]") {
  // Six impacts on from a settled impact, through both stops: the
  // clearance's asymmetric orbit and a chain with stops on two masses.
  System chain = PaperSystem(0.8);
  chain.stops = {{1, StopSide::kUpper, 0.1, 0.7}, {0, StopSide::kLower, -0.4, 0.6}};
  for (const System& s : {Clearance(1.5, 0.5, 0.8), chain}) {
    HybridState state = RestState(s);
    ImpactRecorder recorder;
    Simulator(s).Run(state, 200 * s.ForcingPeriod(), recorder);
    const ImpactView last = recorder.Impacts().back();
    ImpactMapOptions section;
    section.stop = last.stop;
    const ImpactMap map(s, section);
    const Eigen::VectorXd eta = map.ToEta(last.t, last.x, last.v);
    const MapResult image = map.Follow(eta, last.stop, 6, true);
    REQUIRE(image.termination == Termination::kCompleted);
    CHECK(std::find(image.stops.begin(), image.stops.end(), 1 - last.stop) != image.stops.end());
    Eigen::MatrixXd fd(eta.size(), eta.size());
    for (Eigen::Index j = 0; j < eta.size(); ++j) {
      const double h = 1e-6 * (j == map.TimeIndex() ? s.ForcingPeriod() : 1.0);
      Eigen::VectorXd plus = eta, minus = eta;
      plus(j) += h;
      minus(j) -= h;
      const MapResult a = map.Follow(plus, last.stop, 6, false),
                      b = map.Follow(minus, last.stop, 6, false);
      REQUIRE(a.termination == Termination::kCompleted);
      REQUIRE(b.termination == Termination::kCompleted);
      REQUIRE(a.stops == image.stops);
      fd.col(j) = (a.eta - b.eta) / (2 * h);
    }
    const double scale = std::max(1.0, image.jacobian.cwiseAbs().maxCoeff());
    CHECK((image.jacobian - fd).cwiseAbs().maxCoeff() < 1e-5 * scale);
  }
}

TEST_CASE(
    "a clearance's asymmetric P(2,1) grazes a stop: the new contact located, checked by CVODE",
    "[stops]") {
  // The asymmetric orbits of Ω ≈ 1.3 to 1.53 end where a flight's turning
  // point reaches a stop (a new contact; the branch shows it at both ends).
  const System s = Clearance(1.5, 0.5, 0.8);
  const std::optional<OrbitSeed> seed = SeedFromSimulation(s);
  REQUIRE(seed);
  OrbitOptions orbit_options;
  orbit_options.p = 2;
  orbit_options.q = 1;
  orbit_options.map.stop = seed->stop;
  PeriodicOrbit start;
  REQUIRE(FindOrbit(s, seed->eta, orbit_options, &start).termination == Termination::kConverged);
  ContinuationOptions options;
  options.orbit = orbit_options;
  options.from = 1.2;
  options.to = 1.6;
  options.direction = ContinuationDirection::kBoth;
  const Branch branch = ContinueBranch({s, start, {}}, options);
  // Each new contact, recomputed with CVODE along the flight that holds it
  // from the impact that starts it.
  std::vector<int> touched_stops;
  for (const SpecialPoint& graze : branch.special_points) {
    if (graze.type != SpecialPointType::kGrazing || graze.vanishing_impact >= 0) continue;
    const PeriodicOrbit& orbit = graze.point.orbit;
    const OrbitContacts& contacts = orbit.contacts;
    REQUIRE(contacts.clearance);
    System at = s;
    at.omega = graze.point.parameter;
    ImpactMapOptions section;
    section.stop = orbit.stop;
    const ImpactMap map(at, section);
    const MapResult path = map.Apply(orbit.eta, 2, false);
    REQUIRE(path.termination == Termination::kCompleted);
    const int k = contacts.clearance_flight;
    const Eigen::VectorXd& from = k == 0 ? orbit.eta : path.path[k - 1];
    const int from_stop = k == 0 ? orbit.stop : path.stops[k - 1];
    HybridState before = map.ToState(from, from_stop);
    Stop(at, from_stop).Reset(before.v);
    Eigen::VectorXd x = before.x, v = before.v;
    reference::CvodeLinearFlow(at.mass, at.damping, at.stiffness, at.forcing,
                               Eigen::VectorXd::Zero(1), at.omega, before.t, x, v,
                               contacts.clearance_time);
    const StopParameters& touched = at.stops[contacts.clearance_stop];
    CHECK_THAT(x(0), WithinAbs(touched.position, 1e-9));
    CHECK_THAT(v(0), WithinAbs(0.0, 1e-8));
    touched_stops.push_back(contacts.clearance_stop);
  }
  // The branch's two ends are mirror images: one touches each stop.
  std::sort(touched_stops.begin(), touched_stops.end());
  CHECK(touched_stops == std::vector<int>{0, 1});
}

TEST_CASE("stops on both masses hold them at once, released where a closed-form force vanishes",
          "[stops]") {
  // Slowly forced, both masses of the paper's chain are pressed into stops
  // of their own and held together. Then nothing moves, and each stop's
  // force is row c of A cos Ωt - K x at the held positions: with K = [[2,
  // -1], [-1, 1]], Fs1 = 0.5 cos Ωt - 2 (0.05) + 0.1, Fs2 = 0.3 cos Ωt +
  // 0.05 - 0.1. Each phase held together ends where one of them falls to 0.
  System s = PaperSystem(0.1);
  s.forcing = Eigen::Vector2d(0.5, 0.3);
  s.stops = {{0, StopSide::kUpper, 0.05, 0.6}, {1, StopSide::kUpper, 0.1, 0.7}};
  Validate(s);
  const double t_end = 20 * s.ForcingPeriod();
  struct HeldTogether : Observer {
    std::vector<std::pair<double, double>> phases;
    void OnSegment(const Segment& segment) override {
      if (segment.Mode() != SegmentMode::kStuck || !(segment.End() > segment.Begin())) return;
      Eigen::VectorXd x0, v0, x1, v1;
      segment.StateAt(segment.Begin(), &x0, &v0);
      segment.StateAt(segment.End(), &x1, &v1);
      if (x0 == x1 && x0 == Eigen::Vector2d(0.05, 0.1)) {
        phases.emplace_back(segment.Begin(), segment.End());
      }
    }
  } held;
  HybridState state = RestState(s);
  Simulator(s).Run(state, t_end, held);
  REQUIRE(held.phases.size() >= 20);
  auto fs1 = [&](double t) { return 0.5 * std::cos(0.1 * t); };
  auto fs2 = [&](double t) { return 0.3 * std::cos(0.1 * t) - 0.05; };
  for (const auto& [begin, end] : held.phases) {
    INFO("held together over [" << begin << ", " << end << "]");
    const double middle = 0.5 * (begin + end);
    CHECK(fs1(middle) > 0);
    CHECK(fs2(middle) > 0);
    if (end < t_end) CHECK_THAT(std::min(fs1(end), fs2(end)), WithinAbs(0.0, 1e-12));
  }
}

TEST_CASE("simultaneous and near-simultaneous impacts at two stops are both taken, in order",
          "[stops]") {
  // Two identical uncoupled masses, each below a stop of its own: each must
  // move as the one-mass system does, whether their impacts coincide
  // exactly or stop 2 sits 1e-9 higher (its impacts a hair later).
  const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
  const System one =
      UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 1.0), 1.3, 0.5, 0.8);
  const ImpactLog alone = ImpactsOf(one, 60 * one.ForcingPeriod());
  REQUIRE(alone.size() > 40);
  for (double shift : {0.0, 1e-9}) {
    INFO("stop 2 higher by " << shift);
    System twin = GeneralSystem(identity, 0.1 * identity, identity, Eigen::Vector2d(1.0, 1.0), 1.3,
                                0.5, 0.8, 0);
    twin.stops.push_back({1, StopSide::kUpper, 0.5 + shift, 0.8});
    Validate(twin);
    const ImpactLog both = ImpactsOf(twin, 60 * twin.ForcingPeriod());
    std::vector<Impact> at[2];
    for (const ImpactView impact : both) at[impact.stop].push_back(impact.Owned());
    REQUIRE(at[0].size() == alone.size());
    REQUIRE(at[1].size() == alone.size());
    for (std::size_t k = 0; k < alone.size(); ++k) {
      CHECK_THAT(at[0][k].t, WithinAbs(alone[k].t, 1e-9));
      CHECK_THAT(at[1][k].t, WithinAbs(alone[k].t, 1e-6));
      CHECK_THAT(at[0][k].velocity, WithinAbs(alone[k].velocity, 1e-9));
      CHECK_THAT(at[1][k].velocity, WithinAbs(alone[k].velocity, 1e-6));
    }
    // From rest the two masses move alike up to the first impacts: the
    // higher stop's comes a hair later (later impacts differ by the
    // rebounds' own small difference, either way).
    if (shift > 0) CHECK(at[1][0].t > at[0][0].t);
    // In time order, as recorded.
    for (std::size_t k = 1; k < both.size(); ++k) CHECK(both[k].t >= both[k - 1].t);
  }
}
