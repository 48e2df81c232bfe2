// The branch network (continuation/diagram.hpp) and the swept diagram
// (analysis/swept_diagram.hpp): every node recomputed from its located
// point (fresh FindOrbit multipliers, CVODE clearances and arrival depths), the graph's shape
// (both ends of each edge are nodes, no branch traced twice, a repeated
// orbit followed as its primitive), the N = 1 oscillator's P(1,1) nodes
// against its closed form, and sweep windows seeding the isolated P(3,2)
// branch of the paper's system.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <cstdio>
#include <optional>
#include <set>
#include <utility>

#include "closed_form_sdof.hpp"
#include "cvode_flight_top.hpp"
#include "cvode_impacts.hpp"
#include "impactkit/analysis/swept_diagram.hpp"
#include "impactkit/continuation/diagram.hpp"
#include "impactkit/model/parameters.hpp"
#include "recomputed_special_point.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"

using namespace impactkit;
using testing::At;

namespace {

DiagramOptions Options(double lower, double upper, int max_depth) {
  DiagramOptions options;
  options.continuation.from = lower;
  options.continuation.to = upper;
  options.max_depth = max_depth;
  return options;
}

/// A swept diagram's options: `diagram`, seeded by a sweep of `steps`
/// values (300 transient and `recorded` recorded periods each, periods up
/// to `max_q`).
SweptDiagramOptions Swept(const DiagramOptions& diagram, int steps, int recorded, int max_q) {
  SweptDiagramOptions options;
  options.diagram = diagram;
  options.sweep.steps = steps;
  options.sweep.transient_periods = 300;
  options.sweep.recorded_periods = recorded;
  options.sweep.classify.period.max_q = max_q;
  return options;
}

/// The multiplier nearest `target` of a fresh FindOrbit from the node's
/// located point.
std::complex<double> RecomputedMultiplier(const System& base, const Diagram& diagram,
                                          const DiagramNode& node, std::complex<double> target) {
  return testing::RecomputedMultiplier(At(base, diagram.parameter, node.point.parameter), node.p,
                                       node.q, node.point.orbit.eta, target);
}

/// det(D P + I) of a fresh FindOrbit of the node's orbit at μ: its sign is
/// (−1)^(real multipliers below −1), a complex pair adding |λ + 1|² > 0.
double FreshPeriodDoublingTest(const System& base, const Diagram& diagram, const DiagramNode& node,
                               double mu) {
  const PeriodicOrbit orbit = testing::RecomputedOrbit(At(base, diagram.parameter, mu), node.p,
                                                       node.q, node.point.orbit.eta);
  return (orbit.multipliers.array() + 1.0).prod().real();
}

/// The period-doubling node recomputed by fresh solves: the multiplier at
/// its μ within 1e-6 of −1, or, where the multiplier is too steep in μ for
/// that, det(D P + I) changing sign between μ − 1e-9 and μ + 1e-9. The
/// whole diagram's P(19,16) at Ω = 1.7106918903 (2.3e-8 from its fold) has its
/// multiplier move by 9.4e7 per unit of Ω, so a fresh solve's rounding
/// moves it by 1.4e-5 at the node; on P(20,16) at 1.7070738080 the
/// multipliers −1 and −0.63 meet and leave the real axis within 1e-9.
void CheckPeriodDoublingRecomputed(const System& system, const Diagram& diagram,
                                   const DiagramNode& node) {
  const std::complex<double> at = RecomputedMultiplier(system, diagram, node, -1.0);
  if (std::abs(at + 1.0) < 1e-6) return;
  constexpr double kReach = 1e-9;
  const double mu = node.point.parameter;
  const double below = FreshPeriodDoublingTest(system, diagram, node, mu - kReach);
  const double above = FreshPeriodDoublingTest(system, diagram, node, mu + kReach);
  INFO("multiplier " << at << "; det(D P + I) " << below << " and " << above << " at ±" << kReach);
  CHECK(below * above < 0.0);
}

/// The fold node solved again by its own regular defining system
/// (recomputed_special_point.hpp) lands within 1e-8 of the located value
/// and 1e-7 of its orbit, with its multiplier within 1e-6 of 1.
void CheckFoldRecomputed(const System& system, const Diagram& diagram, const DiagramNode& node) {
  SpecialPoint fold;
  fold.type = node.special;
  fold.point = node.point;
  fold.parameter = node.parameter;
  fold.multiplier = node.multiplier;
  const testing::RecomputedFold again = testing::RecomputeFold(system, diagram.parameter, fold);
  CHECK(std::abs(again.parameter - node.parameter) < 1e-8);
  CHECK((again.eta - node.point.orbit.eta).norm() < 1e-7 * (1.0 + node.point.orbit.eta.norm()));
  CHECK(std::abs(again.multiplier - 1.0) < 1e-6);
}

/// xs - max x_c over all free flights of the orbit through `eta` (p
/// impacts), each flight integrated by CVODE (no impact code): sampled, then
/// golden-section refined around the highest sample.
double CvodeClearance(const System& system, const Eigen::VectorXd& eta, int p) {
  const ImpactMap map(system);
  const MapResult image = map.Apply(eta, p, false);
  REQUIRE(image.termination == Termination::kCompleted);
  const int c = system.stops[0].dof, tau = map.TimeIndex();
  double clearance = 1e300;
  for (int k = 0; k < p; ++k) {
    const Eigen::VectorXd& from = k == 0 ? eta : image.path[k - 1];
    const double t0 = from(tau), duration = image.path[k](tau) - t0;
    HybridState before = map.ToState(from);
    before.v(c) *= -system.stops[0].restitution;
    const std::optional<double> top =
        testing::CvodeFlightTop(system, t0, before.x, before.v, t0 + duration);
    if (top) clearance = std::min(clearance, system.stops[0].position - *top);
  }
  return clearance;
}

/// The shallowest arrival at the stop of the orbit through `eta` (p
/// impacts): each flight integrated by CVODE (no impact code) from the
/// rebound of the impact it starts from to the map's next impact time, where
/// its depth v_c² / (2|a_c|) (a_c = x_c'' from the equations of motion) is
/// how far below the stop the motion would turn back. Returns that depth and
/// the arrival's gap xs - x_c.
std::pair<double, double> CvodeShallowestArrival(const System& system, const Eigen::VectorXd& eta,
                                                 int p) {
  const ImpactMap map(system);
  const MapResult image = map.Apply(eta, p, false);
  REQUIRE(image.termination == Termination::kCompleted);
  const int c = system.stops[0].dof, tau = map.TimeIndex();
  std::pair<double, double> shallowest{1e300, 0.0};
  for (int k = 0; k < p; ++k) {
    const Eigen::VectorXd& from = k == 0 ? eta : image.path[k - 1];
    const HybridState before = map.ToState(from);
    Eigen::VectorXd x = before.x, v = before.v;
    v(c) *= -system.stops[0].restitution;
    const double t = image.path[k](tau);
    reference::CvodeLinearFlow(system.mass, system.damping, system.stiffness, system.forcing,
                               Eigen::VectorXd::Zero(system.Dof()), system.omega, from(tau), x, v,
                               t);
    const Eigen::VectorXd force =
        system.forcing * std::cos(system.omega * t) - system.damping * v - system.stiffness * x;
    const double a = system.mass.ldlt().solve(force)(c);
    const double depth = v(c) * v(c) / (2.0 * std::abs(a));
    if (depth < shallowest.first) shallowest = {depth, system.stops[0].position - x(c)};
  }
  return shallowest;
}

/// Each fold, period doubling and Neimark–Sacker node has its critical
/// multiplier at ±1 or on the unit circle to 1e-6 when recomputed (a fresh
/// solve; a fold by its own defining system; a period doubling where its
/// multiplier is steep in μ, by its distance in μ); returns how many were
/// checked.
int CheckMultiplierNodesRecomputed(const System& system, const Diagram& diagram) {
  int checked = 0;
  for (const DiagramNode& node : diagram.nodes) {
    if (node.kind != DiagramNodeKind::kSpecialPoint) continue;
    INFO(node.Name() << " at " << node.parameter << " on P(" << node.p << "," << node.q << ")");
    switch (node.special) {
      case SpecialPointType::kFold:
        CheckFoldRecomputed(system, diagram, node);
        break;
      case SpecialPointType::kPeriodDoubling:
        CheckPeriodDoublingRecomputed(system, diagram, node);
        break;
      case SpecialPointType::kNeimarkSacker:
        CHECK(std::abs(std::abs(RecomputedMultiplier(system, diagram, node, node.multiplier)) -
                       1.0) < 1e-6);
        break;
      default:
        continue;
    }
    ++checked;
  }
  return checked;
}

/// The multiplier nodes as above; each new-contact grazing has a CVODE
/// clearance below 1e-9, and each grazing by a vanishing impact a CVODE
/// arrival at the stop (gap below 1e-9) of the depth it reports to 1e-9:
/// the grazing monitors to 1e-9. Returns how many were checked.
int CheckNodesRecomputed(const System& system, const Diagram& diagram) {
  int checked = CheckMultiplierNodesRecomputed(system, diagram);
  for (const DiagramNode& node : diagram.nodes) {
    if (node.kind != DiagramNodeKind::kSpecialPoint || node.special != SpecialPointType::kGrazing) {
      continue;
    }
    INFO(node.Name() << " at " << node.parameter << " on P(" << node.p << "," << node.q << ")");
    const System at = At(system, diagram.parameter, node.point.parameter);
    if (node.vanishing_impact >= 0) {
      // The node's orbit is at the depth it reports: below 1e-9, or for a
      // long orbit whose corrector stalled short of that, the stall's
      // depth (its parameter then comes from the reduced orbit).
      const auto [depth, gap] = CvodeShallowestArrival(at, node.point.orbit.eta, node.p);
      CHECK(std::abs(depth - node.monitor) < 1e-9);
      CHECK(node.monitor < 1e-6);
      CHECK(std::abs(gap) < 1e-9);
    } else {
      CHECK(std::abs(CvodeClearance(at, node.point.orbit.eta, node.p)) < 1e-9);
    }
    ++checked;
  }
  CHECK(checked > 0);
  return checked;
}

/// Both ends of every edge are nodes, each edge's points lie between its
/// nodes along its branch, and no two edges of different branches cover
/// the same orbits: the midpoint of one is not on the other's curve.
void CheckGraph(const Diagram& diagram) {
  const int nodes = static_cast<int>(diagram.nodes.size());
  for (const DiagramEdge& e : diagram.edges) {
    REQUIRE(e.from >= 0);
    REQUIRE(e.from < nodes);
    REQUIRE(e.to >= 0);
    REQUIRE(e.to < nodes);
    REQUIRE(e.branch < static_cast<int>(diagram.branches.size()));
    CHECK(e.first <= e.last);
    CHECK(e.last < diagram.branches[e.branch].branch.points.size());
  }
  for (const DiagramEdge& a : diagram.edges) {
    const Branch& ba = diagram.branches[a.branch].branch;
    if (a.last - a.first < 2) continue;
    const BranchPoint& mid = ba.points[(a.first + a.last) / 2];
    for (const DiagramEdge& b : diagram.edges) {
      const Branch& bb = diagram.branches[b.branch].branch;
      if (b.branch == a.branch || bb.p != ba.p || bb.q != ba.q) continue;
      // The nearest point of b in (parameter, sorted impact speeds).
      double nearest = 1e300;
      for (std::size_t i = b.first; i <= b.last; ++i) {
        std::vector<double> sa, sb;
        for (const OrbitImpact& x : mid.orbit.impacts) sa.push_back(x.velocity);
        for (const OrbitImpact& x : bb.points[i].orbit.impacts) sb.push_back(x.velocity);
        std::sort(sa.begin(), sa.end());
        std::sort(sb.begin(), sb.end());
        double d = std::abs(mid.parameter - bb.points[i].parameter);
        for (std::size_t k = 0; k < sa.size(); ++k) d = std::max(d, std::abs(sa[k] - sb[k]));
        nearest = std::min(nearest, d);
      }
      INFO("branches " << a.branch << " and " << b.branch << ", P(" << ba.p << "," << ba.q
                       << ") at " << mid.parameter);
      CHECK(nearest > 1e-6);
    }
  }
}

/// The P(1,1) branch's special points of the N = 1 oscillator, in closed
/// form: where u > 0 roots' flip multiplier is -1 (bisection on the
/// closed-form Jacobian) and where the steady amplitude equals xs.
double ClosedFormPeriodDoubling(testing::SdofParameters p, const DiagramNode& node) {
  // The root nearest the node's impact speed, bracketed around its Ω.
  double lo = node.parameter - 1e-3, hi = node.parameter + 1e-3;
  auto g = [&](double w) {
    p.omega = w;
    const auto roots = testing::SdofP11Solutions(p);
    REQUIRE(!roots.empty());
    const testing::SdofP11& o =
        *std::min_element(roots.begin(), roots.end(), [&](auto& a, auto& b) {
          return std::abs(a.u - node.point.orbit.eta(1)) < std::abs(b.u - node.point.orbit.eta(1));
        });
    return (testing::SdofP11Jacobian(p, o) + Eigen::Matrix2d::Identity()).determinant();
  };
  REQUIRE((g(lo) > 0) != (g(hi) > 0));
  for (int k = 0; k < 60; ++k)
    ((g(0.5 * (lo + hi)) > 0) == (g(lo) > 0) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

}  // namespace

TEST_CASE("diagram: the N = 1 oscillator's network from one P(1,1) seed matches the closed form",
          "[diagram]") {
  // m = k = 1, c = 0.1, A = 0.5, xs = 0.1, r = 0.8: the P(1,1) branch from
  // Ω = 0.6 to 3 has a new contact, three period doublings and an impact
  // vanishing where the non-impacting amplitude reaches xs.
  const testing::SdofParameters p{1.0, 1.0, 0.1, 0.5, 0.1, 0.8, 1.3};
  const System system =
      UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), 1.3, p.xs, p.r);
  const DiagramOptions options = Options(0.6, 3.0, 1);
  const Diagram diagram =
      TraceDiagram({{system, testing::SeededOrbit(system, 1, 1), "P(1,1) at 1.3"}}, options);
  CheckGraph(diagram);
  CheckNodesRecomputed(system, diagram);

