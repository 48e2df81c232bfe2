#include "continuation/section_curve.hpp"

#include <algorithm>
#include <cmath>

#include "continuation/arclength.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit::detail {
namespace {

constexpr std::size_t kCachedMaps = 4;

}  // namespace

SectionCurve::SectionCurve(const System& base, std::string parameter, int k, int q, int state_size,
                           MapMaker make_map)
    : base_(base),
      parameter_(base_, parameter),
      k_(k),
      q_(q),
      size_(state_size + 1),
      make_map_(std::move(make_map)) {}

Eigen::VectorXd SectionCurve::Join(const Eigen::VectorXd& state, double mu) {
  Eigen::VectorXd x(state.size() + 1);
  x << state, mu;
  return x;
}

System SectionCurve::SystemAt(double mu) const {
  System system = base_;
  parameter_.Set(system, mu);
  // The map built at μ decomposes the flows and rejects a resonance there.
  ValidateParameters(system);
  return system;
}

const SectionMap* SectionCurve::MapAt(double mu) const {
  // Least recently used first.
  for (auto it = maps_.begin(); it != maps_.end(); ++it) {
    if (it->first == mu) {
      std::rotate(it, it + 1, maps_.end());
      return maps_.back().second.get();
    }
  }
  std::unique_ptr<SectionMap> map;
  try {
    map = make_map_(SystemAt(mu));
  } catch (const InvalidInput&) {
    return nullptr;  // μ outside the parameter's range: the solvers step back
  }
  if (maps_.size() == kCachedMaps) maps_.erase(maps_.begin());
  maps_.emplace_back(mu, std::move(map));
  return maps_.back().second.get();
}

bool SectionCurve::Residual(const Eigen::VectorXd& x, Eigen::VectorXd* u) const {
  // Newton asks for the Jacobian where it has just asked for the residual,
  // and a defining row for D P there too: the analytic D P costs little
  // beside the map, so compute both at once and keep them for that point.
  if (!(cached_x_.size() == x.size() && cached_x_ == x)) {
    if (!x.allFinite()) return false;
    const SectionMap* map = MapAt(Mu(x));
    if (!map) return false;
    const Eigen::VectorXd state = State(x);
    SectionImage image = map->Iterate(state, k_, true);
    stopped_sticking_ = stopped_sticking_ || image.stops_sticking;
    if (!image.Ok()) return false;
    cached_x_ = x;
    image.state(map->TimeIndex()) -= q_ * map->GetSystem().ForcingPeriod();
    cached_residual_ = image.state - state;
    cached_image_ = std::move(image);
  }
  *u = cached_residual_;
  return u->allFinite();
}

bool SectionCurve::MapJacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* dp) const {
  Eigen::VectorXd u;
  if (!Residual(x, &u)) return false;
  *dp = cached_image_.jacobian;
  return true;
}

bool SectionCurve::Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian) const {
  const int n = size_ - 1;
  jacobian->resize(n, size_);
  Eigen::MatrixXd dp;
  if (!MapJacobian(x, &dp)) return false;
  jacobian->leftCols(n) = dp;
  jacobian->leftCols(n).diagonal().array() -= 1.0;
  const double mu = Mu(x);
  const SectionMap* here = MapAt(mu);
  if (!here) return false;
  const double h = here->ParameterStep(dp) * std::max(1.0, std::abs(mu));
  const SectionMap* sides[] = {MapAt(mu - h), MapAt(mu + h)};
  // Central where the map works on both sides, else one-sided: at the edge
  // of the parameter's range, or within h of a family's end, where the map
  // fails beyond it (else the corrector fails there and the branch stops
  // a difference step short of its end).
  const std::pair<int, int> pairs[] = {{0, 1}, {-1, 1}, {0, -1}};  // -1: here
  for (const auto& [low, high] : pairs) {
    const SectionMap* below = low < 0 ? here : sides[low];
    const SectionMap* above = high < 0 ? here : sides[high];
    if (!below || !above) continue;
    const double delta = (low < 0 ? 0.0 : h) + (high < 0 ? 0.0 : h);
    SectionImage rate = here->ParameterRate(State(x), k_, *below, *above, delta, &cached_image_);
    stopped_sticking_ = stopped_sticking_ || rate.stops_sticking;
    if (!rate.Ok()) continue;
    rate.state(here->TimeIndex()) -=
        q_ * (above->GetSystem().ForcingPeriod() - below->GetSystem().ForcingPeriod()) / delta;
    jacobian->col(n) = rate.state;
    return jacobian->allFinite();
  }
  return false;
}

std::optional<Eigen::VectorXd> SectionCurve::Correct(const Eigen::VectorXd& guess,
                                                     const Eigen::VectorXd& c, double value,
                                                     const NewtonOptions& newton,
                                                     int* iterations) const {
  return CorrectBordered(
      [this](const Eigen::VectorXd& x, Eigen::VectorXd* u) { return Residual(x, u); },
      [this](const Eigen::VectorXd& x, Eigen::MatrixXd* j) { return Jacobian(x, j); }, guess, c,
      value, newton, iterations);
}

std::optional<Eigen::VectorXd> SectionCurve::Tangent(const Eigen::VectorXd& x,
                                                     const Eigen::VectorXd& previous) const {
  Eigen::MatrixXd j;
  if (!Jacobian(x, &j)) return std::nullopt;
  return ArclengthTangent(j, previous);
}

}  // namespace impactkit::detail
