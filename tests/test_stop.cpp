// The stop as a component (hybrid/stop.hpp, hybrid/hybrid_system.hpp): its
// reset against a finite difference of itself, its witnesses against the
// gap and the contact force computed here from M, C, K and A directly.

#include <catch2/catch.hpp>
#include <cmath>

#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/hybrid/simulator.hpp"
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
  const Stop stop(system, 0);
  Eigen::VectorXd v(3);
  v << 0.3, 0.7, -0.2;
  Eigen::VectorXd after = v;
  stop.Reset(after);
  // Newton's law through the mass matrix: v+ = v + λ M⁻¹ e_2 with v_2+ = −r v_2.
  const Eigen::Vector3d column = system.mass.inverse().col(1);
  const double impulse = -(1.0 + 0.6) * 0.7 / column(1);
  CHECK((after - (v + impulse * column)).cwiseAbs().maxCoeff() < 1e-15);
  CHECK(after(1) == -0.6 * 0.7);
  // Kinetic energy drops by (1 − r²) v_c² / (2 (M⁻¹)_cc), whatever the others do.
  auto kinetic = [&](const Eigen::VectorXd& u) { return 0.5 * u.dot(system.mass * u); };
  CHECK_THAT(kinetic(after) - kinetic(v), WithinAbs(-(1 - 0.36) * 0.49 / (2 * column(1)), 1e-15));
  // A diagonal M: only v_c changes, to the last bit (the paper's law).
  const Stop paper_stop(PaperSystem(), 0);
  Eigen::VectorXd u(2);
  u << 0.3, 0.7;
  paper_stop.Reset(u);
  CHECK(u(0) == 0.3);
  CHECK(u(1) == -0.7 * 0.7);
  // The reset is linear: its Jacobian is its finite difference, exactly up
  // to rounding, column by column over y = (x, v).
  const Eigen::MatrixXd jacobian = stop.ResetJacobian(3);
  for (int j = 0; j < 6; ++j) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(6);
    y(j) = 1.0;
    Eigen::VectorXd reset_v = y.tail(3);
    stop.Reset(reset_v);  // linear in v: the image of a unit vector is a column
    Eigen::VectorXd image(6);
    image << y.head(3), reset_v;
    CHECK((jacobian.col(j) - image).cwiseAbs().maxCoeff() < 1e-15);
  }
}

TEST_CASE("the stop's witnesses are the gap and the contact force", "[stop]") {
  const System system = GeneralThreeDof();
  const Stop stop(system, 0);
  const Eigen::Vector3d x(-0.3, 0.15, 0.4), v(0.2, 0.0, -0.5);
  const double t = 1.7;
  CHECK_THAT(Evaluate(stop.Gap({0, 1, 2}).output, x, v, system.omega, t),
             WithinAbs(x(1) - 0.15, 1e-16));

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
  const Eigen::VectorXd x_held = hybrid.Held(0, x), v_held = hybrid.Held(0, v);
  CHECK_THAT(hybrid.ContactForce(0, t, x_held, v_held), WithinAbs(fs, 1e-12));
  const Eigen::Vector3d held_positions(0.0, 0.15, 0.0);
  CHECK_THAT(Evaluate(stop.Release(system, {0, 2}, held_positions).output, x_held, v_held,
                      system.omega, t),
             WithinAbs(-fs, 1e-12));
  CHECK(hybrid.Full(0, x_held, 0.15) == x);
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
  CHECK_THAT(hybrid.ContactAcceleration(0, t, x, v, &rate, &force, &acceleration),
             WithinAbs(a(1), 1e-14));
  const double h = 1e-6;
  double ignored;
  const double ahead =
      hybrid.ContactAcceleration(0, t + h, x + h * v, v + h * a, &ignored, &force, &acceleration);
  const double behind =
      hybrid.ContactAcceleration(0, t - h, x - h * v, v - h * a, &ignored, &force, &acceleration);
  CHECK_THAT(rate, WithinAbs((ahead - behind) / (2 * h), 1e-7));
}

TEST_CASE("a full mass matrix no longer gains energy at impacts and stays bounded", "[stop]") {
  // Found by a randomised run: with v_c alone reversed, 57 of its first 60
  // impacts gained kinetic energy and the motion grew to 1e29.
  Eigen::Matrix3d m, c, k;
  m << 1.604088163968363, -0.13246023729548584, 0.4120205873969771, -0.13246023729548584,
      1.1668991331294452, 0.42532035035927784, 0.4120205873969771, 0.42532035035927784,
      0.6992699301464166;
  c << 0.16795211293584097, 0.0698392807381956, -0.006563485935048544, 0.0698392807381956,
      0.07523302848312648, 0.019404482595265837, -0.006563485935048544, 0.019404482595265837,
      0.06908204611476863;
  k << 1.5900817432046708, -0.262989060829579, -0.5644124897898639, -0.262989060829579,
      1.6503621020569692, 1.0767176184331912, -0.5644124897898639, 1.0767176184331912,
      1.6097422309538914;
  const System system = GeneralSystem(
      m, c, k, Eigen::Vector3d(-0.6540884271515945, -0.6612885033997188, -0.883874767405854),
      1.3891451532513255, 0.2458120848002388, 0.8399329871659771, 1);
  class Check : public Observer {
   public:
    explicit Check(const System& s) : s_(s) {}
    void OnImpact(const Impact& impact) override {
      Eigen::VectorXd after = impact.v;
      Stop(s_, 0).Reset(after);
      gained += after.dot(s_.mass * after) > impact.v.dot(s_.mass * impact.v);
      largest = std::max(largest, impact.x.cwiseAbs().maxCoeff());
      ++count;
    }
    const System& s_;
    int gained = 0, count = 0;
    double largest = 0.0;
  } check(system);
  HybridState state = RestState(system);
  Simulate(system, {}, state, 200 * system.ForcingPeriod(), check);
  CHECK(check.count > 50);
  CHECK(check.gained == 0);
  CHECK(check.largest < 2.0);
}
