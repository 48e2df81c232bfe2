// Fold curves that end where their orbit's flight touches the stop (a
// fold–grazing corner by a new contact): the N = 1 oscillator's against
// the closed form, the paper's P(3,1) and its chatter orbit P(8,1)'s
// against one-parameter branches.

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "closed_form_sdof.hpp"
#include "curve_plane.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/model/parameters.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"
#include "touching_vertex.hpp"

using namespace impactkit;
using testing::At;
using testing::SdofParameters;

namespace {

/// A fold–grazing corner, its residuals at the curves' tolerances.
void CheckFoldGrazing(const Codim2Point& corner) {
  CHECK(corner.type == Codim2Type::kFoldGrazing);
  CHECK(corner.defining_residual < 1e-10);
  CHECK(corner.second_residual < 1e-9);
}

/// The stop position xs < 0 at which the closed form's P(1,1) speeds,
/// qa u² + 2 xs d1 u + xs² − X² = 0 (closed_form_sdof.hpp), have a double
/// root at p.omega: xs² (qa − d1²) = qa X². (d and X do not depend on xs.)
double FoldStop(const SdofParameters& p) {
  const Eigen::Vector2d d = testing::SdofImpactDirection(p);
  const double qa = d(0) * d(0) + d(1) * d(1) / (p.omega * p.omega);
  const double x = p.SteadyAmplitude();
  return -std::sqrt(qa * x * x / (qa - d(0) * d(0)));
}

/// The fold orbit at p.omega with the stop at FoldStop: the double root
/// u = −xs d1 / qa.
testing::SdofP11 FoldOrbit(SdofParameters* p) {
  p->xs = FoldStop(*p);
  const Eigen::Vector2d d = testing::SdofImpactDirection(*p);
  const double qa = d(0) * d(0) + d(1) * d(1) / (p->omega * p->omega);
  return testing::SdofP11WithSpeed(*p, -p->xs * d(0) / qa);
}

/// xs minus the highest interior maximum of x over the orbit's flight (the
/// flight starts and ends on the stop, so only maxima with v = 0 count):
/// sampled, then each sign change of v from + to − bisected to 1e-15.
double FlightClearance(const SdofParameters& p, const testing::SdofP11& o) {
  const Eigen::Vector2d start(p.xs, -p.r * o.u);
  auto state = [&](double t) { return testing::SdofFlight(p, o.tau, start, t); };
  constexpr int kSamples = 4000;
  const double period = p.Period();
  double highest = -1e300;
  for (int i = 1; i < kSamples; ++i) {
    double lo = o.tau + period * (i - 1) / kSamples, hi = o.tau + period * i / kSamples;
    if (!(state(lo)(1) > 0.0 && state(hi)(1) <= 0.0)) continue;
    while (hi - lo > 1e-15 * hi) {
      const double mid = 0.5 * (lo + hi);
      (state(mid)(1) > 0.0 ? lo : hi) = mid;
    }
    highest = std::max(highest, state(lo)(0));
  }
  return p.xs - highest;
}

}  // namespace

