// Continuation (continuation.hpp): located special points checked by
// independent recomputation — multipliers from a fresh FindOrbit, grazing
// monitors from CVODE integrations, the N = 1 branch against its closed
// form, the vanishing-impact end against the non-impacting response.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "closed_form_sdof.hpp"
#include "continuation/arclength.hpp"
#include "continuation/existence_monitor.hpp"
#include "cvode_impacts.hpp"
#include "impactkit/analysis/orbit_seed.hpp"
#include "impactkit/analysis/start_orbit.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "recomputed_special_point.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"

using namespace impactkit;
using testing::At;

namespace {

PeriodicOrbit Orbit(const System& system, int p, int q) {
  return testing::SeededOrbit(system, p, q);
}

ContinuationOptions Options(double from, double to, int p, int q,
                            ContinuationDirection direction = ContinuationDirection::kBoth) {
  ContinuationOptions options;
  options.from = from;
  options.to = to;
  options.direction = direction;
  options.orbit.p = p;
  options.orbit.q = q;
  return options;
}

const SpecialPoint* Find(const Branch& branch, SpecialPointType type, double lo, double hi) {
  for (const SpecialPoint& s : branch.special_points) {
    if (s.type == type && s.point.parameter > lo && s.point.parameter < hi) return &s;
  }
  return nullptr;
}

/// The multiplier nearest `target` of the orbit FindOrbit converges to from
/// the located point (a fresh solve and a fresh Jacobian).
std::complex<double> RecomputedMultiplier(const System& base, const Branch& branch,
                                          const SpecialPoint& s, double target) {
  return testing::RecomputedMultiplier(At(base, branch.parameter, s.point.parameter), branch.p,
                                       branch.q, s.point.orbit.eta, target);
}

/// The fold solved again by its own regular defining system
/// (recomputed_special_point.hpp) lands within 1e-8 of the located μ and
/// 1e-7 of its orbit, with its multiplier within 1e-6 of 1.
void CheckFoldRecomputed(const System& system, const Branch& branch, const SpecialPoint& fold) {
  const testing::RecomputedFold again = testing::RecomputeFold(system, branch.parameter, fold);
  CHECK(std::abs(again.parameter - fold.point.parameter) < 1e-8);
  CHECK((again.eta - fold.point.orbit.eta).norm() < 1e-7 * (1.0 + fold.point.orbit.eta.norm()));
  CHECK(std::abs(again.multiplier - 1.0) < 1e-6);
}

/// The state of the orbit's flight after impact `eta` at time t, by CVODE.
void CvodeFlight(const System& system, const Eigen::VectorXd& eta, double t, Eigen::VectorXd* x,
                 Eigen::VectorXd* v) {
  const HybridState before = ImpactMap(system).ToState(eta);
  *x = before.x;
  *v = before.v;
  (*v)(system.stops[0].dof) *= -system.stops[0].restitution;
  reference::CvodeLinearFlow(system.mass, system.damping, system.stiffness, system.forcing,
                             Eigen::VectorXd::Zero(system.Dof()), system.omega, before.t, *x, *v,
                             t);
}

/// xs - max x_c over the flight after the impact `eta` (which lasts
/// `duration`), by CVODE: sampled, then golden-section refined.
double CvodeClearance(const System& system, const Eigen::VectorXd& eta, double duration) {
  const double t0 = eta(system.Dof() - 1);
  const int c = system.stops[0].dof;
  auto height = [&](double t) {
    Eigen::VectorXd x, v;
    CvodeFlight(system, eta, t, &x, &v);
    return x(c);
  };
  const int samples = 400;
  int best = 1;
  for (int i = 1; i < samples; ++i) {
    if (height(t0 + duration * i / samples) > height(t0 + duration * best / samples)) best = i;
  }
  double a = t0 + duration * (best - 1) / samples, b = t0 + duration * (best + 1) / samples;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int k = 0; k < 60; ++k) {
    const double m1 = b - g * (b - a), m2 = a + g * (b - a);
    (height(m1) > height(m2) ? b : a) = height(m1) > height(m2) ? m2 : m1;
  }
  return system.stops[0].position - height(0.5 * (a + b));
}

/// The start of the branch born at `branch`'s period doubling in (low, high),
/// continued with `options` (both required to exist).
BranchStart DoubledStartIn(const System& system, const Branch& branch, double low, double high,
                           const ContinuationOptions& options) {
  const SpecialPoint* pd = Find(branch, SpecialPointType::kPeriodDoubling, low, high);
  REQUIRE(pd != nullptr);
  const std::optional<BranchStart> doubled = DoubledBranchStart(system, branch, *pd, options);
  REQUIRE(doubled.has_value());
  return *doubled;
}

/// Consecutive points differ by no more than the largest step allows.
void CheckNoJumps(const Branch& branch, const ContinuationOptions& options) {
  const double largest = std::hypot(1.0, options.max_correction) * options.max_step;
  for (std::size_t i = 1; i < branch.points.size(); ++i) {
    const BranchPoint &a = branch.points[i - 1], &b = branch.points[i];
    const double distance =
        std::hypot((b.orbit.eta - a.orbit.eta).norm(), b.parameter - a.parameter);
    INFO("points " << i - 1 << ", " << i << " at " << a.parameter << ", " << b.parameter);
    CHECK(distance <= largest * (1 + 1e-9));
  }
}

}  // namespace

TEST_CASE(
    "continuation: the paper's P(1,1) branch ends by grazing near 0.856 and period-doubles "
    "near 1.61, both confirmed independently",
    "[continuation]") {
  const System system = PaperSystem(1.0);
  const ContinuationOptions options = Options(0.5, 2.0, 1, 1);
  const Branch branch = ContinueBranch({system, Orbit(system, 1, 1), {}}, options);
  REQUIRE(branch.begin == Termination::kGrazing);
  REQUIRE(branch.end == Termination::kGrazing);
  CheckNoJumps(branch, options);

  const SpecialPoint* pd = Find(branch, SpecialPointType::kPeriodDoubling, 1.60, 1.62);
  REQUIRE(pd != nullptr);
  CHECK(std::abs(RecomputedMultiplier(system, branch, *pd, -1.0) + 1.0) < 1e-6);

  // The low end: a new contact (clearance 0) near 0.856, by CVODE.
  const SpecialPoint& graze = branch.special_points.front();
  REQUIRE(graze.type == SpecialPointType::kGrazing);
  CHECK(graze.vanishing_impact == -1);
  CHECK(graze.point.parameter == Approx(0.856).margin(1e-3));
  const System at = At(system, "omega", graze.point.parameter);
  CHECK(std::abs(CvodeClearance(at, graze.point.orbit.eta, at.ForcingPeriod())) < 1e-9);
}

