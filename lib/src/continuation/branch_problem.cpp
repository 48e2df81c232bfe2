#include "continuation/branch_problem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "continuation/arclength.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"

namespace impactkit::detail {

BranchProblem::BranchProblem(const System& base, std::string parameter, int p, int q,
                             const ImpactMapOptions& map_options)
    : BranchProblem(OrbitSection::kImpact,
                    SectionCurve(base, std::move(parameter), p, q, 2 * base.Dof(),
                                 [map_options](const System& system) {
                                   return std::make_unique<ImpactMap>(system, map_options);
                                 })) {}

BranchProblem::BranchProblem(const System& base, std::string parameter, int releases, int q,
                             const StickingMapOptions& map_options)
    : BranchProblem(OrbitSection::kRelease,
                    SectionCurve(base, std::move(parameter), releases, q, 2 * base.Dof() - 1,
                                 [map_options](const System& system) {
                                   return std::make_unique<StickingMap>(system, map_options);
                                 })) {}

BranchProblem::BranchProblem(OrbitSection section, SectionCurve curve)
    : section_(section), curve_(std::move(curve)) {
  const int k = Events();
  for (int d = 2; d <= std::min(k, q()) && repeat_divisor_ == 1; ++d) {
    if (k % d == 0 && q() % d == 0) repeat_divisor_ = d;  // the first is prime
  }
}

PeriodicOrbit BranchProblem::OrbitAt(const Eigen::VectorXd& state, double mu) const {
  const SectionMap* map = MapAt(mu);
  Require(map != nullptr, "the parameter value is not valid for the system");
  if (section_ == OrbitSection::kRelease) {
    return DescribeStickingOrbit(static_cast<const StickingMap&>(*map), state, Events(), q());
  }
  return DescribeOrbit(static_cast<const ImpactMap&>(*map), state, Events(), q());
}

std::optional<BranchPoint> BranchProblem::Describe(const Eigen::VectorXd& x,
                                                   const Eigen::VectorXd& previous) const {
  const SectionMap* map = MapAt(Mu(x));
  if (!map) return std::nullopt;
  const Eigen::VectorXd eta = Eta(x);
  BranchPoint point;
  point.parameter = Mu(x);
  try {
    point.orbit = OrbitAt(eta, Mu(x));
  } catch (const InvalidInput&) {
    return std::nullopt;  // the map fails at X
  }
  const std::optional<Eigen::VectorXd> tangent = Tangent(x, previous);
  if (!tangent) return std::nullopt;
  point.tangent = *tangent;
  point.test_values = EvaluateBifurcationTests(point.orbit.jacobian, point.orbit.multipliers);
  if (repeat_divisor_ > 1) {
    std::optional<Eigen::VectorXd> gap = RepeatGap(x);
    if (!gap) return std::nullopt;
    point.repeat_gap = *std::move(gap);
  }
  return point;
}

std::optional<Eigen::VectorXd> BranchProblem::RepeatGap(const Eigen::VectorXd& x) const {
  if (repeat_divisor_ == 1) return std::nullopt;
  const SectionMap* map = MapAt(Mu(x));
  if (!map) return std::nullopt;
  const Eigen::VectorXd eta = Eta(x);
  const SectionImage part = map->Iterate(eta, Events() / repeat_divisor_, false);
  if (!part.Ok()) return std::nullopt;
  Eigen::VectorXd gap = part.state - eta;
  gap(map->TimeIndex()) -= (q() / repeat_divisor_) * map->GetSystem().ForcingPeriod();
  return gap;
}

std::optional<bool> BranchProblem::ApproachesRepeat(const Eigen::VectorXd& x,
                                                    const Eigen::VectorXd& gap,
                                                    const Eigen::VectorXd& direction) const {
  const std::optional<Eigen::VectorXd> ahead = RepeatGap(x + kGapDifference * direction);
  if (!ahead) return std::nullopt;
  return gap.dot(*ahead - gap) < 0;
}

BranchProblem FamilyProblem(const System& system, const ContinuationOptions& options,
                            OrbitSection section, int stop, int k, int q) {
  if (section == OrbitSection::kRelease) {
    StickingMapOptions map = options.orbit.release_map;
    map.stop = stop;
    return BranchProblem(system, options.parameter, k, q, map);
  }
  ImpactMapOptions map = options.orbit.map;
  map.stop = stop;
  return BranchProblem(system, options.parameter, k, q, map);
}

}  // namespace impactkit::detail