TEST_CASE(
    "contact corner: the N = 1 oscillator's P(1,1) fold curve in (omega, xs) below the rest "
    "position ends where its flight touches the stop, at the closed form's corner",
    "[curve][contact-corner]") {
  // The fold at xs = −0.2 (near omega = 2.167) followed up in xs: its
  // flight's maximum rises to the stop near omega = 2.0395, xs = −0.1632,
  // before its impact could vanish (at omega = 2 ω_d, xs = −X).
  const System system =
      UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), 2.3, -0.2, 0.7);
  SdofParameters p{1.0, 1.0, 0.1, 0.5, -0.2, 0.7, 2.3};
  const std::vector<testing::SdofP11> roots = testing::SdofP11Solutions(p);
  REQUIRE(roots.size() == 2);
  OrbitOptions orbit_options;
  PeriodicOrbit orbit;
  REQUIRE(FindOrbit(system, Eigen::Vector2d(roots[0].tau, roots[0].u), orbit_options, &orbit)
              .termination == Termination::kConverged);
  ContinuationOptions search;
  search.from = 1.5;
  search.to = 3.0;
  const std::optional<SpecialPoint> fold =
      LocateSpecialPoint({system, orbit, {}}, search, SpecialPointType::kFold);
  REQUIRE(fold.has_value());
  const Curve curve = ContinueCurve({At(system, "omega", fold->parameter), *fold},
                                    testing::Plane("xs", -0.4, -0.05, 1, 1));
  REQUIRE(curve.end == Termination::kGrazing);
  REQUIRE(!curve.codim2_points.empty());
  const Codim2Point& corner = curve.codim2_points.back();
  CheckFoldGrazing(corner);

  // Along the curve: the closed form's fold stop at each point's omega.
  for (std::size_t k = 0; k < curve.points.size(); k += curve.points.size() / 8) {
    p.omega = curve.points[k].parameter;
    CHECK(std::abs(FoldStop(p) - curve.points[k].parameter2) < 1e-8);
  }
  // The corner: the fold orbit's clearance, zero by bisection in omega.
  auto clearance = [&](double omega) {
    p.omega = omega;
    const testing::SdofP11 o = FoldOrbit(&p);
    return FlightClearance(p, o);
  };
  double lo = 2.03, hi = 2.05;
  REQUIRE((clearance(lo) > 0) != (clearance(hi) > 0));
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    ((clearance(mid) > 0) == (clearance(lo) > 0) ? lo : hi) = mid;
  }
  p.omega = lo;
  INFO("closed form: omega = " << lo << ", xs = " << FoldStop(p));
  CHECK(std::abs(corner.point.parameter - lo) < 1e-8);
  CHECK(std::abs(corner.point.parameter2 - FoldStop(p)) < 1e-8);
}

namespace {

/// The grazing and the fold nearest `omega` on the P(p,q) branch in omega
/// through `seed`'s orbit, with the paper's `second` parameter at `value`,
/// followed by steps up to `max_step` (either empty if not found).
std::pair<std::optional<double>, std::optional<double>> GrazingAndFold(
    const std::string& second, double value, double omega, const CurvePoint& seed, int p, int q,
    double max_step = ContinuationOptions().max_step) {
  ContinuationOptions branch;
  branch.from = omega - 0.02;
  branch.to = omega + 0.02;
  branch.direction = ContinuationDirection::kBoth;
  branch.orbit.p = p;
  branch.orbit.q = q;
  branch.initial_step = std::min(branch.initial_step, max_step);
  branch.max_step = max_step;
  System at;
  PeriodicOrbit orbit;
  bool found = false;
  for (double shift : {0.0, 1e-4, -1e-4, 1e-3, -1e-3}) {
    at = At(At(PaperSystem(omega), second, value), "omega", seed.parameter + shift);
    found =
        FindOrbit(at, seed.orbit.eta, branch.orbit, &orbit).termination == Termination::kConverged;
    if (found) break;
  }
  std::optional<double> grazing, fold;
  if (!found) return {grazing, fold};
  for (const SpecialPoint& s : ContinueBranch({at, orbit, {}}, branch).special_points) {
    if (s.type != SpecialPointType::kGrazing && s.type != SpecialPointType::kFold) continue;
    std::optional<double>& slot = s.type == SpecialPointType::kGrazing ? grazing : fold;
    if (!slot || std::abs(s.parameter - omega) < std::abs(*slot - omega)) slot = s.parameter;
  }
  return {grazing, fold};
}

/// The fold curve in (omega, `second`) of the P(p,q) branch through
/// `seed`: its fold located in omega in [lower, upper], then followed
/// within those bounds and `second` in [lower2, upper2].
Curve FoldCurve(const System& system, const PeriodicOrbit& seed, int p, int q,
                const std::string& second, double lower2, double upper2, double lower,
                double upper) {
  ContinuationOptions search;
  search.from = lower;
  search.to = upper;
  search.orbit.p = p;
  search.orbit.q = q;
  const std::optional<SpecialPoint> fold =
      LocateSpecialPoint({system, seed, {}}, search, SpecialPointType::kFold);
  REQUIRE(fold.has_value());
  CurveOptions options = testing::Plane(second, lower2, upper2, p, q);
  options.from = lower;
  options.to = upper;
  return ContinueCurve({At(system, "omega", fold->parameter), *fold}, options);
}

}  // namespace

