// What a grazing does (analysis/grazing_prediction.hpp): the normal form's
// local attractors against the closed-form windows of the one-dimensional
// square-root map, and the paper's two grazings of Fig. 5, where no
// attractor stays near the grazing orbit, against the simulator a hair past
// them.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <utility>
#include <vector>

#include "impactkit/analysis/grazing_prediction.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/analysis/swept_diagram.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/hybrid/stop.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "seeded_orbit.hpp"
#include "sticking_grazing.hpp"
#include "system_at.hpp"

using namespace impactkit;

namespace {

/// The normal form whose penetration obeys y ↦ λ y + (1 − λ) μ − √y past
/// contact (κ = −1): one dimension, A = λ, n = 1, W = −1/λ, at a grazing
/// orbit with one impact per period.
GrazingNormalForm SquareRootForm(double lambda) {
  GrazingNormalForm form;
  form.parameter = "omega";
  form.parameter_value = 0.5;
  form.p = 1;
  form.q = 1;
  form.linear = Eigen::MatrixXd::Constant(1, 1, lambda);
  form.eigenvalues = Eigen::VectorXcd::Constant(1, lambda);
  form.normal = Eigen::RowVectorXd::Ones(1);
  form.root = Eigen::VectorXd::Constant(1, -1.0 / lambda);
  form.unfolding = 1.0;
  form.reduced = SquareRootReduction{lambda, -1.0, 1.0, 1.0, 0.0};
  return form;
}

/// c_n = (1 − λⁿ) / (1 − λ).
double C(double lambda, int n) { return (1.0 - std::pow(lambda, n)) / (1.0 - lambda); }

/// The window of ν = (1 − λ) μ where the maximal orbit of period n (one
/// contact, n − 1 iterations without) of x ↦ λ x + ν − √x [x > 0] is stable,
/// derived in closed form: with s = √x₀ on the orbit, s² + λⁿ⁻¹ s = c_n ν;
/// its multiplier −λⁿ⁻¹ / (2 s) is −1 at ν = 3 λ^{2n−2} / (4 c_n) (below:
/// unstable), and its last iteration without contact reaches the boundary at
/// ν = λ^{2n−4} / c_{n−1}² (above: not that orbit).
std::pair<double, double> StableWindow(double lambda, int n) {
  return {3.0 * std::pow(lambda, 2 * n - 2) / (4.0 * C(lambda, n)),
          std::pow(lambda, 2 * n - 4) / (C(lambda, n - 1) * C(lambda, n - 1))};
}

/// The grazing orbit's touch drawn back from its stop by 1e-9, run at
/// `past` for `periods` forcing periods.
HybridState RunFromTouch(const System& past, const GrazingNormalForm& form, int periods) {
  const int n = past.Dof();
  const Stop stop(past, form.stop);
  HybridState state;
  state.t = form.time;
  state.x = form.touch.head(n);
  state.v = form.touch.tail(n);
  state.x(stop.Dof()) = stop.Position() - stop.Sign() * 1e-9;
  Simulator(past, SimulationOptions{}).Run(state, form.time + periods * past.ForcingPeriod());
  return state;
}

/// The system's steady motion a distance `distance` from the grazing
/// `form`'s parameter value, simulated from the grazing orbit.
std::string SimulatedMotion(const System& system, const GrazingNormalForm& form, double distance) {
  const System past = testing::At(system, form.parameter, form.parameter_value + distance);
  HybridState state = RunFromTouch(past, form, 1000);
  const double period = past.ForcingPeriod();
  const Simulator simulator(past, SimulationOptions{});
  SteadyWindowRecorder window(period);
  simulator.Run(state, form.time + 1200 * period, window);
  const Classification c =
      ClassifyMotion(past, window.Strobe(), window.Impacts(), window.ChatterEnds());
  return MotionLabel(c.kind, c.period.p, c.period.q);
}

/// The paper's P(p, q) branch seeded at `system`'s omega, followed down to
/// its grazing, with its grazings predicted.
Branch PredictedBranchDown(const System& system, int p, int q) {
  ContinuationOptions options;
  options.from = system.omega;
  options.to = 0.8;
  options.direction = ContinuationDirection::kDecreasing;
  options.orbit.p = p;
  options.orbit.q = q;
  Branch branch = ContinueBranch({system, testing::SeededOrbit(system, p, q), {}}, options);
  PredictGrazings(system, &branch);
  REQUIRE(branch.special_points.back().normal_form.has_value());
  return branch;
}

/// The largest difference between the impact speeds of `orbit` and of
/// `grazing` (each sorted by stop and speed; `grazing`'s impact
/// `vanishing`, if any, left out), relative to the largest of `grazing`'s,
/// from Newton's orbits: what GrazingSweeps::family_speed_gap measures on
/// the sweep.
double OrbitSpeedGap(const PeriodicOrbit& orbit, const PeriodicOrbit& grazing, int vanishing = -1) {
  auto speeds = [](const PeriodicOrbit& o, int skip) {
    std::vector<std::pair<int, double>> s;
    for (std::size_t k = 0; k < o.impacts.size(); ++k) {
      if (static_cast<int>(k) != skip) s.emplace_back(o.impacts[k].stop, o.impacts[k].velocity);
    }
    std::sort(s.begin(), s.end());
    return s;
  };
  const auto a = speeds(orbit, -1), b = speeds(grazing, vanishing);
  REQUIRE(a.size() == b.size());
  double gap = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    REQUIRE(a[k].first == b[k].first);
    gap = std::max(gap, std::abs(a[k].second - b[k].second));
    scale = std::max(scale, b[k].second);
  }
  return gap / scale;
}

