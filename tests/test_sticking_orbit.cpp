// Sticking orbits P(∞, q) as fixed points of the release map: against long
// simulations read through the simulator's recorders, a finite-difference
// monodromy of the simulator's stroboscopic map, finite differences of the
// map itself, and the N = 1 oscillator's closed-form release.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "cvode_flight_top.hpp"
#include "cvode_impacts.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/sticking_seed.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/sticking_map.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"
#include "seeded_orbit.hpp"
#include "sorted_eigenvalues.hpp"

using namespace impactkit;
using Catch::Matchers::WithinAbs;
using testing::SortedEigenvalues;

namespace {

/// How the simulation from rest sticks with parameter `name` at `value`
/// (300 transient periods, periods up to 4); nothing if it does not stick.
std::optional<StickingSeed> SteadySticking(System system, const std::string& name, double value) {
  SetParameter(system, name, value);
  return SeedStickingFromSimulation(system, 300, 4);
}

/// The state a time `after` past the orbit's first release, by simulation.
HybridState OnOrbit(const System& system, const StickingMap& map, const PeriodicOrbit& orbit,
                    double after) {
  HybridState state = map.ToState(orbit.eta);
  Simulator(system).Run(state, state.t + after);
  return state;
}

/// y -> y(t + qT) of the simulator from (t, y) free.
Eigen::VectorXd Strobe(const Simulator& simulator, double t, const Eigen::VectorXd& y,
                       double span) {
  const int n = static_cast<int>(y.size()) / 2;
  HybridState state{t, y.head(n), y.tail(n), false};
  simulator.Run(state, t + span);
  Eigen::VectorXd out(2 * n);
  out << state.x, state.v;
  return out;
}

/// The multipliers, largest first, of the simulator's stroboscopic map over
/// the orbit's q periods, from a point in the free flight after its first
/// release, by central differences (an independent monodromy: no release
/// map).
Eigen::VectorXcd SimulatorMultipliers(const System& system, const PeriodicOrbit& orbit) {
  const StickingMap map(system);
  const double flight = orbit.impacts[0].t - orbit.eta(orbit.eta.size() - 1);
  const HybridState start = OnOrbit(system, map, orbit, 0.5 * flight);
  const int n = 2 * system.Dof();
  Eigen::VectorXd y(n);
  y << start.x, start.v;
  const Simulator simulator(system);
  const double h = 1e-6, span = orbit.q * system.ForcingPeriod();
  Eigen::MatrixXd monodromy(n, n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd plus = y, minus = y;
    plus(j) += h;
    minus(j) -= h;
    monodromy.col(j) =
        (Strobe(simulator, start.t, plus, span) - Strobe(simulator, start.t, minus, span)) /
        (2 * h);
  }
  return SortedEigenvalues(monodromy);
}

}  // namespace

TEST_CASE("paper system at Omega = 0.2: stick and release phases match a long simulation",
          "[sticking]") {
  const System system = PaperSystem(0.2);
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  REQUIRE(orbit.releases == 1);
  REQUIRE(orbit.q == 1);
  CHECK(orbit.residual < 1e-11);

  // Independent: 300 periods from rest, the last period's chatter end and
  // sticking interval as the simulator's recorders saw them.
  const StickingInterval stuck = testing::SimulateStuckPhase(system, 300).interval;
  // The stick time is the chatter's predicted accumulation point on both
  // sides, good to ~5e-8 with the default span (docs/theory.md, the 60-digit
  // stuck time of test_simulate): two runs whose impact times differ in the
  // last bits (a changed root refinement did that) differ there by a few
  // 1e-9, so that is the bound; the release, a root of the contact force on
  // the stuck flow, is compared to 1e-9.
  CHECK_THAT(orbit.stuck[0].stick_phase, WithinAbs(system.Phase(stuck.begin), 5e-8));
  CHECK_THAT(orbit.stuck[0].release_phase, WithinAbs(system.Phase(stuck.end), 1e-9));
  CHECK_THAT(orbit.stuck[0].Duration(), WithinAbs(stuck.end - stuck.begin, 5e-8));
  CHECK(orbit.stable);
  CHECK(orbit.p == orbit.stuck[0].impacts);
  CHECK(orbit.contacts.contact_margin == orbit.stuck[0].contact_force);
  // The extent of x2 over the orbit against the simulator's exact extrema
  // of a steady period.
  const PeriodExtrema period = testing::SteadyPeriodExtrema(system);
  CHECK_THAT(orbit.contacts.contact_max, WithinAbs(period.max(1), 1e-9));
  CHECK_THAT(orbit.contacts.contact_min, WithinAbs(period.min(1), 1e-9));
}

