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
#include "impactkit/continuation/curve.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/grazing_limit.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"

using namespace impactkit;
using testing::At;

namespace {

/// Curves of P(1, q) in (omega, xs), omega in [0.5, 3].
CurveOptions XsPlane(double lower2, double upper2, int q) {
  CurveOptions options;
  options.parameter = "omega";
  options.parameter2 = "xs";
  options.lower = 0.5;
  options.upper = 3.0;
  options.lower2 = lower2;
  options.upper2 = upper2;
  options.orbit.q = q;
  return options;
}

/// The (omega, xs) plane's curve of `type` of P(1, q) through the special
/// point nearest `system`'s omega.
Curve CurveInXs(const System& system, SpecialPointType type, int q, double lower2, double upper2) {
  ContinuationOptions search;
  search.lower = 0.5;
  search.upper = 3.0;
  search.orbit.q = q;
  const std::optional<SpecialPoint> special =
      LocateSpecialPoint({system, testing::SeededOrbit(system, 1, q), {}}, search, type);
  REQUIRE(special.has_value());
  return ContinueCurve({At(system, "omega", special->parameter), *special},
                       XsPlane(lower2, upper2, q));
}

/// The curve's located corner, which must be its last point at one end.
const Codim2Point& Corner(const Curve& curve, Codim2Type type) {
  const auto it = std::find_if(curve.codim2_points.begin(), curve.codim2_points.end(),
                               [&](const Codim2Point& c) { return c.type == type; });
  REQUIRE(it != curve.codim2_points.end());
  const bool at_begin =
      curve.begin == CurveEnd::kGrazing && curve.points.front().parameter == it->point.parameter;
  const bool at_end =
      curve.end == CurveEnd::kGrazing && curve.points.back().parameter == it->point.parameter;
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

/// The special point of `type` in omega nearest `omega` on the P(1, q)
/// branch at stop position xs, through an orbit found from the seed `eta`
/// at omega or beside it (beside a fold the orbit exists on one side only).
double OneParameterOmega(double xs, double omega, const Eigen::VectorXd& eta, int q,
                         SpecialPointType type) {
  ContinuationOptions options;
  options.lower = omega - 0.05;
  options.upper = omega + 0.05;
  options.direction = ContinuationDirection::kBoth;
  options.orbit.q = q;
  for (double shift : {0.0, 2e-3, -2e-3, 1e-2, -1e-2}) {
    const System system = At(PaperSystem(omega + shift), "xs", xs);
    PeriodicOrbit orbit;
    if (FindOrbit(system, eta, options.orbit, &orbit).termination != Termination::kConverged) {
      continue;
    }
    double best = 1e300;
    for (const SpecialPoint& s : ContinueBranch({system, orbit, {}}, options).special_points) {
      if (s.type == type && std::abs(s.parameter - omega) < std::abs(best - omega)) {
        best = s.parameter;
      }
    }
    if (best != 1e300) return best;
  }
  FAIL("no " << ToString(type) << " found at xs = " << xs);
  return 0.0;
}

}  // namespace

TEST_CASE(
    "grazing limit: the split monodromy M(v) of P(1,1) and P(1,2) has the impact map's "
    "multipliers",
    "[curve][grazing-corner]") {
  for (const auto& [omega, q] : {std::pair{1.2, 1}, std::pair{2.0, 2}}) {
    INFO("P(1," << q << ") at omega = " << omega);
    const System system = PaperSystem(omega);
    const PeriodicOrbit orbit = testing::SeededOrbit(system, 1, q);
    const HybridState impact = ImpactMap(system).ToState(orbit.eta);
    const SpeedSplitMonodromy split =
        SingleImpactMonodromy(system, impact.t, impact.x, impact.v, q);
    const Eigen::VectorXcd lambda = split.At(impact.v(1)).eigenvalues();
    // Each multiplier of the map has one of M's within 1e-9.
    for (const std::complex<double>& l : orbit.multipliers) {
      INFO("multiplier " << l);
      CHECK((lambda.array() - l).abs().minCoeff() < 1e-9);
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
  const System system =
      UniformChain({1, 1.0, 1.0, 0.1}, Eigen::VectorXd::Constant(1, 0.5), 1.5, 0.2, 0.8);
  const Curve curve = CurveInXs(system, SpecialPointType::kFold, 1, 0.0, 0.4);
  const Codim2Point& corner = Corner(curve, Codim2Type::kFoldGrazing);
  testing::SdofParameters p{1.0, 1.0, 0.1, 0.5, 0.0, 0.8, 0.0};
  p.omega = 2.0 * p.DampedFrequency();
  p.xs = p.SteadyAmplitude();
  CHECK(std::abs(testing::SdofImpactDirection(p)(0)) < 1e-12);  // d1 = 0 there
  CHECK(std::abs(corner.point.parameter - p.omega) < 1e-8);
  CHECK(std::abs(corner.point.parameter2 - p.xs) < 1e-8);
  CHECK(corner.defining_residual < 1e-10);
  CHECK(corner.second_residual < 1e-12);
}

TEST_CASE(
    "grazing limit: the paper's P(1,1) period-doubling curve in (omega, xs) ends where "
    "one-parameter period doublings, extrapolated, reach the vanishing impact",
    "[curve][grazing-corner]") {
  // From xs = 0.37 up to its corner near xs = 0.386.
  const Curve curve =
      CurveInXs(At(PaperSystem(1.2), "xs", 0.37), SpecialPointType::kPeriodDoubling, 1, 0.0, 0.45);
  const Codim2Point& corner = PaperCorner(curve, Codim2Type::kPeriodDoublingGrazing);
  const double omega_c = corner.point.parameter, xs_c = corner.point.parameter2;
  // The period doubling at xs_c − δ (speed ∝ δ) tends to the corner as
  // δ → 0, smoothly (the curve crosses the grazing curve): the quadratic
  // through δ = 4h, 2h, h at 0 (error ~2e-8 here: 1.1e-6 at h = 2e-4,
  // 1.5e-7 at 1e-4, falling like h³).
  const CurvePoint& near = curve.points[curve.points.size() - 2];
  const double h = 5e-5;
  std::array<double, 3> omegas{};
  for (int k = 0; k < 3; ++k) {
    omegas[k] = OneParameterOmega(xs_c - (4 >> k) * h, omega_c, near.orbit.eta, 1,
                                  SpecialPointType::kPeriodDoubling);
  }
  const double extrapolated = (omegas[0] - 6.0 * omegas[1] + 8.0 * omegas[2]) / 3.0;
  CHECK(std::abs(extrapolated - omega_c) < 1e-7);
}

TEST_CASE(
    "grazing limit: the paper's P(1,2) fold curve in (omega, xs) ends where one-parameter "
    "folds meet the closed-form vanishing impact tangentially",
    "[curve][grazing-corner]") {
  // From xs = 0.1 down to its corner near xs = 0.031.
  const Curve curve =
      CurveInXs(At(PaperSystem(2.0), "xs", 0.1), SpecialPointType::kFold, 2, 0.0, 0.45);
  const Codim2Point& corner = PaperCorner(curve, Codim2Type::kFoldGrazing);
  const double omega_c = corner.point.parameter, xs_c = corner.point.parameter2;
  // At xs_c + δ the branch in omega folds at impact speed ∝ δ, so its
  // omega is the vanishing impact's plus O(δ²): the fold curve touches the
  // grazing curve. D(δ) = ω_fold − ω_graze (ω_graze from the closed-form
  // amplitude) fitted by a δ + b δ² + c δ³ + e δ⁴ at four δ: a parabola
  // b (δ − ε)² + … whose vertex ε = −a / (2b) is where the curves touch.
  // (Below δ ≈ 1.2e-4 the branch no longer resolves the fold from the
  // vanishing impact beside it.)
  const CurvePoint& near = curve.points[1];
  const std::array<double, 4> deltas{1.5e-4, 2e-4, 3e-4, 4e-4};
  Eigen::Matrix4d powers;
  Eigen::Vector4d gaps;
  for (int k = 0; k < 4; ++k) {
    const double d = deltas[k];
    const double fold =
        OneParameterOmega(xs_c + d, omega_c - 0.01, near.orbit.eta, 2, SpecialPointType::kFold);
    powers.row(k) << d, d * d, d * d * d, d * d * d * d;
    gaps(k) = fold - GrazingOmega(xs_c + d, omega_c);
  }
  const Eigen::Vector4d fit = powers.fullPivLu().solve(gaps);
  INFO("fit " << fit.transpose());
  CHECK(fit(1) > 0.0);
  CHECK(std::abs(fit(0) / (2.0 * fit(1))) < 1e-6);
}
