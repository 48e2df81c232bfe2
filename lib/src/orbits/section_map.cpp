#include "impactkit/orbits/section_map.hpp"

#include <algorithm>
#include <cmath>

namespace impactkit {

Eigen::MatrixXd FiniteDifferenceJacobian(const SectionMap& map, const Eigen::VectorXd& x, int k,
                                         double relative_step) {
  const Eigen::Index dim = x.size();
  Eigen::MatrixXd jacobian(dim, dim);
  for (Eigen::Index j = 0; j < dim; ++j) {
    // The time is absolute: its natural scale is the forcing period, not |t|.
    const double scale =
        j == map.TimeIndex() ? map.GetSystem().ForcingPeriod() : std::max(1.0, std::abs(x(j)));
    const double h = relative_step * scale;
    Eigen::VectorXd plus = x, minus = x;
    plus(j) += h;
    minus(j) -= h;
    const SectionImage forward = map.Iterate(plus, k, false),
                       backward = map.Iterate(minus, k, false);
    if (!forward.Ok() || !backward.Ok()) return {};
    jacobian.col(j) = (forward.state - backward.state) / (2.0 * h);
  }
  return jacobian;
}

SectionImage SectionMap::ParameterRate(const Eigen::VectorXd& x, int k, const SectionMap& below,
                                       const SectionMap& above, double delta,
                                       const SectionImage*) const {
  SectionImage low = below.Iterate(x, k, false), high = above.Iterate(x, k, false);
  if (!low.Ok()) return low;
  if (!high.Ok()) return high;
  high.state = (high.state - low.state) / delta;
  return high;
}

}  // namespace impactkit