TEST_CASE(
    "continuation: a vanishing impact ends the P(1,2) branch where the non-impacting "
    "response touches the stop",
    "[continuation]") {
  const System system = PaperSystem(2.0);
  const ContinuationOptions options = Options(1.0, 3.0, 1, 2);
  const Branch branch = ContinueBranch({system, Orbit(system, 1, 2), {}}, options);
  REQUIRE(branch.end == Termination::kGrazing);
  const SpecialPoint& end = branch.special_points.back();
  REQUIRE(end.vanishing_impact == 0);
  // The fold where the impacting motion disappears (the paper: Ω ≈ 2.19).
  const SpecialPoint* fold = Find(branch, SpecialPointType::kFold, 2.1, 2.3);
  REQUIRE(fold != nullptr);
  CheckFoldRecomputed(system, branch, *fold);

  // Closed form: |X2(Ω)| = xs for X = (K - Ω²M + iΩC)⁻¹ A, by bisection.
  auto amplitude = [&](double w) {
    const Eigen::MatrixXcd dynamic =
        system.stiffness.cast<std::complex<double>>() -
        w * w * system.mass.cast<std::complex<double>>() +
        std::complex<double>(0, w) * system.damping.cast<std::complex<double>>();
    const Eigen::VectorXcd x =
        dynamic.partialPivLu().solve(system.forcing.cast<std::complex<double>>());
    return std::abs(x(system.stops[0].dof)) - system.stops[0].position;
  };
  double lo = 1.9, hi = 2.1;
  REQUIRE((amplitude(lo) > 0) != (amplitude(hi) > 0));
  for (int k = 0; k < 100; ++k)
    ((amplitude(0.5 * (lo + hi)) > 0) == (amplitude(lo) > 0) ? lo : hi) = 0.5 * (lo + hi);
  CHECK(std::abs(end.point.parameter - lo) < 1e-5);
  // Located by the reduced orbit's defining equation, not the depth.
  CHECK(std::abs(end.parameter - lo) < 1e-9);

  // The depth v²/(2|a|) recomputed by CVODE over the flight into the impact.
  const System at = At(system, "omega", end.point.parameter);
  const Eigen::VectorXd& eta = end.point.orbit.eta;
  Eigen::VectorXd x, v;
  CvodeFlight(at, eta, eta(1) + 2 * at.ForcingPeriod(), &x, &v);
  const Eigen::VectorXd a =
      at.mass.inverse() * (at.forcing * std::cos(at.omega * (eta(1) + 2 * at.ForcingPeriod())) -
                           at.damping * v - at.stiffness * x);
  const int c = at.stops[0].dof;
  CHECK(v(c) * v(c) / (2 * std::abs(a(c))) < 1e-9);
}

TEST_CASE("continuation: N = 1 branch, fold and period doublings match the closed form",
          "[continuation]") {
  using testing::SdofParameters;
  for (const auto& [xs, r, from, to, type] :
       {std::tuple{0.2, 0.8, 1.5, 3.0, SpecialPointType::kFold},
        std::tuple{0.1, 0.8, 1.3, 0.6, SpecialPointType::kPeriodDoubling}}) {
    INFO("xs = " << xs << ", r = " << r);
    SdofParameters p{1.0, 1.0, 0.1, 0.5, xs, r, from};
    const System system =
        UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), from, xs, r);
    ContinuationOptions options = Options(
        std::min(from, to), std::max(from, to), 1, 1,
        to > from ? ContinuationDirection::kIncreasing : ContinuationDirection::kDecreasing);
    const Branch branch = ContinueBranch({system, Orbit(system, 1, 1), {}}, options);
    CheckNoJumps(branch, options);
    // Every point is a closed-form solution at its Ω: a jump to another
    // solution of the hybrid system would show here. (At the fold itself
    // the closed form's discriminant may round below zero.)
    const SpecialPoint* fold = Find(branch, SpecialPointType::kFold, 0.0, 10.0);
    for (const BranchPoint& point : branch.points) {
      if (fold && std::abs(point.parameter - fold->point.parameter) < 1e-9) continue;
      p.omega = point.parameter;
      double nearest = 1e300;
      for (const testing::SdofP11& o : testing::SdofP11Solutions(p)) {
        const double phase = std::fmod(point.orbit.eta(0), p.Period());
        nearest = std::min(nearest, std::hypot(std::remainder(phase - o.tau, p.Period()),
                                               point.orbit.eta(1) - o.u));
      }
      CHECK(nearest < 1e-8);
    }
    int located = 0;
    for (const SpecialPoint& s : branch.special_points) {
      if (s.type != type) continue;
      ++located;
      // The closed-form event, by bisection in Ω around the located one.
      auto closed_form = [&](double w) {
        p.omega = w;
        const auto roots = testing::SdofP11Solutions(p);
        if (type == SpecialPointType::kFold) return roots.size() == 2 ? 1.0 : -1.0;
        const testing::SdofP11& o =
            *std::min_element(roots.begin(), roots.end(), [&](auto& a, auto& b) {
              return std::abs(a.u - s.point.orbit.eta(1)) < std::abs(b.u - s.point.orbit.eta(1));
            });
        return (testing::SdofP11Jacobian(p, o) + Eigen::Matrix2d::Identity()).determinant();
      };
      double lo = s.point.parameter - 1e-4, hi = s.point.parameter + 1e-4;
      REQUIRE((closed_form(lo) > 0) != (closed_form(hi) > 0));
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((closed_form(mid) > 0) == (closed_form(lo) > 0) ? lo : hi) = mid;
      }
      CHECK(std::abs(s.point.parameter - lo) < 1e-8);
    }
    CHECK(located >= 1);
  }
}

TEST_CASE(
    "continuation: branch switching onto P(2,2) at the period doubling and onto P(2,1) "
    "at the grazing",
    "[continuation]") {
  const System system = PaperSystem(1.0);
  const ContinuationOptions options = Options(0.5, 2.0, 1, 1);
  const Branch branch = ContinueBranch({system, Orbit(system, 1, 1), {}}, options);
  const BranchStart doubled = DoubledStartIn(system, branch, 1.60, 1.62, options);
  CHECK(doubled.orbit.p == 2);
  CHECK(doubled.orbit.residual < 1e-10);
  ContinuationOptions twice = Options(0.5, 2.0, 2, 2, ContinuationDirection::kIncreasing);
  const Branch p22 = ContinueBranch(doubled, twice);
  // Its own period doubling (the paper: near 1.68).
  const SpecialPoint* pd2 = Find(p22, SpecialPointType::kPeriodDoubling, 1.67, 1.69);
  REQUIRE(pd2 != nullptr);
  CHECK(std::abs(RecomputedMultiplier(system, p22, *pd2, -1.0) + 1.0) < 1e-6);

  // At the grazing a P(2,1) seed converges; its branch ends where an impact
  // vanishes — at the same grazing, reached from the other side.
  const SpecialPoint& graze = branch.special_points.front();
  std::optional<Branch> p21;
  for (const GrazingSeed& seed : SeedsAtGrazing(system, branch, graze, options)) {
    PeriodicOrbit orbit;
    if (FindOrbit(seed.system, seed.eta, seed.orbit, &orbit).termination !=
        Termination::kConverged) {
      continue;
    }
    CHECK(orbit.p == 2);
    p21 = ContinueBranch({seed.system, orbit, {}}, Options(0.5, 1.0, 2, 1));
    break;
  }
  REQUIRE(p21.has_value());
  const SpecialPoint& other_side = p21->special_points.back();
  CHECK(other_side.type == SpecialPointType::kGrazing);
  CHECK(other_side.vanishing_impact >= 0);
  CHECK(std::abs(other_side.point.parameter - graze.point.parameter) < 1e-5);
  // The P(2,1) end, located on the reduced P(1,1) orbit, is the P(1,1)
  // grazing located by its clearance (to ~1e-10).
  CHECK(std::abs(other_side.parameter - graze.point.parameter) < 1e-8);
}

