// The single-degree-of-freedom P(1,1) orbit from the independent closed form
// of closed_form_sdof.hpp (explicit Φ, no impactkit code), against the
// library's impact map: fixed point, analytic Jacobian, multipliers, and
// the rejection of solutions that would pass through the stop.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "closed_form_sdof.hpp"
#include "impactkit/orbits/impact_map.hpp"
#include "single_mass.hpp"
#include "sorted_eigenvalues.hpp"

using namespace impactkit;
using testing::SdofP11;
using testing::SdofParameters;
using testing::SdofSystem;
using testing::SortedEigenvalues;

namespace {

struct Case {
  double xs, r, omega;
  bool from_brief;  // one of the grid xs ∈ {0.1, 0.2}, r ∈ {0.7, 0.8}, Ω ∈ {1.2, 1.6, 2.1, 2.6}
};

/// m = k = 1, c = 0.1, A = 0.5. The grid, plus cases with unstable orbits
/// (Ω = 1.1, r = 0.8: just past the period doubling; Ω = 2.3, 2.4: flip
/// multipliers -2.7 and -20; xs = 0.2, Ω = 1.9: a saddle-node pair, one
/// root with multiplier 2.1) and with solutions that cross the stop
/// (Ω = 0.6, 0.8, 0.9), found by scanning Ω from 0.3 to 3.
std::vector<Case> Cases() {
  std::vector<Case> cases;
  for (double xs : {0.1, 0.2}) {
    for (double r : {0.7, 0.8}) {
      for (double omega : {1.2, 1.6, 2.1, 2.6}) cases.push_back({xs, r, omega, true});
    }
  }
  for (const Case& c :
       {Case{0.1, 0.8, 1.1, false}, Case{0.1, 0.7, 2.3, false}, Case{0.1, 0.7, 2.4, false},
        Case{0.2, 0.7, 1.9, false}, Case{0.2, 0.8, 1.9, false}, Case{0.1, 0.7, 0.6, false},
        Case{0.2, 0.8, 0.8, false}, Case{0.1, 0.7, 0.9, false}}) {
    cases.push_back(c);
  }
  return cases;
}

SdofParameters Parameters(const Case& c) { return {1.0, 1.0, 0.1, 0.5, c.xs, c.r, c.omega}; }

Eigen::VectorXd Eta(const SdofP11& o) { return Eigen::Vector2d(o.tau, o.u); }

std::string Describe(const Case& c, const SdofP11& o) {
  return "xs = " + std::to_string(c.xs) + ", r = " + std::to_string(c.r) +
         ", omega = " + std::to_string(c.omega) + ", tau = " + std::to_string(o.tau) +
         ", u = " + std::to_string(o.u);
}

}  // namespace

TEST_CASE("closed-form SDOF reference: Φ, the P(1,1) equations and DP are self-consistent",
          "[orbit]") {
  for (const Case& c : Cases()) {
    const SdofParameters p = Parameters(c);
    const double period = p.Period();
    // The explicit Φ against Eigen's matrix exponential.
    for (double s : {0.3, 1.7, period}) {
      const Eigen::Matrix2d expm = (testing::SdofSystemMatrix(p) * s).exp();
      CHECK((testing::SdofTransition(p, s) - expm).norm() < 1e-13);
    }
    for (const SdofP11& o : testing::SdofP11Solutions(p)) {
      INFO(Describe(c, o));
      CHECK(o.tau >= 0.0);
      CHECK(o.tau < period);
      CHECK(testing::SdofP11Residual(p, o).norm() < 1e-12);
      // Brute RK4 over the flight reproduces (xs, u) at τ + T.
      const Eigen::Vector2d end = testing::SdofFlightRk4(
          p, o.tau, Eigen::Vector2d(p.xs, -p.r * o.u), o.tau + period, 20000);
      CHECK((end - Eigen::Vector2d(p.xs, o.u)).norm() < 1e-10);
      // DP against central differences of the implicit map, solved by Newton
      // on x(τ') = xs from the perturbed start (a different route to DP).
      const Eigen::Matrix2d dp = testing::SdofP11Jacobian(p, o);
      Eigen::Matrix2d fd;
      for (int j = 0; j < 2; ++j) {
        Eigen::Vector2d image[2];
        for (int side = 0; side < 2; ++side) {
          const double h = (side == 0 ? 1 : -1) * 1e-6 * (j == 0 ? period : o.u);
          const double tau = o.tau + (j == 0 ? h : 0.0), u = o.u + (j == 1 ? h : 0.0);
          const Eigen::Vector2d start(p.xs, -p.r * u);
          double t = o.tau + period;
          for (int it = 0; it < 50; ++it) {
            const Eigen::Vector2d y = testing::SdofFlight(p, tau, start, t);
            t -= (y(0) - p.xs) / y(1);
          }
          image[side] = Eigen::Vector2d(t, testing::SdofFlight(p, tau, start, t)(1));
        }
        fd.col(j) = (image[0] - image[1]) / (2e-6 * (j == 0 ? period : o.u));
      }
      CHECK((fd - dp).norm() < 1e-6 * std::max(1.0, dp.norm()));
      // The area contraction of the map: det DP = r² e^{-cT/m}.
      CHECK(dp.determinant() == Approx(p.r * p.r * std::exp(-p.c * period / p.m)).epsilon(1e-10));
    }
  }
}

