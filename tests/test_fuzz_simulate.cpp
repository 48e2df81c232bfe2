// Randomised systems under a stated work bound (issue: "no valid input may
// make the simulator crawl"): 1–4 masses, general M, C (including 0) and K,
// any contact DOF, r = 1 and r near 1 as often as any other, Ω from 0.05 to
// 3. Each run must reach its end or stop at the work bound with that status;
// nothing may be NaN; every impact has a positive speed; no state lies
// beyond the stop by more than the bound docs/theory.md §8 states.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "impactkit/hybrid/simulator.hpp"

using namespace impactkit;

namespace {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  double Uniform(double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(engine_);
  }
  int Integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(engine_); }
  /// A symmetric positive semi-definite matrix B Bᵀ + shift I, scaled.
  Eigen::MatrixXd Spd(int n, double scale, double shift) {
    Eigen::MatrixXd b(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) b(i, j) = Uniform(-1, 1);
    return scale * (b * b.transpose() / n + shift * Eigen::MatrixXd::Identity(n, n));
  }

 private:
  std::mt19937_64 engine_;
};

System RandomSystem(Rng& rng) {
  const int n = rng.Integer(1, 4);
  const Eigen::MatrixXd mass = rng.Integer(0, 1)
                                   ? rng.Spd(n, rng.Uniform(0.3, 3), 0.2)
                                   : Eigen::MatrixXd(Eigen::VectorXd::NullaryExpr(n, [&] {
                                                       return rng.Uniform(0.3, 3);
                                                     }).asDiagonal());
  const Eigen::MatrixXd stiffness = rng.Spd(n, rng.Uniform(0.5, 8), 0.3);
  const int damping_kind = rng.Integer(0, 3);
  const Eigen::MatrixXd damping = damping_kind == 0   ? Eigen::MatrixXd::Zero(n, n)
                                  : damping_kind == 1 ? 0.05 * stiffness
                                                      : rng.Spd(n, rng.Uniform(0.01, 2), 0.0);
  Eigen::VectorXd forcing(n);
  for (int i = 0; i < n; ++i) forcing(i) = rng.Uniform(-1, 1);
  const int r_kind = rng.Integer(0, 3);
  const double r = r_kind == 0   ? 1.0
                   : r_kind == 1 ? 1.0 - std::pow(10.0, rng.Uniform(-6, -1))
                                 : rng.Uniform(0, 1);
  return GeneralSystem(mass, damping, stiffness, forcing, rng.Uniform(0.05, 3),
                       rng.Uniform(-0.1, 0.4), r, rng.Integer(0, n - 1));
}

/// Impact speeds, finiteness, and the overshoot beyond the stop at the end
/// of each free segment (the instant of an impact, where it is largest).
class InvariantChecker : public Observer {
 public:
  explicit InvariantChecker(const System& s) : s_(s) {}
  void OnImpact(const Impact& impact) override {
    positive_speeds_ = positive_speeds_ && impact.velocity > 0 && std::isfinite(impact.velocity);
  }
  void OnSegment(const Segment& segment) override {
    const int c = s_.stops[0].dof;
    // The scale of x_c's rounding: its closed form's coefficients.
    const double scale = segment.Position(c).Scale();
    for (const double t :
         {segment.Begin(), 0.5 * (segment.Begin() + segment.End()), segment.End()}) {
      segment.StateAt(t, &x_, &v_);
      finite_ = finite_ && x_.allFinite() && v_.allFinite();
      if (segment.Mode() != SegmentMode::kFree) continue;
      // The event time carries the search's tolerance and the rounding of
      // t; the state, the rounding of its terms.
      const double allowed = std::abs(v_(c)) * 2 * TimeTolerance(t) + kRelativeRounding * scale;
      worst_overshoot_ = std::max(worst_overshoot_, (x_(c) - s_.stops[0].position) / allowed);
    }
  }
  bool positive_speeds_ = true;
  bool finite_ = true;
  double worst_overshoot_ = -std::numeric_limits<double>::infinity();

 private:
  /// The event search's tolerance at t (events.cpp): 1e-13 or 4 ulps of t.
  static double TimeTolerance(double t) {
    return std::max(1e-13, 4 * std::numeric_limits<double>::epsilon() * std::abs(t));
  }
  static constexpr double kRelativeRounding = 1e-13;
  const System& s_;
  Eigen::VectorXd x_, v_;
};

}  // namespace

TEST_CASE("600 random systems, r = 1 and near 1 included: bounded work, invariants hold",
          "[simulate][fuzz]") {
  constexpr int kRuns = 600, kPeriods = 100;
  Rng rng(20261123);
  SimulationOptions options;
  options.max_events_per_period = 20000;  // the stated work bound of this test
  int runs = 0, work_limited = 0, invalid = 0;
  double worst_overshoot = -INFINITY;
  std::int64_t events = 0;
  while (runs < kRuns) {
    const System s = RandomSystem(rng);
    std::optional<Simulator> simulator;
    try {
      simulator.emplace(s, options);
    } catch (const InvalidInput&) {
      ++invalid;  // an undamped mode forced at resonance: refused, as it must be
      continue;
    }
    ++runs;
    INFO("run " << runs << ": N = " << s.Dof() << ", r = " << s.stops[0].restitution << ", Ω = "
                << s.omega << ", xs = " << s.stops[0].position << ", contact " << s.stops[0].dof);
    HybridState state = RestState(s);
    state.x(s.stops[0].dof) =
        std::min(0.0, s.stops[0].position);  // at rest on the stop when xs < 0
    InvariantChecker checker(s);
    const SimulationSummary summary = simulator->Run(state, kPeriods * s.ForcingPeriod(), checker);
    events += summary.impacts + summary.landings + summary.releases + summary.chatter_jumps;
    REQUIRE((summary.termination == Termination::kCompleted ||
             summary.termination == Termination::kWorkLimit));
    work_limited += summary.termination == Termination::kWorkLimit;
    REQUIRE(checker.finite_);
    REQUIRE(state.x.allFinite());
    REQUIRE(state.v.allFinite());
    CHECK(checker.positive_speeds_);
    CHECK(checker.worst_overshoot_ <= 1.0);
    worst_overshoot = std::max(worst_overshoot, checker.worst_overshoot_);
  }
  WARN("fuzz: " << runs << " runs (" << invalid << " refused), " << work_limited
                << " at the work bound, " << events << " events, worst overshoot "
                << worst_overshoot << " of its bound");
  CHECK(invalid < 50);
  CHECK(work_limited <= 5);  // 1 %: the bound is for pathologies, not for ordinary runs
}
