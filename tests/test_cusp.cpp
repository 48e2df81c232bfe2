// A cusp on a real fold curve: the paper's P(7,4) in (omega, r), where the
// two folds of the branch in omega meet and vanish, checked against
// one-parameter branches on both sides of it.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <vector>

#include "curve_plane.hpp"
#include "impactkit/continuation/curve.hpp"
#include "system_at.hpp"

using namespace impactkit;
using testing::At;

namespace {

/// The P(7,4) branch near the cusp: its orbits have seven impacts in four
/// periods, a regime the paper's Fig. 3 shows between omega = 1.69 and 1.70.
constexpr int kP = 7, kQ = 4;

/// The P(7,4) branch in omega at this r over omega_c ± 2e-4, followed both
/// ways from the orbit that `seed` converges to at `start` (empty if none),
/// by steps short enough to see both folds of an S a few 1e-3 long.
std::optional<Branch> BranchInOmega(double r, double start, const Eigen::VectorXd& seed,
                                    double omega_c) {
  const System system = At(PaperSystem(start), "r", r);
  ContinuationOptions branch;
  branch.from = omega_c - 2e-4;
  branch.to = omega_c + 2e-4;
  branch.initial_step = 1e-4;
  branch.max_step = 2e-4;
  branch.direction = ContinuationDirection::kBoth;
  branch.orbit.p = kP;
  branch.orbit.q = kQ;
  PeriodicOrbit orbit;
  if (FindOrbit(system, seed, branch.orbit, &orbit).termination != Termination::kConverged) {
    return std::nullopt;
  }
  return ContinueBranch({system, orbit, {}}, branch);
}

std::vector<double> Folds(const std::optional<Branch>& branch) {
  REQUIRE(branch.has_value());
  std::vector<double> folds;
  for (const SpecialPoint& s : branch->special_points) {
    if (s.type == SpecialPointType::kFold) folds.push_back(s.parameter);
  }
  return folds;
}

double NearestFold(const std::vector<double>& folds, double omega) {
  double best = folds.front();
  for (double f : folds) {
    if (std::abs(f - omega) < std::abs(best - omega)) best = f;
  }
  return best;
}

}  // namespace