TEST_CASE("paper system at Omega = 0.2: section multipliers match the simulator's monodromy",
          "[sticking]") {
  const System system = PaperSystem(0.2);
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  const Eigen::VectorXcd lambda = SimulatorMultipliers(system, orbit);
  // Sticking collapses x_2 and v_2: two zero multipliers of the strobe map.
  CHECK(std::abs(lambda(2)) < 1e-5);
  CHECK(std::abs(lambda(3)) < 1e-5);
  REQUIRE(orbit.multipliers.size() == 2);
  const Eigen::VectorXcd section = SortedEigenvalues(orbit.jacobian).head(2);
  for (int i = 0; i < 2; ++i) {
    CHECK(std::abs(orbit.multipliers(i) - lambda(i)) < 1e-5);
    CHECK(std::abs(section(i) - lambda(i)) < 1e-5);  // D P_R's other multiplier is 0
  }
}

TEST_CASE(
    "StickingMap::Follow: from a free state over a period, the state and its Jacobian are the "
    "simulator's and its finite-difference monodromy, and a time inside a stuck phase holds the "
    "mass",
    "[sticking]") {
  const System system = PaperSystem(0.2);
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  const StickingMap map(system);
  const double flight = orbit.impacts[0].t - orbit.eta(orbit.eta.size() - 1);
  const HybridState start = OnOrbit(system, map, orbit, 0.5 * flight);
  const double span = orbit.q * system.ForcingPeriod();
  const StickingFlight followed = map.Follow(start, start.t + span, true);
  REQUIRE(followed.termination == Termination::kCompleted);
  const int n = 2 * system.Dof();
  Eigen::VectorXd y(n), end(n);
  y << start.x, start.v;
  end << followed.state.x, followed.state.v;
  const Simulator simulator(system);
  // The simulator's events (its chatter's accumulation included) to ~1e-12.
  CHECK((end - Strobe(simulator, start.t, y, span)).cwiseAbs().maxCoeff() < 1e-10);
  // Central differences of the simulator, h = 1e-6: O(h²) and its
  // rounding over h, ~1e-7; the chatter's count must not change, which
  // holds at this h (the release map's own step, sticking_map.hpp).
  const double h = 1e-6;
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd plus = y, minus = y;
    plus(j) += h;
    minus(j) -= h;
    const Eigen::VectorXd column =
        (Strobe(simulator, start.t, plus, span) - Strobe(simulator, start.t, minus, span)) /
        (2 * h);
    INFO("column " << j << ": " << followed.jacobian.col(j).transpose() << " against "
                   << column.transpose());
    CHECK((followed.jacobian.col(j) - column).cwiseAbs().maxCoeff() < 1e-5);
  }
  // To the middle of the stuck phase: mass 2 held at its stop, at rest,
  // whatever the start (its rows of the Jacobian are 0); mass 1 the
  // simulator's.
  const StuckPhase& stuck = orbit.stuck[0];
  const double period = system.ForcingPeriod();
  double middle = 0.5 * (stuck.stick + stuck.release);
  middle += std::ceil((start.t - middle) / period) * period;
  const StickingFlight held = map.Follow(start, middle, true);
  REQUIRE(held.termination == Termination::kCompleted);
  CHECK(held.state.x(1) == system.stops[0].position);
  CHECK(held.state.v(1) == 0.0);
  CHECK(held.jacobian.row(1).isZero(0.0));
  CHECK(held.jacobian.row(3).isZero(0.0));
  HybridState simulated = start;
  simulator.Run(simulated, middle);
  CHECK(std::abs(held.state.x(0) - simulated.x(0)) < 1e-10);
  CHECK(std::abs(held.state.v(0) - simulated.v(0)) < 1e-10);
}

