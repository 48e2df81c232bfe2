// Two-parameter curves (curve.hpp): points of each curve checked by a
// one-parameter continuation at their second-parameter value, the N = 1
// curves against the closed form, codimension-two points by a fresh orbit
// solve, the defining rows' differenced gradient by Richardson
// extrapolation.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>

#include "closed_form_sdof.hpp"
#include "curve_plane.hpp"
#include "cvode_flight_top.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/model/parameters.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"

using namespace impactkit;
using testing::At;
using testing::Plane;
using testing::Start;

namespace {

/// The special point of `type` that a branch in omega through the curve
/// point finds, at the point's second parameter: its omega.
double OneParameterOmega(const System& base, const Curve& curve, const CurvePoint& point,
                         SpecialPointType type) {
  const System system = At(At(base, curve.parameter2, point.parameter2), "omega", point.parameter);
  ContinuationOptions options;
  options.from = point.parameter - 0.05;
  options.to = point.parameter + 0.05;
  options.direction = ContinuationDirection::kBoth;
  options.orbit.p = curve.p;
  options.orbit.q = curve.q;
  // The branch starts a little inside the orbit's side of a grazing, and
  // off a fold (where Newton's Jacobian is singular) on either side.
  const double side =
      type == SpecialPointType::kGrazing || type == SpecialPointType::kFold ? 0.01 : 0.0;
  double best = 1e300;
  for (double shift : {side, -side}) {
    PeriodicOrbit orbit;
    const System start = At(system, "omega", point.parameter + shift);
    if (FindOrbit(start, point.orbit.eta, options.orbit, &orbit).termination !=
        Termination::kConverged) {
      continue;
    }
    const Branch branch = ContinueBranch({start, orbit, {}}, options);
    for (const SpecialPoint& s : branch.special_points) {
      if (s.type == type && std::abs(s.parameter - point.parameter) < std::abs(best)) {
        best = s.parameter - point.parameter;
      }
    }
  }
  return point.parameter + best;
}

/// Five points spread along the curve (its ends included).
std::vector<const CurvePoint*> Spread(const Curve& curve) {
  std::vector<const CurvePoint*> points;
  for (int k = 0; k < 5; ++k) points.push_back(&curve.points[k * (curve.points.size() - 1) / 4]);
  return points;
}

}  // namespace

TEST_CASE(
    "curves: the paper's P(1,1) period-doubling and grazing curves and P(1,2)'s fold in "
    "(omega, r) match one-parameter continuation at five values of r",
    "[curve]") {
  for (const auto& [omega, type, p, q] :
       {std::tuple{1.5, SpecialPointType::kPeriodDoubling, 1, 1},
        std::tuple{1.0, SpecialPointType::kGrazing, 1, 1},
        std::tuple{2.0, SpecialPointType::kFold, 1, 2},
        std::tuple{2.0, SpecialPointType::kPeriodDoubling, 1, 2}}) {
    INFO(ToString(type) << " of P(" << p << "," << q << ")");
    const System system = PaperSystem(omega);
    const CurveStart start = Start(system, type, p, q);
    const Curve curve = ContinueCurve(start, Plane("r", 0.3, 0.95, p, q));
    CHECK(curve.begin == Termination::kParameterBound);
    CHECK(curve.end == Termination::kParameterBound);
    CHECK(curve.points.front().parameter2 == Approx(0.3).margin(1e-12));
    CHECK(curve.points.back().parameter2 == Approx(0.95).margin(1e-12));
    for (const CurvePoint* point : Spread(curve)) {
      INFO("r = " << point->parameter2);
      CHECK(std::abs(OneParameterOmega(system, curve, *point, type) - point->parameter) < 1e-8);
    }
  }
}

