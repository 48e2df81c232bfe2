#include "continuation/branch_problem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "continuation/arclength.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::detail {
namespace {

constexpr std::size_t kCachedMaps = 4;

}  // namespace

BranchProblem::BranchProblem(const System& base, std::string parameter, int p, int q,
                             const ImpactMapOptions& map_options)
    : base_(base),
      parameter_(std::move(parameter)),
      p_(p),
      q_(q),
      size_(2 * base.Dof() + 1),
      map_options_(map_options) {
  GetParameter(base_, parameter_);  // throws for an unknown name
  for (int d = 2; d <= std::min(p, q) && repeat_divisor_ == 1; ++d) {
    if (p % d == 0 && q % d == 0) repeat_divisor_ = d;  // the first is prime
  }
}

System BranchProblem::SystemAt(double mu) const {
  System system = base_;
  SetParameter(system, parameter_, mu);
  // The map built at μ decomposes the flows and rejects a resonance there.
  ValidateParameters(system);
  return system;
}

const ImpactMap* BranchProblem::MapAt(double mu) const {
  // Least recently used first: the three maps of one Jacobian (μ, μ ± h)
  // stay valid together.
  for (auto it = maps_.begin(); it != maps_.end(); ++it) {
    if (it->first == mu) {
      std::rotate(it, it + 1, maps_.end());
      return maps_.back().second.get();
    }
  }
  std::unique_ptr<ImpactMap> map;
  try {
    map = std::make_unique<ImpactMap>(SystemAt(mu), map_options_);
  } catch (const InvalidInput&) {
    return nullptr;  // μ outside the parameter's range: the solvers step back
  }
  if (maps_.size() == kCachedMaps) maps_.erase(maps_.begin());
  maps_.emplace_back(mu, std::move(map));
  return maps_.back().second.get();
}

Eigen::VectorXd BranchProblem::Join(const Eigen::VectorXd& eta, double mu) {
  Eigen::VectorXd x(eta.size() + 1);
  x << eta, mu;
  return x;
}

std::optional<MapResult> BranchProblem::Image(const Eigen::VectorXd& x, bool with_jacobian) const {
  if (!x.allFinite()) return std::nullopt;
  const ImpactMap* map = MapAt(Mu(x));
  if (!map) return std::nullopt;
  const Eigen::VectorXd eta = Eta(x);
  if (!(map->Speed(eta, map->SectionStop()) > 0)) return std::nullopt;
  MapResult image = map->Apply(eta, p_, with_jacobian);
  if (image.status != MapStatus::kOk) return std::nullopt;
  image.eta(map->TimeIndex()) -= q_ * map->GetSystem().ForcingPeriod();
  image.eta -= eta;  // now U(X)
  return image;
}

bool BranchProblem::Residual(const Eigen::VectorXd& x, Eigen::VectorXd* u) const {
  // Newton asks for the Jacobian where it has just asked for the residual,
  // and a defining row for D P there too: the analytic D P costs little
  // beside the map, so compute both at once and keep them for that point.
  if (!(cached_x_.size() == x.size() && cached_x_ == x)) {
    const std::optional<MapResult> image = Image(x, true);
    if (!image) return false;
    cached_x_ = x;
    cached_residual_ = image->eta;
    cached_map_jacobian_ = image->jacobian;
  }
  *u = cached_residual_;
  return u->allFinite();
}

bool BranchProblem::MapJacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* dp) const {
  Eigen::VectorXd u;
  if (!Residual(x, &u)) return false;
  *dp = cached_map_jacobian_;
  return true;
}

bool BranchProblem::Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian) const {
  const int n = size_ - 1;
  jacobian->resize(n, size_);
  Eigen::MatrixXd dp;
  if (!MapJacobian(x, &dp)) return false;
  jacobian->leftCols(n) = dp;
  jacobian->leftCols(n).diagonal().array() -= 1.0;
  // U_μ: the map's parameter derivative from maps at μ ± h (one-sided at
  // the edge of the parameter's range), accurate even near grazing.
  const double mu = Mu(x), h = 1e-6 * std::max(1.0, std::abs(mu));
  const ImpactMap* here = MapAt(mu);
  const ImpactMap* above = MapAt(mu + h);
  const ImpactMap* below = MapAt(mu - h);
  if (!above && !below) return false;
  const double delta = (above ? h : 0.0) + (below ? h : 0.0);
  if (!above) above = here;
  if (!below) below = here;
  const Eigen::VectorXd eta = Eta(x);
  Eigen::VectorXd du = here->ParameterDerivative(eta, p_, *below, *above, delta);
  if (du.size() == 0) return false;
  du(here->TimeIndex()) -=
      q_ * (above->GetSystem().ForcingPeriod() - below->GetSystem().ForcingPeriod()) / delta;
  jacobian->col(n) = du;
  return jacobian->allFinite();
}

std::optional<Eigen::VectorXd> BranchProblem::Correct(const Eigen::VectorXd& guess,
                                                      const Eigen::VectorXd& c, double value,
                                                      const NewtonOptions& newton,
                                                      int* iterations) const {
  const int n = size_ - 1;
  const impactkit::Residual residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    Eigen::VectorXd u;
    if (!Residual(x, &u)) return false;
    *f << u, c.dot(x) - value;
    return f->allFinite();
  };
  const impactkit::Jacobian jacobian = [&](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    Eigen::MatrixXd ju;
    if (!Jacobian(x, &ju)) return false;
    j->topRows(n) = ju;
    j->row(n) = c.transpose();
    return true;
  };
  Eigen::VectorXd x = guess;
  const SolveSummary summary = SolveNewton(residual, jacobian, newton, &x);
  *iterations = summary.iterations;
  if (summary.termination != Termination::kConverged) return std::nullopt;
  return x;
}

std::optional<Eigen::VectorXd> BranchProblem::Tangent(const Eigen::VectorXd& x,
                                                      const Eigen::VectorXd& previous) const {
  Eigen::MatrixXd j;
  if (!Jacobian(x, &j)) return std::nullopt;
  return ArclengthTangent(j, previous);
}

std::optional<BranchPoint> BranchProblem::Describe(const Eigen::VectorXd& x,
                                                   const Eigen::VectorXd& previous) const {
  const ImpactMap* map = MapAt(Mu(x));
  if (!map) return std::nullopt;
  const Eigen::VectorXd eta = Eta(x);
  if (map->Apply(eta, p_, false).status != MapStatus::kOk) return std::nullopt;
  const std::optional<Eigen::VectorXd> tangent = Tangent(x, previous);
  if (!tangent) return std::nullopt;
  BranchPoint point;
  point.parameter = Mu(x);
  point.orbit = DescribeOrbit(*map, eta, p_, q_);
  point.tangent = *tangent;
  point.test_values = EvaluateBifurcationTests(point.orbit.jacobian, point.orbit.multipliers);
  if (repeat_divisor_ > 1) {
    const MapResult part = map->Apply(eta, p_ / repeat_divisor_, false);
    if (part.status != MapStatus::kOk) return std::nullopt;
    point.repeat_gap = part.eta - eta;
    point.repeat_gap(map->TimeIndex()) -= (q_ / repeat_divisor_) * map->GetSystem().ForcingPeriod();
  }
  return point;
}

}  // namespace impactkit::detail