TEST_CASE("N = 1: closed-form P(1,1) orbits are fixed points of the impact map with its Jacobian",
          "[orbit]") {
  int valid_from_brief = 0, stable = 0, unstable = 0;
  for (const Case& c : Cases()) {
    const SdofParameters p = Parameters(c);
    const ImpactMap map(SdofSystem(p));
    for (const SdofP11& o : testing::SdofP11Solutions(p)) {
      if (!testing::SdofCheckFlight(p, o).Valid()) continue;
      INFO(Describe(c, o));
      valid_from_brief += c.from_brief ? 1 : 0;
      const Eigen::Matrix2d dp = testing::SdofP11Jacobian(p, o);
      const auto lambda = testing::Eigenvalues2(dp);
      (std::abs(lambda[0]) < 1.0 ? stable : unstable) += 1;

      const MapResult image = map.Apply(Eta(o), 1, true);
      REQUIRE(image.termination == Termination::kCompleted);
      REQUIRE(image.impacts_done == 1);
      // (a) fixed point: P(η) = η + (T, 0).
      CHECK((image.eta - Eta(o) - Eigen::Vector2d(p.Period(), 0.0)).cwiseAbs().maxCoeff() < 1e-10);
      // (b) analytic Jacobian = closed-form DP.
      REQUIRE(image.jacobian.rows() == 2);
      REQUIRE(image.jacobian.cols() == 2);
      CHECK((image.jacobian - dp).norm() < 1e-8 * dp.norm());
      // (c) multipliers.
      const auto library = SortedEigenvalues(image.jacobian);
      for (int i = 0; i < 2; ++i) {
        CHECK(std::abs(library[i] - lambda[i]) < 1e-8 * std::max(1.0, std::abs(lambda[i])));
      }
    }
  }
  CHECK(valid_from_brief >= 4);
  // The extra cases give both kinds.
  CHECK(stable >= 4);
  CHECK(unstable >= 3);
}

TEST_CASE("N = 1: a P(1,1) solution that passes through the stop is not an orbit of the map",
          "[orbit]") {
  int rejected = 0;
  for (const Case& c : Cases()) {
    const SdofParameters p = Parameters(c);
    const ImpactMap map(SdofSystem(p));
    for (const SdofP11& o : testing::SdofP11Solutions(p)) {
      const int samples = 20000;
      const testing::SdofFlightCheck check = testing::SdofCheckFlight(p, o, samples);
      if (check.Valid()) continue;
      INFO(Describe(c, o) << ", max x - xs = " << check.max_excess);
      ++rejected;
      const MapResult image = map.Apply(Eta(o), 1, false);
      // (d) The map stops at the earlier contact, not at τ + T.
      REQUIRE(image.termination == Termination::kCompleted);
      const double t_next = image.eta(0);
      CHECK(t_next > o.tau);
      CHECK(t_next < o.tau + p.Period() - 1e-3);
      CHECK((image.eta - Eta(o) - Eigen::Vector2d(p.Period(), 0.0)).norm() > 1e-3);
      // ... and that contact is the first one of the closed-form flight: just
      // before the first sample past the stop, and at the stop with the
      // closed-form speed.
      const double h = p.Period() / samples;
      CHECK(t_next <= check.first_contact);
      CHECK(t_next > check.first_contact - h);
      const Eigen::Vector2d y =
          testing::SdofFlight(p, o.tau, Eigen::Vector2d(p.xs, -p.r * o.u), t_next);
      CHECK(std::abs(y(0) - p.xs) < 1e-10);
      CHECK(std::abs(y(1) - image.eta(1)) < 1e-9 * std::max(1.0, std::abs(y(1))));
    }
  }
  CHECK(rejected >= 3);
}
