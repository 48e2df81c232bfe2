// The discontinuity-map normal form at a grazing (orbits/grazing_normal_form.hpp):
// the single-degree-of-freedom response's against a closed form, the
// paper's against the multipliers of the impact map and against the true
// Poincaré map near the grazing (TrueGrazingMap, simulated), fitted to its
// √δ and δ terms, its reach, and the grazing seen from its two sides (the
// orbit that touches, the orbit whose impact vanishes) giving one normal
// form.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <iomanip>
#include <numbers>

#include "closed_form_sdof.hpp"
#include "impactkit/continuation/continuation.hpp"
#include "impactkit/io/system_file.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/grazing_normal_form.hpp"
#include "seeded_orbit.hpp"
#include "single_mass.hpp"
#include "sticking_grazing.hpp"
#include "system_at.hpp"

using namespace impactkit;
using testing::SdofParameters;
using testing::SdofSystem;

namespace {

/// The paper's branch through the orbit P(p, q) seeded at `omega`, followed
/// towards `to` to its grazing.
Branch PaperBranchToGrazing(double omega, int p, int q, double to) {
  const System system = PaperSystem(omega);
  ContinuationOptions options;
  options.parameter = "omega";
  options.from = omega;
  options.to = to;
  options.direction =
      to < omega ? ContinuationDirection::kDecreasing : ContinuationDirection::kIncreasing;
  options.orbit.p = p;
  options.orbit.q = q;
  const Branch branch = ContinueBranch({system, testing::SeededOrbit(system, p, q), {}}, options);
  REQUIRE(branch.end == Termination::kGrazing);
  REQUIRE(branch.special_points.back().type == SpecialPointType::kGrazing);
  return branch;
}

/// The true map (TrueGrazingMap) from z, required to complete.
Eigen::VectorXd TrueMap(const GrazingOrbit& orbit, const GrazingNormalForm& form,
                        const Eigen::VectorXd& z) {
  const Eigen::VectorXd departure = TrueGrazingMap(orbit, form, z);
  REQUIRE(departure.allFinite());
  return departure;
}

/// z = δ s e_c: a state δ past the touched stop (δ < 0: short of it).
Eigen::VectorXd Penetration(const GrazingOrbit& orbit, const GrazingNormalForm& form,
                            double delta) {
  const Stop stop(orbit.system, form.stop);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(form.touch.size());
  z(stop.Dof()) = stop.Sign() * delta;
  return z;
}

/// The √δ coefficient of the true map's departure from A z along the
/// penetration z = δ s e_c: least squares of r(δ) = P(z) − A z ≈ c₁ √d +
/// c₂ d, d = δ + the touch's own gap, over δ from 1e-9 to 1e-6. The
/// δ^{3/2} terms left out bias c₁ by ~δ_max: 2e-6 to 8e-6 relative here,
/// ten times less than with δ up to 1e-5 (so the fit converges to A W).
Eigen::VectorXd FittedRootTerm(const GrazingOrbit& orbit, const GrazingNormalForm& form) {
  const int n = orbit.system.Dof();
  const double gap = Stop(orbit.system, form.stop).GapOf(form.touch.head(n));
  constexpr int kSamples = 6;
  Eigen::MatrixXd basis(kSamples, 2);
  Eigen::MatrixXd departures(kSamples, 2 * n);
  for (int j = 0; j < kSamples; ++j) {
    const double delta = 1e-9 * std::pow(4.0, j), depth = delta + gap;
    const Eigen::VectorXd z = Penetration(orbit, form, delta);
    basis.row(j) << std::sqrt(depth), depth;
    departures.row(j) = (TrueMap(orbit, form, z) - form.linear * z).transpose();
  }
  const Eigen::MatrixXd coefficients = basis.colPivHouseholderQr().solve(departures);
  return coefficients.row(0).transpose();
}

/// max |P(z) − A z| / δ on the side without contact, z = −δ s e_c: O(δ)
/// if A is the map's linear part there.
double SmoothSideDeparture(const GrazingOrbit& orbit, const GrazingNormalForm& form, double delta) {
  const Eigen::VectorXd z = Penetration(orbit, form, -delta);
  return (TrueMap(orbit, form, z) - form.linear * z).cwiseAbs().maxCoeff() / delta;
}

/// One step of the normal form from z = δ s e_c against the true map,
/// relative to its √δ term |A W| √δ: what GrazingNormalForm::reach bounds.
double RootTermError(const GrazingOrbit& orbit, const GrazingNormalForm& form, double delta) {
  const Eigen::VectorXd z = Penetration(orbit, form, delta);
  const double depth =
      delta + Stop(orbit.system, form.stop).GapOf(form.touch.head(orbit.system.Dof()));
  const Eigen::VectorXd normal_form = form.linear * (z + form.root * std::sqrt(depth));
  return (TrueMap(orbit, form, z) - normal_form).norm() /
         ((form.linear * form.root).norm() * std::sqrt(delta));
}

/// −d(clearance)/dΩ of the orbit of `branch` (of `system`) on its own
/// side of the grazing `graze`, where it exists as a fixed point of its
/// section map: FindOrbit at Ω* + h and Ω* + 2h towards the branch,
/// one-sided second-order differences with the located point's clearance.
/// The clearance is measured at the flight's turn, the unfolding at the
/// touch's fixed time: the two agree to first order.
double ClearanceRate(const System& system, const Branch& branch, const SpecialPoint& graze) {
  const double side = branch.points.front().parameter > graze.parameter ? 1.0 : -1.0;
  const double h = side * 2e-6;
  OrbitOptions options;
  options.p = branch.p;
  options.q = branch.q;
  options.releases = branch.releases;
  options.release_map.stop = branch.stop;
  auto clearance = [&](double omega) {
    PeriodicOrbit orbit;
    REQUIRE(FindOrbit(testing::At(system, "omega", omega), graze.point.orbit.eta, options, &orbit)
                .termination == Termination::kConverged);
    REQUIRE(orbit.contacts.clearance.has_value());
    return *orbit.contacts.clearance;
  };
  const double c0 = *graze.point.orbit.contacts.clearance;
  const double slope =
      (-3.0 * c0 + 4.0 * clearance(graze.parameter + h) - clearance(graze.parameter + 2 * h)) /
      (2.0 * h);
  return -slope;
}

/// The normal form's multipliers against the section map's at the grazing
/// orbit (a sticking orbit's stroboscopic monodromy has the release map's
/// 2N − 2 section multipliers and two zeros: sticking forgets the held
/// mass's state), its √δ term against the true map's, its linear part
/// against the true map without contact, and its unfolding against the
/// orbit's own clearance.
void CheckAgainstTrueMap(const System& system, const Branch& branch) {
  const SpecialPoint& graze = branch.special_points.back();
  REQUIRE(graze.normal_form.has_value());
  const GrazingNormalForm& form = *graze.normal_form;
  const Eigen::VectorXcd& multipliers = graze.point.orbit.multipliers;
  REQUIRE(multipliers.size() <= form.eigenvalues.size());
  for (Eigen::Index k = 0; k < form.eigenvalues.size(); ++k) {
    const std::complex<double> expected = k < multipliers.size() ? multipliers(k) : 0.0;
    CHECK(std::abs(expected - form.eigenvalues(k)) < 1e-8);
  }
  // The orbit's last impact before the touch: its last contact, q periods earlier.
  ContinuationOptions options;
  const GrazingOrbit orbit = GrazingOrbitAt(system, branch, graze, options);
  const Eigen::VectorXd expected = form.linear * form.root;
  const Eigen::VectorXd fitted = FittedRootTerm(orbit, form);
  INFO("A W = " << expected.transpose() << "\nfitted " << fitted.transpose());
  CHECK((fitted - expected).norm() < 5e-5 * expected.norm());
  CHECK(SmoothSideDeparture(orbit, form, 1e-6) < 1e-4);
  // The reach: there one step errs by 10 % of the √ term against the true
  // map, and a hundred times closer by 1 %: the error grows like √δ (the
  // next term of the map is O(δ)).
  INFO("reach " << form.reach);
  const double at_reach = RootTermError(orbit, form, form.reach);
  const double closer = RootTermError(orbit, form, form.reach / 100);
  INFO("error at the reach " << at_reach << ", a hundred times closer " << closer);
  CHECK(std::abs(at_reach - 0.1) < 0.005);
  CHECK(std::abs(closer - 0.01) < 0.001);
  const double rate = ClearanceRate(system, branch, graze);
  INFO(std::setprecision(12) << "unfolding " << form.unfolding << ", clearance rate " << rate);
  CHECK(std::abs(form.unfolding - rate) < 1e-7 * std::abs(rate));
}

}  // namespace