namespace {

/// The first point of the P(4,2) branch born at the paper's P(2,1) period
/// doubling near Ω = 0.8372.
BranchStart P42Start(const System& system) {
  const ContinuationOptions options = Options(0.8, 0.9, 2, 1);
  const Branch p21 = ContinueBranch({system, Orbit(system, 2, 1), {}}, options);
  return DoubledStartIn(system, p21, 0.835, 0.839, options);
}

/// P(4,2)'s branch in fine steps (max 0.002): its period doubling near
/// 0.83246 lies between regular points.
Branch FineP42(const System& system) {
  ContinuationOptions p42 = Options(0.8, 0.9, 4, 2);
  p42.max_step = p42.initial_step = 0.002;
  return ContinueBranch(P42Start(system), p42);
}

}  // namespace

TEST_CASE("continuation: a period doubling on the approach to a vanishing impact is located",
          "[continuation]") {
  // P(4,2) doubles again at 0.83246, 2.4e-4 before its impact 3 vanishes at
  // 0.83222. The secant steps of the approach to a grazing are branch
  // points too: a period doubling between them was missed.
  const System system = PaperSystem(0.83);
  const Branch fine = FineP42(system);
  const SpecialPoint* second = Find(fine, SpecialPointType::kPeriodDoubling, 0.8323, 0.8327);
  REQUIRE(second != nullptr);
  CHECK(std::abs(RecomputedMultiplier(system, fine, *second, -1.0) + 1.0) < 1e-6);

  // With the default steps the branch sees the grazing ahead before the
  // period doubling and approaches it in secant steps.
  const Branch coarse = ContinueBranch(P42Start(system), Options(0.8, 0.9, 4, 2));
  CHECK(coarse.end == Termination::kGrazing);
  const SpecialPoint* found = Find(coarse, SpecialPointType::kPeriodDoubling, 0.8323, 0.8327);
  REQUIRE(found != nullptr);
  CHECK(std::abs(found->parameter - second->parameter) < 1e-8);
}

TEST_CASE(
    "continuation: a long orbit's vanishing impact that the corrector cannot reach is "
    "located by its reduced orbit",
    "[continuation]") {
  // P(8,4), born at P(4,2)'s second period doubling, lives on 8e-6 in Ω:
  // near its vanishing impact its multipliers reach ~1e4, and the corrector
  // may stall at a depth of a few 1e-9, short of the 1e-10 tolerance.
  const System system = PaperSystem(0.83);
  const Branch p42 = ContinueBranch(P42Start(system), Options(0.8, 0.9, 4, 2));
  const ContinuationOptions options = Options(0.8, 0.9, 8, 4);
  const Branch p84 = ContinueBranch(DoubledStartIn(system, p42, 0.8323, 0.8327, options), options);
  CHECK(p84.end == Termination::kGrazing);
  REQUIRE(!p84.special_points.empty());
  const SpecialPoint& end = p84.special_points.back();
  REQUIRE(end.type == SpecialPointType::kGrazing);
  REQUIRE(end.vanishing_impact >= 0);
  // Independently: the square root of the depth is linear in Ω near the
  // vanishing impact (Nordmark). Extrapolated from the last two points
  // that still approach it (the depth falling fourfold; the stalled steps
  // after them creep in by ~1e-8 in Ω) to within ~1e-9.
  // Whether the corrector stalls short of 1e-9 is rounding's choice: here
  // it did with exp and sincos and with the flow's tables (and this test
  // failed without the reduced-orbit fallback), and reaches 9e-10 since the
  // event search's bracket.
  const std::vector<BranchPoint>& points = p84.points;
  std::size_t k = points.size() - 1;
  auto depth = [&](std::size_t i) { return points[i].orbit.contacts.slowest_depth; };
  while (k > 1 && !(depth(k - 1) > 2 * depth(k))) --k;
  const double m1 = std::sqrt(depth(k)), m0 = std::sqrt(depth(k - 1));
  const double mu1 = points[k].parameter, mu0 = points[k - 1].parameter;
  const double extrapolated = mu1 - m1 * (mu1 - mu0) / (m1 - m0);
  CHECK(std::abs(extrapolated - end.parameter) < 1e-8);
}

TEST_CASE(
    "continuation: P(2,1) in xs at omega = 0.6 ends where P(1,1) grazes, though its corrector "
    "may stall short of the tolerance",
    "[continuation]") {
  const System system = At(PaperSystem(0.6), "xs", 0.1);
  ContinuationOptions options = Options(0.1, 0.5, 2, 1);
  options.parameter = "xs";
  const Branch p21 = ContinueBranch({system, Orbit(system, 2, 1), {}}, options);
  REQUIRE(p21.end == Termination::kGrazing);
  const SpecialPoint& end = p21.special_points.back();
  // Near this vanishing impact the corrector stalls at a depth of 1e-10 to
  // 1e-8, depending on the last bits of the flow's rounding (5.8e-9 with
  // exp and sincos, 1.7e-10 with the mode clock's tables): either way the
  // branch ends at the grazing.
  CHECK(end.vanishing_impact >= 0);
  // The other side: P(1,1) from xs = 0.35 down to its new contact, located
  // by its own clearance.
  const System above = At(system, "xs", 0.35);
  ContinuationOptions down = Options(0.2, 0.5, 1, 1);
  down.parameter = "xs";
  const Branch p11 = ContinueBranch({above, Orbit(above, 1, 1), {}}, down);
  const SpecialPoint* contact = Find(p11, SpecialPointType::kGrazing, 0.2, 0.3);
  REQUIRE(contact != nullptr);
  CHECK(contact->vanishing_impact < 0);
  CHECK(std::abs(contact->parameter - end.parameter) < 1e-8);
}