TEST_CASE(
    "curves: the N = 1 oscillator's P(1,1) fold and period-doubling curves in (omega, r) "
    "are the closed form's",
    "[curve]") {
  using testing::SdofParameters;
  for (const auto& [xs, omega, type] : {std::tuple{0.2, 1.5, SpecialPointType::kFold},
                                        std::tuple{0.1, 1.3, SpecialPointType::kPeriodDoubling}}) {
    INFO(ToString(type));
    const System system =
        UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), omega, xs, 0.8);
    const CurveStart start = Start(system, type, 1, 1);
    const Curve curve = ContinueCurve(start, Plane("r", 0.3, 0.95, 1, 1));
    REQUIRE(curve.points.size() >= 5);
    for (const CurvePoint* point : Spread(curve)) {
      SdofParameters p{1.0, 1.0, 0.1, 0.5, xs, point->parameter2, point->parameter};
      // The closed-form event in omega at this r, by bisection around the
      // curve's value: two P(1,1) solutions or none (fold), det(DP + I) of
      // the solution nearest the curve's orbit (period doubling).
      auto closed_form = [&](double w) {
        p.omega = w;
        const auto roots = testing::SdofP11Solutions(p);
        if (type == SpecialPointType::kFold) return roots.size() == 2 ? 1.0 : -1.0;
        REQUIRE(!roots.empty());
        const testing::SdofP11& o =
            *std::min_element(roots.begin(), roots.end(), [&](auto& a, auto& b) {
              return std::abs(a.u - point->orbit.eta(1)) < std::abs(b.u - point->orbit.eta(1));
            });
        return (testing::SdofP11Jacobian(p, o) + Eigen::Matrix2d::Identity()).determinant();
      };
      double lo = point->parameter - 1e-4, hi = point->parameter + 1e-4;
      INFO("r = " << point->parameter2);
      REQUIRE((closed_form(lo) > 0) != (closed_form(hi) > 0));
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((closed_form(mid) > 0) == (closed_form(lo) > 0) ? lo : hi) = mid;
      }
      CHECK(std::abs(point->parameter - lo) < 1e-8);
    }
  }
}

TEST_CASE(
    "curves: the paper's P(1,1) fold curve in (omega, A2) through A2 = -0.5 is a closed loop, "
    "traced once round, whose points one-parameter continuation confirms",
    "[curve]") {
  // With the second mass forced against the first, P(1,1)'s branch in
  // omega folds (at 1.0536 for A2 = -0.5); the folds form a loop in
  // omega in [0.72, 1.19], A2 in [-0.79, -0.33] (arclength 7.16 in X).
  const System system = At(PaperSystem(1.2), "A2", -0.5);
  const Curve curve =
      ContinueCurve(Start(system, SpecialPointType::kFold, 1, 1), Plane("A2", -1.5, 0.5, 1, 1));
  REQUIRE(curve.end == Termination::kClosed);
  CHECK(curve.begin == Termination::kClosed);
  REQUIRE(curve.points.size() > 20);
  const CurvePoint& start = curve.points.front();
  CHECK(curve.points.back().x == start.x);
  // Once round: no point but those at the ends comes back near the start.
  for (std::size_t k = 3; k + 3 < curve.points.size(); ++k) {
    CHECK((curve.points[k].x - start.x).norm() > 0.01);
  }
  for (const CurvePoint* point : Spread(curve)) {
    INFO("A2 = " << point->parameter2);
    CHECK(std::abs(OneParameterOmega(system, curve, *point, SpecialPointType::kFold) -
                   point->parameter) < 1e-8);
  }
}

TEST_CASE("curves: P(2,1)'s vanishing impact is followed as P(1,1)'s grazing, the same curve",
          "[curve]") {
  const System system = PaperSystem(0.6);
  const PeriodicOrbit p21 = testing::SeededOrbit(system, 2, 1);
  ContinuationOptions options;
  options.from = 0.5;
  options.to = 1.0;
  options.orbit.p = 2;
  const Branch branch = ContinueBranch({system, p21, {}}, options);
  REQUIRE(!branch.special_points.empty());
  const SpecialPoint& vanishing = branch.special_points.back();
  REQUIRE(vanishing.vanishing_impact >= 0);
  const std::optional<CurveStart> reduced = ReducedGrazingStart(system, branch, vanishing, options);
  REQUIRE(reduced.has_value());
  CHECK(reduced->special.point.orbit.p == 1);
  const Curve from_p21 = ContinueCurve(*reduced, Plane("r", 0.3, 0.95, 1, 1));
  const Curve direct = ContinueCurve(Start(PaperSystem(1.0), SpecialPointType::kGrazing, 1, 1),
                                     Plane("r", 0.3, 0.95, 1, 1));
  for (const Curve* curve : {&from_p21, &direct}) {
    REQUIRE(curve->begin == Termination::kParameterBound);
    REQUIRE(curve->end == Termination::kParameterBound);
  }
  CHECK(std::abs(from_p21.points.front().parameter - direct.points.front().parameter) < 1e-8);
  CHECK(std::abs(from_p21.points.back().parameter - direct.points.back().parameter) < 1e-8);
}

