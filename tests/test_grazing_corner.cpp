// Where fold and period-doubling curves of P(1,q) reach the curve on which
// the orbit's impact vanishes (orbits/grazing_limit.hpp): the split
// monodromy against the impact map's multipliers, the N = 1 corner against
// the closed form, the paper's corners against one-parameter continuation
// extrapolated to the grazing.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>

#include "closed_form_sdof.hpp"
#include "curve_plane.hpp"
#include "impactkit/continuation/curve.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/grazing_limit.hpp"
#include "impactkit/orbits/grazing_normal_form.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"
#include "touching_vertex.hpp"

using namespace impactkit;
using testing::At;
using testing::Plane;

namespace {

/// The curve of `type` of P(p, q) in (omega, second) through the special
/// point nearest `system`'s omega.
Curve CurveIn(const std::string& second, const System& system, SpecialPointType type, int p, int q,
              double lower2, double upper2) {
  return ContinueCurve(testing::Start(system, type, p, q), Plane(second, lower2, upper2, p, q));
}

/// The curve's located corner, which must be its last point at one end.
const Codim2Point& Corner(const Curve& curve, Codim2Type type) {
  const auto it = std::find_if(curve.codim2_points.begin(), curve.codim2_points.end(),
                               [&](const Codim2Point& c) { return c.type == type; });
  REQUIRE(it != curve.codim2_points.end());
  const bool at_begin =
      curve.begin == Termination::kGrazing && curve.points.front().parameter == it->point.parameter;
  const bool at_end =
      curve.end == Termination::kGrazing && curve.points.back().parameter == it->point.parameter;
  CHECK((at_begin || at_end));
  return *it;
}

/// The paper system's non-impacting amplitude of mass 2, |X_2| for
/// X = (K − Ω²M + iΩC)⁻¹ A, written out for the 2 x 2 chain (A2 = 0).
double PaperAmplitude(double omega) {
  using C = std::complex<double>;
  const double w = omega;
  const C a = 2.0 - w * w + C(0, 0.2 * w), b = -1.0 - C(0, 0.1 * w);
  const C d = 1.0 - w * w + C(0, 0.1 * w);
  return std::abs(-b * 0.5 / (a * d - b * b));
}

/// The paper system's corner of `type` that ends `curve`, checked to lie
/// where the impact vanishes: the response touches the stop there.
const Codim2Point& PaperCorner(const Curve& curve, Codim2Type type) {
  const Codim2Point& corner = Corner(curve, type);
  INFO("corner at omega = " << corner.point.parameter << ", xs = " << corner.point.parameter2);
  CHECK(std::abs(PaperAmplitude(corner.point.parameter) - corner.point.parameter2) < 1e-12);
  return corner;
}

/// Where the paper system's response touches the stop at xs, near omega:
/// PaperAmplitude(ω) = xs by secant steps.
double GrazingOmega(double xs, double omega) {
  double a = omega, b = omega + 1e-6;
  double fa = PaperAmplitude(a) - xs, fb = PaperAmplitude(b) - xs;
  for (int k = 0; k < 50 && fb != 0.0 && std::abs(b - a) > 1e-15; ++k) {
    const double c = b - fb * (b - a) / (fb - fa);
    a = b;
    fa = fb;
    b = c;
    fb = PaperAmplitude(b) - xs;
  }
  return b;
}

/// The paper system's P(p, q) branch in omega (within 0.05 of `omega`) at
/// `second` = value that has a special point of `type`, and that point's
/// omega nearest `omega`; through an orbit found from the seed `eta` at
/// omega or beside it (beside a fold the orbit exists on one side only).
std::pair<Branch, double> BranchWith(const std::string& second, double value, double omega,
                                     const Eigen::VectorXd& eta, int p, int q,
                                     SpecialPointType type) {
  ContinuationOptions options;
  options.from = omega - 0.05;
  options.to = omega + 0.05;
  options.direction = ContinuationDirection::kBoth;
  options.orbit.p = p;
  options.orbit.q = q;
  for (double shift : {0.0, 2e-3, -2e-3, 1e-2, -1e-2}) {
    const System system = At(PaperSystem(omega + shift), second, value);
    PeriodicOrbit orbit;
    // An orbit whose impact is below the arrival resolution (at the corner
    // itself) is no start: the map the branch follows cannot see it.
    const OrbitSummary found = FindOrbit(system, eta, options.orbit, &orbit);
    if (found.termination != Termination::kConverged || found.unresolved_impacts > 0) continue;
    Branch branch = ContinueBranch({system, orbit, {}}, options);
    double best = 1e300;
    for (const SpecialPoint& s : branch.special_points) {
      if (s.type == type && std::abs(s.parameter - omega) < std::abs(best - omega)) {
        best = s.parameter;
      }
    }
    if (best != 1e300) return {std::move(branch), best};
  }
  FAIL("no " << ToString(type) << " found at " << second << " = " << value);
  return {};
}

double OneParameterOmega(const std::string& second, double value, double omega,
                         const Eigen::VectorXd& eta, int p, int q, SpecialPointType type) {
  return BranchWith(second, value, omega, eta, p, q, type).second;
}

/// Lagrange's quadratic through three (x, y) at x = 0.
std::complex<double> QuadraticAtZero(
    const std::array<std::pair<double, std::complex<double>>, 3>& samples) {
  std::complex<double> at_zero = 0.0;
  for (int i = 0; i < 3; ++i) {
    double weight = 1.0;
    for (int j = 0; j < 3; ++j) {
      if (j != i) weight *= samples[j].first / (samples[j].first - samples[i].first);
    }
    at_zero += weight * samples[i].second;
  }
  return at_zero;
}

/// The multiplier of `orbit` nearest `target`.
std::complex<double> Nearest(const PeriodicOrbit& orbit, std::complex<double> target) {
  Eigen::Index k = 0;
  (orbit.multipliers.array() - target).abs().minCoeff(&k);
  return orbit.multipliers(k);
}

/// As a branch's impact vanishes (speed v → 0) its multipliers but one
/// tend to those of the grazing limit (grazing_limit.hpp): the one nearest
/// `target`, extrapolated to v = 0 by the quadratic in √depth ∝ v through
/// the branch's three shallowest points (of distinct depths: the branch
/// repeats its last point), if they lie below √depth 1e-4; else none.
std::optional<std::complex<double>> BranchLimitMultiplier(const Branch& branch,
                                                          std::complex<double> target) {
  std::vector<std::pair<double, std::complex<double>>> samples;  // (√depth, λ)
  for (const BranchPoint& point : branch.points) {
    samples.emplace_back(std::sqrt(point.orbit.contacts.slowest_depth),
                         Nearest(point.orbit, target));
  }
  std::sort(samples.begin(), samples.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::array<std::pair<double, std::complex<double>>, 3> distinct;
  std::size_t count = 0;
  for (const auto& sample : samples) {
    if (count == 3) break;
    if (count == 0 || sample.first > 1.01 * distinct[count - 1].first) distinct[count++] = sample;
  }
  if (count < 3 || distinct[2].first > 1e-4) return std::nullopt;
  return QuadraticAtZero(distinct);
}

/// The distance from `target` of the limit multiplier: from the branch's
/// own points where its approach resolved the last stretch, else from
/// orbits found afresh at √depth ≈ 1, 2, 4 times the branch's shallowest
/// (at least 5e-6), placed in Ω by √depth's linear fall to 0 at `graze`
/// (each FindOrbit from the last, the first from the branch's shallowest
/// point, with Newton's tolerance eased for the conditioning as the
/// continuation's approach eases it). Where the approach stepped is
/// rounding's choice: P(1,1)'s shallowest points at √depth 6e-6 and 1.7e-4
/// extrapolate to 2.5e-4 from −1, the fresh ones to 2.7e-6.
double LimitMultiplierGap(const Branch& branch, const System& system, double graze, int p, int q,
                          std::complex<double> target) {
  if (const auto limit = BranchLimitMultiplier(branch, target)) return std::abs(*limit - target);
  const BranchPoint& shallowest = *std::min_element(
      branch.points.begin(), branch.points.end(), [](const auto& a, const auto& b) {
        return a.orbit.contacts.slowest_depth < b.orbit.contacts.slowest_depth;
      });
  const double root = std::sqrt(shallowest.orbit.contacts.slowest_depth);
  REQUIRE(root > 0);
  OrbitOptions options;
  options.p = p;
  options.q = q;
  // As the continuation's approach does: Newton's residual to what the
  // conditioning (multipliers ~1/v) allows.
  options.newton.residual_tolerance *=
      std::max(1.0, 1e-4 * shallowest.orbit.multipliers.cwiseAbs().maxCoeff());
  Eigen::VectorXd seed = shallowest.orbit.eta;
  std::array<std::pair<double, std::complex<double>>, 3> samples;  // (√depth, λ)
  for (int k = 0; k < 3; ++k) {
    const double wanted = std::max(root, 5e-6) * (1 << k);
    const double omega = graze + (shallowest.parameter - graze) * wanted / root;
    PeriodicOrbit orbit;
    REQUIRE(FindOrbit(At(system, "omega", omega), seed, options, &orbit).termination ==
            Termination::kConverged);
    seed = orbit.eta;
    samples[k] = {std::sqrt(orbit.contacts.slowest_depth), Nearest(orbit, target)};
  }
  return std::abs(QuadraticAtZero(samples) - target);
}

/// The curve's point next to its corner (the last with an orbit).
const CurvePoint& NextToCorner(const Curve& curve) {
  return curve.begin == Termination::kGrazing ? curve.points[1]
                                              : curve.points[curve.points.size() - 2];
}

/// The N = 1 oscillator of the corner tests (m = k = 1, c = 0.1, A = 0.5,
/// r = 0.8) at Ω = 1.5, xs = 0.2, and its closed form's parameters (Ω and
/// xs set by each test).
System SdofSystem() {
  return UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), 1.5, 0.2, 0.8);
}
testing::SdofParameters SdofReference() { return {1.0, 1.0, 0.1, 0.5, 0.0, 0.8, 0.0}; }