TEST_CASE(
    "continuation: a long orbit's vanishing impact is located where the orbit without it "
    "touches, though both orbits' multipliers reach 1e4 there",
    "[continuation]") {
  // The clearance example's P(16,6), born at P(8,3)'s period doubling at
  // 1.2825, loses impact 4 near 1.258. Its corrector stalls 3e-4 short, and
  // the orbit without the impact, P(15,6), leaves a seed from a neighbour
  // 1e-6 away outside its map's reach: the locator must extrapolate it.
  System system = ReadSystemFile(IMPACTKIT_SOURCE_DIR "/examples/systems/clearance-1dof.toml");
  system = At(system, "omega", 1.29);
  StartOrbitRequest request;
  request.p = 8;
  request.q = 3;
  const StartOrbit p83 = FindStartOrbit(system, request);
  REQUIRE(p83.summary.termination == Termination::kConverged);
  const Branch single = ContinueBranch(
      {system, p83.orbit, {}}, Options(1.25, 1.29, 8, 3, ContinuationDirection::kDecreasing));
  const ContinuationOptions options =
      Options(1.25, 1.29, 16, 6, ContinuationDirection::kIncreasing);
  const Branch doubled =
      ContinueBranch(DoubledStartIn(system, single, 1.282, 1.283, options), options);
  REQUIRE(doubled.end == Termination::kGrazing);
  const SpecialPoint& end = doubled.special_points.back();
  REQUIRE(end.vanishing_impact >= 0);
  // Independently: P(15,6), from the seed past the end, continued to its
  // new contact, located by its own clearance.
  std::optional<Branch> reduced;
  for (const GrazingSeed& seed : SeedsAtGrazing(system, doubled, end, options)) {
    PeriodicOrbit orbit;
    if (seed.orbit.p != 15 || FindOrbit(seed.system, seed.eta, seed.orbit, &orbit).termination !=
                                  Termination::kConverged) {
      continue;
    }
    reduced = ContinueBranch({seed.system, orbit, {}}, Options(1.25, 1.29, 15, 6));
  }
  REQUIRE(reduced.has_value());
  const SpecialPoint* contact = Find(*reduced, SpecialPointType::kGrazing, 1.2579, 1.2581);
  REQUIRE(contact != nullptr);
  CHECK(contact->vanishing_impact < 0);
  CHECK(std::abs(contact->parameter - end.parameter) < 1e-9);
}

TEST_CASE("a range's ends may come in either order", "[continuation]") {
  const System system = PaperSystem(1.2);
  const PeriodicOrbit orbit = Orbit(system, 1, 1);
  const Branch ordered = ContinueBranch({system, orbit, {}}, Options(1.1, 1.3, 1, 1));
  const Branch reversed = ContinueBranch({system, orbit, {}}, Options(1.3, 1.1, 1, 1));
  REQUIRE(ordered.points.size() == reversed.points.size());
  for (std::size_t k = 0; k < ordered.points.size(); ++k) {
    CHECK(ordered.points[k].parameter == reversed.points[k].parameter);
  }
  CHECK(ordered.points.front().parameter == Approx(1.1).margin(1e-12));
  CHECK(ordered.points.back().parameter == Approx(1.3).margin(1e-12));
}

TEST_CASE("continuation: bad input is rejected with a clear error", "[continuation]") {
  const System system = PaperSystem(1.2);
  const PeriodicOrbit orbit = Orbit(system, 1, 1);
  auto in = [](const std::string& name, double lower, double upper) {
    ContinuationOptions options = Options(lower, upper, 1, 1);
    options.parameter = name;
    return options;
  };
  CHECK_THROWS_WITH(ContinueBranch({system, orbit, {}}, in("frequency", 1.0, 1.5)),
                    Catch::Contains("frequency"));
  CHECK_THROWS_WITH(ContinueBranch({system, orbit, {}}, in("n", 1.0, 1.5)),
                    Catch::Contains("integer"));
  ContinuationOptions options = Options(1.5, 1.5, 1, 1);
  CHECK_THROWS_WITH(ContinueBranch({system, orbit, {}}, options),
                    Catch::Contains("two finite, different ends"));
  options = Options(1.3, 1.5, 1, 1);
  CHECK_THROWS_WITH(ContinueBranch({system, orbit, {}}, options),
                    Catch::Contains("outside the bounds"));
  CHECK_THROWS_WITH(ContinueBranch({system, orbit, {}}, in("r", 0.5, 1.5)),
                    Catch::Contains("not valid"));
  PeriodicOrbit off = orbit;
  off.eta(1) += 1e-3;
  CHECK_THROWS_WITH(ContinueBranch({system, off, {}}, Options(1.0, 1.5, 1, 1)),
                    Catch::Contains("not a P(1,1) orbit"));
}

TEST_CASE(
    "continuation: any parameter — the branch in r and in xs agrees with FindOrbit at "
    "the bound",
    "[continuation]") {
  const System system = PaperSystem(1.2);
  const PeriodicOrbit start = Orbit(system, 1, 1);
  for (const auto& [name, to] :
       {std::pair{std::string("r"), 0.9}, std::pair{std::string("xs"), 0.15}}) {
    INFO(name);
    ContinuationOptions options =
        Options(GetParameter(system, name), to, 1, 1, ContinuationDirection::kIncreasing);
    options.parameter = name;
    const Branch branch = ContinueBranch({system, start, {}}, options);
    REQUIRE(branch.end == Termination::kParameterBound);
    const BranchPoint& end = branch.points.back();
    CHECK(end.parameter == to);
    // An independent solve at the bound from the start orbit's seed.
    PeriodicOrbit orbit;
    REQUIRE(FindOrbit(At(system, name, to), start.eta, OrbitOptions{}, &orbit).termination ==
            Termination::kConverged);
    CHECK(std::abs(orbit.impacts[0].velocity - end.orbit.impacts[0].velocity) < 1e-9);
    CHECK(std::abs(std::remainder(orbit.impacts[0].phase - end.orbit.impacts[0].phase,
                                  system.ForcingPeriod())) < 1e-9);
  }
}

TEST_CASE("test functions vanish at their bifurcations and names round-trip", "[continuation]") {
  // D P with multipliers λ1, λ2 (upper triangular): fold test (λ1-1)(λ2-1),
  // period-doubling test (λ1+1)(λ2+1), Neimark–Sacker test λ1 λ2 - 1.
  auto tests_of = [](double l1, double l2) {
    Eigen::Matrix2d dp;
    dp << l1, 0.3, 0.0, l2;
    Eigen::VectorXcd multipliers(2);
    multipliers << l1, l2;
    return EvaluateBifurcationTests(dp, multipliers);
  };
  const auto values = tests_of(0.5, -0.25);
  CHECK_THAT(values[0], Catch::Matchers::WithinAbs((0.5 - 1) * (-0.25 - 1), 1e-15));
  CHECK_THAT(values[1], Catch::Matchers::WithinAbs((0.5 + 1) * (-0.25 + 1), 1e-15));
  CHECK_THAT(values[2], Catch::Matchers::WithinAbs(0.5 * -0.25 - 1, 1e-15));
  CHECK_THAT(tests_of(1.0, 0.2)[0], Catch::Matchers::WithinAbs(0.0, 1e-15));
  CHECK_THAT(tests_of(-1.0, 0.2)[1], Catch::Matchers::WithinAbs(0.0, 1e-15));
  // A rotation by 0.7 rad: a complex pair on the unit circle.
  Eigen::Matrix2d rotation;
  rotation << std::cos(0.7), -std::sin(0.7), std::sin(0.7), std::cos(0.7);
  const Eigen::VectorXcd pair = rotation.eigenvalues();
  CHECK_THAT(EvaluateBifurcationTests(rotation, pair)[2], Catch::Matchers::WithinAbs(0.0, 1e-14));
  const TestFunction& ns = BifurcationTests()[2];
  CHECK(ns.type == SpecialPointType::kNeimarkSacker);
  CHECK(ns.distance(std::polar(1.0, 0.7)) < 1e-15);
  CHECK(ns.distance(std::complex<double>(2.0, 0.0)) > ns.max_distance);  // real: a neutral saddle
  for (SpecialPointType type : {SpecialPointType::kFold, SpecialPointType::kPeriodDoubling,
                                SpecialPointType::kNeimarkSacker, SpecialPointType::kGrazing,
                                SpecialPointType::kSticking}) {
    CHECK(SpecialPointTypeFromName(ToString(type)) == type);
  }
  CHECK_FALSE(SpecialPointTypeFromName("cusp").has_value());
}

