// The single-degree-of-freedom oscillator's P(1,1) orbit in closed form
// (Shaw & Holmes 1983 style), against the library's impact map and FindOrbit.
//
// m x'' + c x' + k x = A cos Ωt, stop at xs, restitution r. With y = (x, v),
// y_p(t) = (X cos θ, -X Ω sin θ), θ = Ωt - φ, the steady response, and Φ(s)
// the homogeneous transition (here Eigen's matrix exponential, independent
// of the library's modal formula), a P(1,1) orbit with impact speed u at τ
// satisfies y(τ+T)- = (xs, u) and y(τ)+ = (xs, -r u), so since y_p is
// T-periodic
//     (I - Φ(T)) y_p(τ) = (I - Φ(T)) w + u (I + r Φ(T)) e2,   w = (xs, 0),
// i.e. y_p(τ) = w + u d with d = (I - Φ(T))⁻¹ (I + r Φ(T)) e2. Then
// (xs + u d1)² + (u d2 / Ω)² = X² is a quadratic in u, and θ follows.
// Its 2 x 2 Jacobian comes from implicit differentiation of
//     G(τ, u, τ', u') = (xs, u') - y_p(τ') - Φ(τ' - τ) [(xs, -r u) - y_p(τ)] = 0.

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "impactkit/orbits/impact_map.hpp"
#include "impactkit/orbits/orbit.hpp"

using namespace impactkit;

namespace {

struct Sdof {
  double m, k, c, a, xs, r, omega;

  double Period() const { return 2 * std::numbers::pi / omega; }
  double Amplitude() const { return a / std::hypot(k - m * omega * omega, c * omega); }
  double Lag() const { return std::atan2(c * omega, k - m * omega * omega); }
  Eigen::Matrix2d B() const { return (Eigen::Matrix2d() << 0, 1, -k / m, -c / m).finished(); }
  Eigen::Matrix2d Phi(double s) const { return (B() * s).exp(); }
  Eigen::Vector2d Steady(double t) const {
    const double theta = omega * t - Lag();
    return {Amplitude() * std::cos(theta), -Amplitude() * omega * std::sin(theta)};
  }
  Eigen::Vector2d SteadyRate(double t) const {
    const double theta = omega * t - Lag();
    return {-Amplitude() * omega * std::sin(theta), -Amplitude() * omega * omega * std::cos(theta)};
  }
};

struct Orbit11 {
  double tau, u;
};

std::vector<Orbit11> ClosedFormOrbits(const Sdof& s) {
  const Eigen::Matrix2d phi = s.Phi(s.Period());
  const Eigen::Vector2d e2(0, 1);
  const Eigen::Vector2d d = (Eigen::Matrix2d::Identity() - phi)
                                .lu()
                                .solve((Eigen::Matrix2d::Identity() + s.r * phi) * e2);
  const double x = s.Amplitude();
  const double qa = d(0) * d(0) + d(1) * d(1) / (s.omega * s.omega);
  const double qb = 2 * s.xs * d(0), qc = s.xs * s.xs - x * x;
  const double disc = qb * qb - 4 * qa * qc;
  std::vector<Orbit11> orbits;
  if (disc < 0) return orbits;
  for (double sign : {-1.0, 1.0}) {
    const double u = (-qb + sign * std::sqrt(disc)) / (2 * qa);
    if (u <= 0) continue;
    const double theta = std::atan2(-u * d(1) / (x * s.omega), (s.xs + u * d(0)) / x);
    const double tau = std::fmod((theta + s.Lag()) / s.omega + 10 * s.Period(), s.Period());
    orbits.push_back({tau, u});
  }
  return orbits;
}

/// The map's Jacobian at a P(1,1) orbit by implicit differentiation of G.
Eigen::Matrix2d ClosedFormJacobian(const Sdof& s, const Orbit11& o) {
  const double t1 = o.tau + s.Period();
  const Eigen::Matrix2d phi = s.Phi(s.Period());
  const Eigen::Vector2d start = Eigen::Vector2d(s.xs, -s.r * o.u) - s.Steady(o.tau);
  Eigen::Matrix2d dg_next, dg_now;
  dg_next.col(0) = -s.SteadyRate(t1) - s.B() * phi * start;         // ∂G/∂τ'
  dg_next.col(1) = Eigen::Vector2d(0, 1);                           // ∂G/∂u'
  dg_now.col(0) = s.B() * phi * start + phi * s.SteadyRate(o.tau);  // ∂G/∂τ
  dg_now.col(1) = s.r * phi * Eigen::Vector2d(0, 1);                // ∂G/∂u
  return -dg_next.lu().solve(dg_now);
}

/// Largest x - xs strictly inside the flight (τ, τ + T), sampled finely.
double LargestGapInside(const Sdof& s, const Orbit11& o) {
  const Eigen::Vector2d start = Eigen::Vector2d(s.xs, -s.r * o.u) - s.Steady(o.tau);
  double largest = -INFINITY;
  for (int i = 1; i < 20000; ++i) {
    const double t = o.tau + i * s.Period() / 20000;
    largest = std::max(largest, (s.Steady(t) + s.Phi(t - o.tau) * start)(0) - s.xs);
  }
  return largest;
}

}  // namespace