/// The orbit P(p, q) of `system` by Newton from `eta`.
PeriodicOrbit NewtonOrbit(const System& system, const Eigen::VectorXd& eta, int p, int q,
                          int stop = 0) {
  OrbitOptions options;
  options.p = p;
  options.q = q;
  options.map.stop = stop;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, eta, options, &orbit).termination == Termination::kConverged);
  return orbit;
}

}  // namespace

TEST_CASE(
    "prediction: the 1-D square-root map's period-adding windows (lambda = 0.3) are the normal "
    "form's attractors, P(n+1, n) inside the closed-form window of period n",
    "[grazing][prediction]") {
  const double lambda = 0.3;
  const GrazingNormalForm form = SquareRootForm(lambda);
  for (int n = 3; n <= 6; ++n) {
    const auto [low, high] = StableWindow(lambda, n);
    REQUIRE(low < high);
    const double nu = std::sqrt(low * high);  // the window's geometric middle
    GrazingPredictionOptions options;
    options.distances = {nu / (1.0 - lambda), 100.0 * nu / (1.0 - lambda)};
    const GrazingPrediction prediction = PredictGrazing(PaperSystem(0.5), form, options);
    INFO("n = " << n << ", nu = " << nu);
    CHECK(prediction.local);
    CHECK(prediction.attractors.front().period == n);
    CHECK(prediction.attractors.front().contacts == 1);
    CHECK(prediction.motion == "P(" + std::to_string(n + 1) + "," + std::to_string(n) + ")");
    CHECK(prediction.one_dimensional == "period_adding_chaos");
    CHECK(prediction.side == 1.0);
  }
}

TEST_CASE(
    "prediction: for lambda = 0.8 the normal form's attractor is chaotic (no maximal orbit is "
    "stable past lambda = 2/3), and it shrinks with mu",
    "[grazing][prediction]") {
  const GrazingPrediction prediction = PredictGrazing(PaperSystem(0.5), SquareRootForm(0.8));
  CHECK(prediction.local);
  CHECK(prediction.motion == "chaotic");
  CHECK(prediction.scenario == "chaos");
  CHECK(prediction.one_dimensional == "chaos");
  CHECK(prediction.attractors.front().lyapunov > 0.01);
}

TEST_CASE(
    "prediction: attractors whose penetration m distance exceeds the form's reach are flagged, "
    "and the description says so where the nearest is",
    "[grazing][prediction]") {
  GrazingNormalForm form = SquareRootForm(0.3);
  GrazingPredictionOptions options;
  options.distances = {1e-8, 1e-6, 1e-4};
  form.reach = 1e-6;  // the unfolding is 1: penetrations equal distances
  GrazingPrediction prediction = PredictGrazing(PaperSystem(0.5), form, options);
  REQUIRE(prediction.attractors.size() == 3);
  CHECK(prediction.attractors[0].within_reach);
  CHECK(prediction.attractors[1].within_reach);
  CHECK_FALSE(prediction.attractors[2].within_reach);
  CHECK_THAT(prediction.Describe(), !Catch::Contains("reach"));
  form.reach = 1e-9;
  prediction = PredictGrazing(PaperSystem(0.5), form, options);
  CHECK_FALSE(prediction.attractors[0].within_reach);
  REQUIRE(prediction.local);
  CHECK_THAT(prediction.Describe(), Catch::Contains("beyond the normal form's reach"));
}

