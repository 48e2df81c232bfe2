#include <algorithm>
#include <catch2/catch.hpp>
#include <complex>

#include "cvode_impacts.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "sorted_eigenvalues.hpp"

using Catch::Matchers::WithinAbs;
using namespace impactkit;
using testing::SortedEigenvalues;

namespace {

/// A stable orbit of the paper's system, converged by simulation: the last
/// impact after a long transient, and the stroboscopic state before it.
struct SteadyOrbit {
  System system;
  Eigen::VectorXd eta;
  HybridState strobe;
};

SteadyOrbit Steady(double omega) {
  SteadyOrbit o{PaperSystem(omega), {}, {}};
  const Simulator simulator(o.system);
  const double period = o.system.ForcingPeriod();
  HybridState state = RestState(o.system);
  simulator.Run(state, 800 * period);
  o.strobe = state;
  ImpactRecorder impacts;
  simulator.Run(state, 804 * period, impacts);
  const ImpactView last = impacts.Impacts().back();
  o.eta = ImpactMap(o.system).ToEta(last.t, last.x, last.v);
  return o;
}

/// The stroboscopic map's Jacobian over q periods by central differences of
/// plain simulations: an independent route to the same multipliers.
Eigen::MatrixXd StroboscopicMonodromy(const SteadyOrbit& o, int q) {
  const Simulator simulator(o.system);
  const int n = o.system.Dof();
  const double h = 1e-6;
  Eigen::MatrixXd monodromy(2 * n, 2 * n);
  for (int j = 0; j < 2 * n; ++j) {
    Eigen::VectorXd image[2];
    for (int side = 0; side < 2; ++side) {
      HybridState s = o.strobe;
      (j < n ? s.x(j) : s.v(j - n)) += side == 0 ? h : -h;
      simulator.Run(s, s.t + q * o.system.ForcingPeriod());
      image[side].resize(2 * n);
      image[side] << s.x, s.v;
    }
    monodromy.col(j) = (image[0] - image[1]) / (2 * h);
  }
  return monodromy;
}

}  // namespace

