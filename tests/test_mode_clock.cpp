#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <limits>
#include <random>

#include "impactkit/dynamics/mode_clock.hpp"

using namespace impactkit;

namespace {

/// e^{λτ} from exp and sincos in long double: an independent reference.
std::complex<double> Reference(std::complex<double> rate, double tau) {
  const long double decay = std::exp(static_cast<long double>(rate.real()) * tau);
  const long double angle = static_cast<long double>(rate.imag()) * tau;
  return {static_cast<double>(decay * std::cos(angle)),
          static_cast<double>(decay * std::sin(angle))};
}

}  // namespace

// Any double evaluation of e^{λτ} carries the rounding of λτ (ε|λ|τ) beside
// its own few ulps: the table must stay within 4 ε (1 + |λ|τ), relative.
TEST_CASE("ExponentialTable: e^{λτ} within 4 ε (1 + |λ|τ) over the table's range", "[mode_clock]") {
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  std::mt19937_64 random(7);
  // Under-damped modes slow and fast, an undamped one, the forcing's rotor.
  for (const std::complex<double> rate :
       {std::complex<double>(-0.05, 1.0), std::complex<double>(-0.3, 37.0),
        std::complex<double>(0.0, 2.0), std::complex<double>(0.0, 0.25)}) {
    const ExponentialTable table(rate);
    // The range ends between 8192 and 16384 steps h, h|λ| in [1/32, 1/16).
    const double range = 16000.0 / (32.0 * std::abs(rate));
    std::uniform_real_distribution<double> uniform(0.0, range);
    double worst = 0.0;
    int evaluated = 0;
    for (int i = 0; i < 20000; ++i) {
      const double tau = i < 10 ? i * 1e-3 : uniform(random);
      std::complex<double> value;
      if (!table.Evaluate(tau, &value)) continue;
      ++evaluated;
      const std::complex<double> reference = Reference(rate, tau);
      const double error = std::abs(value - reference) / std::abs(reference);
      worst = std::max(worst, error / (kEpsilon * (1.0 + std::abs(rate) * tau)));
    }
    CAPTURE(rate, worst);
    CHECK(evaluated == 20000);
    CHECK(worst < 4.0);
  }
}

TEST_CASE("ExponentialTable declines outside its range, and the clock falls back exactly",
          "[mode_clock]") {
  const ExponentialTable table({-0.1, 1.0});
  std::complex<double> value;
  CHECK_FALSE(table.Evaluate(-1e-9, &value));
  CHECK_FALSE(table.Evaluate(1e6, &value));
  CHECK_FALSE(table.Evaluate(std::nan(""), &value));
  CHECK_FALSE(ExponentialTable().Evaluate(0.0, &value));

  // Over-damped and critically damped modes have no table: exactly ModeBasis.
  const ModeClock clock(
      {ModeBasis::Make(0.5, 0.8), ModeBasis::Make(2.0, -1.0), ModeBasis::Make(1.0, 0.0)}, 1.3);
  for (const double tau : {0.0, 0.7, 5.0, 1e6, -0.2}) {
    for (int j = 0; j < 3; ++j) {
      double ec, es, exact_c, exact_s;
      clock.Evaluate(j, tau, &ec, &es);
      clock.Modes()[j].Evaluate(tau, &exact_c, &exact_s);
      CAPTURE(j, tau);
      if (j > 0 || tau < 0 || tau > 1e5) {
        CHECK(ec == exact_c);  // outside the table: the closed form itself
        CHECK(es == exact_s);
      }
      CHECK(std::abs(ec - exact_c) <= 1e-15 * std::max(1.0, std::abs(exact_c)) + 1e-300);
      CHECK(std::abs(es - exact_s) <= 1e-15 * std::max(1.0, std::abs(exact_s)) + 1e-300);
    }
    const std::complex<double> rotor = clock.Rotor(tau);
    CHECK(std::abs(rotor - std::polar(1.0, 1.3 * tau)) < 1e-15);
  }
}

TEST_CASE("the forcing rotor at an instant is std::polar's, whichever instant was asked before",
          "[mode_clock]") {
  // The per-thread memo must never hand one instant's rotor to another:
  // repeated, alternating and nearby instants and two forcing frequencies.
  const double instants[] = {0.0, 1.5, 1.5, 1.5 + 1e-15, 0.0, 1e4, 1.5, -3.0};
  for (const double omega : {0.6, 1.4, 0.6}) {
    for (const double t : instants) {
      const std::complex<double> expected = std::polar(1.0, omega * t);
      CAPTURE(omega, t);
      CHECK(ForcingRotor(omega, t) == expected);
      CHECK(ForcingRotor(omega, t) == expected);
    }
  }
  // One instant, another frequency.
  CHECK(ForcingRotor(0.6, 2.0) == std::polar(1.0, 0.6 * 2.0));
  CHECK(ForcingRotor(1.4, 2.0) == std::polar(1.0, 1.4 * 2.0));
}