TEST_CASE(
    "curves: P(1,2)'s vanishing impact in (omega, xs) is where the closed-form "
    "non-impacting amplitude equals xs",
    "[curve]") {
  const System system = PaperSystem(2.0);
  const CurveStart start = Start(system, SpecialPointType::kGrazing, 1, 2);
  REQUIRE(start.special.vanishing_impact == 0);
  const Curve curve = ContinueCurve(start, Plane("xs", 0.0, 0.3, 1, 2));
  CHECK(curve.p == 0);
  REQUIRE(curve.points.size() >= 5);
  // |X_2| for X = (K − Ω²M + iΩC)⁻¹ A, written out for the 2 x 2 chain.
  const auto amplitude = [](double w) {
    using C = std::complex<double>;
    const C a = 2.0 - w * w + C(0, 0.2 * w), b = -1.0 - C(0, 0.1 * w);
    const C d = 1.0 - w * w + C(0, 0.1 * w);
    return std::abs(-b * 0.5 / (a * d - b * b));
  };
  for (const CurvePoint& point : curve.points) {
    INFO("xs = " << point.parameter2);
    CHECK(std::abs(amplitude(point.parameter) - point.parameter2) < 1e-10);
  }
  CHECK(CompareCurveJacobian(start, Plane("xs", 0.0, 0.3, 1, 2), curve.points[2]) < 1e-5);
}

TEST_CASE("curves: codimension-two points are recomputed by a fresh orbit solve", "[curve]") {
  // Where P(1,1)'s grazing curve in (omega, A1) meets its period doubling,
  // and where its period-doubling curve in (omega, xs) has a double -1.
  const System system = PaperSystem(1.0);
  const Curve grazing =
      ContinueCurve(Start(system, SpecialPointType::kGrazing, 1, 1), Plane("A1", 0.1, 0.6, 1, 1));
  const Curve flip = ContinueCurve(Start(PaperSystem(1.5), SpecialPointType::kPeriodDoubling, 1, 1),
                                   Plane("xs", -1.0, 0.15, 1, 1));
  int checked = 0;
  for (const Curve* curve : {&grazing, &flip}) {
    for (const Codim2Point& c : curve->codim2_points) {
      INFO(c.Describe(curve->parameter, curve->parameter2));
      const System at =
          At(At(system, curve->parameter2, c.point.parameter2), "omega", c.point.parameter);
      OrbitOptions options;
      PeriodicOrbit orbit;
      REQUIRE(FindOrbit(at, c.point.orbit.eta, options, &orbit).termination ==
              Termination::kConverged);
      const double flip_test = (orbit.jacobian + Eigen::MatrixXd::Identity(4, 4)).determinant();
      if (c.type == Codim2Type::kPeriodDoublingGrazing) {
        REQUIRE(orbit.contacts.clearance.has_value());
        CHECK(std::abs(*orbit.contacts.clearance) < 1e-8);
        CHECK(std::abs(flip_test) < 1e-8);
        ++checked;
      } else if (c.type == Codim2Type::kResonance12) {
        int near = 0;
        for (const std::complex<double>& l : orbit.multipliers) near += std::abs(l + 1.0) < 1e-4;
        CHECK(near == 2);
        CHECK(std::abs(flip_test) < 1e-8);
        ++checked;
      }
    }
  }
  CHECK(checked >= 2);
}

