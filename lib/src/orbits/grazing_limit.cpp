#include "impactkit/orbits/grazing_limit.hpp"

#include <cmath>
#include <numbers>

#include "impactkit/hybrid/hybrid_system.hpp"

namespace impactkit {

Eigen::MatrixXd SpeedSplitMonodromy::At(double speed) const {
  return regular + singular * normal / speed;
}

double SpeedSplitMonodromy::GrazingLimit(double lambda) const {
  const Eigen::Index n = regular.rows();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n + 1, n + 1);
  k.topLeftCorner(n, n) = regular - lambda * Eigen::MatrixXd::Identity(n, n);
  k.topRightCorner(n, 1) = singular.normalized();
  k.bottomLeftCorner(1, n) = normal.normalized();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(k);
  const double least = svd.singularValues()(n);
  return k.partialPivLu().determinant() < 0 ? -least : least;
}

SpeedSplitMonodromy SingleImpactMonodromy(const System& system, double t, const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& v, int q) {
  system.SoleStop("the grazing limit of an orbit's monodromy");
  const HybridSystem hybrid(system);
  const Stop& stop = hybrid.GetStop(0);
  const int n = system.Dof(), c = stop.Dof();
  const Eigen::MatrixXd reset = stop.ResetJacobian(n);
  // f⁺ − R f⁻ with the mass arriving at `speed`: affine in it.
  auto jump = [&](double speed) {
    Eigen::VectorXd before = v;
    before(c) = stop.Sign() * speed;
    Eigen::VectorXd after = before;
    stop.Reset(after);
    return Eigen::VectorXd(hybrid.VectorField(t, x, after) -
                           reset * hybrid.VectorField(t, x, before));
  };
  const Eigen::VectorXd d0 = jump(0.0), d1 = jump(1.0) - d0;
  Eigen::RowVectorXd normal = Eigen::RowVectorXd::Zero(2 * n);
  normal(c) = stop.Sign();
  const Eigen::MatrixXd phi = hybrid.FreeFlow().Transition(q * system.ForcingPeriod());
  return {phi * (reset + d1 * normal), phi * d0, normal};
}

SpeedSplitMonodromy ResponseTouchMonodromy(const System& system, int q) {
  const HybridSystem hybrid(system);
  const Stop& stop = hybrid.GetStop(0);
  const LinearFlow& flow = hybrid.FreeFlow();
  // x_c(t) = a cos Ωt + b sin Ωt: the stop's side of it is largest at
  // Ωt = atan2(s b, s a).
  const double period = system.ForcingPeriod();
  Eigen::VectorXd x, v;
  flow.SteadyState(0.0, &x, &v);
  const double a = stop.Sign() * x(stop.Dof());
  flow.SteadyState(0.25 * period, &x, &v);
  const double b = stop.Sign() * x(stop.Dof());
  const double touch = std::atan2(b, a) / (2.0 * std::numbers::pi) * period;
  flow.SteadyState(touch, &x, &v);
  return SingleImpactMonodromy(system, touch, x, v, q);
}

}  // namespace impactkit