/// The codimension-two points of `type` on `curve`.
std::vector<Codim2Point> PointsOf(const Curve& curve, Codim2Type type) {
  std::vector<Codim2Point> found;
  for (const Codim2Point& c : curve.codim2_points) {
    if (c.type == type) found.push_back(c);
  }
  return found;
}

/// The resonant grazing of `type` on the grazing curve in (omega, second)
/// through `branch`'s vanishing impact at omega = `graze` (the branch in
/// omega of `system`, at its second value), nearest `omega`. For p >= 2
/// that curve is P(p − 1, q)'s grazing by a new contact.
Codim2Point ResonantGrazingNear(const System& system, const Branch& branch, double graze,
                                const std::string& second, Codim2Type type, double omega) {
  const auto special = std::find_if(
      branch.special_points.begin(), branch.special_points.end(), [&](const SpecialPoint& s) {
        return s.type == SpecialPointType::kGrazing && s.parameter == graze;
      });
  REQUIRE(special != branch.special_points.end());
  CurveStart start{At(system, "omega", graze), *special};
  if (branch.p >= 2) {
    ContinuationOptions options;
    options.orbit.p = branch.p;
    options.orbit.q = branch.q;
    const std::optional<CurveStart> reduced =
        ReducedGrazingStart(system, branch, *special, options);
    REQUIRE(reduced.has_value());
    start = *reduced;
  }
  const Curve curve =
      ContinueCurve(start, Plane(second, 0.0, 1.0, start.special.point.orbit.p, branch.q));
  const std::vector<Codim2Point> found = PointsOf(curve, type);
  REQUIRE(!found.empty());
  return *std::min_element(found.begin(), found.end(), [&](const auto& a, const auto& b) {
    return std::abs(a.point.parameter - omega) < std::abs(b.point.parameter - omega);
  });
}

}  // namespace