namespace {

/// A point of a model curve for the zero locator: only where it is.
struct ModelPoint {
  double arclength = 0.0;
};

}  // namespace

TEST_CASE(
    "the zero locator corrects a trial the corrector cannot reach from the bracket's start nearer "
    "the bracket's end",
    "[continuation]") {
  // tanh(4 (s - 0.55)) on [0, 1], zero at s = 0.55; the model corrector
  // converges only within `reach` of the point it starts from. The first
  // secant trial, s = 0.508, lies 0.49 from either end.
  const auto value = [](const ModelPoint& point) {
    return std::tanh(4.0 * (point.arclength - 0.55));
  };
  const ModelPoint a{0.0}, b{1.0};
  for (double reach : {1.0, 0.3, 0.04}) {
    const auto advance = [reach](const ModelPoint& from, double s) -> std::optional<ModelPoint> {
      if (std::abs(s) > reach) return std::nullopt;
      return ModelPoint{from.arclength + s};
    };
    CHECK_THAT(IllinoisZero(a, b, advance, value).arclength,
               Catch::Matchers::WithinAbs(0.55, 1e-13));
  }
  // Out of reach even after kTrialRetreats halvings: the nearer end in value.
  const auto nowhere = [](const ModelPoint&, double) -> std::optional<ModelPoint> {
    return std::nullopt;
  };
  CHECK(IllinoisZero(a, b, nowhere, value).arclength == 1.0);
}

namespace {

/// A point of a model branch for the monitor approach: where it is, and
/// an orbit whose largest multiplier (the approach's conditioning) is 1.
struct ModelBranchPoint {
  explicit ModelBranchPoint(double s) : arclength(s) {}
  double arclength;
  struct {
    Eigen::VectorXcd multipliers = Eigen::VectorXcd::Ones(1);
  } orbit;
};

}  // namespace

TEST_CASE(
    "the monitor approach reaches a zero before the corrector's failures and stops early at one "
    "beyond them",
    "[continuation]") {
  // A clearance 1 - s along the branch, zero at s = 1, from points at
  // s = 0 and 0.1; the model corrector fails beyond s = wall.
  using detail::Monitor;
  const auto monitor = [](const ModelBranchPoint& point, Monitor) -> std::optional<double> {
    return 1.0 - point.arclength;
  };
  const auto never = [](const ModelBranchPoint&) { return false; };
  const ModelBranchPoint a(0.0), b(0.1);
  int trials = 0;
  const auto corrector_to = [&trials](double wall) {
    return [&trials, wall](const ModelBranchPoint& from, double s,
                           double) -> std::optional<ModelBranchPoint> {
      ++trials;
      if (from.arclength + s > wall) return std::nullopt;
      return ModelBranchPoint(from.arclength + s);
    };
  };
  std::vector<ModelBranchPoint> path;
  // Wall at 1.5: the secant reaches the zero.
  const auto reached =
      detail::ApproachMonitorZero(a, b, Monitor::kClearance, monitor, corrector_to(1.5), 1.0,
                                  detail::kEventReach, never, &path);
  REQUIRE(reached.has_value());
  CHECK_THAT(reached->best.arclength, Catch::Matchers::WithinAbs(1.0, 1e-12));
  // Wall at 0.3: trials at 1.0, 0.55 and 0.325 fail (each step half the
  // last), and the monitor cannot fall below 0.7 before the wall: stop.
  // Creeping up to the wall by halvings, as the approach did before, took
  // 44 trials.
  trials = 0;
  path.clear();
  const auto stopped =
      detail::ApproachMonitorZero(a, b, Monitor::kClearance, monitor, corrector_to(0.3), 1.0,
                                  detail::kEventReach, never, &path);
  REQUIRE(stopped.has_value());
  CHECK(trials == 3);
  CHECK(path.empty());
  CHECK_THAT(stopped->linear, Catch::Matchers::WithinAbs(0.9, 1e-15));
}

TEST_CASE(
    "continuation: a vanishing impact is located by its defining equation where the slope "
    "is small",
    "[continuation]") {
  // N = 1, m = 2, k = 3, c = 0.1, A = 1.2, xs = 0.05, r = 0.75: the P(1,1)
  // impact vanishes where the non-impacting amplitude |A / (k − mΩ² + icΩ)|
  // equals xs. The depth alone left an error of 3.4e-4 here.
  const System system = GeneralSystem(
      Eigen::MatrixXd::Constant(1, 1, 2.0), Eigen::MatrixXd::Constant(1, 1, 0.1),
      Eigen::MatrixXd::Constant(1, 1, 3.0), Eigen::VectorXd::Constant(1, 1.2), 1.5, 0.05, 0.75);
  const Branch branch = ContinueBranch({system, Orbit(system, 1, 1), {}},
                                       Options(1.5, 6.0, 1, 1, ContinuationDirection::kIncreasing));
  REQUIRE(branch.end == Termination::kGrazing);
  const SpecialPoint& end = branch.special_points.back();
  REQUIRE(end.vanishing_impact == 0);
  auto excess = [](double w) {  // amplitude − xs, closed form
    return 1.2 / std::abs(std::complex<double>(3.0 - 2.0 * w * w, 0.1 * w)) - 0.05;
  };
  double lo = 3.0, hi = 4.5;
  REQUIRE((excess(lo) > 0) != (excess(hi) > 0));
  for (int k = 0; k < 200; ++k)
    ((excess(0.5 * (lo + hi)) > 0) == (excess(lo) > 0) ? lo : hi) = 0.5 * (lo + hi);
  CHECK_THAT(end.parameter, Catch::Matchers::WithinAbs(lo, 1e-9));
  CHECK_THAT(lo, Catch::Matchers::WithinAbs(3.674043252, 1e-9));
}

