#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "cvode_impacts.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/model/system.hpp"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using namespace impactkit;

namespace {

/// A linear regime to test: M, C, K, A, constant force, Ω.
struct Regime {
  const char* name;
  Eigen::MatrixXd m, c, k;
  Eigen::VectorXd a, f0;
  double omega;
};

Regime ChainRegime(const char* name, int n, double c, double omega) {
  const System s =
      UniformChain({n, 1.0, 1.0, c}, Eigen::VectorXd::LinSpaced(n, 0.5, 0.1), omega, 0.1, 0.7);
  return {name, s.mass, s.damping, s.stiffness, s.forcing, Eigen::VectorXd::Zero(n), omega};
}

/// Non-proportional damping: a dashpot on the first mass only.
Regime NonProportional() {
  Regime r = ChainRegime("3-DOF non-proportional", 3, 0.0, 0.8);
  r.m.diagonal() << 1.0, 2.0, 0.5;
  r.c(0, 0) = 0.4;
  r.c(2, 2) = 0.05;
  r.f0 = Eigen::Vector3d(0.0, 0.1, -0.2);
  return r;
}

std::vector<Regime> Regimes() {
  Regime stuck = ChainRegime("1-DOF with constant force (stuck subsystem)", 1, 0.2, 0.7);
  stuck.f0 = Eigen::VectorXd::Constant(1, 0.1);
  return {ChainRegime("1-DOF under-damped", 1, 0.1, 1.3),
          ChainRegime("1-DOF over-damped", 1, 3.0, 0.4),
          ChainRegime("1-DOF critically damped", 1, 2.0, 0.9),
          ChainRegime("2-DOF paper", 2, 0.1, 1.4),
          ChainRegime("2-DOF over-damped", 2, 8.0, 1.4),
          ChainRegime("5-DOF under-damped", 5, 0.1, 0.9),
          ChainRegime("5-DOF over-damped", 5, 10.0, 0.9),
          NonProportional(),
          stuck};
}

}  // namespace