TEST_CASE(
    "grazing limit: the split monodromy M(v) of P(1,1), P(1,2) and P(2,1) has the impact "
    "map's multipliers",
    "[curve][grazing-corner]") {
  for (const auto& [omega, p, q] :
       {std::tuple{1.2, 1, 1}, std::tuple{2.0, 1, 2}, std::tuple{0.8, 2, 1}}) {
    INFO("P(" << p << "," << q << ") at omega = " << omega);
    const System system = PaperSystem(omega);
    const PeriodicOrbit orbit = testing::SeededOrbit(system, p, q);
    const ImpactMap map(system);
    const MapResult path = map.Apply(orbit.eta, p, false);
    REQUIRE(path.termination == Termination::kCompleted);
    // The orbit's impacts from η on, split at each in turn.
    for (int split = 0; split < p; ++split) {
      std::vector<StopContact> contacts;
      for (int k = split; k < split + p; ++k) {
        const Eigen::VectorXd& eta = k == 0 ? orbit.eta : path.path[(k - 1) % p];
        HybridState impact = map.ToState(eta);
        if (k > p) impact.t += q * system.ForcingPeriod();
        contacts.push_back({impact, 0});
      }
      const SpeedSplitMonodromy m = SplitMonodromy(system, contacts, q);
      const Eigen::VectorXcd lambda = m.At(contacts.front().state.v(1)).eigenvalues();
      // Each multiplier of the map has one of M's within 1e-9.
      for (const std::complex<double>& l : orbit.multipliers) {
        INFO("split at impact " << split << ", multiplier " << l);
        CHECK((lambda.array() - l).abs().minCoeff() < 1e-9);
      }
    }
  }
}