TEST_CASE("prediction: a normal form without its eigenvalues is refused with a clear error",
          "[grazing][prediction]") {
  GrazingNormalForm form = SquareRootForm(0.5);
  form.eigenvalues.resize(0);
  CHECK_THROWS_WITH(PredictGrazing(PaperSystem(0.5), form),
                    Catch::Contains("needs a whole normal form"));
}

TEST_CASE(
    "prediction: the paper's grazings of Fig. 5 keep no attractor near them: the motion jumps to "
    "P(3,2) below omega = 0.8564 and to P(2,1) below 0.8322, as the simulator finds 1e-6 past",
    "[grazing][prediction]") {
  struct Case {
    double from;
    int p, q;
    const char* jump;
  };
  for (const Case& c : {Case{0.9, 1, 1, "P(3,2)"}, Case{0.84, 3, 2, "P(2,1)"}}) {
    const System system = PaperSystem(c.from);
    const Branch branch = PredictedBranchDown(system, c.p, c.q);
    const SpecialPoint& graze = branch.special_points.back();
    REQUIRE(graze.normal_form.has_value());
    REQUIRE(graze.normal_form->prediction.has_value());
    const GrazingPrediction& prediction = *graze.normal_form->prediction;
    INFO(prediction.Describe());
    CHECK(prediction.side == -1.0);  // the orbit penetrates as omega falls
    CHECK_FALSE(prediction.local);
    CHECK(prediction.scenario == "jump");
    CHECK(prediction.motion == c.jump);
    const System at = testing::At(system, "omega", graze.parameter);
    CHECK(SimulatedMotion(at, *graze.normal_form, -1e-6) == c.jump);
  }
}

TEST_CASE(
    "prediction: sweeps through the paper's grazings of Fig. 5 both ways find the predicted jump "
    "just past each, and hysteresis: the sweep back keeps the other motion",
    "[grazing][prediction]") {
  struct Case {
    double from;
    int p, q;
  };
  for (const Case& c : {Case{0.9, 1, 1}, Case{0.84, 3, 2}}) {
    const System system = PaperSystem(c.from);
    const Branch branch = PredictedBranchDown(system, c.p, c.q);
    const GrazingNormalForm& form = *branch.special_points.back().normal_form;
    const GrazingSweeps sweeps =
        SweepThroughGrazing(testing::At(system, "omega", form.parameter_value), form);
    std::string table;
    for (std::size_t k = 0; k < sweeps.values.size(); ++k) {
      table +=
          std::to_string(sweeps.values[k]) + " " + sweeps.toward[k] + " " + sweeps.back[k] + "\n";
    }
    INFO(table);
    CHECK(sweeps.agrees);
    CHECK(sweeps.past == form.prediction->motion);
    CHECK(sweeps.hysteresis);
    // Before the grazing the sweep towards it is on the grazing orbit's family
    // (past lies at decreasing omega: before is the sweep's top).
    CHECK(sweeps.past_distance < 0);
    CHECK(sweeps.toward.back() == "P(" + std::to_string(c.p) + "," + std::to_string(c.q) + ")");
    // It follows the grazing orbit's family: its impact speeds at the last
    // value before the grazing are those of Newton's orbit there, so their
    // distance to the grazing orbit's is that orbit's.
    CHECK(sweeps.follows);
    REQUIRE(sweeps.family_speed_gap.has_value());
    const SpecialPoint& graze = branch.special_points.back();
    const double last_before = sweeps.values[sweeps.values.size() / 2 + 1];
    const PeriodicOrbit family =
        NewtonOrbit(testing::At(system, "omega", last_before), graze.point.orbit.eta, c.p, c.q);
    const double expected = OrbitSpeedGap(family, graze.point.orbit);
    INFO("gap " << *sweeps.family_speed_gap << ", Newton's " << expected);
    // The sweep's speeds settle to ~1e-10; the grazing orbit's come from
    // one pass of the simulator from its touch.
    CHECK(std::abs(*sweeps.family_speed_gap - expected) < 1e-8);
    CHECK(*sweeps.family_speed_gap <= 3.0 * *sweeps.family_speed_step);
  }
}