TEST_CASE(
    "curves: P(1,1)'s Neimark-Sacker curve in (xs, omega) has strong resonances, its 1:2 "
    "the period-doubling curve's",
    "[curve]") {
  const System system = PaperSystem(1.2);
  ContinuationOptions search;
  search.parameter = "xs";
  search.from = 0.1;
  search.to = 0.5;
  const std::optional<SpecialPoint> ns = LocateSpecialPoint(
      {system, testing::SeededOrbit(system, 1, 1), {}}, search, SpecialPointType::kNeimarkSacker);
  REQUIRE(ns.has_value());
  CurveOptions options = Plane("omega", 0.9, 1.7, 1, 1);
  options.parameter = "xs";
  options.from = 0.1;
  options.to = 0.5;
  options.max_points = 120;
  const Curve torus = ContinueCurve({At(system, "xs", ns->parameter), *ns}, options);
  CurveOptions flip_options = Plane("xs", 0.05, 0.39, 1, 1);
  flip_options.max_points = 200;
  const Curve flip =
      ContinueCurve(Start(PaperSystem(1.6), SpecialPointType::kPeriodDoubling, 1, 1), flip_options);

  // Each resonance recomputed from a fresh orbit: the critical multipliers.
  int found = 0;
  for (const Codim2Point& c : torus.codim2_points) {
    INFO(c.Describe(torus.parameter, torus.parameter2));
    const System at = At(At(system, "xs", c.point.parameter), "omega", c.point.parameter2);
    PeriodicOrbit orbit;
    REQUIRE(FindOrbit(at, c.point.orbit.eta, OrbitOptions{}, &orbit).termination ==
            Termination::kConverged);
    auto near = [&](std::complex<double> target) {
      int count = 0;
      for (const std::complex<double>& l : orbit.multipliers) count += std::abs(l - target) < 1e-6;
      return count;
    };
    const double third = 2.0 * std::numbers::pi / 3.0;
    switch (c.type) {
      case Codim2Type::kResonance13:
        CHECK(near(std::polar(1.0, third)) == 1);
        CHECK(near(std::polar(1.0, -third)) == 1);
        ++found;
        break;
      case Codim2Type::kResonance14:
        CHECK(near({0.0, 1.0}) == 1);
        CHECK(near({0.0, -1.0}) == 1);
        ++found;
        break;
      case Codim2Type::kResonance11:
      case Codim2Type::kResonance12: {
        const double sign = c.type == Codim2Type::kResonance11 ? 1.0 : -1.0;
        const Eigen::MatrixXd a = orbit.jacobian - sign * Eigen::MatrixXd::Identity(4, 4);
        // A double multiplier ±1: D P ∓ I singular, of rank 3 (a Jordan pair).
        CHECK(std::abs(a.determinant()) < 1e-8);
        ++found;
        break;
      }
      default:
        break;
    }
  }
  CHECK(found >= 4);
  // The 1:2 point where the NS curve meets the period-doubling curve, found
  // from both curves.
  const auto resonance12 = [](const Curve& curve, const std::string& xs, double near_xs) {
    for (const Codim2Point& c : curve.codim2_points) {
      const double value = xs == curve.parameter ? c.point.parameter : c.point.parameter2;
      if (c.type == Codim2Type::kResonance12 && std::abs(value - near_xs) < 1e-3) return &c;
    }
    return static_cast<const Codim2Point*>(nullptr);
  };
  const Codim2Point* on_torus = resonance12(torus, "xs", 0.3843);
  const Codim2Point* on_flip = resonance12(flip, "xs", 0.3843);
  REQUIRE(on_torus != nullptr);
  REQUIRE(on_flip != nullptr);
  CHECK(std::abs(on_torus->point.parameter - on_flip->point.parameter2) < 1e-8);
  CHECK(std::abs(on_torus->point.parameter2 - on_flip->point.parameter) < 1e-8);
}

TEST_CASE(
    "curves: P(1,1)'s grazing curve in (omega, xs) ends at a double grazing, both maxima of "
    "its flight at the stop by CVODE",
    "[curve]") {
  // Along the curve the flight's own touch is held at the stop; towards low
  // omega a second maximum of the same flight rises to it. Beyond, the map
  // takes an extra impact: the curve ends there, a located codimension-two
  // point (it used to end with corrector_failed).
  const System system = PaperSystem(1.0);
  CurveOptions options = Plane("xs", -1.0, 1.0, 1, 1);
  options.from = 0.1;
  const Curve curve = ContinueCurve(Start(system, SpecialPointType::kGrazing, 1, 1), options);
  REQUIRE(!curve.codim2_points.empty());
  const Codim2Point& corner = curve.codim2_points.back();
  REQUIRE(corner.type == Codim2Type::kDoubleGrazing);
  CHECK(curve.end == Termination::kGrazing);
  CHECK(corner.point.parameter == Approx(0.47956).margin(1e-4));
  CHECK(corner.point.parameter2 == Approx(0.31957).margin(1e-4));
  // Recomputed: a fresh orbit at the corner, and CVODE over its one flight
  // (from the rebound to the next impact) has two interior maxima, each
  // within 1e-8 of the stop.
  const System at = At(At(system, "xs", corner.point.parameter2), "omega", corner.point.parameter);
  OrbitOptions orbit_options;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(at, corner.point.orbit.eta, orbit_options, &orbit).termination ==
          Termination::kConverged);
  const ImpactMap map(at);
  HybridState rebound = map.ToState(orbit.eta);
  rebound.v(1) *= -at.stops[0].restitution;
  const std::vector<double> tops =
      testing::CvodeFlightTops(at, rebound.t, rebound.x, rebound.v, rebound.t + at.ForcingPeriod());
  int at_stop = 0;
  for (double top : tops) at_stop += std::abs(at.stops[0].position - top) < 1e-8;
  CHECK(at_stop == 2);
}