TEST_CASE(
    "grazing limit: the N = 1 oscillator's fold curve in (omega, xs) ends at the closed "
    "form's fold-grazing corner",
    "[curve][grazing-corner]") {
  // The closed form's P(1,1) speeds solve qa u² + 2 xs d1 u + xs² − X² = 0
  // (closed_form_sdof.hpp); its fold (a double root) reaches u = 0 where
  // both lower coefficients vanish: X = xs and d1 = 0, where
  // d1 = (1 + r) Φ12(T) / det(I − Φ(T)) and Φ12(T) = e^{−aT} sin(ω_d T) / ω_d,
  // so at Ω = 2 ω_d (T = π / ω_d).
  const System system = SdofSystem();
  const Curve curve = CurveIn("xs", system, SpecialPointType::kFold, 1, 1, 0.0, 0.4);
  const Codim2Point& corner = Corner(curve, Codim2Type::kFoldGrazing);
  testing::SdofParameters p = SdofReference();
  p.omega = 2.0 * p.DampedFrequency();
  p.xs = p.SteadyAmplitude();
  CHECK(std::abs(testing::SdofImpactDirection(p)(0)) < 1e-12);  // d1 = 0 there
  CHECK(std::abs(corner.point.parameter - p.omega) < 1e-8);
  CHECK(std::abs(corner.point.parameter2 - p.xs) < 1e-8);
  CHECK(corner.defining_residual < 1e-10);
  CHECK(corner.second_residual < 1e-12);
}

TEST_CASE(
    "resonant grazing: on the N = 1 oscillator's grazing curve in (omega, xs) the fold and "
    "period-doubling curves of P(1,1) leave at Omega = 2 omega_d / j, the closed form",
    "[curve][grazing-corner]") {
  // nᵀ adj(Φ(T) − λ I) Φ(T) d0 = −λ (1 + r) a Φ12(T) for one mass
  // (docs/theory.md §6a), Φ12(T) = e^{−aT} sin(ω_d T) / ω_d: zero for every
  // λ where ω_d T = jπ, Ω = 2 ω_d / j (Molenaar, de Weger & van de Water
  // 2001; Simpson & Ghosh 2026), on the curve xs = X(Ω). In omega's range
  // [0.5, 3]: j = 1, 2, 3.
  const System system = SdofSystem();
  const Curve curve =
      CurveIn("xs", system, SpecialPointType::kGrazing, 1, 1, 0.0, 8.0);  // X(ω_d) ≈ 5
  REQUIRE(curve.p == 0);  // the non-impacting response's grazing
  testing::SdofParameters p = SdofReference();
  for (Codim2Type type :
       {Codim2Type::kResonantGrazingFold, Codim2Type::kResonantGrazingPeriodDoubling}) {
    std::vector<Codim2Point> found = PointsOf(curve, type);
    REQUIRE(found.size() == 3);
    std::sort(found.begin(), found.end(),
              [](const auto& a, const auto& b) { return a.point.parameter > b.point.parameter; });
    for (int j = 1; j <= 3; ++j) {
      p.omega = 2.0 * p.DampedFrequency() / j;
      const Codim2Point& at = found[j - 1];
      INFO(ToString(type) << " j = " << j << " at omega = " << at.point.parameter);
      CHECK(std::abs(at.point.parameter - p.omega) < 1e-8);
      CHECK(std::abs(at.point.parameter2 - p.SteadyAmplitude()) < 1e-8);
      CHECK(at.second_residual < 1e-12);
      // Its normal form (unfolded in omega) is the response's closed form,
      // A = Φ(T) = (−1)^j e^{−aT} I, and the square-root coefficient of the
      // P(1,1) fixed point, n · (I − A)⁻¹ A W, vanishes.
      p.xs = at.point.parameter2;
      REQUIRE(at.normal_form.has_value());
      const GrazingNormalForm& form = *at.normal_form;
      const Eigen::Matrix2d phi = testing::SdofTransition(p, p.Period());
      CHECK((form.linear - phi).cwiseAbs().maxCoeff() < 1e-8);
      CHECK(std::abs(phi(0, 1)) < 1e-8);
      const Eigen::Vector2d root(0.0, -(1.0 + p.r) * p.omega * std::sqrt(2.0 * p.xs));
      CHECK((form.root - root).cwiseAbs().maxCoeff() < 1e-8);
      // The unfolding's central difference errs by h² X'''/6, h = 1e-5:
      // largest at j = 2, on the resonance peak (X ≈ 5), 4e-8 relative.
      CHECK(std::abs(form.unfolding - p.SteadyAmplitudeRate()) <
            1e-7 * std::abs(p.SteadyAmplitudeRate()));
      const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
      const double kappa =
          form.normal.dot((identity - form.linear).lu().solve(form.linear * form.root));
      CHECK(std::abs(kappa) < 1e-8 * form.root.norm());
    }
  }
}