  // The P(1,1) nodes, in parameter order, against the closed form.
  std::vector<const DiagramNode*> p11;
  for (const DiagramNode& n : diagram.nodes) {
    if (n.kind == DiagramNodeKind::kSpecialPoint && n.p == 1 && n.q == 1) p11.push_back(&n);
  }
  std::sort(p11.begin(), p11.end(), [](auto* a, auto* b) { return a->parameter < b->parameter; });
  REQUIRE(p11.size() == 5);
  CHECK(p11[0]->special == SpecialPointType::kGrazing);
  CHECK(p11[0]->vanishing_impact == -1);
  for (int k = 1; k <= 3; ++k) {
    REQUIRE(p11[k]->special == SpecialPointType::kPeriodDoubling);
    CHECK_THAT(p11[k]->parameter,
               Catch::Matchers::WithinAbs(ClosedFormPeriodDoubling(p, *p11[k]), 1e-8));
  }
  // Between them, as the closed form's multipliers say (the flip
  // multiplier below -1 on 1.065..1.130 and 2.265..): 1.0648, 1.1300, 2.2653.
  CHECK_THAT(p11[1]->parameter, Catch::Matchers::WithinAbs(1.0648, 1e-4));
  CHECK_THAT(p11[2]->parameter, Catch::Matchers::WithinAbs(1.1300, 1e-4));
  CHECK_THAT(p11[3]->parameter, Catch::Matchers::WithinAbs(2.2653, 1e-4));
  // The amplitude A / sqrt((k - mΩ²)² + (cΩ)²) = xs: Ω² solves
  // Ω⁴ + (c² - 2) Ω² + 1 - (A/xs)² = 0.
  const double b = p.c * p.c - 2.0, c = 1.0 - (p.a / p.xs) * (p.a / p.xs);
  const double vanishing = std::sqrt(0.5 * (-b + std::sqrt(b * b - 4.0 * c)));
  CHECK(p11[4]->special == SpecialPointType::kGrazing);
  CHECK(p11[4]->vanishing_impact == 0);
  CHECK_THAT(p11[4]->parameter, Catch::Matchers::WithinAbs(vanishing, 1e-9));

