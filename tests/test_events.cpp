#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/flow.hpp"

using Catch::Matchers::WithinAbs;
using namespace impactkit;

namespace {

constexpr double kPi = std::numbers::pi;

/// An undamped, unforced unit oscillator started at x = amplitude, v = 0:
/// x(t) = amplitude cos t. Returns the gap x - stop along it.
struct FreeOscillator {
  Eigen::MatrixXd one = Eigen::MatrixXd::Ones(1, 1);
  LinearFlow flow{one, 0.0 * one, one, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), 1.0};
  Eigen::VectorXd z0;

  explicit FreeOscillator(double amplitude)
      : z0(flow.Transient(0.0, Eigen::VectorXd::Constant(1, amplitude), Eigen::VectorXd::Zero(1))) {
  }

  Signal Gap(double stop) const {
    return flow.Output(flow.Prepare({one, 0.0 * one, 0.0, -stop}), 0.0, z0);
  }
};

}  // namespace

TEST_CASE("a near-grazing crossing that a fixed-step sign check misses is found", "[events]") {
  const double amplitude = 1.0;
  for (double depth : {1e-6, 1e-9, 1e-12}) {
    INFO("excursion beyond the stop: " << depth);
    const double stop = amplitude - depth;
    const FreeOscillator oscillator(amplitude);
    const Signal gap = oscillator.Gap(stop);
    // A fixed-step integrator with h = 0.01 checking signs sees no crossing:
    // the excursion lasts 2 acos(stop) ~ 2 sqrt(2 depth) around t = 2π.
    bool sign_check_sees_it = false;
    for (double t = 0.5; t <= 7.0; t += 0.01) sign_check_sees_it |= gap.Value(t) >= 0;
    REQUIRE_FALSE(sign_check_sees_it);

    const auto crossing = FirstUpcrossing(gap, 0.5, 7.0, EventOptions{1e-13, 2 * kPi});
    REQUIRE(crossing.has_value());
    const double exact = 2 * kPi - std::acos(stop / amplitude);
    // A root of multiplicity near 2 is conditioned as sqrt(rounding / curvature).
    CHECK_THAT(*crossing, WithinAbs(exact, std::max(1e-12, 2e-16 / std::sqrt(2 * depth))));
  }
}

TEST_CASE("a trajectory that stays below the stop has no crossing", "[events]") {
  const FreeOscillator oscillator(1.0);
  for (double gap : {1e-3, 1e-9, 1e-13}) {
    CHECK_FALSE(
        FirstUpcrossing(oscillator.Gap(1.0 + gap), 0.5, 20.0, EventOptions{1e-13, 2 * kPi}));
  }
}

TEST_CASE("the first of several crossings is returned, refined to 1e-12", "[events]") {
  const FreeOscillator oscillator(1.0);
  const Signal gap = oscillator.Gap(0.5);  // crossings at 2π ± π/3, 4π ± π/3
  const auto first = FirstUpcrossing(gap, 0.5 * kPi, 30.0, EventOptions{1e-13, 2 * kPi});
  REQUIRE(first);
  CHECK_THAT(*first, WithinAbs(2 * kPi - kPi / 3, 1e-12));
}

TEST_CASE("a gap whose parts cancel within the resolution of 0 is empty, a rise above it is not",
          "[events]") {
  // Two uncoupled unit oscillators, x1 = cos t and x2 = (1 - ε) cos t, and
  // w = x1 - x2 - δ = ε cos t - δ: w'' nearly cancels while the bound of
  // |w''| over the flight, from the parts, is 2. With ε = 0 w rests 1e-15
  // below 0 (within the resolution, 1e-14): no event, certified by the
  // bound of |w''| from its ends (CurvatureBound) in a few halvings, where
  // the flight's bound needs millions. With ε = 2e-12, δ = 1e-12 w rises 1e-12
  // above 0 from t = 5π/3 on: an event, where w' is 1.7e-12 and the parts'
  // rounding (~1e-16) places it to ~1e-4.
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(2, 2);
  const LinearFlow flow{
      identity, 0.0 * identity, identity, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2), 1.0};
  EventOptions options{1e-13, 2 * kPi};
  options.resolution = 1e-14;
  const auto gap = [&](double epsilon, double delta) {
    const PreparedOutput output =
        flow.Prepare({Eigen::RowVector2d(1.0, -1.0), Eigen::RowVector2d::Zero(), 0.0, -delta});
    return flow.Output(
        output, 0.0,
        flow.Transient(0.0, Eigen::Vector2d(1.0, 1.0 - epsilon), Eigen::Vector2d::Zero()));
  };
  CHECK_FALSE(FirstUpcrossing(gap(0.0, 1e-15), 2.0, 40.0, options));
  const auto rise = FirstUpcrossing(gap(2e-12, 1e-12), 2.0, 40.0, options);
  REQUIRE(rise);
  CHECK_THAT(*rise, WithinAbs(5 * kPi / 3, 1e-3));
}

TEST_CASE("leaving the surface is not an event, arriving is", "[events]") {
  // x = cos t against a stop at 0.9: start on the surface at acos(0.9)
  // moving away; the next arrival is at 2π - acos(0.9).
  const FreeOscillator oscillator(1.0);
  const Signal gap = oscillator.Gap(0.9);
  const double leave = std::acos(0.9);
  const auto next = FirstUpcrossing(gap, leave, 3.0 * kPi, EventOptions{1e-13, 2 * kPi});
  REQUIRE(next);
  CHECK_THAT(*next, WithinAbs(2 * kPi - leave, 1e-12));
}

TEST_CASE("sign changes of the velocity are the extrema", "[events]") {
  const FreeOscillator oscillator(0.3);
  const Signal velocity = oscillator.Gap(0.0).Derivative();
  const std::vector<double> times = SignChanges(velocity, 0.1, 10.0, EventOptions{1e-13, 2 * kPi});
  REQUIRE(times.size() == 3);
  for (int i = 0; i < 3; ++i) CHECK_THAT(times[i], WithinAbs((i + 1) * kPi, 1e-12));
}