TEST_CASE(
    "normal form: the SDOF response touching its stop matches the closed form (A = Φ(T), "
    "W = (0, −(1 + r) Ω √(2X)), unfolding X'(Ω) or −1 in xs) to 1e-8",
    "[grazing][normal-form]") {
  SdofParameters p;
  p.omega = 1.2;
  p.xs = p.SteadyAmplitude();  // the response's maximum touches the stop
  const System system = SdofSystem(p);
  const GrazingOrbit orbit{system, 1, {ResponseTouch(system, 0)}};
  const GrazingNormalForm form = ComputeGrazingNormalForm(orbit, "omega");
  const double amplitude = p.SteadyAmplitude();
  CHECK(std::abs(form.phase - p.SteadyLag() / p.omega) < 1e-12);
  CHECK((form.linear - testing::SdofTransition(p, p.Period())).cwiseAbs().maxCoeff() < 1e-8);
  CHECK(std::abs(form.curvature - p.omega * p.omega * amplitude) < 1e-8);
  CHECK(form.normal.isApprox(Eigen::RowVector2d(1.0, 0.0)));
  const Eigen::Vector2d root(0.0, -(1.0 + p.r) * p.omega * std::sqrt(2.0 * amplitude));
  CHECK((form.root - root).cwiseAbs().maxCoeff() < 1e-8);
  CHECK(std::abs(form.unfolding - p.SteadyAmplitudeRate()) <
        1e-8 * std::abs(p.SteadyAmplitudeRate()));
  // Φ(T) of an under-damped mass has a complex pair: no 1-D reduction.
  CHECK_FALSE(form.reduced.has_value());
  CHECK_THAT(form.reduction_note, Catch::Contains("complex pair"));
  CHECK(std::abs(ComputeGrazingNormalForm(orbit, "xs").unfolding + 1.0) < 1e-8);
  // Its reach: the true map errs by 10 % there, or by less where the scan
  // stopped at the largest penetration the true map can be set up for.
  const double at_reach = RootTermError(orbit, form, form.reach);
  INFO("reach " << form.reach << (form.reach_bounded ? " (bounded)" : "") << ", error there "
                << at_reach);
  if (form.reach_bounded) {
    CHECK(at_reach <= 0.1);
  } else {
    CHECK(std::abs(at_reach - 0.1) < 0.005);
  }
}