TEST_CASE(
    "grazing limit: the paper's P(1,1) period-doubling curve in (omega, xs) and P(2,1)'s in "
    "(omega, r) end where their branches' impacts vanish with a multiplier tending to -1",
    "[curve][grazing-corner]") {
  // P(1,1) from xs = 0.37 up to its corner near xs = 0.386 (on the
  // response's grazing); P(2,1) from r = 0.7 through its fold-flip point to
  // its corner near r = 0.522 (on P(1,1)'s grazing by a new contact).
  for (const auto& [second, omega, value, p, lower2, upper2] :
       {std::tuple{"xs", 1.2, 0.37, 1, 0.0, 0.45}, std::tuple{"r", 0.8, 0.7, 2, 0.45, 1.0}}) {
    INFO("P(" << p << ",1) in (omega, " << second << ")");
    const Curve curve = CurveIn(second, At(PaperSystem(omega), second, value),
                                SpecialPointType::kPeriodDoubling, p, 1, lower2, upper2);
    const Codim2Point& corner = Corner(curve, Codim2Type::kPeriodDoublingGrazing);
    const double omega_c = corner.point.parameter, value_c = corner.point.parameter2;
    INFO("corner at omega = " << omega_c << ", " << second << " = " << value_c);
    CHECK(corner.defining_residual < 1e-8);
    CHECK(corner.second_residual < 1e-9);
    const CurvePoint& near = NextToCorner(curve);
    // The branch in omega at the corner's second value ends where its
    // impact vanishes, located by its own (reduced-orbit) equation: there;
    // and as it does, one of its multipliers tends to −1.
    const auto [branch, graze] =
        BranchWith(second, value_c, omega_c, near.orbit.eta, p, 1, SpecialPointType::kGrazing);
    CHECK(std::abs(graze - omega_c) < 1e-8);
    // (At the shallowest point it is some 1e-3 from −1 for P(1,1), 1e-4
    // for P(2,1); extrapolated, a few 1e-6 or less.)
    CHECK(LimitMultiplierGap(branch, At(PaperSystem(omega_c), second, value_c), graze, p, 1, -1.0) <
          1e-5);
    // Seen from the grazing curve the corner is a resonant grazing: the
    // period-doubling curve leaves it there.
    const Codim2Point resonant =
        ResonantGrazingNear(At(PaperSystem(omega_c), second, value_c), branch, graze, second,
                            Codim2Type::kResonantGrazingPeriodDoubling, omega_c);
    CHECK(std::abs(resonant.point.parameter - omega_c) < 1e-8);
    CHECK(std::abs(resonant.point.parameter2 - value_c) < 1e-8);
    // P(1,1): the period doubling at value_c − δ (speed ∝ δ) tends to the
    // corner as δ → 0, smoothly (the curve crosses the grazing curve): the
    // quadratic through δ = 4h, 2h, h at 0 (error ~2e-8: 1.1e-6 at
    // h = 2e-4, 1.5e-7 at 1e-4, falling like h³). P(2,1)'s branches tell
    // its period doubling from the vanishing impact beside it only for
    // δ >= 5e-4, too far for that.
    if (p == 2) continue;
    const double h = 5e-5;
    std::array<double, 3> omegas{};
    for (int k = 0; k < 3; ++k) {
      omegas[k] = OneParameterOmega(second, value_c - (4 >> k) * h, omega_c, near.orbit.eta, p, 1,
                                    SpecialPointType::kPeriodDoubling);
    }
    const double extrapolated = (omegas[0] - 6.0 * omegas[1] + 8.0 * omegas[2]) / 3.0;
    CHECK(std::abs(extrapolated - omega_c) < 1e-7);
  }
}