TEST_CASE(
    "prediction: a sweep that holds a coexisting orbit of the grazing orbit's label does not "
    "follow it (the clearance's two P(8,3) at omega = 1.2884), its distance that of Newton's "
    "orbits",
    "[grazing][prediction]") {
  const System system =
      ReadSystemFile(IMPACTKIT_SOURCE_DIR "/examples/systems/clearance-1dof.toml");
  // `impactkit diagram --from 1.286 --to 1.306` on the clearance's file.
  SweptDiagramOptions options;
  options.diagram.continuation.from = 1.286;
  options.diagram.continuation.to = 1.306;
  options.sweep.steps = 481;
  options.sweep.transient_periods = 300;
  options.sweep.recorded_periods = 40;
  options.sweep.classify.period.max_q = 16;
  options.seeds.max_p = 16;
  Diagram diagram = TraceSweptDiagram(system, {}, options).diagram;
  PredictGrazings(system, &diagram);
  const std::vector<GrazingCheck> checks = CheckGrazings(system, diagram);
  const auto check = std::find_if(checks.begin(), checks.end(), [](const GrazingCheck& c) {
    return std::abs(c.parameter - 1.2883567) < 1e-6;
  });
  REQUIRE(check != checks.end());
  REQUIRE(check->grazing_orbit == "P(8,3)");
  const GrazingSweeps& sweeps = check->sweeps;
  // The label alone would pass: the sweep shows P(8,3) before the grazing.
  const std::size_t last_before = sweeps.values.size() / 2 + (check->prediction.side > 0 ? -1 : 1);
  CHECK(sweeps.toward[last_before] == "P(8,3)");
  CHECK_FALSE(sweeps.follows);
  CHECK_FALSE(sweeps.agrees);
  REQUIRE(sweeps.family_speed_gap.has_value());
  CHECK(*sweeps.family_speed_gap > 3.0 * *sweeps.family_speed_step);
  // The other P(8,3), which a simulation from rest reaches there too,
  // against the grazing orbit: both by Newton.
  const auto node = std::find_if(diagram.nodes.begin(), diagram.nodes.end(), [&](auto& n) {
    return n.normal_form && n.parameter == check->parameter;
  });
  REQUIRE(node != diagram.nodes.end());
  const System at = testing::At(system, "omega", sweeps.values[last_before]);
  const std::optional<OrbitSeed> seed = SeedFromSimulation(at);
  REQUIRE(seed.has_value());
  REQUIRE(seed->motion.p == 8);
  REQUIRE(seed->motion.q == 3);
  const PeriodicOrbit other = NewtonOrbit(at, seed->eta, 8, 3, seed->stop);
  // The node's orbit, located where its vanishing impact's speed is ~1e-4,
  // lies 5e-5 in omega from the grazing; its other speeds change ~3 per
  // unit omega (family_speed_step over the sweep's step), so it stands for
  // the grazing orbit to ~2e-4.
  const double expected = OrbitSpeedGap(other, node->point.orbit, node->vanishing_impact);
  INFO("gap " << *sweeps.family_speed_gap << ", Newton's " << expected);
  CHECK(expected > 0.03);
  CHECK(std::abs(*sweeps.family_speed_gap - expected) < 2e-4);
}

TEST_CASE("prediction: invalid prediction or sweep options are refused with a clear error",
          "[grazing][prediction]") {
  GrazingNormalForm form = SquareRootForm(0.5);
  GrazingPredictionOptions options;
  options.distances = {1e-6};
  CHECK_THROWS_WITH(PredictGrazing(PaperSystem(0.5), form, options),
                    Catch::Contains("at least two distances"));
  options.distances = {1e-4, 1e-6};
  CHECK_THROWS_WITH(PredictGrazing(PaperSystem(0.5), form, options),
                    Catch::Contains("positive and increasing"));
  GrazingSweepOptions sweeps;
  sweeps.steps = 40;
  CHECK_THROWS_WITH(SweepThroughGrazing(PaperSystem(0.5), form, sweeps),
                    Catch::Contains("an odd number of steps"));
  // A form never predicted cannot be checked.
  CHECK_THROWS_WITH(SweepThroughGrazing(PaperSystem(0.5), form),
                    Catch::Contains("predict it first"));
}

namespace {

/// The impacts at the touched stop in each of `count` forcing periods
/// centred on the touch's phase, simulated from the grazing orbit at a
/// distance `distance` past it, after 500 periods.
std::vector<int> ImpactsAtTouchedStop(const System& system, const GrazingNormalForm& form,
                                      double distance, int count) {
  const System past = testing::At(system, form.parameter, form.parameter_value + distance);
  HybridState state = RunFromTouch(past, form, 500);
  const double period = past.ForcingPeriod();
  const double first = form.time + 501 * period - 0.5 * period;
  ImpactRecorder recorder;
  Simulator(past, SimulationOptions{}).Run(state, first + count * period, recorder);
  std::vector<int> counts(static_cast<std::size_t>(count), 0);
  for (const auto& impact : recorder.Impacts()) {
    const double k = std::floor((impact.t - first) / period);
    if (impact.stop == form.stop && k >= 0 && k < count) ++counts[static_cast<std::size_t>(k)];
  }
  return counts;
}

/// paper-mass1-stop's sticking family followed down to its new contact at
/// Ω = 0.19016, its grazings predicted.
Branch PredictedStickingBranch(const System& system) {
  Branch branch = testing::StickingBranchToNewContact(system);
  PredictGrazings(system, &branch);
  REQUIRE(branch.special_points.back().normal_form.has_value());
  REQUIRE(branch.special_points.back().normal_form->prediction.has_value());
  return branch;
}

}  // namespace

