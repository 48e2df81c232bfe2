#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "impactkit/core/errors.hpp"
#include "impactkit/dynamics/mode_clock.hpp"

using namespace impactkit;

namespace {

/// e^{λτ} from exp and sincos in long double: an independent reference.
std::complex<double> ReferenceExponential(std::complex<double> rate, double tau) {
  const long double decay = std::exp(static_cast<long double>(rate.real()) * tau);
  const long double angle = static_cast<long double>(rate.imag()) * tau;
  return {static_cast<double>(decay * std::cos(angle)),
          static_cast<double>(decay * std::sin(angle))};
}

/// e^{λτ} − 1 in long double: the reference for the increments (expm1 of
/// the real part, the cosine's −2 sin²(y/2), no cancellation).
std::complex<double> ReferenceIncrement(std::complex<double> rate, double tau) {
  const long double x = static_cast<long double>(rate.real()) * tau;
  const long double y = static_cast<long double>(rate.imag()) * tau;
  const long double half_sine = std::sin(y / 2);
  return {static_cast<double>(std::expm1(x) * std::cos(y) - 2 * half_sine * half_sine),
          static_cast<double>(std::exp(x) * std::sin(y))};
}

/// The error of an increment in units of its own rounding: ε times its
/// size, plus the rounding of λτ itself (ε |λ|τ |e^{λτ}|, which no double
/// evaluation avoids).
double IncrementError(std::complex<double> increment, std::complex<double> rate, double tau) {
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  const std::complex<double> reference = ReferenceIncrement(rate, tau);
  const double scale =
      std::abs(reference) + std::abs(rate) * tau * std::abs(ReferenceExponential(rate, tau));
  return std::abs(increment - reference) / (kEpsilon * scale);
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
      const std::complex<double> reference = ReferenceExponential(rate, tau);
      const double error = std::abs(value - reference) / std::abs(reference);
      worst = std::max(worst, error / (kEpsilon * (1.0 + std::abs(rate) * tau)));
    }
    CAPTURE(rate, worst);
    CHECK(evaluated == 20000);
    CHECK(worst < 4.0);
  }
}

// The increment e^{λτ} − 1 carries rounding relative to itself, however
// small τ is: from 1e-12 of the step h up to the table's range.
TEST_CASE("ExponentialTable: e^{λτ} − 1 within 8 ulps of itself and of λτ's rounding",
          "[mode_clock]") {
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  std::mt19937_64 random(11);
  for (const std::complex<double> rate :
       {std::complex<double>(-0.05, 1.0), std::complex<double>(-0.3, 37.0),
        std::complex<double>(0.0, 2.0), std::complex<double>(0.0, 0.25)}) {
    const ExponentialTable table(rate);
    const double range = 16000.0 / (32.0 * std::abs(rate));
    std::uniform_real_distribution<double> exponent(-14.0, std::log10(range));
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
      const double tau = std::pow(10.0, exponent(random));
      std::complex<double> increment;
      REQUIRE(table.EvaluateIncrement(tau, &increment));
      worst = std::max(worst, IncrementError(increment, rate, tau));
    }
    CAPTURE(rate, worst);
    CHECK(worst < 8.0);
  }
  // Modes without a table and the rotor beyond the range: expm1 forms.
  const ModeClock clock(
      {ModeBasis::Make(0.5, 0.8), ModeBasis::Make(2.0, -1.0), ModeBasis::Make(1.0, 0.0)}, 1.3);
  for (const double tau : {1e-13, 1e-7, 0.3, 1e6}) {
    const long double t = tau;
    const long double expected[] = {std::expm1(-0.5L * t) * std::cos(std::sqrt(0.8L) * t) -
                                        2 * std::pow(std::sin(std::sqrt(0.8L) * t / 2), 2),
                                    (std::expm1(-1.0L * t) + std::expm1(-3.0L * t)) / 2,
                                    std::expm1(-1.0L * t)};
    for (int j = 0; j < 3; ++j) {
      double ec, es, increment;
      clock.Evaluate(j, tau, &ec, &es, &increment);
      CAPTURE(j, tau);
      CHECK(std::abs(increment - static_cast<double>(expected[j])) <=
            8 * kEpsilon * std::abs(static_cast<double>(expected[j])));
    }
    CHECK(IncrementError(clock.RotorIncrement(tau), {0.0, 1.3}, tau) < 8.0);
  }
}

/// e^{λτ} − 1 − λτ in long double by its series (|λτ| <= 1 here): the
/// modes' closed forms built from it below lose (a/β) long-double ulps to
/// cancellation, far below a double's.
std::complex<long double> ReferenceSecondIncrement(std::complex<long double> rate, double tau) {
  const std::complex<long double> z = rate * static_cast<long double>(tau);
  std::complex<long double> sum = 0.0L, term = z * z / 2.0L;
  for (int n = 3; n <= 45; ++n, term *= z / static_cast<long double>(n - 1)) sum += term;
  return sum;
}

