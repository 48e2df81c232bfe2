// Near-grazing P(1,1) orbits (issue 41, item 3): FindOrbit against the
// independent closed form of closed_form_sdof.hpp as the impact speed v
// vanishes like δ = Ω_g − Ω and the leading multiplier grows like 1/δ.

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "closed_form_sdof.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/orbits/orbit.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using namespace impactkit;
using testing::SdofP11;
using testing::SdofParameters;

namespace {

/// System B of the issue: m = 2, k = 3, c = 0.1, A = 1.2, xs = 0.05, r = 0.75.
constexpr double kGrazingOmega = 3.674043251526545;

SdofParameters Parameters(double omega) { return {2.0, 3.0, 0.1, 1.2, 0.05, 0.75, omega}; }

System SystemB(double omega) {
  const auto scalar = [](double value) { return Eigen::MatrixXd::Constant(1, 1, value); };
  return GeneralSystem(scalar(2.0), scalar(0.1), scalar(3.0), Eigen::VectorXd::Constant(1, 1.2),
                       omega, 0.05, 0.75);
}

/// The impacting root: the speeds' quadratic has one positive root here
/// (the other, u ≈ −0.24, is no impact).
SdofP11 ClosedFormOrbit(const SdofParameters& p) {
  const std::vector<SdofP11> roots = testing::SdofP11Solutions(p);
  REQUIRE(roots.size() == 1);
  REQUIRE(testing::SdofCheckFlight(p, roots.front()).Valid());
  return roots.front();
}

/// Errors against the closed form: τ's absolute, the others relative.
struct Errors {
  double tau, speed, leading, other;
};

/// FindOrbit from `guess` at Ω_g − δ, checked against the closed form.
Errors SolveAndCompare(double delta, const Eigen::Vector2d& guess) {
  const SdofParameters p = Parameters(kGrazingOmega - delta);
  const SdofP11 expected = ClosedFormOrbit(p);
  PeriodicOrbit orbit;
  const OrbitSummary summary = FindOrbit(SystemB(p.omega), guess, OrbitOptions{}, &orbit);
  INFO(summary.BriefReport());
  REQUIRE(summary.termination == Termination::kConverged);
  // A residual above the tolerance is accepted only below the floor the
  // summary reports, by the fixed-time formulation.
  CHECK(summary.residual <= std::max(1e-11, summary.residual_floor));
  if (summary.residual > 1e-11) CHECK(summary.used_shooting);
  // The multipliers: the leading one from the closed-form DP, the other
  // from det DP / λ1 (Eigenvalues2's second cancels when |λ1| ~ 1/δ).
  const double leading = testing::Eigenvalues2(testing::SdofP11Jacobian(p, expected))[0].real();
  const double other = testing::SdofP11Determinant(p) / leading;
  REQUIRE(orbit.multipliers.size() == 2);
  CHECK(std::abs(orbit.multipliers(0).imag()) == 0.0);
  return {orbit.eta(0) - expected.tau, orbit.eta(1) / expected.u - 1.0,
          orbit.multipliers(0).real() / leading - 1.0,
          std::abs(orbit.multipliers(1) / other - 1.0)};
}

}  // namespace

TEST_CASE("the grazing frequency of P(1,1): the closed form's speed vanishes at the given Ω_g",
          "[orbit-grazing]") {
  // Independently: X(Ω) = xs, i.e. m²w² + (c² − 2km) w + k² − A²/xs² = 0
  // for w = Ω² (the non-impacting response touches the stop), in long
  // double; above resonance the larger root.
  const SdofParameters p = Parameters(kGrazingOmega);
  const long double a = p.m * p.m, b = p.c * p.c - 2.0L * p.k * p.m;
  const long double c = p.k * p.k - static_cast<long double>(p.a) * p.a / (p.xs * p.xs);
  const long double w = (-b + std::sqrt(b * b - 4.0L * a * c)) / (2.0L * a);
  CHECK_THAT(static_cast<double>(std::sqrt(w)), WithinRel(kGrazingOmega, 4e-16));
  // And the closed-form orbit's speed is linear in δ, vanishing at Ω_g:
  // u/δ settles to 0.0742276 (to the rounding of δ = Ω_g − Ω and of X).
  for (const double delta : {1e-6, 1e-7, 1e-8}) {
    const SdofP11 o = ClosedFormOrbit(Parameters(kGrazingOmega - delta));
    CHECK_THAT(o.u / delta, WithinRel(0.0742276, 1e-5));
  }
}