TEST_CASE(
    "prediction: past a sticking family's new contact (paper-mass1-stop at omega = 0.19016) the "
    "simulator has the normal form's attractor: the new impact every other period 1e-8 past, "
    "every period 1e-6 past",
    "[grazing][prediction][sticking]") {
  // Mass 2 sticks every period while mass 1 strikes its stop three times;
  // going down in Ω a fourth turn of mass 1 touches it. The leading
  // multiplier is −0.129 and κ is small (most of the jump is forgotten
  // where mass 2 sticks), so closer than μ ~ κ² / (1 − λ)² the square-root
  // term overshoots: the new contact comes every other period.
  const System system = testing::PaperWithMass1StopFile();
  const Branch branch = PredictedStickingBranch(system);
  const SpecialPoint& graze = branch.special_points.back();
  const GrazingNormalForm& form = *graze.normal_form;
  const GrazingPrediction& prediction = *form.prediction;
  INFO(prediction.Describe());
  CHECK(prediction.local);
  const auto& impacts = graze.point.orbit.impacts;
  const int family = static_cast<int>(std::count_if(
      impacts.begin(), impacts.end(), [&](const OrbitImpact& i) { return i.stop == form.stop; }));
  REQUIRE(family == 3);
  const System at = testing::At(system, "omega", form.parameter_value);
  for (const LocalAttractor& attractor : prediction.attractors) {
    if (!attractor.within_reach) continue;
    const std::vector<int> counts = ImpactsAtTouchedStop(at, form, attractor.distance, 12);
    std::string seen;
    for (const int c : counts) seen += std::to_string(c) + " ";
    INFO("distance " << attractor.distance << ": " << attractor.motion << " with "
                     << attractor.contacts << " contact(s) in " << attractor.period
                     << " period(s); simulated impacts per period " << seen);
    REQUIRE(attractor.period >= 1);
    for (std::size_t k = 0; k < counts.size(); ++k) {
      const auto j = k % static_cast<std::size_t>(attractor.period);
      CHECK(counts[k] == counts[j]);  // the attractor's period
      CHECK((counts[k] == family || counts[k] == family + 1));
    }
    int added = 0;
    for (int k = 0; k < attractor.period; ++k)
      added += counts[static_cast<std::size_t>(k)] - family;
    CHECK(added == attractor.contacts);
  }
  CHECK(prediction.attractors[0].period == 2);
  CHECK(prediction.attractors[1].period == 1);
}

TEST_CASE(
    "prediction: sweeps through a sticking family's new contact (paper-mass1-stop at omega = "
    "0.19016) follow its family, whose impact speeds, chatter included, are Newton's orbit's",
    "[grazing][prediction][sticking]") {
  const System system = testing::PaperWithMass1StopFile();
  const Branch branch = PredictedStickingBranch(system);
  const SpecialPoint& graze = branch.special_points.back();
  const GrazingNormalForm& form = *graze.normal_form;
  const GrazingSweeps sweeps =
      SweepThroughGrazing(testing::At(system, "omega", form.parameter_value), form);
  INFO(form.prediction->Describe());
  CHECK(sweeps.follows);
  CHECK(sweeps.agrees);
  CHECK(sweeps.toward[sweeps.values.size() / 2 + 1] == "P(inf,1)");
  REQUIRE(sweeps.family_speed_gap.has_value());
  // Newton's sticking orbit at the last value before the grazing (above
  // it), against the grazing orbit: the gap the sweep's speeds show.
  const double last_before = sweeps.values[sweeps.values.size() / 2 + 1];
  OrbitOptions options;
  options.releases = 1;
  options.q = 1;
  options.release_map.stop = 1;
  PeriodicOrbit family;
  REQUIRE(
      FindOrbit(testing::At(system, "omega", last_before), graze.point.orbit.eta, options, &family)
          .termination == Termination::kConverged);
  const double expected = OrbitSpeedGap(family, graze.point.orbit);
  INFO("gap " << *sweeps.family_speed_gap << ", Newton's " << expected);
  CHECK(std::abs(*sweeps.family_speed_gap - expected) < 1e-8);
}