  // Complete from the one seed: a doubled branch leaves every period
  // doubling.
  for (int k = 1; k <= 3; ++k) {
    const int node = static_cast<int>(p11[k] - diagram.nodes.data());
    const bool doubled = std::any_of(diagram.edges.begin(), diagram.edges.end(), [&](auto& e) {
      const Branch& b = diagram.branches[e.branch].branch;
      return (e.from == node || e.to == node) && b.p == 2 && b.q == 2;
    });
    INFO("period doubling at " << p11[k]->parameter);
    CHECK(doubled);
  }
  CHECK(diagram.branches.front().branch.p == 1);
  CHECK(diagram.termination ==
        Termination::kMaxPoints);  // max_depth 1 stops below the doubled branches' own switches

  // The same network on two threads: the same nodes, bit for bit.
  DiagramOptions two = options;
  two.threads = 2;
  const Diagram again =
      TraceDiagram({{system, testing::SeededOrbit(system, 1, 1), "P(1,1) at 1.3"}}, two);
  REQUIRE(again.nodes.size() == diagram.nodes.size());
  REQUIRE(again.edges.size() == diagram.edges.size());
  for (std::size_t k = 0; k < diagram.nodes.size(); ++k) {
    CHECK(again.nodes[k].parameter == diagram.nodes[k].parameter);
  }
}