TEST_CASE(
    "curves: P(2,1)'s period-doubling curve in (omega, r) meets a fold at a fold-flip point, "
    "recomputed by a fresh orbit solve",
    "[curve]") {
  const Curve flip = ContinueCurve(Start(PaperSystem(0.8), SpecialPointType::kPeriodDoubling, 2, 1),
                                   Plane("r", 0.45, 1.0, 2, 1));
  const auto corner =
      std::find_if(flip.codim2_points.begin(), flip.codim2_points.end(),
                   [](const Codim2Point& c) { return c.type == Codim2Type::kFoldFlip; });
  REQUIRE(corner != flip.codim2_points.end());
  CHECK(corner->point.parameter == Approx(0.87292).margin(1e-4));
  CHECK(corner->point.parameter2 == Approx(0.48506).margin(1e-4));
  // A fresh P(2,1) at the point has the multipliers +1 and -1 at once.
  const System at =
      At(At(PaperSystem(0.8), "r", corner->point.parameter2), "omega", corner->point.parameter);
  OrbitOptions options;
  options.p = 2;
  options.q = 1;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(at, corner->point.orbit.eta, options, &orbit).termination ==
          Termination::kConverged);
  double plus = 1e300, minus = 1e300;
  for (const std::complex<double>& l : orbit.multipliers) {
    plus = std::min(plus, std::abs(l - 1.0));
    minus = std::min(minus, std::abs(l + 1.0));
  }
  CHECK(plus < 1e-6);
  CHECK(minus < 1e-6);
}

TEST_CASE("curves: the defining rows' differenced gradient agrees with Richardson extrapolation",
          "[curve]") {
  for (SpecialPointType type : {SpecialPointType::kGrazing, SpecialPointType::kPeriodDoubling}) {
    INFO(ToString(type));
    const CurveStart start =
        Start(PaperSystem(type == SpecialPointType::kGrazing ? 1.0 : 1.5), type, 1, 1);
    CurveOptions options = Plane("r", 0.6, 0.8, 1, 1);
    const Curve curve = ContinueCurve(start, options);
    REQUIRE(curve.points.size() >= 3);
    CHECK(CompareCurveJacobian(start, options, curve.points[curve.points.size() / 2]) < 1e-5);
  }
}

TEST_CASE("curves: a bound at the end of the parameter's range (r = 1) is reached", "[curve]") {
  const System system =
      UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), 1.5, 0.2, 0.8);
  const Curve curve =
      ContinueCurve(Start(system, SpecialPointType::kFold, 1, 1), Plane("r", 0.05, 1.0, 1, 1));
  CHECK(curve.end == Termination::kParameterBound);
  CHECK(curve.points.back().parameter2 == 1.0);
}

TEST_CASE("curves: bad input is rejected with a clear error", "[curve]") {
  const CurveStart start = Start(PaperSystem(1.5), SpecialPointType::kPeriodDoubling, 1, 1);
  CurveOptions same = Plane("omega", 0.5, 3.0, 1, 1);
  CHECK_THROWS_WITH(ContinueCurve(start, same), Catch::Contains("must differ"));
  CHECK_THROWS_WITH(ContinueCurve(start, Plane("n", 1, 3, 1, 1)),
                    Catch::Contains("cannot be continued"));
  CHECK_THROWS_WITH(ContinueCurve(start, Plane("r", 0.8, 0.95, 1, 1)),
                    Catch::Contains("outside the bounds"));
  CurveStart sticking = start;
  sticking.special.type = SpecialPointType::kSticking;
  CHECK_THROWS_WITH(ContinueCurve(sticking, Plane("r", 0.3, 0.95, 1, 1)),
                    Catch::Contains("no two-parameter curve"));
  std::string error;
  CHECK(CurveOptions{}.IsValid(&error) == false);  // the default bounds are empty: [0, 0]
  CHECK_THAT(error, Catch::Contains("two finite, different ends"));
}
