// Branch switching (continuation.hpp): onto the period-doubled branch at a
// period doubling, onto the crossing branch at a pitchfork, and past a
// grazing onto the orbit with an impact more or fewer.

#include <algorithm>
#include <cmath>

#include "continuation/branch_problem.hpp"
#include "impactkit/continuation/continuation.hpp"

namespace impactkit {

using detail::BranchProblem;

namespace {

/// The problem of `branch`'s family, or of the same orbits traversed
/// `times` times.
BranchProblem ProblemOf(const System& system, const Branch& branch,
                        const ContinuationOptions& options, int times = 1) {
  const int k = branch.section == OrbitSection::kRelease ? branch.releases : branch.p;
  return detail::FamilyProblem(system, options, branch.section, branch.stop, times * k,
                               times * branch.q);
}

/// The new branch leaves the special point `at` along the eigenvector w with
/// μ stationary: corrected on the hyperplane `offset` along (w, 0) from it.
/// *away: the unit direction from `at` towards that hyperplane, ±(w, 0) by
/// the sign of `offset` (the eigenvector's own sign is arbitrary).
std::optional<Eigen::VectorXd> CorrectAlong(const BranchProblem& problem, const SpecialPoint& at,
                                            const ContinuationOptions& options, double offset,
                                            Eigen::VectorXd* away) {
  const Eigen::VectorXd x_at = BranchProblem::Join(at.point.orbit.eta, at.point.parameter);
  const Eigen::VectorXd w = BranchProblem::Join(at.eigenvector, 0.0).normalized();
  *away = offset > 0 ? w : Eigen::VectorXd(-w);
  NewtonOptions newton = options.orbit.newton;
  newton.max_iterations = 4 * options.corrector_iterations;
  int iterations = 0;
  return problem.Correct(x_at + offset * w, w, w.dot(x_at) + offset, newton, &iterations);
}

/// The start at the corrected point x of `problem`'s branch, heading away
/// from the special point (along `away`, CorrectAlong's).
std::optional<BranchStart> StartAt(const BranchProblem& problem, const Eigen::VectorXd& x,
                                   const Eigen::VectorXd& away) {
  const std::optional<Eigen::VectorXd> tangent = problem.Tangent(x, away);
  if (!tangent) return std::nullopt;
  BranchStart start;
  start.system = problem.SystemAt(BranchProblem::Mu(x));
  start.orbit = problem.OrbitAt(BranchProblem::Eta(x), BranchProblem::Mu(x));
  start.direction = *tangent;
  return start;
}

/// The unit chord of `branch` between its points just before and just after
/// arclength s (the special point there excluded); empty at an end.
Eigen::VectorXd BranchChord(const Branch& branch, double s) {
  const BranchPoint* before = nullptr;
  const BranchPoint* after = nullptr;
  for (const BranchPoint& point : branch.points) {
    if (point.arclength < s && (!before || point.arclength > before->arclength)) before = &point;
    if (point.arclength > s && (!after || point.arclength < after->arclength)) after = &point;
  }
  if (!before || !after) return {};
  return (BranchProblem::PointX(*after) - BranchProblem::PointX(*before)).normalized();
}

/// The doubled branch's start corrected `side` along the flip eigenvector
/// from `pd`, heading away from it; empty where the corrector fails or
/// lands on the single orbit (a fixed point of P_I^p solves the doubled
/// equations too). *leaves: whether its repeat gap grows along its
/// direction, as a start near the flip does.
std::optional<BranchStart> DoubledStartAt(const BranchProblem& doubled, const BranchProblem& single,
                                          const SpecialPoint& pd,
                                          const ContinuationOptions& options, double side,
                                          bool* leaves) {
  Eigen::VectorXd away;
  const std::optional<Eigen::VectorXd> x = CorrectAlong(doubled, pd, options, side, &away);
  if (!x) return std::nullopt;
  Eigen::VectorXd u;
  if (single.Residual(*x, &u) && u.cwiseAbs().maxCoeff() < 0.1 * std::abs(side)) {
    return std::nullopt;
  }
  std::optional<BranchStart> start = StartAt(doubled, *x, away);
  if (!start) return std::nullopt;
  const std::optional<Eigen::VectorXd> gap = doubled.RepeatGap(*x);
  *leaves = gap && doubled.ApproachesRepeat(*x, *gap, start->direction) == false;
  return start;
}

}  // namespace

std::optional<BranchStart> DoubledBranchStart(const System& system, const Branch& branch,
                                              const SpecialPoint& pd,
                                              const ContinuationOptions& options, double offset) {
  if (pd.type != SpecialPointType::kPeriodDoubling || pd.eigenvector.size() == 0) {
    throw InvalidInput("DoubledBranchStart needs a located period doubling point");
  }
  // At the flip the doubled orbits leave the single one along the flip
  // eigenvector (a pitchfork of P^{2k}), on both sides: the two halves are
  // the same orbits, mirror images (impacts renumbered by p).
  const BranchProblem doubled = ProblemOf(system, branch, options, 2);
  const BranchProblem single = ProblemOf(system, branch, options);
  // The eigenvector's sign is arbitrary. The hyperplane `offset` from the
  // flip also cuts the single orbit's branch, which solves the doubled
  // equations too, and on a long orbit's (whose η moves fast with μ) that
  // cut can be as near as the doubled orbit: where the corrector lands on
  // it, or fails, the other side.
  // Near the flip the doubled orbits leave the single one along w, their
  // repeat gap growing; deep in a cascade the doubled branch's stretch to
  // its own flip can be far shorter than `offset` (P(64,32) from P(32,16)
  // at Ω = 1.6872142: ~5e-6 in Ω), and there the corrector fails, or lands
  // on a doubled orbit whose gap shrinks along w, from which the branch ran
  // back across the flip. So the offset is cut tenfold, twice, until the
  // start leaves the single orbit; failing that, the first start found.
  std::optional<BranchStart> first;
  for (const double scale : {1.0, 0.1, 0.01}) {
    for (const double side : {scale * offset, -scale * offset}) {
      bool leaves = false;
      std::optional<BranchStart> start =
          DoubledStartAt(doubled, single, pd, options, side, &leaves);
      if (leaves) return start;
      if (!first) first = std::move(start);
    }
  }
  return first;
}

std::optional<BranchStart> PitchforkBranchStart(const System& system, const Branch& branch,
                                                const SpecialPoint& pitchfork,
                                                const ContinuationOptions& options, double offset) {
  if (pitchfork.type != SpecialPointType::kPitchfork || pitchfork.eigenvector.size() == 0) {
    throw InvalidInput("PitchforkBranchStart needs a located pitchfork");
  }
  // The crossing branch leaves along the eigenvector of the multiplier +1.
  const BranchProblem problem = ProblemOf(system, branch, options);
  Eigen::VectorXd away;
  const std::optional<Eigen::VectorXd> x = CorrectAlong(problem, pitchfork, options, offset, &away);
  if (!x) return std::nullopt;
  // Genuinely the other branch: off the line of this one (the hyperplane
  // also cuts this branch). Its direction is the chord between the branch
  // points around the pitchfork: the tangent computed at it is any vector
  // of the two-dimensional null space there.
  const Eigen::VectorXd x_at =
      BranchProblem::Join(pitchfork.point.orbit.eta, pitchfork.point.parameter);
  const Eigen::VectorXd t = BranchChord(branch, pitchfork.point.arclength);
  const Eigen::VectorXd d = *x - x_at;
  if (t.size() == 0 || (d - d.dot(t) * t).norm() < 0.5 * std::abs(offset)) return std::nullopt;
  return StartAt(problem, *x, away);
}

namespace {

/// The seed `state` with `orbit` at `offset` either side of μ, where the
/// parameter's range allows.
std::vector<GrazingSeed> SidesOf(const BranchProblem& problem, double mu, double offset,
                                 const OrbitOptions& orbit, const Eigen::VectorXd& state) {
  std::vector<GrazingSeed> seeds;
  for (double side : {-1.0, 1.0}) {
    try {
      seeds.push_back({problem.SystemAt(mu + side * offset), orbit, state});
    } catch (const InvalidInput&) {
      // That side is outside the parameter's range.
    }
  }
  return seeds;
}

}  // namespace

std::vector<GrazingSeed> SeedsAtGrazing(const System& system, const Branch& branch,
                                        const SpecialPoint& graze,
                                        const ContinuationOptions& options, double offset) {
  if (graze.type != SpecialPointType::kGrazing && graze.type != SpecialPointType::kSticking) {
    throw InvalidInput("SeedsAtGrazing needs a located grazing or sticking point");
  }
  const BranchPoint& point = graze.point;
  const BranchProblem problem = ProblemOf(system, branch, options);
  if (branch.section == OrbitSection::kRelease) {
    OrbitOptions orbit = options.orbit;
    orbit.releases = branch.releases;
    orbit.q = branch.q;
    orbit.release_map.stop = point.orbit.stop;
    return SidesOf(problem, point.parameter, offset, orbit, point.orbit.eta);
  }
  const ImpactMap* map = problem.ImpactMapAt(point.parameter);
  const MapResult image = map->Apply(point.orbit.eta, branch.p, false);
  auto impact_state = [&](int k) { return k == 0 ? point.orbit.eta : image.path[k - 1]; };
  auto impact_stop = [&](int k) { return k == 0 ? map->SectionStop() : image.stops[k - 1]; };
  OrbitOptions orbit = options.orbit;
  orbit.q = branch.q;
  Eigen::VectorXd eta;
  if (graze.vanishing_impact >= 0) {
    if (branch.p == 1) return {};  // no orbit is left without impacts
    orbit.p = branch.p - 1;
    eta = impact_state((graze.vanishing_impact + 1) % branch.p);
    orbit.map.stop = impact_stop((graze.vanishing_impact + 1) % branch.p);
  } else {
    // The new contact: the grazing point itself, as an impact whose speed
    // is what a parabola through the stop gives for a penetration of the
    // clearance's rate times `offset` (the rate from the branch's last step).
    const OrbitContacts& contacts = point.orbit.contacts;
    const Eigen::VectorXd from = impact_state(contacts.clearance_flight);
    const int from_stop = impact_stop(contacts.clearance_flight);
    const StopParameters& touched = system.stops[contacts.clearance_stop];
    const HybridState at = map->FlightState(from, contacts.clearance_time, from_stop);
    double value, slope, curvature;
    map->FlightCoordinate(from, touched.dof, from_stop)
        .ValueSlopeCurvature(contacts.clearance_time, &value, &slope, &curvature);
    const auto before =
        std::find_if(branch.points.rbegin(), branch.points.rend(), [&](const BranchPoint& b) {
          return b.parameter != point.parameter && b.orbit.contacts.clearance;
        });
    double rate = 1.0;  // clearance per unit parameter
    if (before != branch.points.rend()) {
      rate = std::abs(*before->orbit.contacts.clearance / (before->parameter - point.parameter));
    }
    const double speed = std::sqrt(2.0 * std::abs(curvature) * rate * offset);
    // A touch with no curvature or no clearance rate gives no impact to
    // start from (a speed of 0 is no impact state).
    if (!(speed > 0)) return {};
    Eigen::VectorXd v = at.v;
    v(touched.dof) = touched.Sign() * speed;
    orbit.p = branch.p + 1;
    orbit.map.stop = contacts.clearance_stop;
    eta = map->ToEta(at.t, at.x, v, contacts.clearance_stop);
  }
  return SidesOf(problem, point.parameter, offset, orbit, eta);
}

}  // namespace impactkit