TEST_CASE(
    "grazing limit: the paper's P(1,2) fold curve in (omega, xs) ends where its branch's impact "
    "vanishes with a multiplier tending to +1, and one-parameter folds touch it there",
    "[curve][grazing-corner]") {
  // From xs = 0.1 down to its corner near xs = 0.031.
  const Curve curve =
      CurveIn("xs", At(PaperSystem(2.0), "xs", 0.1), SpecialPointType::kFold, 1, 2, 0.0, 0.45);
  const Codim2Point& corner = PaperCorner(curve, Codim2Type::kFoldGrazing);
  const double omega_c = corner.point.parameter, xs_c = corner.point.parameter2;
  // At xs_c + δ the branch in omega folds at impact speed ∝ δ, so its
  // omega is the vanishing impact's plus O(δ²): the fold curve touches the
  // grazing curve. D(δ) = ω_fold − ω_graze (ω_graze from the closed-form
  // amplitude) fitted by a δ + b δ² + c δ³ + e δ⁴ at four δ: a parabola
  // b (δ − ε)² + … whose vertex ε = −a / (2b) is where the curves touch.
  // (Below δ ≈ 1.2e-4 the branch no longer resolves the fold from the
  // vanishing impact beside it.)
  const CurvePoint& near = NextToCorner(curve);
  // At xs_c the branch's impact vanishes at omega_c, a multiplier tending
  // to +1 as it does.
  const auto [branch, graze] =
      BranchWith("xs", xs_c, omega_c - 0.01, near.orbit.eta, 1, 2, SpecialPointType::kGrazing);
  CHECK(std::abs(graze - omega_c) < 1e-8);
  CHECK(LimitMultiplierGap(branch, At(PaperSystem(omega_c), "xs", xs_c), graze, 1, 2, 1.0) < 1e-5);
  // Seen from the grazing curve the corner is P(1,2)'s resonant grazing:
  // the fold curve leaves it there.
  const Codim2Point resonant =
      ResonantGrazingNear(At(PaperSystem(omega_c), "xs", xs_c), branch, graze, "xs",
                          Codim2Type::kResonantGrazingFold, omega_c);
  CHECK(std::abs(resonant.point.parameter - omega_c) < 1e-8);
  CHECK(std::abs(resonant.point.parameter2 - xs_c) < 1e-8);
  const std::array<double, 4> deltas{1.5e-4, 2e-4, 3e-4, 4e-4};
  Eigen::Vector4d gaps;
  for (int k = 0; k < 4; ++k) {
    const double fold = OneParameterOmega("xs", xs_c + deltas[k], omega_c - 0.01, near.orbit.eta, 1,
                                          2, SpecialPointType::kFold);
    gaps(k) = fold - GrazingOmega(xs_c + deltas[k], omega_c);
  }
  testing::CheckTouchingAtCorner(deltas, gaps, 1e-6);
}

TEST_CASE(
    "grazing limit: a split monodromy of no contacts, or of contacts beyond q periods, is "
    "refused with a clear error",
    "[curve][grazing-corner]") {
  const System system = PaperSystem(1.2);
  CHECK_THROWS_AS(SplitMonodromy(system, {}, 1), InvalidInput);
  const StopContact first{RestState(system), 0};
  StopContact late = first;
  late.state.t = 1.5 * system.ForcingPeriod();
  CHECK_THROWS_WITH(SplitMonodromy(system, {first, late}, 1),
                    Catch::Contains("must lie within its q = 1 forcing periods"));
  CHECK_NOTHROW(SplitMonodromy(system, {first, late}, 2));
  CHECK_THROWS_WITH(SplitMonodromy(system, {first, {late.state, 1}}, 2),
                    Catch::Contains("a contact's stop must be one of the system's 1 stops"));
  CHECK_THROWS_WITH(ResponseTouch(system, -1),
                    Catch::Contains("the stop touched must be one of the system's 1 stops"));
}
