#include "continuation/curve_problem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "continuation/arclength.hpp"
#include "continuation/defining_function.hpp"
#include "continuation/vanishing_impact.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/grazing_limit.hpp"

namespace impactkit::detail {

CurveProblem::CurveProblem(const System& base, const CurveOptions& options, SpecialPointType type,
                           int grazing_flight, int grazing_stop, bool response)
    : base_(base),
      options_(options),
      mu1_(base_, options_.parameter),
      mu2_(base_, options_.parameter2),
      type_(type),
      grazing_flight_(grazing_flight),
      response_(response),
      touched_stop_(response ? NonImpactingTouchStop(base) : grazing_stop),
      eta_size_(response ? 0 : 2 * base.Dof()),
      size_(response ? 2 : 2 * base.Dof() + 2 + (type == SpecialPointType::kGrazing ? 1 : 0)) {
  for (const auto& [stop, what] : {std::pair{options_.orbit.map.stop, "the orbit's section stop"},
                                   std::pair{touched_stop_, "the stop touched"}}) {
    Require(stop >= 0 && stop < base_.StopCount(),
            fmt::format("{} must be one of the system's {} stops (0 to {}), got {}", what,
                        base_.StopCount(), base_.StopCount() - 1, stop));
  }
}

Eigen::VectorXd CurveProblem::Join(const Eigen::VectorXd& eta, double contact_time, double mu1,
                                   double mu2) const {
  Eigen::VectorXd x(size_);
  x.head(eta_size_) = eta;
  if (HasContactTime()) x(eta_size_) = contact_time;
  x(size_ - 2) = mu1;
  x(size_ - 1) = mu2;
  return x;
}

System CurveProblem::SystemAt(double mu1, double mu2) const {
  System system = base_;
  mu2_.Set(system, mu2);
  mu1_.Set(system, mu1);
  ValidateParameters(system);
  return system;
}

const BranchProblem& CurveProblem::Along(const NamedParameter& fixed, double value,
                                         const NamedParameter& free, CachedBranch* cache) const {
  if (!cache->problem || cache->fixed_at != value) {
    System at = base_;
    fixed.Set(at, value);
    cache->problem = std::make_unique<BranchProblem>(at, free.Name(), options_.orbit.p,
                                                     options_.orbit.q, options_.orbit.map);
    cache->fixed_at = value;
  }
  return *cache->problem;
}

const BranchProblem& CurveProblem::Along1(double mu2) const {
  return Along(mu2_, mu2, mu1_, &along1_);
}

const BranchProblem& CurveProblem::Along2(double mu1) const {
  return Along(mu1_, mu1, mu2_, &along2_);
}

bool CurveProblem::Defining(const Eigen::VectorXd& x, Eigen::VectorXd* g,
                            Eigen::VectorXd* u) const {
  if (!x.allFinite()) return false;
  if (response_) {
    g->resize(1);
    try {
      (*g)(0) = NonImpactingClearance(SystemAt(Mu1(x), Mu2(x)), touched_stop_);
    } catch (const InvalidInput&) {
      return false;  // outside a parameter's range
    }
    return std::isfinite((*g)(0));
  }
  const ImpactMap* map = Along1(Mu2(x)).ImpactMapAt(Mu1(x));
  if (!map) return false;
  const Eigen::VectorXd eta = Eta(x);
  if (!(map->Speed(eta, map->SectionStop()) > 0)) return false;
  if (type_ == SpecialPointType::kGrazing) {
    // The flight's state at t*, ignoring the stops: smooth on both sides of
    // the grazing (Residual rejects the side where the orbit crosses it).
    // The touched stop's gap s (x_c − xs), held kGrazingMargin inside, and
    // v_c = 0.
    const std::optional<FlightStart> start = GrazingFlightStart(*map, eta);
    if (!start) return false;
    const HybridState at = map->FlightState(start->eta, x(eta_size_), start->stop);
    const StopParameters& touched = map->GetSystem().stops[touched_stop_];
    g->resize(2);
    *g << touched.Sign() * (at.x(touched.dof) - touched.position) + kGrazingMargin,
        at.v(touched.dof);
    return g->allFinite();
  }
  // U and D P come from one map application, which Residual has usually
  // just made (BranchProblem keeps them).
  const BranchProblem& along = Along1(Mu2(x));
  const Eigen::VectorXd at = BranchProblem::Join(eta, Mu1(x));
  Eigen::VectorXd own_u;
  Eigen::MatrixXd dp;
  if (!along.Residual(at, u ? u : &own_u) || !along.MapJacobian(at, &dp)) return false;
  g->resize(1);
  const TestFunction& own = *TestFunctionOf(type_);
  if (own.critical_multiplier) {
    (*g)(0) = kMultiplierRowWeight * MultiplierFunction(dp, *own.critical_multiplier, borders_);
  } else {
    const Eigen::VectorXcd lambda = dp.eigenvalues();
    (*g)(0) = own.value(dp, lambda);
  }
  return g->allFinite();
}

std::optional<CurveProblem::FlightStart> CurveProblem::GrazingFlightStart(
    const ImpactMap& map, const Eigen::VectorXd& eta) const {
  if (grazing_flight_ == 0) return FlightStart{eta, map.SectionStop()};
  // The impacts before the flight may be at any stops.
  const MapResult before = map.Follow(eta, map.SectionStop(), grazing_flight_, false);
  if (before.termination != Termination::kCompleted) return std::nullopt;
  return FlightStart{before.eta, before.stops.back()};
}

bool CurveProblem::TouchInsideFlight(const Eigen::VectorXd& x) const {
  const ImpactMap* map = Along1(Mu2(x)).ImpactMapAt(Mu1(x));
  if (!map) return false;
  const std::optional<FlightStart> start = GrazingFlightStart(*map, Eta(x));
  if (!start) return false;
  const MapResult next = map->Follow(start->eta, start->stop, 1, false);
  const double t = x(eta_size_);
  const int time = map->TimeIndex();
  return next.termination == Termination::kCompleted && t > start->eta(time) && t < next.eta(time);
}

bool CurveProblem::Residual(const Eigen::VectorXd& x, Eigen::VectorXd* f) const {
  if (response_) return Defining(x, f);
  if (!x.allFinite()) return false;
  Eigen::VectorXd u, g;
  if (!Along1(Mu2(x)).Residual(BranchProblem::Join(Eta(x), Mu1(x)), &u)) return false;
  if (!Defining(x, &g)) return false;
  // Beyond the grazing the flight crosses the stop before t*: the map took
  // an extra impact there and U is another orbit's.
  if (IsGrazing() && !TouchInsideFlight(x)) return false;
  f->resize(size_ - 1);
  *f << u, g;
  return true;
}

bool CurveProblem::Jacobian(const Eigen::VectorXd& x, Eigen::MatrixXd* jacobian,
                            double step_scale) const {
  if (response_) return DefiningGradient(x, step_scale, jacobian);
  const Eigen::VectorXd eta = Eta(x);
  Eigen::MatrixXd along1, along2;
  if (!Along1(Mu2(x)).Jacobian(BranchProblem::Join(eta, Mu1(x)), &along1)) return false;
  if (!Along2(Mu1(x)).Jacobian(BranchProblem::Join(eta, Mu2(x)), &along2)) return false;
  jacobian->setZero(size_ - 1, size_);
  jacobian->topLeftCorner(eta_size_, eta_size_) = along1.leftCols(eta_size_);
  jacobian->block(0, size_ - 2, eta_size_, 1) = along1.col(eta_size_);
  jacobian->block(0, size_ - 1, eta_size_, 1) = along2.col(eta_size_);
  const Eigen::MatrixXd u_jacobian = jacobian->topRows(eta_size_);
  Eigen::MatrixXd defining;
  if (!DefiningGradient(x, step_scale, &defining, &u_jacobian)) return false;
  jacobian->bottomRows(defining.rows()) = defining;
  return jacobian->allFinite();
}

bool CurveProblem::DefiningGradient(const Eigen::VectorXd& x, double step_scale,
                                    Eigen::MatrixXd* gradient,
                                    const Eigen::MatrixXd* u_jacobian) const {
  Eigen::VectorXd g, u;
  // Rows built on D P are differenced only between maps that follow the
  // same impacts (SameImpacts); the grazing rows follow one flight and
  // ignore the stop, so they are smooth across it.
  const bool guarded = u_jacobian && !IsGrazing() && Defining(x, &g, &u);
  return CentralDifferenceGradient(
      [&](const Eigen::VectorXd& at, Eigen::VectorXd* rows) {
        if (!guarded) return Defining(at, rows);
        Eigen::VectorXd u_at;
        return Defining(at, rows, &u_at) && SameImpacts(u_at - u, *u_jacobian * (at - x));
      },
      x, kDefiningStep * step_scale, gradient);
}

Eigen::VectorXd CurveProblem::Inside(const Eigen::VectorXd& x) const {
  Eigen::VectorXd f, g;
  Eigen::MatrixXd gradient;
  if (!HasContactTime() || Residual(x, &f) || !Defining(x, &g) || !(g(0) > 0) ||
      !DefiningGradient(x, 1.0, &gradient)) {
    return x;
  }
  // Reflected across the linearised surface s (x_c(t*) − xs) = −margin: as far
  // inside as the prediction was outside.
  const Eigen::VectorXd normal = gradient.row(0).transpose();
  const double norm2 = normal.squaredNorm();
  return norm2 > 0 ? Eigen::VectorXd(x - 2.0 * g(0) * normal / norm2) : x;
}

void CurveProblem::UpdateBorders(const Eigen::VectorXd& x) {
  const TestFunction* own = TestFunctionOf(type_);
  if (!own || !own->critical_multiplier) return;
  Eigen::MatrixXd dp;
  if (!Along1(Mu2(x)).MapJacobian(BranchProblem::Join(Eta(x), Mu1(x)), &dp)) return;
  borders_ = MultiplierBorders(dp, *own->critical_multiplier);
}

std::optional<Eigen::VectorXd> CurveProblem::Correct(const Eigen::VectorXd& guess,
                                                     const Eigen::VectorXd& c, double value,
                                                     const NewtonOptions& newton,
                                                     int* iterations) const {
  return CorrectBordered(
      [this](const Eigen::VectorXd& x, Eigen::VectorXd* u) { return Residual(x, u); },
      [this](const Eigen::VectorXd& x, Eigen::MatrixXd* j) { return Jacobian(x, j); },
      Inside(guess), c, value, newton, iterations);
}

std::optional<Eigen::VectorXd> CurveProblem::Tangent(const Eigen::VectorXd& x,
                                                     const Eigen::VectorXd& previous) const {
  Eigen::MatrixXd j;
  if (!Jacobian(x, &j)) return std::nullopt;
  return ArclengthTangent(j, previous);
}

std::optional<CurvePoint> CurveProblem::Describe(const Eigen::VectorXd& x,
                                                 const Eigen::VectorXd& previous) const {
  // The tangent first: its differences rebuild the maps at other μ2.
  const std::optional<Eigen::VectorXd> tangent = Tangent(x, previous);
  if (!tangent) return std::nullopt;
  CurvePoint point;
  if (!Defining(x, &point.defining)) return std::nullopt;
  point.parameter = Mu1(x);
  point.parameter2 = Mu2(x);
  point.x = x;
  point.tangent = *tangent;
  if (response_) {  // no orbit: the response has no impacts
    if (!GrazingLimits(x, &point)) return std::nullopt;
    return point;
  }
  const ImpactMap* map = Along1(Mu2(x)).ImpactMapAt(Mu1(x));
  const Eigen::VectorXd eta = Eta(x);
  if (!map || map->Apply(eta, options_.orbit.p, false).termination != Termination::kCompleted) {
    return std::nullopt;
  }
  point.orbit = DescribeOrbit(*map, eta, options_.orbit.p, options_.orbit.q);
  point.test_values = EvaluateBifurcationTests(point.orbit.jacobian, point.orbit.multipliers);
  if (HasContactTime()) point.contact_time = x(eta_size_);
  if (IsGrazing() && !GrazingLimits(x, &point)) return std::nullopt;
  return point;
}

std::optional<GrazingOrbit> CurveProblem::GrazingOrbitAt(const Eigen::VectorXd& x) const {
  GrazingOrbit orbit{SystemAt(Mu1(x), Mu2(x)), options_.orbit.q, {}};
  if (response_) {
    orbit.contacts = {ResponseTouch(orbit.system, touched_stop_)};
    return orbit;
  }
  const ImpactMap* map = Along1(Mu2(x)).ImpactMapAt(Mu1(x));
  if (!map) return std::nullopt;
  std::optional<std::vector<StopContact>> contacts = TouchContacts(
      *map, Eta(x), options_.orbit.p, orbit.q, grazing_flight_, ContactTime(x), touched_stop_);
  if (!contacts) return std::nullopt;
  orbit.contacts = std::move(*contacts);
  return orbit;
}

bool CurveProblem::GrazingLimits(const Eigen::VectorXd& x, CurvePoint* point) const {
  const std::optional<GrazingOrbit> orbit = GrazingOrbitAt(x);
  if (!orbit) return false;
  const SpeedSplitMonodromy split = SplitMonodromy(orbit->system, orbit->contacts, orbit->q);
  point->grazing_limits = {split.GrazingLimit(1.0), split.GrazingLimit(-1.0)};
  return std::isfinite(point->grazing_limits[0]) && std::isfinite(point->grazing_limits[1]);
}

}  // namespace impactkit::detail