// A mode's parts past the first order, ec2 = e^{-aτ}C − 1 + aτ and
// es2 = e^{-aτ}S − τ, are what an anchored gap is made of (Signal::AnchorAt):
// within the clock's span they must be rounded relative to their own size,
// (|λ|τ)² and τ |λ|τ, in every regime, and near critical damping, where the
// closed forms divide by a small β or b, too.
TEST_CASE("ModeClock: the parts past the first order within 8 ulps of their size over its span",
          "[mode_clock]") {
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  struct Case {
    double decay, beta2;
  };
  const Case cases[] = {{0.05, 1.0}, {0.3, 1369.0}, {0.0, 4.0},   {0.5, 0.8},   {2.0, -1.0},
                        {1.0, 0.0},  {1.0, 1e-6},   {1.0, -1e-6}, {1e-3, -1e-6}};
  std::vector<ModeBasis> modes;
  for (const Case& c : cases) modes.push_back(ModeBasis::Make(c.decay, c.beta2));
  const double omega = 1.3;
  const ModeClock clock(modes, omega);
  double largest_rate = omega;
  for (const ModeBasis& mode : modes) largest_rate = std::max(largest_rate, mode.LargestRate());
  CHECK(clock.AnchoredSpan() == 1.0 / largest_rate);
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> exponent(-10.0, std::log10(clock.AnchoredSpan()));
  for (std::size_t j = 0; j < modes.size(); ++j) {
    const long double a = cases[j].decay, beta2 = cases[j].beta2;
    const long double root = std::sqrt(std::abs(beta2));
    const double rate = modes[j].LargestRate();
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double tau = std::pow(10.0, exponent(random));
      long double expected_c, expected_s;
      if (beta2 > 0) {  // λ = −a + iβ: ec2 = Re E(λτ), es2 = Im E(λτ) / β
        const std::complex<long double> second = ReferenceSecondIncrement({-a, root}, tau);
        expected_c = second.real();
        expected_s = second.imag() / root;
      } else if (beta2 < 0) {  // λ = −a ± b: the mean and the divided difference
        const long double slow = ReferenceSecondIncrement({-a + root, 0.0L}, tau).real();
        const long double fast = ReferenceSecondIncrement({-a - root, 0.0L}, tau).real();
        expected_c = (slow + fast) / 2;
        expected_s = (slow - fast) / (2 * root);
      } else {  // e^{-aτ} and τ e^{-aτ}
        expected_c = ReferenceSecondIncrement({-a, 0.0L}, tau).real();
        expected_s = tau * std::expm1(-a * tau);
      }
      double ec, es, ec_second, es_second;
      clock.EvaluateSecond(static_cast<int>(j), tau, &ec, &es, &ec_second, &es_second);
      const double size = rate * tau;
      worst = std::max(
          {worst, std::abs(ec_second - static_cast<double>(expected_c)) / (kEpsilon * size * size),
           std::abs(es_second - static_cast<double>(expected_s)) / (kEpsilon * tau * size)});
    }
    CAPTURE(cases[j].decay, cases[j].beta2, worst);
    CHECK(worst < 8.0);
  }
  for (int i = 0; i < 2000; ++i) {
    const double tau = std::pow(10.0, exponent(random));
    const std::complex<long double> expected = ReferenceSecondIncrement({0.0L, omega}, tau);
    const std::complex<double> rotor = clock.RotorSecondIncrement(tau);
    CAPTURE(tau);
    CHECK(std::abs(rotor - std::complex<double>(expected)) <=
          8 * kEpsilon * (omega * tau) * (omega * tau));
  }
}

TEST_CASE("ExponentialTable declines outside its range, and the clock falls back exactly",
          "[mode_clock]") {
  const ExponentialTable table(std::complex<double>(-0.1, 1.0));
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

// The rotor's table is shorter (ModeClock::kRotorCoarse): within its range
// the same bits as the full table's, and e^{iΩτ} to a few ulps; beyond it
// exactly std::polar. Its range, 2048 h with hΩ in (1/32, 1/16], reaches
// at least 10 forcing periods whatever Ω.
TEST_CASE("the rotor's short table: the full table's bits for 10 forcing periods, then std::polar",
          "[mode_clock]") {
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  for (const double omega : {0.1, 0.6, 1.0, 1.4, 1.75, 23.0}) {
    const ExponentialTable full(std::complex<double>(0.0, omega));
    const ExponentialTable short_table(std::complex<double>(0.0, omega), ModeClock::kRotorCoarse);
    const ModeClock clock({}, omega);
    const double period = 2 * std::numbers::pi / omega;
    for (int i = 0; i <= 4000; ++i) {
      const double tau = i * 10.0 * period / 4000;  // up to 10 periods
      std::complex<double> from_full, from_short;
      CAPTURE(omega, tau);
      REQUIRE(full.Evaluate(tau, &from_full));
      REQUIRE(short_table.Evaluate(tau, &from_short));
      CHECK(from_short == from_full);
      CHECK(clock.Rotor(tau) == from_full);
      const double error = std::abs(from_short - ReferenceExponential({0.0, omega}, tau));
      CHECK(error < 4.0 * kEpsilon * (1.0 + omega * tau));
    }
    for (const double periods : {20.5, 40.0, 300.0}) {
      const double tau = periods * period;
      std::complex<double> value;
      CAPTURE(omega, periods);
      CHECK_FALSE(short_table.Evaluate(tau, &value));
      CHECK(clock.Rotor(tau) == std::polar(1.0, omega * tau));
    }
  }
  // A range outside 1 to kCoarse coarse entries is refused, not clamped.
  CHECK_THROWS_AS(ExponentialTable(std::complex<double>(0.0, 1.0), 0u), InvalidInput);
  CHECK_THROWS_AS(ExponentialTable(std::complex<double>(0.0, 1.0), ExponentialTable::kCoarse + 1),
                  InvalidInput);
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