TEST_CASE("release map: analytic Jacobian agrees with finite differences", "[sticking]") {
  SECTION("paper system, Omega = 0.2, at the orbit and off it, one and two releases") {
    const System system = PaperSystem(0.2);
    const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
    const StickingMap map(system);
    Eigen::VectorXd off = orbit.eta;
    off(0) -= 2e-3;  // Fs lower: released a little earlier, still a release
    off(1) += 1e-3;
    for (const Eigen::VectorXd& s : {orbit.eta, off}) {
      for (int k : {1, 2}) {
        const StickingMapResult image = map.Apply(s, k, true);
        REQUIRE(image.termination == Termination::kCompleted);
        const Eigen::MatrixXd fd = FiniteDifferenceJacobian(map, s, k);
        REQUIRE(fd.size() == image.jacobian.size());
        // Map rounding ~1e-12 over steps of 1e-6: ~1e-6 absolute at most.
        CHECK((image.jacobian - fd).cwiseAbs().maxCoeff() < 1e-5);
        // The image lies on the release surface: ∇Fs · D P_R = 0.
        CHECK((map.ContactForceGradient(image.state) * image.jacobian).cwiseAbs().maxCoeff() <
              1e-10);
        CHECK(std::abs(map.ContactForce(image.state)) < 1e-10);
      }
    }
  }
  SECTION("three masses with a coupled mass matrix (the impulse moves the others)") {
    Eigen::MatrixXd mass = Eigen::MatrixXd::Identity(3, 3);
    mass(0, 1) = mass(1, 0) = 0.2;
    mass(1, 2) = mass(2, 1) = 0.1;
    const Eigen::MatrixXd stiffness = ChainCouplingMatrix(3);
    const Eigen::MatrixXd damping = 0.1 * stiffness;
    const System system =
        GeneralSystem(mass, damping, stiffness, Eigen::Vector3d(0.5, 0.0, 0.0), 0.2, 0.1, 0.7);
    const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
    const StickingMap map(system);
    const Eigen::MatrixXd fd = FiniteDifferenceJacobian(map, orbit.eta, orbit.releases);
    REQUIRE(fd.size() == orbit.jacobian.size());
    CHECK((orbit.jacobian - fd).cwiseAbs().maxCoeff() < 1e-5);
  }
}

TEST_CASE("N = 1: the sticking orbit's release has the closed form cos(Omega t) = k xs / A",
          "[sticking]") {
  // m x'' + c x' + k x = A cos Ωt; held at xs the stop's force is
  // Fs = A cos Ωt − k xs, which falls through 0 (sin Ωt > 0) at
  // Ω t_r = arccos(k xs / A): the release phase whatever came before, so
  // D P_R = 0 and the section has no direction left.
  const double k = 1.0, xs = 0.1, a = 0.5, omega = 0.2;
  const System system =
      UniformChain({1, 1.0, k, 0.1}, Eigen::VectorXd::Constant(1, a), omega, xs, 0.7);
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  const double release = std::acos(k * xs / a) / omega;
  CHECK_THAT(orbit.stuck[0].release_phase, WithinAbs(release, 1e-12));
  CHECK_THAT(orbit.eta(0), WithinAbs(release, 1e-12));
  CHECK(orbit.jacobian.cwiseAbs().maxCoeff() < 1e-12);
  CHECK(orbit.multipliers.size() == 0);
  CHECK(orbit.stable);
  // Sticking can only begin where the stop pushes: Fs(t*) > 0.
  const double t_star = orbit.stuck[0].stick_phase;
  CHECK(a * std::cos(omega * t_star) - k * xs > 0);
  CHECK_THAT(orbit.stuck[0].Duration(),
             WithinAbs(std::fmod(release - t_star + system.ForcingPeriod(), system.ForcingPeriod()),
                       1e-12));
}