TEST_CASE("continuation: a doubled branch ends where it meets the orbit it doubled, walked once",
          "[continuation]") {
  // P(2,2) from Ω = 1.7 down: it meets P(1,1) traversed twice at P(1,1)'s
  // period doubling; beyond, it would walk its own orbits again with the
  // impacts renumbered (the same period doubling found twice).
  const System system = PaperSystem(1.7);
  const Branch p22 = ContinueBranch({system, Orbit(system, 2, 2), {}},
                                    Options(1.6, 1.7, 2, 2, ContinuationDirection::kDecreasing));
  REQUIRE(p22.end == Termination::kBranchPoint);
  const SpecialPoint& meet = p22.special_points.back();
  CHECK(meet.type == SpecialPointType::kBranchPoint);
  int doublings = 0;
  for (const SpecialPoint& s : p22.special_points) {
    doublings += s.type == SpecialPointType::kPeriodDoubling;
    CHECK(s.type != SpecialPointType::kFold);
  }
  CHECK(doublings == 1);
  // Independently: P(1,1)'s own period doubling, by its own branch.
  const System at_14 = PaperSystem(1.4);
  const Branch p11 = ContinueBranch({at_14, Orbit(at_14, 1, 1), {}},
                                    Options(1.4, 1.7, 1, 1, ContinuationDirection::kIncreasing));
  const SpecialPoint* pd = Find(p11, SpecialPointType::kPeriodDoubling, 1.6, 1.62);
  REQUIRE(pd != nullptr);
  CHECK_THAT(meet.parameter, Catch::Matchers::WithinAbs(pd->parameter, 1e-8));
  CHECK(PrimitivePeriod(ImpactMap(At(system, "omega", meet.parameter)), meet.point.orbit.eta, 2, 2,
                        1e-6)
            .p == 1);

  // Started on P(1,1) traversed twice, the branch is followed as P(1,1).
  PeriodicOrbit twice;
  OrbitOptions as_p22;
  as_p22.p = as_p22.q = 2;
  REQUIRE(FindOrbit(at_14, Orbit(at_14, 1, 1).eta, as_p22, &twice).termination ==
          Termination::kConverged);
  const Branch relabelled = ContinueBranch(
      {at_14, twice, {}}, Options(1.4, 1.5, 2, 2, ContinuationDirection::kIncreasing));
  CHECK(relabelled.p == 1);
  CHECK(relabelled.q == 1);
}

namespace {

/// The orbit P(p, q) of the paper's system at Ω = `omega`, from `eta`.
std::pair<System, PeriodicOrbit> PaperOrbit(double omega, int p, int q,
                                            const std::vector<double>& eta) {
  const System system = PaperSystem(omega);
  OrbitOptions options;
  options.p = p;
  options.q = q;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, Eigen::Map<const Eigen::VectorXd>(eta.data(), 4), options, &orbit)
              .termination == Termination::kConverged);
  return {system, orbit};
}

/// The branch doubled at the period doubling of `branch` in (low, high),
/// followed over [from, to] from its start.
Branch DoubledBranchIn(const System& system, const Branch& branch, double low, double high,
                       double from, double to) {
  const ContinuationOptions single = Options(from, to, branch.p, branch.q);
  const BranchStart start = DoubledStartIn(system, branch, low, high, single);
  return ContinueBranch(
      start, Options(from, to, 2 * branch.p, 2 * branch.q, ContinuationDirection::kIncreasing));
}

/// P(22,32) from P(11,16)'s period doubling at Ω = 1.823650395, on
/// [1.8233, 1.8240]. P(11,16)'s η there is recorded from `impactkit
/// diagram --from 0.4 --to 2.3 --sweep-values 2401`.
Branch P22From11() {
  const auto [system, orbit] = PaperOrbit(
      1.8236503947508154, 11, 16,
      {-0.13666513885904719, 2.5766773629696536, -0.882694199276055, 0.054331278310384146});
  const Branch p11 = ContinueBranch({system, orbit, {}}, Options(1.8233, 1.8240, 11, 16));
  return DoubledBranchIn(system, p11, 1.82364, 1.82366, 1.8233, 1.8240);
}

/// The period doubling of `branch` in (low, high), required, and checked
/// independently: orbits found by Newton (FindOrbit) `offset` either side
/// of it, from its orbit, have their real multiplier nearest -1 on either
/// side of -1 (and within 0.1 of it: a long orbit's moves by 4e-3 there).
const SpecialPoint& CheckedPeriodDoubling(const Branch& branch, double low, double high,
                                          double offset = 1e-7) {
  const SpecialPoint* pd = Find(branch, SpecialPointType::kPeriodDoubling, low, high);
  REQUIRE(pd != nullptr);
  double sides = 1.0;
  for (double shift : {-offset, offset}) {
    const std::complex<double> lambda =
        testing::RecomputedMultiplier(At(PaperSystem(1.0), "omega", pd->parameter + shift),
                                      branch.p, branch.q, pd->point.orbit.eta, -1.0);
    CHECK(lambda.imag() == 0.0);
    CHECK(std::abs(lambda + 1.0) < 0.1);
    sides *= lambda.real() + 1.0;
  }
  CHECK(sides < 0);
  return *pd;
}

}  // namespace

TEST_CASE(
    "continuation: a doubled branch whose first step lands on the orbit it doubled goes on to "
    "its own period doubling (P(22,32) from P(11,16) near 1.8237)",
    "[continuation]") {
  // The doubled branch starts 1e-3 from P(11,16)'s doubling; its first
  // step (0.01) landed on P(11,16) traversed twice, which solves
  // P(22,32)'s equations too, and the branch ended there at a branch point:
  // its own period doubling, behind it. It goes down in Ω to P(22,32)'s
  // period doubling, at 1.823387967 in the 2401-value run, whose P(22,32)
  // branch started differently.
  const Branch p22 = P22From11();
  CHECK(p22.end != Termination::kBranchPoint);
  REQUIRE(p22.points.size() > 2);
  const SpecialPoint& pd = CheckedPeriodDoubling(p22, 1.8233, 1.8236);
  CHECK_THAT(pd.parameter, Catch::Matchers::WithinAbs(1.823387967, 1e-8));
}

TEST_CASE(
    "continuation: where one side of a period doubling's flip eigenvector corrects onto the "
    "orbit it doubles, the doubled branch starts on the other (P(44,64) from P(22,32) near "
    "1.8234)",
    "[continuation]") {
  // At P(22,32)'s period doubling the hyperplane 1e-3 along the flip
  // eigenvector cuts P(22,32)'s own branch 2e-5 away in Ω (its η moves
  // fast with Ω), and the corrector landed there: no start, and no
  // P(44,64). The other side is the mirror half, the same orbits. The
  // branch goes down to P(44,64)'s period doubling, at 1.823339173 in the
  // 2401-value run.
  const Branch p22 = P22From11();
  const SpecialPoint& pd = CheckedPeriodDoubling(p22, 1.8233, 1.8236);
  const System system = At(PaperSystem(1.0), "omega", pd.parameter);
  const std::optional<BranchStart> start =
      DoubledBranchStart(system, p22, pd, Options(1.8233, 1.8240, 22, 32));
  REQUIRE(start.has_value());
  const ImpactMap map(start->system);
  CHECK(PrimitivePeriod(map, start->orbit.eta, 44, 64, 1e-6).p == 44);
  const Branch p44 =
      ContinueBranch(*start, Options(1.8233, 1.8240, 44, 64, ContinuationDirection::kIncreasing));
  CHECK(p44.end != Termination::kBranchPoint);
  const SpecialPoint& doubling = CheckedPeriodDoubling(p44, 1.8233, 1.82338);
  CHECK_THAT(doubling.parameter, Catch::Matchers::WithinAbs(1.823339173, 1e-8));
}