TEST_CASE(
    "diagram: a repeated orbit is followed as its primitive, and a branch reached twice "
    "is traced once",
    "[diagram]") {
  const System system = PaperSystem(1.1);
  const PeriodicOrbit p11 = testing::SeededOrbit(system, 1, 1);
  // The same orbit described as P(2,2), and P(1,1) again at another Ω.
  const PeriodicOrbit twice = DescribeOrbit(ImpactMap(system), p11.eta, 2, 2);
  const System later = PaperSystem(1.3);
  const Diagram diagram = TraceDiagram(
      {{system, twice, "P(1,1) twice"}, {later, testing::SeededOrbit(later, 1, 1), "again"}},
      Options(1.0, 1.4, 0));
  REQUIRE(diagram.branches.size() == 1);
  CHECK(diagram.branches[0].branch.p == 1);
  CHECK(diagram.branches[0].branch.q == 1);
  CHECK(diagram.duplicate_starts == 1);
  // Both ends at the bounds: two nodes, one edge.
  CHECK(diagram.nodes.size() == 2);
  REQUIRE(diagram.edges.size() == 1);
  CHECK(diagram.nodes[diagram.edges[0].from].Name() == "parameter_bound");
  CHECK(diagram.nodes[diagram.edges[0].to].Name() == "parameter_bound");
}