TEST_CASE(
    "cusp: the paper's P(7,4) fold curve in (omega, r) turns back at a cusp, where two folds "
    "of the branch in omega meet",
    "[curve][cusp][slow]") {
  // The seed: a P(7,4) orbit of the brute-force diagram at r = 0.7 (a
  // guess only; the fold is located from the orbit it converges to).
  const System system = PaperSystem(1.6915);
  OrbitOptions seed_options;
  seed_options.p = kP;
  seed_options.q = kQ;
  PeriodicOrbit seed;
  REQUIRE(FindOrbit(system, Eigen::Vector4d(0.4277, 2.1354, -1.2808, 0.1051), seed_options, &seed)
              .termination == Termination::kConverged);
  ContinuationOptions search;
  search.from = 1.68;
  search.to = 1.70;
  search.orbit = seed_options;
  const std::optional<SpecialPoint> fold =
      LocateSpecialPoint({system, seed, {}}, search, SpecialPointType::kFold);
  REQUIRE(fold.has_value());
  CurveOptions options = testing::Plane("r", 0.6, 0.95, kP, kQ);
  options.from = 1.68;
  options.to = 1.71;
  const Curve curve = ContinueCurve({At(system, "omega", fold->parameter), *fold}, options);

  std::vector<Codim2Point> cusps;
  for (const Codim2Point& c : curve.codim2_points) {
    if (c.type == Codim2Type::kCusp) cusps.push_back(c);
  }
  REQUIRE(cusps.size() == 1);
  const Codim2Point& cusp = cusps.front();
  const double omega_c = cusp.point.parameter, r_c = cusp.point.parameter2;
  INFO("cusp at omega = " << omega_c << ", r = " << r_c);
  CHECK(cusp.defining_residual < 1e-8);
  // The test function is the tangent's (omega, r) part along its direction
  // before the cusp; here the whole part is below 1e-6 of a unit tangent.
  CHECK(cusp.point.tangent.tail(2).norm() < 1e-6);

  // The curve's points on either side of the cusp, within 1.5e-3 in r of it,
  // are folds of the branch in omega at their r (to 1e-8); at the cusp
  // itself the two folds merge and the branch's fold test has a double zero.
  int checked = 0;
  for (const CurvePoint& point : curve.points) {
    const double distance = std::abs(point.parameter2 - r_c);
    if (distance > 1.5e-3 || distance < 2e-5) continue;
    // From the fold point itself a branch starts on its fold, unbracketed:
    // it starts 1e-5 to the side where the orbit exists.
    std::optional<Branch> branch;
    for (double shift : {1e-5, -1e-5}) {
      if (!branch) {
        branch = BranchInOmega(point.parameter2, point.parameter + shift, point.orbit.eta,
                               point.parameter);
      }
    }
    const std::vector<double> folds = Folds(branch);
    REQUIRE(!folds.empty());
    INFO("curve point omega = " << point.parameter << ", r = " << point.parameter2);
    CHECK(std::abs(NearestFold(folds, point.parameter) - point.parameter) < 1e-8);
    ++checked;
  }
  CHECK(checked >= 5);

  // Below r_c the branch in omega has two folds near omega_c (an S). Near
  // the cusp r_c − r = α s² + O(s³) along the curve, so the folds at
  // r_c − δ lie at s± = ±(δ/α)^{1/2} (1 + O(δ^{1/2})), s−(√δ) = s+(−√δ):
  // their midpoint, even in √δ, is omega_c + b δ + O(δ²), and their gap,
  // odd in √δ, C δ^{3/2} (1 + O(δ)). Fitted by quadratics in δ over
  // δ = 1e-5 … 5e-5 (farther the post-cusp side turns back at r_c − 1.7e-3),
  // gap^{2/3} vanishes at δ = 0 and the midpoint is omega_c there: the cusp
  // found again from one-parameter branches alone.
  const std::array<double, 5> deltas{1e-5, 2e-5, 3e-5, 4e-5, 5e-5};
  Eigen::MatrixXd basis(deltas.size(), 3);
  Eigen::VectorXd gaps(deltas.size()), midpoints(deltas.size());
  for (std::size_t k = 0; k < deltas.size(); ++k) {
    const double delta = deltas[k];
    const std::vector<double> folds =
        Folds(BranchInOmega(r_c - delta, omega_c, cusp.point.orbit.eta, omega_c));
    REQUIRE(folds.size() >= 2);
    const double lo = NearestFold(folds, omega_c);
    std::vector<double> others;
    for (double f : folds) {
      if (f != lo) others.push_back(f);
    }
    const double hi = NearestFold(others, omega_c);
    INFO("r_c - " << delta << ": folds " << lo << ", " << hi);
    CHECK(std::abs(hi - lo) < 1e-6);
    basis.row(k) << 1.0, delta, delta * delta;
    gaps(k) = std::cbrt((hi - lo) * (hi - lo));
    midpoints(k) = 0.5 * (lo + hi);
  }
  const Eigen::Vector3d gap_fit = basis.colPivHouseholderQr().solve(gaps);
  const Eigen::Vector3d midpoint_fit = basis.colPivHouseholderQr().solve(midpoints);
  INFO("gap^(2/3) fit " << gap_fit.transpose() << ", midpoint fit " << midpoint_fit.transpose());
  CHECK(std::abs(gap_fit(0) / gap_fit(1)) < 1e-8);
  CHECK(std::abs(midpoint_fit(0) - omega_c) < 1e-8);

  // Above r_c the branch is seeded from the end of the one at r_c − 1e-4
  // beyond both folds (near the cusp itself η moves like (r − r_c)^{1/3}).
  const std::optional<Branch> near =
      BranchInOmega(r_c - 1e-4, omega_c, cusp.point.orbit.eta, omega_c);
  REQUIRE(near.has_value());
  const BranchPoint& beyond = near->points.back();
  const std::optional<Branch> above =
      BranchInOmega(r_c + 2e-4, beyond.parameter, beyond.orbit.eta, omega_c);
  REQUIRE(above.has_value());
  CHECK(above->begin == Termination::kParameterBound);
  CHECK(above->end == Termination::kParameterBound);
  for (const double f : Folds(above)) CHECK(std::abs(f - omega_c) > 1e-4);
}