TEST_CASE(
    "normal form: the paper's grazings of Fig. 5 (P(1,1) at omega = 0.8564, P(3,2) at 0.8322) "
    "against the impact map's multipliers, the true map's sqrt term and the orbits' clearance",
    "[grazing][normal-form]") {
  CheckAgainstTrueMap(PaperSystem(), PaperBranchToGrazing(0.9, 1, 1, 0.8));
  CheckAgainstTrueMap(PaperSystem(), PaperBranchToGrazing(0.84, 3, 2, 0.8));
}

TEST_CASE(
    "normal form: the grazing at omega = 0.8564 seen from P(2,1), whose impact vanishes there, "
    "is the one seen from P(1,1), which touches",
    "[grazing][normal-form]") {
  const Branch p11 = PaperBranchToGrazing(0.9, 1, 1, 0.8);
  const Branch p21 = PaperBranchToGrazing(0.82, 2, 1, 0.9);
  const SpecialPoint& vanishing = p21.special_points.back();
  CHECK(vanishing.vanishing_impact >= 0);
  REQUIRE(vanishing.normal_form.has_value());
  const GrazingNormalForm& touch = *p11.special_points.back().normal_form;
  const GrazingNormalForm& reduced = *vanishing.normal_form;
  CHECK(std::abs(reduced.phase - touch.phase) < 1e-7);
  CHECK((reduced.touch - touch.touch).cwiseAbs().maxCoeff() < 1e-7);
  CHECK((reduced.linear - touch.linear).cwiseAbs().maxCoeff() < 1e-7);
  CHECK((reduced.root - touch.root).cwiseAbs().maxCoeff() < 1e-7);
  CHECK(std::abs(reduced.unfolding - touch.unfolding) < 1e-6);
}