TEST_CASE("FindOrbit finds near-grazing P(1,1) orbits, Ω_g − Ω = 1e-3 … 1e-8", "[orbit-grazing]") {
  for (const double delta : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    const SdofP11 exact = ClosedFormOrbit(Parameters(kGrazingOmega - delta));
    // From the exact orbit, and 1e-3 relative off in phase, 10% in speed.
    for (const double off : {0.0, 1.0}) {
      INFO("delta = " << delta << ", perturbed = " << off);
      const Eigen::Vector2d guess(exact.tau * (1.0 + 1e-3 * off), exact.u * (1.0 + 0.1 * off));
      const Errors e = SolveAndCompare(delta, guess);
      INFO("tau " << e.tau << ", speed " << e.speed << ", leading " << e.leading << ", other "
                  << e.other);
      CHECK(std::abs(e.tau) <= 1e-13);
      // The closed form's own speed is good to ~3e-8 relative at δ = 1e-8
      // (closed_form_sdof.hpp); the multipliers inherit it (λ1 ∝ 1/v).
      CHECK(std::abs(e.speed) <= 1e-6);
      CHECK(std::abs(e.leading) <= 1e-6);
      // An eigensolver on DP (norm ~1/δ) would place λ2 only to ~ε ‖DP‖
      // absolutely (2e-7 at δ = 1e-8, where λ2 ~ 4e-10); FindOrbit takes
      // it from the split monodromy's pencil.
      CHECK(std::abs(e.other) <= 1e-6);
    }
  }
}

TEST_CASE("below the rounding floor a near-grazing impact is found and reported unresolved",
          "[orbit-grazing]") {
  // At δ = 1e-7 the orbit's impact (speed 7.4e-9, a ≈ 0.7) rises
  // u²/(2a) ≈ 4e-17 above the stop: below the gap's rounding, 64 ulps of
  // its scale (~0.2). The simulator and the map see a grazing touch there
  // (one rule, hybrid/chatter_rule.hpp); the fixed-time equations still
  // determine the orbit, which FindOrbit returns saying so.
  const double delta = 1e-7;
  const SdofP11 exact = ClosedFormOrbit(Parameters(kGrazingOmega - delta));
  CHECK(exact.u * exact.u / (2 * 0.7) < 64 * std::numeric_limits<double>::epsilon() * 0.2);
  const System system = SystemB(kGrazingOmega - delta);
  PeriodicOrbit orbit;
  const OrbitSummary summary = FindOrbit(system, Eigen::Vector2d(exact.tau, exact.u), {}, &orbit);
  REQUIRE(summary.termination == Termination::kConverged);
  CHECK(summary.unresolved_impacts == 1);
  CHECK_THAT(summary.BriefReport(), Catch::Matchers::Contains("below the arrival resolution"));
  // The map from it indeed finds no impact where the orbit has one (the
  // rise is below the search's resolution, or the arrival is judged a
  // grazing touch).
  const ImpactMap map(system);
  const double next = orbit.eta(0) + system.ForcingPeriod();
  const std::optional<ImpactMap::FlightEnd> end = map.FirstArrival(orbit.eta, 0, next * (1 + 1e-9));
  CHECK((!end || !end->impact));
  // Resolved impacts are not reported so.
  PeriodicOrbit resolved;
  const SdofP11 farther = ClosedFormOrbit(Parameters(kGrazingOmega - 1e-5));
  CHECK(FindOrbit(SystemB(kGrazingOmega - 1e-5), Eigen::Vector2d(farther.tau, farther.u), {},
                  &resolved)
            .unresolved_impacts == 0);
}

TEST_CASE("the orbit of the issue's command is found from its exact solution", "[orbit-grazing]") {
  // `impactkit orbit --p 1 --q 1 --guess 0.8509130733897027,7.422846623612595e-07`
  // at δ = 1e-5 stopped at "residual 1.41e-11 after 2 iterations": Newton on
  // the map could not get U below its rounding, ~ε ‖DP‖ with ‖DP‖ ~ 1e6, and
  // the fixed-time formulation took over. Since the map's arrivals are
  // refined from the gap's value and slope at the impact (Signal::AnchorAt)
  // U is evaluated to ~6e-12 there and the map's own solve converges;
  // either way the orbit is the closed form's.
  const double omega = 3.674033251526545;
  PeriodicOrbit orbit;
  const OrbitSummary summary = FindOrbit(
      SystemB(omega), Eigen::Vector2d(0.8509130733897027, 7.422846623612595e-07), {}, &orbit);
  INFO(summary.BriefReport());
  REQUIRE(summary.termination == Termination::kConverged);
  if (summary.used_shooting) {
    CHECK(summary.shooting_residual <= 1e-15);
    CHECK(summary.residual <= summary.residual_floor);
  } else {
    CHECK(summary.residual <= 1e-11);
  }
  CHECK_THAT(orbit.multipliers(0).real(), WithinRel(-1078484.94, 1e-8));
  const SdofP11 expected = ClosedFormOrbit(Parameters(omega));
  CHECK_THAT(orbit.eta(1), WithinRel(expected.u, 1e-8));
  CHECK_THAT(orbit.eta(0), WithinAbs(expected.tau, 1e-14));
}