TEST_CASE(
    "diagram: the paper's network near the P(2,1) period doubling joins the doubled "
    "branch's pitchfork and the sweep's isolated P(3,2) window",
    "[diagram]") {
  const System system = PaperSystem(0.8);
  const SweptDiagramOptions options = Swept(Options(0.8, 0.9, 3), 41, 20, 8);
  const SweptDiagram swept = TraceSweptDiagram(system, {}, options);
  const Diagram& diagram = swept.diagram;
  CheckGraph(diagram);
  CheckNodesRecomputed(system, diagram);
  // The P(2,1) period doubling near 0.8372 is one node where the P(4,2)
  // branch starts and, as a branch point, ends: not a fold.
  const auto pd = std::find_if(diagram.nodes.begin(), diagram.nodes.end(), [](auto& n) {
    return n.special == SpecialPointType::kPeriodDoubling && n.p == 2 && n.q == 1;
  });
  REQUIRE(pd != diagram.nodes.end());
  CHECK_THAT(pd->parameter, Catch::Matchers::WithinAbs(0.8372, 1e-4));
  const int pd_node = static_cast<int>(pd - diagram.nodes.begin());
  std::set<std::pair<int, int>> at_pd;
  for (const DiagramEdge& e : diagram.edges) {
    if (e.from != pd_node && e.to != pd_node) continue;
    const Branch& b = diagram.branches[e.branch].branch;
    at_pd.insert({b.p, b.q});
  }
  CHECK(at_pd.count({2, 1}) == 1);
  CHECK(at_pd.count({4, 2}) == 1);
  // The isolated P(3,2) between 0.832 and 0.859, found from the sweep alone.
  const auto p32 = std::find_if(diagram.branches.begin(), diagram.branches.end(),
                                [](auto& b) { return b.branch.p == 3 && b.branch.q == 2; });
  REQUIRE(p32 != diagram.branches.end());
  CHECK(p32->origin.find("sweep window") == 0);
  double lo = 1e300, hi = -1e300;
  for (const BranchPoint& point : p32->branch.points) {
    lo = std::min(lo, point.parameter);
    hi = std::max(hi, point.parameter);
  }
  CHECK_THAT(lo, Catch::Matchers::WithinAbs(0.832, 1e-3));
  CHECK_THAT(hi, Catch::Matchers::WithinAbs(0.859, 1e-3));
}

TEST_CASE("diagram: a branch traced again over part of another's range is covered by it",
          "[diagram]") {
  // Traced independently, the shorter branch's points are not the longer
  // one's: they are on it through interpolation between its points.
  const System system = PaperSystem(1.2);
  const auto trace = [](const System& s, double lower, double upper) {
    return TraceDiagram({{s, testing::SeededOrbit(s, 1, 1), "P(1,1)"}}, Options(lower, upper, 0))
        .branches.at(0)
        .branch;
  };
  const Branch whole = trace(system, 1.0, 1.4), part = trace(system, 1.1, 1.3);
  CHECK(CoveredBy(part, whole));
  CHECK_FALSE(CoveredBy(whole, part));  // reaches 1.0 and 1.4, beyond the part
  // A nearby but different branch (r 0.7 -> 0.72: speeds change by ~1%).
  const Branch other = trace(At(system, "r", 0.72), 1.1, 1.3);
  CHECK_FALSE(CoveredBy(other, whole));
  Branch later = part;
  later.q = 2;
  CHECK_FALSE(CoveredBy(later, whole));  // another period is another branch
}

