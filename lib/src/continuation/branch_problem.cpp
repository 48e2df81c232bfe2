#include "continuation/branch_problem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "continuation/arclength.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::detail {

BranchProblem::BranchProblem(const System& base, std::string parameter, int p, int q,
                             const ImpactMapOptions& map_options)
    : curve_(base, std::move(parameter), p, q, 2 * base.Dof(), [map_options](const System& system) {
        return std::make_unique<ImpactMap>(system, map_options);
      }) {
  for (int d = 2; d <= std::min(p, q) && repeat_divisor_ == 1; ++d) {
    if (p % d == 0 && q % d == 0) repeat_divisor_ = d;  // the first is prime
  }
}

std::optional<BranchPoint> BranchProblem::Describe(const Eigen::VectorXd& x,
                                                   const Eigen::VectorXd& previous) const {
  const ImpactMap* map = MapAt(Mu(x));
  if (!map) return std::nullopt;
  const Eigen::VectorXd eta = Eta(x);
  if (map->Apply(eta, p(), false).status != MapStatus::kOk) return std::nullopt;
  const std::optional<Eigen::VectorXd> tangent = Tangent(x, previous);
  if (!tangent) return std::nullopt;
  BranchPoint point;
  point.parameter = Mu(x);
  point.orbit = DescribeOrbit(*map, eta, p(), q());
  point.tangent = *tangent;
  point.test_values = EvaluateBifurcationTests(point.orbit.jacobian, point.orbit.multipliers);
  if (repeat_divisor_ > 1) {
    const MapResult part = map->Apply(eta, p() / repeat_divisor_, false);
    if (part.status != MapStatus::kOk) return std::nullopt;
    point.repeat_gap = part.eta - eta;
    point.repeat_gap(map->TimeIndex()) -=
        (q() / repeat_divisor_) * map->GetSystem().ForcingPeriod();
  }
  return point;
}

}  // namespace impactkit::detail