TEST_CASE("sticking orbits: bad input is a clear error", "[sticking]") {
  const System system = PaperSystem(0.2);
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(system);
  OrbitOptions options = testing::OneRelease();
  PeriodicOrbit out;
  SECTION("q = 0 or negative releases") {
    options.q = 0;
    CHECK_THROWS_AS(FindOrbit(system, orbit.eta, options, &out), InvalidInput);
    options.q = 1;
    options.releases = -1;
    CHECK_THROWS_AS(FindOrbit(system, orbit.eta, options, &out), InvalidInput);
  }
  SECTION("a guess of the wrong size or with a NaN") {
    CHECK_THROWS_AS(FindOrbit(system, Eigen::VectorXd::Zero(2), options, &out), InvalidInput);
    Eigen::VectorXd nan = orbit.eta;
    nan(0) = std::nan("");
    CHECK_THROWS_AS(FindOrbit(system, nan, options, &out), InvalidInput);
  }
  SECTION("Follow: a state of the wrong size or with a NaN, a time before it, a stop it lacks") {
    const StickingMap map(system);
    const HybridState start = map.ToState(orbit.eta);
    HybridState short_state = start;
    short_state.x = Eigen::VectorXd::Zero(1);
    CHECK_THROWS_WITH(map.Follow(short_state, start.t + 1.0, true),
                      Catch::Matchers::Contains("2 positions and velocities"));
    HybridState nan = start;
    nan.v(0) = std::nan("");
    CHECK_THROWS_WITH(map.Follow(nan, start.t + 1.0, true), Catch::Matchers::Contains("finite"));
    CHECK_THROWS_WITH(map.Follow(start, start.t - 1.0, true),
                      Catch::Matchers::Contains("followed forward"));
    CHECK_THROWS_WITH(map.Follow(start, start.t + 1.0, true, 3),
                      Catch::Matchers::Contains("the system has 1 stop"));
  }
  SECTION("a guess where the stop still pushes (no release)") {
    Eigen::VectorXd held = orbit.eta;
    held(2) = 0.0;  // Fs = 0.5 + x1 - 0.1 > 0 at t = 0
    CHECK_THROWS_WITH(FindOrbit(system, held, options, &out),
                      Catch::Matchers::Contains("not a release"));
  }
}

TEST_CASE("sticking orbits: a release state the map cannot follow is a failure, as for impacts",
          "[sticking]") {
  // Ω = 0.5: the motion impacts without a chatter sequence accumulating.
  // The guess is a release state; no sticking orbit goes through it, which
  // FindOrbit reports as it does a guess whose impact is lost.
  const PeriodicOrbit orbit = testing::SeededStickingOrbit(PaperSystem(0.2));
  PeriodicOrbit out;
  const OrbitSummary summary = FindOrbit(PaperSystem(0.5), orbit.eta, testing::OneRelease(), &out);
  CHECK(summary.termination == Termination::kFailure);
  CHECK_THAT(summary.message,
             Catch::Matchers::Contains("the map failed at the seed: after 0 of 1 releases, "
                                       "impacts without a chatter sequence accumulating"));
  CHECK(out.eta == orbit.eta);

  // The same for an impact state whose next impact comes after the map's
  // longest flight (here a millionth of a period).
  PeriodicOrbit impacting;
  Eigen::VectorXd eta(4);
  eta << 0.0, 0.0, 0.1, 0.5;
  OrbitOptions short_flights;
  short_flights.map.max_flight_periods = 1e-6;
  short_flights.shooting_fallback = false;
  const OrbitSummary lost = FindOrbit(PaperSystem(0.5), eta, short_flights, &impacting);
  CHECK(lost.termination == Termination::kFailure);
  CHECK_THAT(lost.message, Catch::Matchers::Contains(
                               "the map failed at the seed: after 0 of 1 impacts, lost impact"));
}
TEST_CASE("sticking branch in Omega: its end recomputed, and where simulation stops sticking",
          "[sticking][continuation]") {
  const System system = PaperSystem(0.2);
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  ContinuationOptions options;
  options.from = 0.1;
  options.to = 0.6;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == Termination::kNoSticking);
  REQUIRE(!branch.special_points.empty());
  const SpecialPoint& end = branch.special_points.back();
  CHECK(end.type == SpecialPointType::kNoSticking);
  const double omega_end = end.point.parameter;
  CHECK(omega_end > 0.3);
  CHECK(omega_end < 0.31);

  // Recomputed from the located point: an orbit there, whose chatter only
  // just ends in sticking (Fs(t*) small beside its ~0.2 mid-branch) ...
  const OrbitOptions orbit_options = testing::OneRelease();
  PeriodicOrbit again;
  REQUIRE(
      FindOrbit(PaperSystem(omega_end), end.point.orbit.eta, orbit_options, &again).termination ==
      Termination::kConverged);
  CHECK((again.eta - end.point.orbit.eta).cwiseAbs().maxCoeff() < 1e-8);
  CHECK(again.contacts.contact_margin > 0);
  CHECK(again.contacts.contact_margin < 5e-3);
  // ... and no sticking orbit just beyond it.
  Eigen::VectorXd beyond_guess = again.eta;
  PeriodicOrbit beyond;
  bool sticks = true;
  try {
    sticks = FindOrbit(PaperSystem(omega_end + 1e-4), beyond_guess, orbit_options, &beyond)
                 .termination == Termination::kConverged;
  } catch (const InvalidInput&) {
    sticks = false;
  }
  CHECK(!sticks);
  // Independent: the simulator from rest sticks periodically 1e-3 below
  // the end and not 1e-3 above it.
  CHECK(SeedStickingFromSimulation(PaperSystem(omega_end - 1e-3), 300, 4));
  CHECK(!SeedStickingFromSimulation(PaperSystem(omega_end + 1e-3), 300, 4));
  // The other end of the branch: the lower bound.
  const Branch down = [&] {
    ContinuationOptions o = options;
    o.direction = ContinuationDirection::kDecreasing;
    return ContinueBranch({system, start, {}}, o);
  }();
  CHECK(down.end == Termination::kParameterBound);
  CHECK_THAT(down.points.back().parameter, WithinAbs(0.1, 1e-12));
  // Every point of the branches is a sticking orbit of its system.
  for (const BranchPoint& p : branch.points) CHECK(p.orbit.residual < 1e-9);
}

