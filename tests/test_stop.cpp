// The stop as a component (hybrid/stop.hpp, hybrid/hybrid_system.hpp): its
// reset against a finite difference of itself, its witnesses against the
// gap and the contact force computed here from M, C, K and A directly.

#include <catch2/catch.hpp>
#include <cmath>

#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/hybrid/stop.hpp"

using namespace impactkit;
using Catch::Matchers::WithinAbs;

namespace {

/// Full mass matrix, non-proportional damping, the stop on mass 2.
System GeneralThreeDof() {
  Eigen::Matrix3d m, k, c;
  m << 1.2, 0.1, 0, 0.1, 0.8, 0.05, 0, 0.05, 1.5;
  k << 3.0, -1.2, 0, -1.2, 2.5, -0.9, 0, -0.9, 1.4;
  c << 0.2, -0.05, 0, -0.05, 0.1, 0, 0, 0, 0.3;
  return GeneralSystem(m, c, k, Eigen::Vector3d(0.6, -0.2, 0.3), 0.8, 0.15, 0.6, 1);
}

double Evaluate(const LinearOutput& w, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                double omega, double t) {
  return w.wx.dot(x) + w.wv.dot(v) + w.cos_amplitude * std::cos(omega * t) + w.offset;
}

}  // namespace

TEST_CASE("the stop's reset and its Jacobian", "[stop]") {
  const System system = GeneralThreeDof();
  const Stop stop(system);
  Eigen::VectorXd v(3);
  v << 0.3, 0.7, -0.2;
  Eigen::VectorXd after = v;
  stop.Reset(after);
  CHECK(after(0) == v(0));
  CHECK(after(2) == v(2));
  CHECK(after(1) == -0.6 * 0.7);
  // The reset is linear: its Jacobian is its finite difference, exactly up
  // to rounding, column by column over y = (x, v).
  const Eigen::MatrixXd jacobian = stop.ResetJacobian(3);
  for (int j = 0; j < 6; ++j) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(6);
    y(j) = 1.0;
    Eigen::VectorXd reset_v = y.tail(3);
    stop.Reset(reset_v);
    Eigen::VectorXd image(6);
    image << y.head(3), reset_v;
    CHECK((jacobian.col(j) - image).cwiseAbs().maxCoeff() < 1e-15);
  }
}

TEST_CASE("the stop's witnesses are the gap and the contact force", "[stop]") {
  const System system = GeneralThreeDof();
  const Stop stop(system);
  const Eigen::Vector3d x(-0.3, 0.15, 0.4), v(0.2, 0.0, -0.5);
  const double t = 1.7;
  CHECK_THAT(Evaluate(stop.Gap(3).output, x, v, system.omega, t), WithinAbs(x(1) - 0.15, 1e-16));

  // Held: x_2 = xs, v_2 = a_2 = 0. The other rows of M a = f − R e_2, R
  // the stop's reaction, give a without row 2, and row 2 then gives the
  // force pressing the mass into the stop: Fs = R = f_2 − (M a)_2, with
  // f = A cos Ωt − C v − K x.
  const Eigen::Vector3d f =
      system.forcing * std::cos(system.omega * t) - system.damping * v - system.stiffness * x;
  Eigen::Matrix2d m_held;
  m_held << system.mass(0, 0), system.mass(0, 2), system.mass(2, 0), system.mass(2, 2);
  const Eigen::Vector2d a_held = m_held.lu().solve(Eigen::Vector2d(f(0), f(2)));
  const Eigen::Vector3d a(a_held(0), 0.0, a_held(1));
  const double fs = f(1) - system.mass.row(1).dot(a);

  const HybridSystem hybrid(system);
  const Eigen::VectorXd x_held = hybrid.Held(x), v_held = hybrid.Held(v);
  CHECK_THAT(hybrid.ContactForce(t, x_held, v_held), WithinAbs(fs, 1e-12));
  CHECK_THAT(Evaluate(stop.Release(system).output, x_held, v_held, system.omega, t),
             WithinAbs(-fs, 1e-12));
  CHECK(hybrid.Full(x_held, 0.15) == x);
  CHECK(Stop::Holds(1e-9));
  CHECK_FALSE(Stop::Holds(0.0));
  CHECK_FALSE(Stop::Holds(-1e-9));
}

TEST_CASE("the hybrid system's vector field is M⁻¹(A cos Ωt − C v − K x)", "[stop]") {
  const System system = GeneralThreeDof();
  const HybridSystem hybrid(system);
  const Eigen::Vector3d x(-0.3, 0.15, 0.4), v(0.2, 0.1, -0.5);
  const double t = 0.9;
  const Eigen::Vector3d a = system.mass.lu().solve(system.forcing * std::cos(system.omega * t) -
                                                   system.damping * v - system.stiffness * x);
  const Eigen::VectorXd f = hybrid.VectorField(t, x, v);
  CHECK((f.head(3) - v).cwiseAbs().maxCoeff() == 0.0);
  CHECK((f.tail(3) - a).cwiseAbs().maxCoeff() < 1e-14);
  // a_c and its rate: the rate against a central difference in t along the
  // free flow's own vector field (x' = v, v' = a).
  double rate = 0.0;
  Eigen::VectorXd force(3), acceleration(3);
  CHECK_THAT(hybrid.ContactAcceleration(t, x, v, &rate, &force, &acceleration),
             WithinAbs(a(1), 1e-14));
  const double h = 1e-6;
  double ignored;
  const double ahead =
      hybrid.ContactAcceleration(t + h, x + h * v, v + h * a, &ignored, &force, &acceleration);
  const double behind =
      hybrid.ContactAcceleration(t - h, x - h * v, v - h * a, &ignored, &force, &acceleration);
  CHECK_THAT(rate, WithinAbs((ahead - behind) / (2 * h), 1e-7));
}