TEST_CASE("the map's fixed points are the simulated orbits", "[impact_map]") {
  struct Case {
    double omega;
    int p, q;
  };
  for (const Case& c : {Case{0.9, 1, 1}, Case{0.6, 2, 1}, Case{2.0, 1, 2}, Case{1.7, 4, 4}}) {
    INFO("omega = " << c.omega);
    const SteadyOrbit o = Steady(c.omega);
    const ImpactMap map(o.system);
    const MapResult image = map.Apply(o.eta, c.p, false);
    REQUIRE(image.termination == Termination::kCompleted);
    Eigen::VectorXd shift = Eigen::VectorXd::Zero(o.eta.size());
    shift(map.TimeIndex()) = c.q * o.system.ForcingPeriod();
    CHECK((image.eta - o.eta - shift).cwiseAbs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("analytic and finite-difference Jacobians agree, and match the stroboscopic map",
          "[impact_map]") {
  struct Case {
    double omega;
    int p, q;
  };
  for (const Case& c : {Case{0.9, 1, 1}, Case{0.6, 2, 1}, Case{2.0, 1, 2}}) {
    INFO("omega = " << c.omega << ", P(" << c.p << "," << c.q << ")");
    const SteadyOrbit o = Steady(c.omega);
    const ImpactMap map(o.system);
    const MapResult image = map.Apply(o.eta, c.p, true);
    REQUIRE(image.termination == Termination::kCompleted);
    const Eigen::MatrixXd fd = FiniteDifferenceJacobian(map, o.eta, c.p);
    REQUIRE(fd.size() > 0);
    CHECK((image.jacobian - fd).norm() <= 1e-6 * fd.norm());

    const Eigen::VectorXcd from_map = SortedEigenvalues(image.jacobian);
    const Eigen::VectorXcd from_simulation = SortedEigenvalues(StroboscopicMonodromy(o, c.q));
    REQUIRE(from_map.size() == from_simulation.size());
    for (Eigen::Index i = 0; i < from_map.size(); ++i) {
      INFO("multiplier " << from_map(i) << " vs " << from_simulation(i));
      CHECK(std::abs(from_map(i) - from_simulation(i)) < 1e-5);
    }
  }
}

TEST_CASE(
    "the map's rate in omega, on the steps of its Jacobian or followed again, is the "
    "difference of its images",
    "[impact_map]") {
  struct Case {
    double omega;
    int p;
  };
  for (const Case& c : {Case{0.9, 1}, Case{0.6, 2}, Case{1.7, 4}}) {
    INFO("omega = " << c.omega << ", " << c.p << " impacts");
    const ImpactMap map(PaperSystem(c.omega));
    // The impact's time in [0, T), as continuation keeps it: at t ~ 800 T
    // a step in omega would move the forcing's phase by radians.
    const Eigen::VectorXd eta = map.WithPhase(Steady(c.omega).eta);
    auto at = [&](double omega) { return ImpactMap(PaperSystem(omega)); };
    const double h = 1e-6;
    const ImpactMap below = at(c.omega - h), above = at(c.omega + h);
    const SectionImage image = map.Iterate(eta, c.p, true);
    REQUIRE(image.Ok());
    REQUIRE(image.steps.size() == static_cast<std::size_t>(c.p));
    // The steps are the iterate's: their Jacobians' product is its Jacobian.
    Eigen::MatrixXd product = Eigen::MatrixXd::Identity(eta.size(), eta.size());
    for (const SectionStep& step : image.steps) product = step.jacobian * product;
    CHECK((product - image.jacobian).norm() <= 1e-14 * image.jacobian.norm());
    const SectionImage reused = map.ParameterRate(eta, c.p, below, above, 2 * h, &image);
    const SectionImage followed = map.ParameterRate(eta, c.p, below, above, 2 * h);
    REQUIRE(reused.Ok());
    REQUIRE(followed.Ok());
    // The same steps, so the same numbers.
    CHECK(reused.state == followed.state);
    // Independently: the plain central difference of P^p at fixed η, away
    // from grazing; its truncation over a step of 1e-4 is 1e-7 to 2e-6 of
    // the rate on these orbits.
    const double step = 1e-4;
    const SectionImage high = at(c.omega + step).Iterate(eta, c.p, false);
    const SectionImage low = at(c.omega - step).Iterate(eta, c.p, false);
    REQUIRE(high.Ok());
    REQUIRE(low.Ok());
    const Eigen::VectorXd difference = (high.state - low.state) / (2 * step);
    CHECK((reused.state - difference).norm() <= 1e-5 * difference.norm());
  }
}

TEST_CASE("map failures are reported, never returned as numbers", "[impact_map]") {
  SECTION("a flight with no further impact") {
    const System s = PaperSystem(4.0);  // far above resonance: tiny response
    ImpactMapOptions options;
    options.max_flight_periods = 4.0;
    const ImpactMap map(s, options);
    Eigen::VectorXd eta(4);
    eta << 0.0, 0.0, 0.0, 0.01;
    const MapResult r = map.Apply(eta, 1, true);
    CHECK(r.termination == Termination::kNoImpact);
    CHECK(r.jacobian.size() == 0);
  }
  SECTION("a chatter sequence: impacts accumulate at the stop") {
    // At Ω = 0.2 every period ends in complete chatter (docs/simulation.md):
    // the map from its first impact follows the geometric sequence until an
    // arrival's height is unresolved (a landing), and says chatter.
    const System s = PaperSystem(0.2);
    const Simulator simulator(s);
    HybridState state = RestState(s);
    simulator.Run(state, 100 * s.ForcingPeriod());
    ImpactRecorder impacts;
    simulator.Run(state, 101 * s.ForcingPeriod(), impacts);
    const ImpactView first = impacts.Impacts().front();
    const ImpactMap map(s);
    const MapResult r = map.Apply(map.ToEta(first.t, first.x, first.v), 200, true);
    CHECK(r.termination == Termination::kSticking);
    CHECK(r.impacts_done > 20);
    CHECK(r.jacobian.size() == 0);
  }
  SECTION("the map and the simulator judge arrivals by one rule") {
    // With a coarse height resolution (1e-7 of the gap's scale) both end a
    // chatter sequence early: the simulator sums its tail after the first
    // impact whose rebound is unresolved, and the map meets the next
    // arrival as a landing. The same impacts, the same count.
    const System s = PaperSystem(0.2);
    SimulationOptions coarse;
    coarse.bounce_height_resolution = 1e-7;
    const Simulator simulator(s, coarse);
    HybridState state = RestState(s);
    simulator.Run(state, 100 * s.ForcingPeriod());
    struct Sequence : Observer {
      ImpactRecorder impacts;
      bool ended = false;
      void OnImpact(const Impact& impact) override {
        if (!ended) impacts.OnImpact(impact);
      }
      void OnChatter(const ChatterEnd&) override { ended = true; }
      bool ShouldStop() const override { return ended; }
    } sequence;
    simulator.Run(state, 101 * s.ForcingPeriod(), sequence);
    REQUIRE(sequence.ended);
    const ImpactLog& simulated = sequence.impacts.Impacts();
    REQUIRE(simulated.size() > 5);
    ImpactMapOptions options;
    options.simulation = coarse;
    const ImpactMap map(s, options);
    const ImpactView first = simulated.front();
    const MapResult r = map.Apply(map.ToEta(first.t, first.x, first.v), 200, false);
    CHECK(r.termination == Termination::kSticking);
    REQUIRE(r.impacts_done == static_cast<int>(simulated.size()) - 1);
    for (int k = 0; k < r.impacts_done; ++k) {
      CHECK_THAT(r.path[k](map.TimeIndex()), Catch::Matchers::WithinAbs(simulated[k + 1].t, 1e-9));
    }
  }
  SECTION("bad impact states and p") {
    const ImpactMap map(PaperSystem(0.9));
    Eigen::VectorXd eta(4);
    eta << 0.0, 0.0, 0.0, -0.1;  // moving away from the stop
    CHECK_THROWS_AS(map.Apply(eta, 1, false), InvalidInput);
    eta(3) = std::nan("");
    CHECK_THROWS_AS(map.Apply(eta, 1, false), InvalidInput);
    CHECK_THROWS_AS(map.Apply(Eigen::VectorXd::Ones(3), 1, false), InvalidInput);
    CHECK_THROWS_AS(map.Apply(Eigen::VectorXd::Ones(4), 0, false), InvalidInput);
  }
}

TEST_CASE("a mode that holds a mass is decomposed only where one is held", "[impact_map]") {
  // Undamped, forced at the natural frequency sqrt(2) of mass 1 while the
  // stop holds mass 2: that mode has no bounded steady response, the free
  // one (frequencies 0.618, 1.618) has.
  System s = PaperSystem(std::sqrt(2.0));
  SetParameter(s, "c", 0.0);
  SECTION("the simulator, which may hold the mass, refuses the system at once") {
    CHECK_THROWS_WITH(Simulator(s), Catch::Contains("stuck subsystem (mass 2 held at the stop)"));
  }
  SECTION("the impact map, which holds no mass, follows the impacts CVODE finds") {
    const reference::ReferenceRun cvode =
        reference::CvodeImpacts(s, RestState(s).x, RestState(s).v, 0.0, 60.0, {});
    REQUIRE(cvode.impacts.size() >= 4);
    // The state just before the first impact, by CVODE's smooth flow.
    Eigen::VectorXd x = RestState(s).x, v = RestState(s).v;
    reference::CvodeLinearFlow(s.mass, s.damping, s.stiffness, s.forcing, Eigen::VectorXd::Zero(2),
                               s.omega, 0.0, x, v, cvode.impacts[0].t);
    const ImpactMap map(s);
    const MapResult r = map.Apply(map.ToEta(cvode.impacts[0].t, x, v), 3, false);
    REQUIRE(r.termination == Termination::kCompleted);
    for (int k = 0; k < 3; ++k) {
      // CVODE's global error after 60 time units: ~1e-10 (cvode_impacts.hpp).
      CHECK_THAT(r.path[k](map.TimeIndex()), WithinAbs(cvode.impacts[k + 1].t, 1e-8));
      CHECK_THAT(map.Speed(r.path[k], 0), WithinAbs(cvode.impacts[k + 1].velocity, 1e-8));
    }
  }
}