TEST_CASE("sticking branch in xs ends at an early release, recomputed there",
          "[sticking][continuation]") {
  const System system = PaperSystem(0.2);
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  ContinuationOptions options;
  options.parameter = "xs";
  options.from = 0.0;
  options.to = 0.6;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == Termination::kEarlyRelease);
  const BranchPoint& end = branch.special_points.back().point;
  // Recomputed at the located xs: an orbit whose stuck phase only just
  // holds (Fs's interior minimum small beside its Fs(t*) ~ 0.09) ...
  System at_end = system;
  at_end.stops[0].position = end.parameter;
  PeriodicOrbit again;
  REQUIRE(FindOrbit(at_end, end.orbit.eta, testing::OneRelease(), &again).termination ==
          Termination::kConverged);
  CHECK(again.contacts.hold_margin > 0);
  CHECK(again.contacts.hold_margin < 1e-3);
  // ... and the simulation 1e-3 beyond it sticks twice per period: the
  // early release and the sticking that follows it.
  const std::optional<StickingSeed> seed = SteadySticking(system, "xs", end.parameter + 1e-3);
  REQUIRE(seed);
  CHECK(seed->releases == 2);
  CHECK(seed->q == 1);
}

TEST_CASE(
    "sticking branch in c at Omega = 0.27 period-doubles, confirmed by the simulator's "
    "monodromy and its period-2 sticking beyond",
    "[sticking][continuation]") {
  const System system = PaperSystem(0.27);
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  ContinuationOptions options;
  options.parameter = "c";
  options.from = 0.01;
  options.to = 0.1;
  options.direction = ContinuationDirection::kDecreasing;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  const auto pd = std::find_if(
      branch.special_points.begin(), branch.special_points.end(),
      [](const SpecialPoint& s) { return s.type == SpecialPointType::kPeriodDoubling; });
  REQUIRE(pd != branch.special_points.end());
  const double c = pd->point.parameter;
  CHECK(c > 0.03);
  CHECK(c < 0.04);
  // Recomputed: a fresh solve at the located c has a multiplier -1 to
  // 1e-6, and the simulator's own monodromy there one within 1e-4.
  System at = system;
  SetParameter(at, "c", c);
  PeriodicOrbit again;
  REQUIRE(FindOrbit(at, pd->point.orbit.eta, testing::OneRelease(), &again).termination ==
          Termination::kConverged);
  double nearest = 1e300;
  for (const std::complex<double>& m : again.multipliers)
    nearest = std::min(nearest, std::abs(m + 1.0));
  CHECK(nearest < 1e-6);
  const Eigen::VectorXcd lambda = SimulatorMultipliers(at, again);
  CHECK(std::abs(lambda(0) + 1.0) < 1e-4);
  // From rest, the simulation sticks once per period above the doubling
  // and once every two periods below it.
  const std::optional<StickingSeed> once = SteadySticking(system, "c", c + 2e-3);
  const std::optional<StickingSeed> twice = SteadySticking(system, "c", c - 2e-3);
  REQUIRE(once);
  REQUIRE(twice);
  CHECK(once->q == 1);
  CHECK(twice->q == 2);
}

