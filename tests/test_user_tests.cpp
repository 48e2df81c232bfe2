// The user's test functions (ContinuationOptions and CurveOptions::
// user_tests): a quantity of the orbit crossing a level, located along
// branches, in diagrams and along two-parameter curves without a line of
// their code knowing the test, and checked against a fresh orbit solve at
// the located value.
#include <catch2/catch.hpp>
#include <cmath>

#include "curve_plane.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/continuation/diagram.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"

using namespace impactkit;

namespace {

/// The contact mass's excursion, max − min of x_c over the orbit, minus a
/// level: zero where the excursion crosses it.
UserTest ExcursionAbove(double level) {
  return {"excursion",
          [level](const PeriodicOrbit& orbit) { return orbit.contacts.Range() - level; }};
}

ContinuationOptions Along(double lower, double upper, const UserTest& test) {
  ContinuationOptions options;
  options.from = lower;
  options.to = upper;
  options.direction = ContinuationDirection::kBoth;
  options.user_tests = {test};
  return options;
}

/// The excursion of the orbit a fresh Newton solve finds from `eta` in
/// `system` (the paper's P(1,1)).
double FreshExcursion(const System& system, const Eigen::VectorXd& eta) {
  OrbitOptions options;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, eta, options, &orbit).termination == Termination::kConverged);
  return orbit.contacts.Range();
}

double FreshExcursion(double omega, const Eigen::VectorXd& eta) {
  return FreshExcursion(PaperSystem(omega), eta);
}

}  // namespace

TEST_CASE("a user test's zero is located along a branch where a fresh solve has it",
          "[continuation][user_test]") {
  const System system = PaperSystem(1.65);
  const PeriodicOrbit start = testing::SeededOrbit(system, 1, 1);
  // A level between the excursions at the branch's two ends, so that the
  // branch must cross it.
  const Branch plain = ContinueBranch({system, start, {}}, Along(1.5, 1.8, ExcursionAbove(0)));
  const double level = 0.5 * (plain.points.front().orbit.contacts.Range() +
                              plain.points.back().orbit.contacts.Range());
  const Branch branch = ContinueBranch({system, start, {}}, Along(1.5, 1.8, ExcursionAbove(level)));
  int found = 0;
  for (const SpecialPoint& s : branch.special_points) {
    if (s.type != SpecialPointType::kUserTest) continue;
    ++found;
    CHECK(s.user_test == "excursion");
    CHECK(std::abs(s.monitor) < 1e-10);
    // Independently: the orbit solved afresh at the located omega.
    CHECK_THAT(FreshExcursion(s.parameter, s.point.orbit.eta),
               Catch::Matchers::WithinAbs(level, 1e-9));
    CHECK_THAT(s.Describe("omega"), Catch::Matchers::Contains("user test 'excursion'"));
  }
  CHECK(found >= 1);
  // The bifurcations are the same with and without the user's test.
  auto count = [](const Branch& b, SpecialPointType type) {
    return std::count_if(b.special_points.begin(), b.special_points.end(),
                         [type](const SpecialPoint& s) { return s.type == type; });
  };
  CHECK(count(branch, SpecialPointType::kPeriodDoubling) ==
        count(plain, SpecialPointType::kPeriodDoubling));
}

TEST_CASE("a user test reaches every branch of a diagram", "[diagram][user_test]") {
  const System system = PaperSystem(1.65);
  DiagramOptions options;
  options.continuation = Along(1.5, 1.8, ExcursionAbove(0.0));
  options.max_depth = 1;
  // The level the main branch crosses, as above.
  const Branch main =
      ContinueBranch({system, testing::SeededOrbit(system, 1, 1), {}}, options.continuation);
  const double level = 0.5 * (main.points.front().orbit.contacts.Range() +
                              main.points.back().orbit.contacts.Range());
  options.continuation.user_tests = {ExcursionAbove(level)};
  const Diagram diagram =
      TraceDiagram({{system, testing::SeededOrbit(system, 1, 1), "P(1,1) at 1.65"}}, options);
  int found = 0;
  for (const DiagramNode& node : diagram.nodes) {
    if (node.kind != DiagramNodeKind::kSpecialPoint ||
        node.special != SpecialPointType::kUserTest) {
      continue;
    }
    ++found;
    CHECK(node.user_test == "excursion");
    CHECK(node.Name() == "user_test");
    CHECK_THAT(FreshExcursion(node.parameter, node.point.orbit.eta),
               Catch::Matchers::WithinAbs(level, 1e-9));
  }
  CHECK(found >= 1);
}

TEST_CASE("a user test's zero is a codimension-two point along a curve", "[curve][user_test]") {
  // The period-doubling curve of the paper's P(1,1) in (omega, r), and a
  // level of the excursion between its values at the curve's two ends.
  const System system = PaperSystem(1.5);
  const CurveStart start = testing::Start(system, SpecialPointType::kPeriodDoubling, 1, 1);
  CurveOptions options = testing::Plane("r", 0.3, 0.95, 1, 1);
  const Curve plain = ContinueCurve(start, options);
  const double level = 0.5 * (plain.points.front().orbit.contacts.Range() +
                              plain.points.back().orbit.contacts.Range());
  options.user_tests = {ExcursionAbove(level)};
  const Curve curve = ContinueCurve(start, options);
  int found = 0;
  for (const Codim2Point& point : curve.codim2_points) {
    if (point.type != Codim2Type::kUserTest) continue;
    ++found;
    CHECK(point.user_test == "excursion");
    CHECK(point.second_residual < 1e-10);
    const System at = testing::At(PaperSystem(point.point.parameter), "r", point.point.parameter2);
    CHECK_THAT(FreshExcursion(at, point.point.orbit.eta), Catch::Matchers::WithinAbs(level, 1e-9));
    CHECK_THAT(point.Describe("omega", "r"), Catch::Matchers::Contains("user_test 'excursion'"));
  }
  CHECK(found >= 1);
}

TEST_CASE("user tests without a name, a function or with one name twice are refused",
          "[continuation][user_test]") {
  ContinuationOptions options;
  options.from = 1.5;
  options.to = 1.8;
  std::string error;
  options.user_tests = {{"", [](const PeriodicOrbit&) { return 0.0; }}};
  CHECK_FALSE(options.IsValid(&error));
  CHECK_THAT(error, Catch::Matchers::Contains("needs a name and a value function"));
  options.user_tests = {{"a", nullptr}};
  CHECK_FALSE(options.IsValid(&error));
  options.user_tests = {ExcursionAbove(0.1), ExcursionAbove(0.2)};
  CHECK_FALSE(options.IsValid(&error));
  CHECK_THAT(error, Catch::Matchers::Contains("two user tests are named 'excursion'"));
  CurveOptions curve = testing::Plane("r", 0.3, 0.95, 1, 1);
  curve.user_tests = options.user_tests;
  CHECK_FALSE(curve.IsValid(&error));
  CHECK_THAT(error, Catch::Matchers::Contains("two user tests are named 'excursion'"));
}