TEST_CASE(
    "contact corner: the paper's P(3,1) fold curve in (omega, A1) ends where a new contact is "
    "born, and one-parameter folds touch that grazing there",
    "[curve][contact-corner]") {
  const System system = PaperSystem(0.44);
  const Curve curve =
      FoldCurve(system, testing::SeededOrbit(system, 3, 1), 3, 1, "A1", 0.05, 3.0, 0.1, 2.0);
  // The tangent's parameter part once jumped sign here, where the σ row was
  // differenced across the new contact: that was reported as a cusp.
  for (const Codim2Point& c : curve.codim2_points) CHECK(c.type != Codim2Type::kCusp);
  REQUIRE(curve.begin == Termination::kGrazing);
  const Codim2Point& corner = curve.codim2_points.front();
  CheckFoldGrazing(corner);
  const double omega_c = corner.point.parameter, a1_c = corner.point.parameter2;
  INFO("corner at omega = " << omega_c << ", A1 = " << a1_c);
  const CurvePoint& seed = curve.points[6];
  // At the corner's A1 the branch in omega grazes at the corner's omega.
  const auto [grazing_c, fold_c] = GrazingAndFold("A1", a1_c, omega_c, seed, 3, 1);
  REQUIRE(grazing_c.has_value());
  CHECK(std::abs(*grazing_c - omega_c) < 1e-8);
  // Below it the branch folds just before it grazes, D(δ) = ω_graze − ω_fold
  // at A1 = a1_c − δ; fitted by a δ + b δ² + c δ³ + d δ⁴, a parabola whose
  // vertex −a / (2b) is where the fold curve touches the grazing curve.
  const std::array<double, 4> deltas{1e-4, 1.5e-4, 2e-4, 3e-4};
  Eigen::Vector4d gaps;
  for (int k = 0; k < 4; ++k) {
    const auto [grazing, fold_near] = GrazingAndFold("A1", a1_c - deltas[k], omega_c, seed, 3, 1);
    REQUIRE(grazing.has_value());
    REQUIRE(fold_near.has_value());
    gaps(k) = *grazing - *fold_near;
  }
  testing::CheckTouchingAtCorner(deltas, gaps, 1e-6);
}

TEST_CASE(
    "contact corner: the paper's chatter orbit P(8,1) has a fold curve in (omega, xs) that ends "
    "where a chatter impact is born, at the grazing of the branch in omega",
    "[curve][contact-corner]") {
  // The seed: a P(8,1) orbit of `impactkit diagram --from 0.3 --to 0.5`
  // near its fold (a guess; the fold is located from the orbit it
  // converges to). Eight impacts per period: the chatter before sticking.
  const System system = PaperSystem(0.3142);
  OrbitOptions orbit;
  orbit.p = 8;
  PeriodicOrbit seed;
  REQUIRE(FindOrbit(system, Eigen::Vector4d(0.35183, 19.7822, 0.11437, 0.24441), orbit, &seed)
              .termination == Termination::kConverged);
  const Curve curve = FoldCurve(system, seed, 8, 1, "xs", 0.0, 0.3, 0.2, 0.6);
  REQUIRE(curve.end == Termination::kGrazing);
  const Codim2Point& corner = curve.codim2_points.back();
  CheckFoldGrazing(corner);
  const double omega_c = corner.point.parameter, xs_c = corner.point.parameter2;
  INFO("corner at omega = " << omega_c << ", xs = " << xs_c);
  // A new contact: the corner orbit's highest flight maximum is at the
  // stop. At its xs the branch in omega grazes at its omega.
  const std::optional<double>& clearance = corner.point.orbit.contacts.clearance;
  REQUIRE(clearance.has_value());
  CHECK(std::abs(*clearance) < 1e-9);
  // Steps of 1e-4: beside these orbits, whose second flight rises to 1e-4
  // below the stop, lie P(8,1) orbits with a slow impact there instead
  // (depth 3e-5, no such maximum); steps of 1e-3 jumped to those and passed
  // the grazing unseen.
  const auto [grazing, fold_c] =
      GrazingAndFold("xs", xs_c, omega_c, curve.points[curve.points.size() - 6], 8, 1, 1e-4);
  REQUIRE(grazing.has_value());
  CHECK(std::abs(*grazing - omega_c) < 1e-8);
}