TEST_CASE(
    "sticking branch in A1 ends where the flight after the release grazes the stop, "
    "recomputed there by CVODE",
    "[sticking][continuation]") {
  // At Ω = 0.25 the mass released from the stop swings back towards it;
  // as A1 grows that swing reaches the stop (a new impact) and beyond it
  // the release map carries the extra impact on continuously. The family
  // used to run through it and stop further on, labelled no_sticking with
  // Fs(t*) = 0.37.
  System system = PaperSystem(0.25);
  SetParameter(system, "A1", 0.5);
  const PeriodicOrbit start = testing::SeededStickingOrbit(system);
  ContinuationOptions options;
  options.parameter = "A1";
  options.from = 0.5;
  options.to = 3.0;
  const Branch branch = ContinueBranch({system, start, {}}, options);
  REQUIRE(branch.end == Termination::kGrazing);  // a new impact
  REQUIRE(branch.special_points.back().vanishing_impact < 0);
  const BranchPoint& end = branch.special_points.back().point;
  CHECK(end.orbit.contacts.contact_margin > 0.3);  // the chatter still ends firmly in sticking
  System at_end = system;
  SetParameter(at_end, "A1", end.parameter);
  PeriodicOrbit again;
  REQUIRE(FindOrbit(at_end, end.orbit.eta, testing::OneRelease(), &again).termination ==
          Termination::kConverged);
  CHECK((again.eta - end.orbit.eta).cwiseAbs().maxCoeff() < 1e-8);
  // Independently: CVODE from the release over the flight to the first
  // impact rises to the stop (to 1e-7) in between.
  const HybridState released = StickingMap(at_end).ToState(again.eta);
  const std::optional<double> top =
      testing::CvodeFlightTop(at_end, released.t, released.x, released.v, again.impacts.front().t);
  REQUIRE(top.has_value());
  CHECK(std::abs(at_end.stops[0].position - *top) < 1e-7);
  // Beyond it the first impact after the release is that swing's, ten
  // times sooner.
  System beyond = system;
  SetParameter(beyond, "A1", end.parameter + 1e-4);
  PeriodicOrbit past;
  REQUIRE(FindOrbit(beyond, end.orbit.eta, testing::OneRelease(), &past).termination ==
          Termination::kConverged);
  const double delay = again.impacts.front().t - released.t;
  CHECK(past.impacts.front().t - past.eta(past.eta.size() - 1) < 0.2 * delay);
  // Followed back from there, that first impact slows to a graze at the
  // same A1: the family beyond ends where this one did. Its corrector stops
  // with the impact at a speed of ~2e-8 (the release map's Jacobian grows
  // like 1/v), which falls linearly with A1: ~2e-8 short of the graze.
  ContinuationOptions back = options;
  back.direction = ContinuationDirection::kDecreasing;
  const Branch other = ContinueBranch({beyond, past, {}}, back);
  REQUIRE(other.end == Termination::kGrazing);  // a vanishing impact: the first after the release
  REQUIRE(other.special_points.back().vanishing_impact == 0);
  const BranchPoint& other_end = other.special_points.back().point;
  CHECK_THAT(other_end.parameter, WithinAbs(end.parameter, 1e-5));
  CHECK(other_end.orbit.impacts.front().velocity < 1e-5);
  // Independently: CVODE from that orbit's release rises to the stop (to
  // 1e-7) where its first impact vanishes. (Not FindOrbit again: at an
  // impact speed of 2e-8 the map's rounding in U, ~ε/v, is above its
  // tolerance.)
  System at_other = system;
  SetParameter(at_other, "A1", other_end.parameter);
  const HybridState released_there = StickingMap(at_other).ToState(other_end.orbit.eta);
  const std::optional<double> touch =
      testing::CvodeFlightTop(at_other, released_there.t, released_there.x, released_there.v,
                              other_end.orbit.impacts.front().t + 0.1);
  REQUIRE(touch.has_value());
  CHECK(std::abs(at_other.stops[0].position - *touch) < 1e-7);
}