TEST_CASE("closed-form flow agrees with CVODE to 1e-9 over several periods", "[flow]") {
  for (const Regime& r : Regimes()) {
    INFO(r.name);
    const LinearFlow flow(r.m, r.c, r.k, r.a, r.f0, r.omega);
    const Eigen::Index n = r.m.rows();
    Eigen::VectorXd x0 = Eigen::VectorXd::LinSpaced(n, 0.3, -0.2);
    Eigen::VectorXd v0 = Eigen::VectorXd::LinSpaced(n, -0.4, 0.6);
    const double t0 = 0.7, t1 = t0 + 5.0 * 2.0 * std::numbers::pi / r.omega;
    const Eigen::VectorXd z0 = flow.Transient(t0, x0, v0);
    Eigen::VectorXd x, v;
    flow.State(t0, z0, t1, &x, &v);
    reference::CvodeLinearFlow(r.m, r.c, r.k, r.a, r.f0, r.omega, t0, x0, v0, t1);
    CHECK((x - x0).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((v - v0).cwiseAbs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("state transition equals the matrix exponential e^{S tau}", "[flow]") {
  for (const Regime& r : Regimes()) {
    INFO(r.name);
    const LinearFlow flow(r.m, r.c, r.k, r.a, r.f0, r.omega);
    for (double tau : {0.0, 0.37, 4.1}) {
      const Eigen::MatrixXd expected = (flow.SystemMatrix() * tau).exp();
      CHECK((flow.Transition(tau) - expected).cwiseAbs().maxCoeff() < 1e-11);
    }
  }
}

TEST_CASE("1-DOF closed forms: critical damping and the steady amplitude", "[flow]") {
  // x'' + 2x' + x = 0: x(t) = (x0 + (v0 + x0) t) e^{-t}.
  const Eigen::MatrixXd one = Eigen::MatrixXd::Ones(1, 1);
  const LinearFlow critical(one, 2.0 * one, one, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1),
                            1.0);
  const double x0 = 0.3, v0 = -1.1;
  const Eigen::VectorXd z0 =
      critical.Transient(0.0, Eigen::VectorXd::Constant(1, x0), Eigen::VectorXd::Constant(1, v0));
  Eigen::VectorXd x, v;
  for (double t : {0.5, 2.0, 9.0}) {
    critical.State(0.0, z0, t, &x, &v);
    CHECK_THAT(x(0), WithinAbs((x0 + (v0 + x0) * t) * std::exp(-t), 1e-15));
  }
  // m x'' + c x' + k x = A cos Ωt: amplitude A / sqrt((k - m Ω²)² + (c Ω)²).
  const double m = 2.0, c = 0.3, k = 5.0, a = 0.7, omega = 1.9;
  const LinearFlow forced(m * one, c * one, k * one, Eigen::VectorXd::Constant(1, a),
                          Eigen::VectorXd::Zero(1), omega);
  double peak = 0.0;
  for (int i = 0; i < 2000; ++i) {
    forced.SteadyState(i * 2.0 * std::numbers::pi / omega / 2000, &x, &v);
    peak = std::max(peak, std::hypot(x(0), v(0) / omega));
  }
  CHECK_THAT(peak, WithinRel(a / std::hypot(k - m * omega * omega, c * omega), 1e-12));
}

TEST_CASE("signal derivative bounds hold everywhere after their start", "[flow]") {
  for (const Regime& r : Regimes()) {
    INFO(r.name);
    const LinearFlow flow(r.m, r.c, r.k, r.a, r.f0, r.omega);
    const Eigen::Index n = r.m.rows();
    const Eigen::VectorXd z0 =
        flow.Transient(0.0, Eigen::VectorXd::Constant(n, 0.2), Eigen::VectorXd::Constant(n, -0.3));
    LinearOutput last{Eigen::RowVectorXd::Unit(n, n - 1), Eigen::RowVectorXd::Zero(n), 0.1, -0.1};
    const Signal w = flow.Output(flow.Prepare(last), 0.0, z0);
    Eigen::VectorXd x, v;
    for (int order = 0; order <= 3; ++order) {
      const Signal d = w.Derivative(order);
      for (double from : {0.0, 3.0}) {
        const double bound = w.DerivativeBound(order, from);
        for (double t = from; t < from + 40.0; t += 0.01) {
          REQUIRE(std::abs(d.Value(t)) <= bound * (1 + 1e-12));
        }
      }
    }
    // The output is the state's: l·x + 0.1 cos Ωt - 0.1.
    for (double t : {0.3, 7.0}) {
      flow.State(0.0, z0, t, &x, &v);
      CHECK_THAT(w.Value(t), WithinAbs(x(n - 1) + 0.1 * std::cos(r.omega * t) - 0.1, 1e-14));
      double value, slope;
      w.ValueAndSlope(t, &value, &slope);
      CHECK_THAT(slope, WithinAbs(v(n - 1) - 0.1 * r.omega * std::sin(r.omega * t), 1e-14));
    }
  }
}

// The gap after an impact is 0 exactly; from there its change over a short
// flight must be rounded relative to that change (the terms' size times the
// flight's duration s), not to the terms' size: that is what places a slow
// bounce's return (docs/theory.md §4). The reference is the closed form of
// the 1-DOF flight written without cancellation in long double.
TEST_CASE(
    "an anchored signal's and a state's change since the flight's start are rounded "
    "relative to themselves",
    "[flow]") {
  constexpr double m = 1.0, k = 1.0, c = 0.1, a = 1.2, omega = 0.46, xs = 0.3;
  constexpr double t0 = 3.7, v0 = -1e-6;  // just after an impact, leaving the stop slowly
  const LinearFlow flow(Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
                        Eigen::MatrixXd::Constant(1, 1, k), Eigen::VectorXd::Constant(1, a),
                        Eigen::VectorXd::Zero(1), omega);
  const Eigen::VectorXd z0 =
      flow.Transient(t0, Eigen::VectorXd::Constant(1, xs), Eigen::VectorXd::Constant(1, v0));
  Signal gap = flow.Output(
      flow.Prepare({Eigen::RowVectorXd::Ones(1), Eigen::RowVectorXd::Zero(1), 0.0, -xs}), t0, z0);
  gap.AnchorAt(0.0, v0);
  // x_p = X cos θ, θ = Ωt − φ; the transient from (xs − x_p, v0 − v_p) at t0.
  // Every constant in long double: one rounded in double would put an error
  // ~ε s into the increments checked below.
  const long double w = omega, detuning = k - m * w * w;
  const long double amplitude = a / std::hypot(detuning, c * w);
  const long double theta0 = w * static_cast<long double>(t0) - std::atan2(c * w, detuning);
  const long double decay = c / (2 * static_cast<long double>(m));
  const long double rate = std::sqrt(k / static_cast<long double>(m) - decay * decay);
  const long double dx = xs - amplitude * std::cos(theta0);
  const long double dv = v0 + amplitude * w * std::sin(theta0);
  for (const double step : {1e-9, 1e-6, 1e-3, 0.1, 1.0, 4.0, 200.0}) {
    const double s = (t0 + step) - t0;  // the step the signal sees (exact)
    // x(t0 + s) − xs = Δx_p + (Φ11 − 1) dx + Φ12 dv, each without cancellation.
    const long double half_step = w * s / 2;
    const long double steady = -2 * amplitude * std::sin(theta0 + half_step) * std::sin(half_step);
    const long double sine = std::sin(rate * s), half_sine = std::sin(rate * s / 2);
    const long double cosine_part = std::cos(rate * s) + decay / rate * sine;
    const long double phi11_increment =
        std::expm1(-decay * s) * cosine_part - 2 * half_sine * half_sine + decay / rate * sine;
    const long double phi12 = std::exp(-decay * s) * sine / rate;
    const double expected = static_cast<double>(steady + phi11_increment * dx + phi12 * dv);
    // v(t0 + s) − v0 = Δv_p + Φ21 dx + (Φ22 − 1) dv.
    const long double steady_velocity =
        -2 * amplitude * w * std::cos(theta0 + half_step) * std::sin(half_step);
    const long double phi21 = -(k / m) / rate * std::exp(-decay * s) * sine;
    const long double phi22_increment =
        std::expm1(-decay * s) * (std::cos(rate * s) - decay / rate * sine) -
        2 * half_sine * half_sine - decay / rate * sine;
    const double expected_velocity =
        static_cast<double>(steady_velocity + phi21 * dx + phi22_increment * dv);
    CAPTURE(s, expected, expected_velocity);
    // The terms are of size ~1 (X ≈ 1.4, the rates ≤ 1). The anchored gap
    // is value + slope s + the terms' second-order remainders, ~s²: 32 ulps
    // of s² (and of the result), beside the reference's own rounding (16
    // long-double ulps of its first-order terms, ~s). An evaluation from
    // the first order on would err by ~ε s, 100 times more at s = 1e-9.
    // Beyond s = 1/ρ = 1 the terms' own rounding, ~ε: the anchored sum
    // would err by ~ε s there, 200 times more at s = 200.
    constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
    const double reference_rounding = 16 * std::numeric_limits<long double>::epsilon() * s;
    const double change = std::min(s, 1.0);
    double value, slope, curvature;
    gap.PreciseValueSlopeCurvature(t0 + s, &value, &slope, &curvature);
    CHECK(std::abs(value - expected) <=
          32 * kEpsilon * (change * change + std::abs(expected)) + reference_rounding);
    // The state from the flight's start, by first-order increments (~s),
    // to 32 ulps of s, and of the start's own values.
    Eigen::VectorXd x, v;
    flow.StateFrom(t0, Eigen::VectorXd::Constant(1, xs), Eigen::VectorXd::Constant(1, v0), z0,
                   t0 + s, &x, &v);
    CHECK(std::abs((x(0) - xs) - expected) <= 32 * kEpsilon * s + kEpsilon * xs);
    CHECK(std::abs((v(0) - v0) - expected_velocity) <= 32 * kEpsilon * s + kEpsilon * std::abs(v0));
  }
  double value, slope, curvature;
  gap.PreciseValueSlopeCurvature(t0, &value, &slope, &curvature);
  CHECK(value == 0.0);
}