TEST_CASE(
    "normal form: a vanishing impact whose reduced orbit repeats (the clearance's P(7,3) without "
    "its impact is P(2,1) three times) gives the shortest grazing orbit's, P(2,1)'s multipliers",
    "[grazing][normal-form]") {
  // At Omega = 1.0383071 P(7,3)'s impact vanishes where P(2,1) touches
  // (docs/continuation.md, the clearance's grazing table). The normal form
  // over three periods with one touch would miss the touches of the other
  // two; over P(2,1)'s one period its multipliers are P(2,1)'s, found
  // afresh by FindOrbit beside the grazing (to the family's O(distance)).
  System system = ReadSystemFile(IMPACTKIT_SOURCE_DIR "/examples/systems/clearance-1dof.toml");
  SetParameter(system, "omega", 1.0384);
  OrbitOptions orbit_options;
  orbit_options.p = 7;
  orbit_options.q = 3;
  PeriodicOrbit p73;
  REQUIRE(FindOrbit(system, Eigen::Vector2d(5.872954073819907, 0.46334922286225705), orbit_options,
                    &p73)
              .termination == Termination::kConverged);
  ContinuationOptions options;
  options.from = 1.0384;
  options.to = 1.03;
  options.direction = ContinuationDirection::kDecreasing;
  options.orbit = orbit_options;
  const Branch branch = ContinueBranch({system, p73, {}}, options);
  const auto graze =
      std::find_if(branch.special_points.begin(), branch.special_points.end(),
                   [](const SpecialPoint& s) { return s.type == SpecialPointType::kGrazing; });
  REQUIRE(graze != branch.special_points.end());
  CHECK(graze->vanishing_impact >= 0);
  REQUIRE(graze->normal_form.has_value());
  const GrazingNormalForm& form = *graze->normal_form;
  CHECK((form.p == 2 && form.q == 1));
  // P(2,1) just before the grazing (on the side where it has no contact),
  // from its impact at the lower stop there.
  SetParameter(system, "omega",
               graze->parameter - form.unfolding / std::abs(form.unfolding) * 1e-7);
  orbit_options.p = 2;
  orbit_options.q = 1;
  orbit_options.map.stop = 1;
  PeriodicOrbit p21;
  REQUIRE(FindOrbit(system, Eigen::Vector2d(3.1420920997917707, -1.2438752868666993), orbit_options,
                    &p21)
              .termination == Termination::kConverged);
  REQUIRE(p21.multipliers.size() == form.eigenvalues.size());
  for (Eigen::Index k = 0; k < form.eigenvalues.size(); ++k) {
    CHECK(std::abs(p21.multipliers(k) - form.eigenvalues(k)) < 1e-5);
  }
}

TEST_CASE(
    "normal form: a sticking family's new contact (paper-mass1-stop at omega = 0.19016) against "
    "the release map's multipliers, the true map's sqrt term and the orbits' clearance",
    "[grazing][normal-form][sticking]") {
  // Mass 2 sticks at its stop every period while mass 1 strikes its own
  // three times between releases; going down in Ω, a fourth turn of mass 1
  // touches its stop (tests/test_sticking_stops.cpp).
  const System system = testing::PaperWithMass1StopFile();
  const Branch branch = testing::StickingBranchToNewContact(system);
  const GrazingNormalForm& form = *branch.special_points.back().normal_form;
  CHECK(form.releases == 1);
  CHECK(form.stop == 0);
  CheckAgainstTrueMap(system, branch);
}

TEST_CASE(
    "normal form: a sticking family's vanishing impact (paper-mass1-stop at omega = 0.19016, "
    "followed back up) gives the new contact's normal form, seen from the family that touches",
    "[grazing][normal-form][sticking]") {
  // Below the new contact the family with mass 1's fourth impact, followed
  // back up, ends where that impact vanishes: the same grazing
  // (tests/test_sticking_stops.cpp). Its grazing orbit is the neighbouring
  // family's touch, solved afresh from its clearance's zero.
  const System system = testing::PaperWithMass1StopFile();
  const Branch touching = testing::StickingBranchToNewContact(system);
  const SpecialPoint& graze = touching.special_points.back();
  const ContinuationOptions down = testing::DownToNewContact();
  const std::vector<GrazingSeed> seeds = SeedsAtGrazing(system, touching, graze, down);
  REQUIRE(!seeds.empty());
  PeriodicOrbit below;
  REQUIRE(FindOrbit(seeds[0].system, seeds[0].eta, seeds[0].orbit, &below).termination ==
          Termination::kConverged);
  ContinuationOptions up = down;
  up.direction = ContinuationDirection::kIncreasing;
  const Branch vanishing = ContinueBranch({seeds[0].system, below, {}}, up);
  REQUIRE(vanishing.end == Termination::kGrazing);
  const SpecialPoint& gone = vanishing.special_points.back();
  REQUIRE(gone.vanishing_impact >= 0);
  INFO(gone.normal_form_note);
  REQUIRE(gone.normal_form.has_value());
  const GrazingNormalForm& touch = *graze.normal_form;
  const GrazingNormalForm& reduced = *gone.normal_form;
  // Both located to end_tolerance (1e-9) in the parameter; the touch's
  // time is flat in it (a maximum), so the phases agree to ~1e-8; each
  // unfolding carries its one-sided difference's ~1e-7.
  CHECK(std::abs(reduced.parameter_value - touch.parameter_value) < 1e-9);
  CHECK(std::abs(reduced.phase - touch.phase) < 1e-7);
  CHECK((reduced.touch - touch.touch).cwiseAbs().maxCoeff() < 1e-8);
  CHECK((reduced.linear - touch.linear).cwiseAbs().maxCoeff() < 1e-7);
  CHECK((reduced.root - touch.root).cwiseAbs().maxCoeff() < 1e-7);
  CHECK(std::abs(reduced.unfolding - touch.unfolding) < 2e-7);
}