TEST_CASE("N = 1: the P(1,1) orbit and its multipliers match the closed form", "[orbit]") {
  int valid = 0, checked_rejections = 0;
  for (double xs : {0.1, 0.2}) {
    for (double r : {0.7, 0.8}) {
      for (double omega : {1.2, 1.6, 2.1, 2.6}) {
        const Sdof s{1.0, 1.0, 0.1, 0.5, xs, r, omega};
        const System system =
            UniformChain({1, s.m, s.k, s.c}, Eigen::VectorXd::Constant(1, s.a), omega, xs, r);
        const ImpactMap map(system);
        for (const Orbit11& o : ClosedFormOrbits(s)) {
          INFO("xs = " << xs << ", r = " << r << ", omega = " << omega << ", u = " << o.u);
          const Eigen::Vector2d eta(o.tau, o.u);
          const MapResult image = map.Apply(eta, 1, true);
          if (LargestGapInside(s, o) > 1e-9) {
            // Not a true orbit: it would pass through the stop. The map must
            // find the earlier contact instead of returning after T.
            CHECK((image.termination != Termination::kCompleted ||
                   image.eta(0) < o.tau + s.Period() - 1e-6));
            ++checked_rejections;
            continue;
          }
          ++valid;
          REQUIRE(image.termination == Termination::kCompleted);
          CHECK((image.eta - eta - Eigen::Vector2d(s.Period(), 0)).cwiseAbs().maxCoeff() < 1e-10);
          const Eigen::Matrix2d expected = ClosedFormJacobian(s, o);
          CHECK((image.jacobian - expected).norm() <= 1e-8 * expected.norm());
          // FindOrbit from a seed 1e-3 away lands on the closed form.
          OrbitOptions options;
          PeriodicOrbit orbit;
          const OrbitSummary summary =
              FindOrbit(system, eta + Eigen::Vector2d(1e-3, 1e-3), options, &orbit);
          REQUIRE(summary.termination == Termination::kConverged);
          CHECK(std::abs(orbit.eta(1) - o.u) < 1e-10);
          Eigen::Vector2cd lambda = Eigen::EigenSolver<Eigen::Matrix2d>(expected).eigenvalues();
          if (std::abs(lambda(1)) > std::abs(lambda(0))) std::swap(lambda(0), lambda(1));
          CHECK(std::abs(std::abs(orbit.multipliers(0)) - std::abs(lambda(0))) < 1e-8);
          CHECK(std::abs(std::abs(orbit.multipliers(1)) - std::abs(lambda(1))) < 1e-8);
          CHECK(orbit.stable == (std::abs(lambda(0)) < 1.0));
        }
      }
    }
  }
  CHECK(valid >= 4);
  INFO("rejected candidates checked: " << checked_rejections);
}