TEST_CASE(
    "continuation: a period doubling in the same step as a multiplier passing through infinity "
    "is located (P(88,128) from P(44,64) near 1.8233288)",
    "[continuation]") {
  // P(88,128)'s one multiplier not near 0 goes from 0.16 through -1 and
  // round through infinity to 14.95 within a step (to Ω = 1.8232682):
  // det(DP + I) flips twice and keeps its sign, det(DP - I) flips once
  // with no multiplier at +1. The period doubling is at 1.823328809 in the
  // 2401-value run.
  const System system = PaperSystem(1.8234);
  const Branch p44 = DoubledBranchIn(system, P22From11(), 1.8233, 1.8236, 1.8233, 1.8240);
  const Branch p88 = DoubledBranchIn(system, p44, 1.8233, 1.82338, 1.8229, 1.8240);
  const SpecialPoint& pd88 = CheckedPeriodDoubling(p88, 1.82332, 1.823335, 1e-8);
  CHECK_THAT(pd88.parameter, Catch::Matchers::WithinAbs(1.823328809, 1e-8));
}

namespace {

/// P(32,16)'s period doubling, and its η there, recorded from `impactkit
/// diagram --from 0.4 --to 2.3`.
constexpr double kP32Doubling = 1.6872142162694004;
const std::vector<double> kP32Eta = {0.48584608421134295, 2.094147020164269, -1.2768061120898602,
                                     0.06425237069170288};

/// The branch doubled at the period doubling within `window` of Ω =
/// `omega` of the paper's P(p,q) (η `eta` at `omega`), both branches traced
/// on [omega - 8e-4, omega + 8e-4].
Branch DoubledPaperBranch(double omega, int p, int q, const std::vector<double>& eta,
                          double window) {
  const auto [system, orbit] = PaperOrbit(omega, p, q, eta);
  const Branch single =
      ContinueBranch({system, orbit, {}}, Options(omega - 8e-4, omega + 8e-4, p, q));
  return DoubledBranchIn(system, single, omega - window, omega + window, omega - 8e-4,
                         omega + 8e-4);
}

/// The doubled branch born at the period doubling of the paper's P(p,q)
/// (η `eta` there, at Ω = `omega`), traced on [omega - 8e-4, omega + 8e-4]:
/// it goes on, each of its points a primitive P(2p,2q) (the repeat checked
/// again by the orbit's own map), as is the orbit Newton (FindOrbit) finds
/// again at its far end, which lies below `below`.
void CheckDoubledGoesOn(double omega, int p, int q, const std::vector<double>& eta, double below) {
  const System system = PaperSystem(omega);
  const Branch doubled = DoubledPaperBranch(omega, p, q, eta, 1e-5);
  CHECK(doubled.end != Termination::kBranchPoint);
  REQUIRE(doubled.points.size() > 2);
  for (const BranchPoint& point : doubled.points) {
    const ImpactMap map(At(system, "omega", point.parameter));
    CHECK(PrimitivePeriod(map, point.orbit.eta, 2 * p, 2 * q, 1e-6).p == 2 * p);
  }
  const BranchPoint& last = doubled.points.back();
  CHECK(last.parameter < below);
  OrbitOptions options;
  options.p = 2 * p;
  options.q = 2 * q;
  PeriodicOrbit again;
  REQUIRE(
      FindOrbit(At(system, "omega", last.parameter), last.orbit.eta, options, &again).termination ==
      Termination::kConverged);
  CHECK((again.eta - last.orbit.eta).norm() < 1e-6);
  CHECK(
      PrimitivePeriod(ImpactMap(At(system, "omega", last.parameter)), again.eta, 2 * p, 2 * q, 1e-6)
          .p == 2 * p);
}

}  // namespace

TEST_CASE(
    "continuation: deep in a period-doubling cascade the doubled branch starts nearer its "
    "doubling, leaving it (P(64,32) from P(32,16) near 1.6872142)",
    "[continuation]") {
  // P(4,2), P(8,4), P(16,8) and P(32,16) double at 1.68779, 1.68735,
  // 1.687239 and 1.6872142: intervals shrinking ~4.6-fold, so P(64,32)
  // doubles again ~5e-6 below. 1e-3 along the flip eigenvector is past that
  // stretch: there the corrector failed, or (in the connected diagram)
  // landed on a P(64,32) from which the first step ran back across the
  // doubling onto P(32,16) twice, a branch point. The start nearer the
  // doubling goes down in Ω.
  CheckDoubledGoesOn(kP32Doubling, 32, 16, kP32Eta, 1.6871);
}

TEST_CASE(
    "continuation: a period doubling within a doubled branch's first step is located although "
    "the branch bends too sharply there for the secant's trial (P(64,32) near 1.6872089)",
    "[continuation]") {
  // P(64,32)'s multiplier goes from +1 at its birth to -1 within its first
  // step (det(DP + I) from 1.96 to -4.87 in the connected diagram), where
  // μ goes like the square of the distance from the birth: the corrector
  // did not converge from the tangent prediction of the Illinois method's
  // first trial, and the doubling was not located. The cascade's intervals
  // (shrinking ~4.6-fold) put it ~5e-6 below P(32,16)'s.
  const Branch doubled = DoubledPaperBranch(kP32Doubling, 32, 16, kP32Eta, 1e-5);
  CheckedPeriodDoubling(doubled, kP32Doubling - 1e-5, kP32Doubling - 1e-6);
}

TEST_CASE(
    "continuation: a period doubling 1.4e-7 from the doubled branch's birth is located (P(40,32) "
    "near 1.706015066)",
    "[continuation]") {
  // In the connected diagram the bracketing's best point had its
  // multiplier 2e-9 from -1 and the critical-point solve from it (holding
  // σ only to Newton's tolerance) 2.5e-7, beyond what a period doubling is
  // kept with (1e-7): the doubling was dropped, and the better of the two
  // is taken now. From this start the two are 9e-9 and 1.0e-8, so this
  // test checks the doubling, not that choice. P(20,16)'s η at its
  // doubling is recorded from `impactkit diagram --from 0.4 --to 2.3`.
  const double omega = 1.7060152029582736;
  const Branch doubled = DoubledPaperBranch(
      omega, 20, 16,
      {0.13801249708723845, 2.3536190353919482, -1.3356317999160379, 0.066517585321108588}, 1e-6);
  // Newton either side near enough for the multiplier, which moves by 0.3
  // in 2e-8 there (1e-7 away Newton lands on orbits with no multiplier
  // near -1).
  CheckedPeriodDoubling(doubled, omega - 1e-6, omega, 5e-9);
}