TEST_CASE("diagram: a grazing located just past a bound seeds nothing outside the range",
          "[diagram]") {
  // P(1,1)'s new contact at 0.8564 is approached from the branch side and
  // located below the bound 0.9: the P(2,1) seeded beside it lies outside
  // [0.9, 1.3] and is skipped (ContinueBranch would refuse it).
  const System system = PaperSystem(1.0);
  Diagram diagram;
  REQUIRE_NOTHROW(diagram = TraceDiagram({{system, testing::SeededOrbit(system, 1, 1), "P(1,1)"}},
                                         Options(0.9, 1.3, 2)));
  REQUIRE(diagram.branches.size() == 1);
  CHECK(diagram.nodes.size() == 2);  // the grazing and the upper bound
  CheckGraph(diagram);
}

TEST_CASE("diagram: default options are valid and bad ones are refused", "[diagram]") {
  std::string error;
  DiagramOptions options = Options(0.5, 1.0, 2);
  CHECK(options.IsValid(&error));
  CHECK(SweepSeedOptions{}.IsValid(&error));
  CHECK(SweptDiagramOptions{}.IsValid(&error) == false);  // no range yet: lower == upper
  CHECK(SweepRefineOptions{}.IsValid(&error));
  SweptDiagramOptions swept;
  swept.diagram = Options(0.5, 1.0, 2);
  CHECK(swept.IsValid(&error));
  swept.refine.factor = 0;
  CHECK_FALSE(swept.IsValid(&error));
  CHECK(error.find("factor") != std::string::npos);
  options.threads = 0;
  CHECK_FALSE(options.IsValid(&error));
  CHECK(error.find("threads") != std::string::npos);
  CHECK_THROWS_AS(TraceDiagram({}, Options(0.5, 1.0, 2)), InvalidInput);
}

TEST_CASE(
    "diagram: a long orbit's multiplier passing through infinity is not a fold (the N = 1 "
    "cascade to P(16,16))",
    "[diagram][slow]") {
  // det(D P - I) of P(16,16) changes sign near Ω = 2.281 where one
  // multiplier passes through infinity (an impact slows to a graze), not
  // through +1: it was reported as a fold with multiplier -0.000016. Every
  // fold, period doubling and Neimark–Sacker point of the depth-8 network
  // is recomputed (its folds, such as P(7,8)'s 2.4e-9 from a period
  // doubling, by their own defining system).
  const System system =
      UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), 1.3, 0.1, 0.8);
  const Diagram diagram = TraceDiagram(
      {{system, testing::SeededOrbit(system, 1, 1), "P(1,1) at 1.3"}}, Options(0.6, 3.0, 8));
  CHECK(CheckMultiplierNodesRecomputed(system, diagram) >= 10);
  const bool cascade = std::any_of(diagram.branches.begin(), diagram.branches.end(),
                                   [](const DiagramBranch& b) { return b.branch.p == 16; });
  CHECK(cascade);
}

TEST_CASE(
    "diagram: every fold, period doubling, Neimark-Sacker and grazing node of the paper's whole "
    "diagram is recomputed (`impactkit diagram` with its defaults)",
    "[diagram][slow]") {
  // The network `impactkit diagram` traces with no options: Ω from 0.1 to
  // 2.5, seeded by a 481-value sweep (300 + 40 periods, periods to 16),
  // depth 8. Which windows the sweep seeds depends on its chaotic runs to
  // the last bit (P(10,4), below, was seeded until the event search changed
  // in the 15th digit), so only the count of nodes is asked for.
  const System system = PaperSystem(1.0);
  SweptDiagramOptions options = Swept(Options(0.1, 2.5, 8), 481, 40, 16);
  options.diagram.threads = options.sweep.threads = 2;
  options.seeds.max_p = 16;
  const SweptDiagram swept = TraceSweptDiagram(system, {}, options);
  const Diagram& diagram = swept.diagram;
  CheckGraph(diagram);
  CHECK(CheckNodesRecomputed(system, diagram) >= 100);
}

TEST_CASE(
    "diagram: P(10,4)'s fold at omega = 1.676008591, which bracketing left at multiplier 1.0017, "
    "is solved to a multiplier within 1e-7 of 1",
    "[diagram]") {
  // Before folds were solved directly where bracketing falls short, the
  // default diagram reported this fold with multiplier 1.0017. Its P(10,4)
  // came from the diagram's sweep; here from that orbit's η at its period
  // doubling (omega = 1.6757404649), recorded from that run.
  const System system = PaperSystem(1.6757404648804137);
  Eigen::VectorXd eta(4);
  eta << -0.5260041455264385, 3.640000807468266, 1.099331705076845, 0.03201655807530875;
  OrbitOptions orbit_options;
  orbit_options.p = 10;
  orbit_options.q = 4;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, eta, orbit_options, &orbit).termination == Termination::kConverged);
  ContinuationOptions options = Options(1.67, 1.68, 1).continuation;
  options.orbit = orbit_options;
  options.direction = ContinuationDirection::kBoth;
  const Branch branch = ContinueBranch({system, orbit, {}}, options);
  const auto fold = std::find_if(branch.special_points.begin(), branch.special_points.end(),
                                 [](auto& s) { return s.type == SpecialPointType::kFold; });
  REQUIRE(fold != branch.special_points.end());
  CHECK_THAT(fold->parameter, Catch::Matchers::WithinAbs(1.676008591, 1e-9));
  CHECK(std::abs(fold->multiplier - 1.0) < 1e-7);
}