TEST_CASE(
    "chatter orbits with many impacts: P(64,1) just above the sticking region of r = 0.9, its "
    "impacts by CVODE and its branch between two grazings",
    "[sticking][continuation]") {
  // With the paper's r = 0.7 the P(n,1) windows above n ~ 36 lie within
  // 1e-6 of the sticking family's end and their last impacts are slower
  // than the chatter rule resolves (docs/continuation.md); with r = 0.9
  // they are wider: the steady motion at Ω = 0.165606 is P(64,1).
  System system = PaperSystem(0.165606);
  system.stops[0].restitution = 0.9;
  const std::optional<OrbitSeed> seed = SeedFromSimulation(system, 500);
  REQUIRE(seed);
  CHECK(seed->motion.p == 64);
  CHECK(seed->motion.q == 1);
  OrbitOptions options;
  options.p = 64;
  options.q = 1;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, seed->eta, options, &orbit).termination == Termination::kConverged);
  CHECK(orbit.stable);
  // Independently, flight by flight: CVODE from the rebound of each of the
  // 64 impacts meets the next at the same time and speed (over a whole
  // period the chatter amplifies any difference by ~1/r per impact).
  const ImpactMap map(system);
  const MapResult image = map.Apply(orbit.eta, 64, false);
  REQUIRE(image.termination == Termination::kCompleted);
  reference::CvodeOptions one_flight;
  one_flight.max_impacts = 1;
  for (int k = 0; k < 64; ++k) {
    INFO("flight after impact " << k);
    HybridState state = map.ToState(k == 0 ? orbit.eta : image.path[k - 1]);
    state.v(1) *= -system.stops[0].restitution;
    const OrbitImpact& next = orbit.impacts[(k + 1) % 64];
    const double t_next = next.t + (k == 63 ? system.ForcingPeriod() : 0.0);
    const reference::ReferenceRun cvode = reference::CvodeImpacts(
        system, state.x, state.v, state.t, t_next + 1e-3 * (t_next - state.t), one_flight);
    REQUIRE(cvode.impacts.size() == 1);
    CHECK_THAT(cvode.impacts[0].t, WithinAbs(t_next, 1e-9));
    CHECK_THAT(cvode.impacts[0].velocity, WithinAbs(next.velocity, 1e-9));
  }
  // Its branch, continued with the ordinary impact map, lies between the
  // new contact that makes it P(65,1) below and the vanishing impact that
  // makes it P(63,1) above; that end is where P(63,1)'s own branch, traced
  // separately, meets its new contact.
  ContinuationOptions continuation;
  continuation.from = 0.1655;
  continuation.to = 0.1658;
  continuation.direction = ContinuationDirection::kBoth;
  continuation.orbit = options;
  const Branch p64 = ContinueBranch({system, orbit, {}}, continuation);
  CHECK(p64.begin == Termination::kGrazing);
  CHECK(p64.special_points.front().vanishing_impact == -1);
  REQUIRE(p64.end == Termination::kGrazing);
  CHECK(p64.special_points.back().vanishing_impact >= 0);
  System above = system;
  above.omega = p64.special_points.back().parameter + 1e-6;
  const std::optional<OrbitSeed> seed63 = SeedFromSimulation(above, 500);
  REQUIRE(seed63);
  REQUIRE(seed63->motion.p == 63);
  options.p = 63;
  continuation.orbit = options;
  continuation.direction = ContinuationDirection::kDecreasing;
  PeriodicOrbit orbit63;
  REQUIRE(FindOrbit(above, seed63->eta, options, &orbit63).termination == Termination::kConverged);
  const Branch p63 = ContinueBranch({above, orbit63, {}}, continuation);
  REQUIRE(p63.end == Termination::kGrazing);
  CHECK(p63.special_points.back().vanishing_impact == -1);
  CHECK_THAT(p63.special_points.back().parameter,
             WithinAbs(p64.special_points.back().parameter, 1e-9));
}