TEST_CASE(
    "continuation: a branch whose corrector fails above its tolerance's rounding floor says so, "
    "and Newton solves its last orbit again (P(6,4) from P(3,2) near 1.6837)",
    "[continuation]") {
  // P(6,4), doubled from P(3,2) at 1.680313472, ends `corrector_failed`
  // near 1.683711 with multipliers of ~3000: its refused solves stop at
  // max |U| 1e-11 to 4e-11, above the corrector's 1e-11 and below U's
  // rounding floor (4.4e-10). The family goes on (docs/continuation.md,
  // Known limits): a fresh FindOrbit there converges. P(3,2)'s η at its
  // doubling is recorded from `impactkit diagram --from 0.4 --to 2.3`.
  const double omega = 1.680313471517176;
  const auto [system, orbit] = PaperOrbit(
      omega, 3, 2,
      {0.11864031853455775, 2.2816397812312026, -1.4930689187935309, 0.17652571087642485});
  const Branch single = ContinueBranch({system, orbit, {}}, Options(1.6800, 1.6806, 3, 2));
  const Branch doubled = DoubledBranchIn(system, single, omega - 1e-6, omega + 1e-6, 1.6803, 1.69);
  REQUIRE(doubled.end == Termination::kCorrectorFailed);
  CHECK_THAT(doubled.end_message, Catch::Matchers::Contains("rounding floor"));
  const BranchPoint& last = doubled.points.back();
  OrbitOptions options;
  options.p = 6;
  options.q = 4;
  PeriodicOrbit again;
  REQUIRE(
      FindOrbit(At(system, "omega", last.parameter), last.orbit.eta, options, &again).termination ==
      Termination::kConverged);
  CHECK((again.eta - last.orbit.eta).norm() < 1e-6);
  CHECK(ResidualFloor(again.jacobian, again.eta) > 10 * NewtonOptions{}.residual_tolerance);
}

TEST_CASE(
    "continuation: a step onto the orbit it doubled started from another of its impacts is no "
    "branch point (P(36,16) from P(18,8) near 1.6848)",
    "[continuation]") {
  // P(18,8), born near P(9,4) traversed twice, has its impacts 0 and 9
  // close. A step of the doubled branch from its start landed on P(18,8)
  // twice, and the orbit's meeting point, located by secant steps on
  // P(18,8)'s det(DP + I), was its period doubling started from impact 9:
  // ahead of the start, 1.3e-2 away from it for a step of 5e-3, and the
  // branch ended there. It goes down in Ω (to 1.684603 when written).
  // P(18,8)'s η at its doubling is recorded from `impactkit diagram --from
  // 0.4 --to 2.3`, as is P(20,16)'s below.
  CheckDoubledGoesOn(
      1.6848320037472346, 18, 8,
      {0.2270529211123809, 2.2831689766573504, -1.439545545814765, 0.02390468639651502}, 1.68463);
}

TEST_CASE(
    "continuation: a doubled branch leaving the orbit it doubled passes no branch point (P(40,32) "
    "from P(20,16) near 1.7229)",
    "[continuation]") {
  // The first step from the start landed on P(20,16) twice 4.3e-5 higher
  // in Ω, where secant steps on P(20,16)'s det(DP + I) found a zero beside
  // the step, near where P(20,16) itself is born from P(10,8): ahead of
  // the start and on the step's stretch, and the branch ended there. At its
  // start the branch leaves P(20,16) (its repeat gap grows), so it cannot
  // meet it within a step. It goes down in Ω (to 1.722599 when written).
  CheckDoubledGoesOn(
      1.7229064964213758, 20, 16,
      {0.1304281918447981, 2.3663635415366597, -1.2588010212966088, 0.06354957847962905}, 1.72263);
}

TEST_CASE("continuation: a bound at the end of the parameter's range (r = 1) is reached",
          "[continuation]") {
  const System system = PaperSystem(1.2);
  ContinuationOptions options = Options(0.7, 1.0, 1, 1, ContinuationDirection::kIncreasing);
  options.parameter = "r";
  const Branch branch = ContinueBranch({system, Orbit(system, 1, 1), {}}, options);
  CHECK(branch.end == Termination::kParameterBound);
  CHECK(branch.points.back().parameter == 1.0);
  // The end point is an orbit at r = 1 (a fresh solve converges to it).
  PeriodicOrbit fresh;
  OrbitOptions orbit_options;
  REQUIRE(FindOrbit(At(system, "r", 1.0), branch.points.back().orbit.eta, orbit_options, &fresh)
              .termination == Termination::kConverged);
  CHECK((fresh.eta - branch.points.back().orbit.eta).cwiseAbs().maxCoeff() < 1e-8);
}

TEST_CASE(
    "continuation: a period-doubling sign change the locator cannot account for is reported with "
    "the step that holds it (P(160,128) near 1.70601503)",
    "[continuation]") {
  // Doubled from P(80,64) at its period doubling (η recorded from `impactkit
  // diagram --from 0.4 --to 2.3`), P(160,128) doubles again ~7e-9 below
  // (the cascade's intervals shrink ~4.7-fold). There its orbits are at
  // their rounding floor (1.2e-11, above the corrector's 1e-11; the branch
  // ends `corrector_failed` 1e-7 beyond), and the doubling is located
  // neither over the step nor in its eighths. Before, it was dropped
  // silently; now the step is in Branch::unlocated.
  const double omega = 1.7060150349934093;
  const Branch doubled = DoubledPaperBranch(
      omega, 80, 64,
      {0.13809216395673257, 2.353563004550682, -1.3356099128280987, 0.06652775885643308}, 1e-6);
  CHECK(Find(doubled, SpecialPointType::kPeriodDoubling, omega - 1e-6, omega) == nullptr);
  REQUIRE(doubled.unlocated.size() == 1);
  const UnlocatedZero& step = doubled.unlocated.front();
  CHECK(step.type == SpecialPointType::kPeriodDoubling);
  CHECK(step.Describe("omega").starts_with("period doubling not located between omega = "));
  // Independently: the cascade's intervals shrink by Feigenbaum's δ =
  // 4.6692 (4.4 to 5.1 over this one), so from P(40,32)'s and P(80,64)'s
  // doublings P(160,128)'s lies 6.6e-9 below P(80,64)'s, to ~1e-9. (The
  // connected diagram's own P(160,128), traced from another start, locates
  // it at 1.7060150284.)
  const double p40_doubling = 1.706015065643547;
  const double predicted = omega - (p40_doubling - omega) / 4.6692;
  CHECK(std::min(step.from, step.to) - 1e-9 < predicted);
  CHECK(predicted < std::max(step.from, step.to) + 1e-9);
}