TEST_CASE(
    "diagram: refining the sweep where the motion changes finds the paper's P(4,6) window, "
    "narrower than the sweep's spacing, between its period doubling and its fold",
    "[diagram]") {
  // The window is 1.7728-1.7749 (P(4,6) between its period doubling, where
  // P(8,12) begins below, and its fold: docs/continuation.md); a sweep of
  // spacing 0.004 has at most one value in it, so no window and no seed.
  const System system = PaperSystem(1.7);
  SweptDiagramOptions options;
  options.sweep.parameter = "omega";
  options.sweep.from = 1.70;
  options.sweep.to = 1.80;
  options.sweep.steps = 26;
  const SweepResult coarse = RunSweep(system, options.sweep);
  const auto p46 = [](const std::vector<DiagramSeed>& seeds) {
    return std::find_if(seeds.begin(), seeds.end(), [](const DiagramSeed& s) {
      return !s.orbit.Sticks() && s.orbit.p == 4 && s.orbit.q == 6;
    });
  };
  const std::vector<DiagramSeed> unrefined =
      SeedsFromSweep(system, options.sweep, coarse, options.seeds);
  CHECK(p46(unrefined) == unrefined.end());

  SweepResult refined = coarse;
  refined.points = RefineSweep(system, options.sweep, coarse, options.refine);
  REQUIRE(refined.points.size() > coarse.points.size());
  for (std::size_t k = 1; k < refined.points.size(); ++k) {
    CHECK(refined.points[k].value > refined.points[k - 1].value);  // sweep order kept
  }
  const std::vector<DiagramSeed> seeds =
      SeedsFromSweep(system, options.sweep, refined, options.seeds);
  const auto seed = p46(seeds);
  REQUIRE(seed != seeds.end());
  // The branch through the seed, followed by continuation (not by a sweep):
  // the seed lies where it is stable, between its period doubling and fold.
  ContinuationOptions continuation;
  continuation.from = 1.76;
  continuation.to = 1.78;
  continuation.orbit.p = 4;
  continuation.orbit.q = 6;
  continuation.direction = ContinuationDirection::kBoth;
  const Branch branch = ContinueBranch({seed->system, seed->orbit, {}}, continuation);
  auto located = [&](SpecialPointType type) {
    for (const SpecialPoint& s : branch.special_points) {
      if (s.type == type) return s.point.parameter;
    }
    return std::nan("");
  };
  const double doubling = located(SpecialPointType::kPeriodDoubling);
  const double fold = located(SpecialPointType::kFold);
  CHECK_THAT(doubling, Catch::Matchers::WithinAbs(1.772792, 2e-6));
  CHECK_THAT(fold, Catch::Matchers::WithinAbs(1.774922, 2e-6));
  CHECK(seed->system.omega > doubling);
  CHECK(seed->system.omega < fold);
}

TEST_CASE(
    "diagram: a seed on the branch of an earlier seed of its family is not traced, while "
    "another family is traced beside them",
    "[diagram]") {
  // Counted by the progress reports, one per accepted point of any branch
  // traced: the same with and without the repeated P(1,1), on two threads.
  const System at_11 = PaperSystem(1.1), at_21 = PaperSystem(0.6), later = PaperSystem(1.3);
  DiagramOptions options = Options(0.5, 1.4, 0);
  options.threads = 2;
  const auto trace = [&](const std::vector<DiagramSeed>& seeds, std::int64_t* points) {
    *points = 0;
    const RunControl control([&](const Progress&) { ++*points; });
    return TraceDiagram(seeds, options, control);
  };
  const DiagramSeed p11{at_11, testing::SeededOrbit(at_11, 1, 1), "P(1,1)"};
  const DiagramSeed p21{at_21, testing::SeededOrbit(at_21, 2, 1), "P(2,1)"};
  const DiagramSeed again{later, testing::SeededOrbit(later, 1, 1), "P(1,1) again"};
  std::int64_t without = 0, with = 0;
  const Diagram two = trace({p11, p21}, &without);
  const Diagram three = trace({p11, p21, again}, &with);
  REQUIRE(two.branches.size() == 2);
  REQUIRE(three.branches.size() == 2);
  CHECK(three.duplicate_starts == 1);
  CHECK(with == without);
  CHECK(without > 0);
}

