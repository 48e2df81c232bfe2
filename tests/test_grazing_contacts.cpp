// Contacts down to the rounding floor (issue 41, item 1): a mass on its
// stop-free steady response, with the stop placed δ below (an impact) or
// above (none) the response's maximum, for δ from 1e-2 to 1e-12. The
// expected first impact is a closed form independent of the flow and the
// event search: x_c(t) = |X_c| cos(Ωt + arg X_c), X = (K − Ω²M + iΩC)⁻¹A,
// reaches xs = |X_c| − δ where Ωt + arg X_c = −θ (mod 2π) with
// 1 − cos θ = δ/|X_c|, at the speed Ω|X_c| sin θ = Ω √(δ (2|X_c| − δ))
// (Nordmark's square-root law, exactly, for a harmonic motion).
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/model/system.hpp"

using namespace impactkit;

namespace {

struct ContactCase {
  std::string name;
  System system;
};

System ChainSystem(int n, double c, double omega) {
  ChainParameters chain;
  chain.dof = n;
  chain.damping = c;
  Eigen::VectorXd forcing = Eigen::VectorXd::Zero(n);
  forcing(0) = 0.5;
  return UniformChain(chain, forcing, omega, 0.1, 0.7);
}

/// The systems the issue names: the paper's chain at three frequencies, a
/// single mass, a 3-mass chain and a lightly damped chain.
std::vector<ContactCase> ContactCases() {
  std::vector<ContactCase> cases;
  for (const double omega : {0.5, 1.0, 1.7}) {
    cases.push_back({"paper chain at omega " + std::to_string(omega), PaperSystem(omega)});
  }
  cases.push_back({"1-DOF", GeneralSystem(Eigen::MatrixXd::Constant(1, 1, 1.0),
                                          Eigen::MatrixXd::Constant(1, 1, 0.05),
                                          Eigen::MatrixXd::Constant(1, 1, 1.0),
                                          Eigen::VectorXd::Constant(1, 0.5), 0.9, 0.1, 0.7)});
  cases.push_back({"3-mass chain", ChainSystem(3, 0.1, 1.1)});
  cases.push_back({"lightly damped chain", ChainSystem(2, 0.001, 1.3)});
  return cases;
}

struct FirstImpact : Observer {
  std::optional<Impact> first;
  void OnImpact(const Impact& impact) override {
    if (!first) first = impact;
  }
  bool ShouldStop() const override { return first.has_value(); }
};

}  // namespace

TEST_CASE(
    "a grazing contact is an impact down to the rounding floor, where the square-root law "
    "puts it",
    "[grazing-contacts][simulate]") {
  for (const ContactCase& base : ContactCases()) {
    const System& s0 = base.system;
    const int c = s0.stops[0].dof;
    const double omega = s0.omega, period = 2 * std::numbers::pi / omega;
    const std::complex<double> i(0.0, 1.0);
    const Eigen::MatrixXcd dynamic = s0.stiffness.cast<std::complex<double>>() -
                                     omega * omega * s0.mass.cast<std::complex<double>>() +
                                     i * omega * s0.damping.cast<std::complex<double>>();
    const Eigen::VectorXcd amplitude =
        dynamic.partialPivLu().solve(s0.forcing.cast<std::complex<double>>());
    const double top = std::abs(amplitude(c)), lag = std::arg(amplitude(c));
    for (const double magnitude : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
      for (const double delta : {magnitude, -magnitude}) {
        INFO(base.name << ", the stop " << delta << " below the steady maximum");
        System s = s0;
        s.stops[0].position = top - delta;
        HybridState state;
        state.x = amplitude.real();
        state.v = (i * omega * amplitude).real();
        FirstImpact observer;
        const SimulationSummary summary = Simulator(s).Run(state, 1.5 * period, observer);
        if (delta < 0) {
          CHECK(!observer.first);
          CHECK(summary.landings == 0);
          continue;
        }
        REQUIRE(observer.first);
        const double theta = 2.0 * std::asin(std::sqrt(delta / (2.0 * top)));
        double expected_t = std::fmod(-theta - lag, 2 * std::numbers::pi) / omega;
        while (expected_t <= 0) expected_t += period;
        const double expected_v = omega * std::sqrt(delta * (2.0 * top - delta));
        // The gap's rounding h (64 ulps of its scale, ~1e-14) moves the
        // speed by up to a h / v (a = Ω²|X_c|) and the time by h / v: the
        // floor below which nothing in double precision can do better.
        const double acceleration = omega * omega * top, rounding = 1e-14;
        CHECK(std::abs(observer.first->velocity - expected_v) <=
              1e-6 * expected_v + acceleration * rounding / expected_v);
        CHECK(std::abs(observer.first->t - expected_t) <= 1e-9 + rounding / expected_v);
      }
    }
  }
}
