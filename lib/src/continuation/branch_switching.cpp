// Branch switching (continuation.hpp): onto the period-doubled branch at a
// period doubling, and past a grazing onto the orbit with an impact more or
// fewer.

#include <algorithm>
#include <cmath>

#include "continuation/branch_problem.hpp"
#include "impactkit/continuation/continuation.hpp"

namespace impactkit {

using detail::BranchProblem;

std::optional<BranchStart> DoubledBranchStart(const System& system, const Branch& branch,
                                              const SpecialPoint& pd,
                                              const ContinuationOptions& options, double offset) {
  if (pd.type != SpecialPointType::kPeriodDoubling || pd.eigenvector.size() == 0) {
    throw InvalidInput("DoubledBranchStart needs a located period doubling point");
  }
  const int p = branch.p, q = branch.q;
  const BranchProblem doubled(system, branch.parameter, 2 * p, 2 * q, options.orbit.map);
  // At the flip the doubled orbits leave the single one along the flip
  // eigenvector with μ stationary (a pitchfork of P_I^{2p}): correct on
  // the hyperplane `offset` along (w, 0).
  const Eigen::VectorXd x_pd = BranchProblem::Join(pd.point.orbit.eta, pd.point.parameter);
  const Eigen::VectorXd w = BranchProblem::Join(pd.eigenvector, 0.0).normalized();
  NewtonOptions newton = options.orbit.newton;
  newton.max_iterations = 4 * options.corrector_iterations;
  int iterations = 0;
  const std::optional<Eigen::VectorXd> x =
      doubled.Correct(x_pd + offset * w, w, w.dot(x_pd) + offset, newton, &iterations);
  if (!x) return std::nullopt;
  // Genuinely doubled: not a fixed point of P_I^p (the single orbit also
  // solves the doubled equations).
  const BranchProblem single(system, branch.parameter, p, q, options.orbit.map);
  Eigen::VectorXd u;
  if (single.Residual(*x, &u) && u.cwiseAbs().maxCoeff() < 0.1 * offset) return std::nullopt;
  const std::optional<Eigen::VectorXd> tangent = doubled.Tangent(*x, w);
  if (!tangent) return std::nullopt;
  BranchStart start;
  start.system = doubled.SystemAt(BranchProblem::Mu(*x));
  start.orbit =
      DescribeOrbit(*doubled.MapAt(BranchProblem::Mu(*x)), BranchProblem::Eta(*x), 2 * p, 2 * q);
  start.direction = *tangent;
  return start;
}

std::vector<GrazingSeed> SeedsAtGrazing(const System& system, const Branch& branch,
                                        const SpecialPoint& graze,
                                        const ContinuationOptions& options, double offset) {
  if (graze.type != SpecialPointType::kGrazing && graze.type != SpecialPointType::kSticking) {
    throw InvalidInput("SeedsAtGrazing needs a located grazing or sticking point");
  }
  const BranchPoint& point = graze.point;
  const BranchProblem problem(system, branch.parameter, branch.p, branch.q, options.orbit.map);
  const ImpactMap* map = problem.MapAt(point.parameter);
  const MapResult image = map->Apply(point.orbit.eta, branch.p, false);
  auto impact_state = [&](int k) { return k == 0 ? point.orbit.eta : image.path[k - 1]; };
  OrbitOptions orbit = options.orbit;
  orbit.q = branch.q;
  Eigen::VectorXd eta;
  if (graze.vanishing_impact >= 0) {
    if (branch.p == 1) return {};  // no orbit is left without impacts
    orbit.p = branch.p - 1;
    eta = impact_state((graze.vanishing_impact + 1) % branch.p);
  } else {
    // The new contact: the grazing point itself, as an impact whose speed
    // is what a parabola through the stop gives for a penetration of the
    // clearance's rate times `offset` (the rate from the branch's last step).
    const OrbitContacts& contacts = point.orbit.contacts;
    const Eigen::VectorXd from = impact_state(contacts.clearance_flight);
    const HybridState at = map->FlightState(from, contacts.clearance_time);
    double value, slope, curvature;
    map->FlightCoordinate(from, system.stops[0].dof)
        .ValueSlopeCurvature(contacts.clearance_time, &value, &slope, &curvature);
    const auto before =
        std::find_if(branch.points.rbegin(), branch.points.rend(), [&](const BranchPoint& b) {
          return b.parameter != point.parameter && b.orbit.contacts.clearance;
        });
    double rate = 1.0;  // clearance per unit parameter
    if (before != branch.points.rend()) {
      rate = std::abs(*before->orbit.contacts.clearance / (before->parameter - point.parameter));
    }
    Eigen::VectorXd v = at.v;
    v(system.stops[0].dof) = std::sqrt(2.0 * std::abs(curvature) * rate * offset);
    orbit.p = branch.p + 1;
    eta = map->ToEta(at.t, at.x, v);
  }
  std::vector<GrazingSeed> seeds;
  for (double side : {-1.0, 1.0}) {
    try {
      seeds.push_back({problem.SystemAt(point.parameter + side * offset), orbit, eta});
    } catch (const InvalidInput&) {
      // That side is outside the parameter's range.
    }
  }
  return seeds;
}

}  // namespace impactkit