TEST_CASE(
    "diagram: on the paper's range the defaults' refined sweep seeds every window the 2401 "
    "uniform values seed",
    "[diagram]") {
  // Each window of the 2401-value sweep (Ω 0.4 to 2.3, no refinement) has a
  // window of the same P(p,q) in the defaults' 481 refined values that
  // overlaps it, or lies within 0.005 in Ω (a coarse spacing) of it: the
  // same windows, P(4,6) included. A window's range is its seed's origin,
  // "sweep window P(p,q) omega lo..hi".
  const auto range = [](const DiagramSeed& seed) {
    double lo = 0, hi = 0;
    REQUIRE(std::sscanf(seed.origin.c_str() + seed.origin.rfind(' ') + 1, "%lf..%lf", &lo, &hi) ==
            2);
    return std::pair{lo, hi};
  };
  const System system = PaperSystem(0.4);
  SweptDiagramOptions defaults;
  defaults.sweep.from = 0.4;
  defaults.sweep.to = 2.3;
  defaults.sweep.threads = 2;
  SweepOptions uniform = defaults.sweep;
  uniform.steps = 2401;
  const std::vector<DiagramSeed> fine =
      SeedsFromSweep(system, uniform, RunSweep(system, uniform), defaults.seeds);
  SweepResult coarse = RunSweep(system, defaults.sweep);
  coarse.points = RefineSweep(system, defaults.sweep, coarse, defaults.refine);
  const std::vector<DiagramSeed> refined =
      SeedsFromSweep(system, defaults.sweep, coarse, defaults.seeds);
  REQUIRE(fine.size() >= 10);
  bool p46 = false;
  for (const DiagramSeed& seed : fine) {
    INFO(seed.origin);
    const bool matched = std::any_of(refined.begin(), refined.end(), [&](const DiagramSeed& other) {
      const auto [lo, hi] = range(seed);
      const auto [other_lo, other_hi] = range(other);
      return other.orbit.p == seed.orbit.p && other.orbit.q == seed.orbit.q &&
             other_lo <= hi + 5e-3 && lo <= other_hi + 5e-3;
    });
    CHECK(matched);
    p46 = p46 || (seed.orbit.p == 4 && seed.orbit.q == 6);
  }
  CHECK(p46);
}

TEST_CASE(
    "diagram: a grazing seed 1e-4 from the grazing, the network's second try, converges onto "
    "the branch the seed 1e-3 away reaches",
    "[diagram]") {
  // P(1,1)'s new contact near 0.8564: on each side where both seeds
  // converge, the P(2,1) branches traced from their orbits cover each
  // other (CoveredBy: every point of one on the other's curve).
  const System system = PaperSystem(1.0);
  ContinuationOptions options = Options(0.5, 1.2, 1).continuation;
  options.direction = ContinuationDirection::kBoth;
  options.orbit.p = options.orbit.q = 1;
  const Branch branch = ContinueBranch({system, testing::SeededOrbit(system, 1, 1), {}}, options);
  const auto graze =
      std::find_if(branch.special_points.begin(), branch.special_points.end(),
                   [](const SpecialPoint& s) { return s.type == SpecialPointType::kGrazing; });
  REQUIRE(graze != branch.special_points.end());
  CHECK_THAT(graze->point.parameter, Catch::Matchers::WithinAbs(0.8564344, 1e-6));
  const std::vector<GrazingSeed> near = SeedsAtGrazing(system, branch, *graze, options);
  const std::vector<GrazingSeed> nearer = SeedsAtGrazing(system, branch, *graze, options, 1e-4);
  const auto trace = [&](const GrazingSeed& seed) -> std::optional<Branch> {
    PeriodicOrbit orbit;
    if (FindOrbit(seed.system, seed.eta, seed.orbit, &orbit).termination !=
        Termination::kConverged) {
      return std::nullopt;
    }
    ContinuationOptions p21 = options;
    p21.orbit = seed.orbit;
    return ContinueBranch({seed.system, orbit, {}}, p21);
  };
  int compared = 0;
  for (std::size_t side = 0; side < std::min(near.size(), nearer.size()); ++side) {
    const std::optional<Branch> a = trace(near[side]), b = trace(nearer[side]);
    if (!a || !b) continue;
    CHECK(a->p == 2);
    CHECK(CoveredBy(*a, *b));
    CHECK(CoveredBy(*b, *a));
    ++compared;
  }
  CHECK(compared >= 1);
}
