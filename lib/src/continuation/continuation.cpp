#include "impactkit/continuation/continuation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include "continuation/arclength.hpp"
#include "continuation/branch_problem.hpp"
#include "continuation/critical_point.hpp"
#include "continuation/existence_monitor.hpp"
#include "continuation/sticking_end.hpp"
#include "continuation/vanishing_impact.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/sticking_orbit.hpp"

namespace impactkit {
namespace {

using detail::BranchProblem;
using detail::kGrazingTolerance;
using detail::Monitor;
using detail::MonitorLength;
using detail::StickingEnd;

/// A vanishing impact whose approach stalls at a depth below this (the
/// depth of NearContact's message) is located by its reduced orbit.
constexpr double kReducibleDepth = 1e-6;
/// A fold or period doubling whose bracketed point has its multiplier
/// within this of ±1 is located; otherwise it is solved directly (and
/// reported only within the test function's max_distance).
constexpr double kCriticalSolved = 1e-9;
/// Equal steps a step is cut into where a multiplier passing through
/// infinity may hide a fold or period doubling (LocateMaskedZeros).
constexpr int kMaskSamples = 8;

/// One traced direction of a branch.
struct HalfBranch {
  std::vector<BranchPoint> points;
  std::vector<SpecialPoint> special_points;
  std::vector<UnlocatedZero> unlocated;
  Termination end = Termination::kMaxPoints;
  std::string end_message;
};

/// A branch point's existence monitor in its linear form
/// (existence_monitor.hpp).
std::optional<double> BranchPointMonitor(const BranchPoint& point, Monitor monitor) {
  return detail::LinearMonitor(point.orbit, monitor);
}

/// Why a branch may stop short of a located grazing: "; an impact vanishes
/// just beyond (depth 2.2e-09, not located to 1e-10)" when a monitor is
/// small, else nothing.
std::string NearContact(const BranchPoint& point) {
  return detail::ShortOfEvent(point.orbit.contacts, kReducibleDepth, "just beyond", true);
}

/// Why a corrector failing at `point` may not be the family's end: "; the
/// orbit's rounding floor 4.4e-10 is above the corrector's tolerance 1e-11,
/// so its orbits may go on" where ResidualFloor there exceeds `tolerance`,
/// else nothing. Past that floor a converged step is refused
/// (docs/continuation.md, Known limits).
std::string AboveFloor(const BranchPoint& point, double tolerance) {
  const double floor = ResidualFloor(point.orbit.jacobian, point.orbit.eta);
  if (!(floor > tolerance)) return "";
  return fmt::format(
      "; the orbit's rounding floor {:.1e} is above the corrector's tolerance {:g}, so its orbits "
      "may go on",
      floor, tolerance);
}

/// Traces one direction of a branch from an oriented start point.
class BranchTracer {
 public:
  BranchTracer(const BranchProblem& problem, const ContinuationOptions& options,
               const RunControl& control)
      : problem_(problem),
        options_(options),
        control_(control),
        sticks_(problem.Section() == OrbitSection::kRelease) {
    newton_ = options.orbit.newton;
    newton_.max_iterations = options.corrector_iterations;
  }

  HalfBranch Trace(const BranchPoint& start) {
    refused_ = {};
    HalfBranch half;
    half.points.push_back(start);
    double step = options_.initial_step;
    while (true) {
      if (static_cast<int>(half.points.size()) >= options_.max_points) {
        half.end = Termination::kMaxPoints;
        half.end_message = fmt::format("{} points reached", options_.max_points);
        return half;
      }
      if (control_.Cancelled()) {
        half.end = Termination::kStopped;
        half.end_message = Describe(Termination::kStopped);
        return half;
      }
      const BranchPoint from = half.points.back();
      int iterations = 0;
      std::optional<BranchPoint> next = Advance(from, step, &iterations);
      if (!next) {
        // The corrector cannot work beyond a bound where the parameter
        // leaves its range (r > 1): the point on the bound, from the
        // prediction, ends the branch.
        const Eigen::VectorXd predicted = BranchProblem::PointX(from) + step * from.tangent;
        const double mu = BranchProblem::Mu(predicted);
        if (mu > options_.Upper() || mu < options_.Lower()) {
          if (std::optional<BranchPoint> on = OnBound(from, predicted)) {
            EndOnBound(from, *on, &half);
            return half;
          }
        }
        if (step > options_.min_step) {
          step = std::max(step / 2.0, options_.min_step);
          continue;
        }
        if (sticks_ ? EndOfSticking(half) : EndAtGrazing(half, /*last_resort=*/true)) return half;
        half.end = Termination::kCorrectorFailed;
        half.end_message = fmt::format(
            "the corrector did not converge with the smallest step {:g} at {} = {:.10g}{}{}",
            options_.min_step, problem_.Parameter(), from.parameter, NearContact(from),
            AboveFloor(from, newton_.residual_tolerance));
        return half;
      }
      const bool beyond = next->parameter < options_.Lower() || next->parameter > options_.Upper();
      if (beyond) {
        const double bound =
            next->parameter > options_.Upper() ? options_.Upper() : options_.Lower();
        next = OnBound(from, BranchProblem::PointX(*next));
        if (!next && step > options_.min_step) {
          step = std::max(step / 2.0, options_.min_step);
          continue;
        }
        if (!next) {
          half.end = Termination::kCorrectorFailed;
          half.end_message = fmt::format(
              "no orbit found on the bound {} = {:.10g} next to {:.10g}, even with the smallest "
              "step",
              problem_.Parameter(), bound, from.parameter);
          return half;
        }
      }
      if (PassesRepeat(from, *next)) {
        // No test function is located in this last interval: at the branch
        // point the shorter orbit's multiplier −1 is +1 for this one, a
        // fold that is not one.
        if (const std::optional<BranchPoint> at = BranchPointAhead(from, *next)) {
          EndAtBranchPoint(*at, &half);
          return half;
        }
        // The corrector left the branch without passing the point where it
        // meets the shorter orbit: for the shorter orbit's branch, which
        // solves this family's equations too (a doubled branch's start lies
        // 1e-3 from its period doubling, its first step is longer), or for
        // the mirror half beyond the meeting point. A jump to another
        // branch, as max_correction refuses one: a shorter step.
        if (step > options_.min_step) {
          step = std::max(step / 2.0, options_.min_step);
          continue;
        }
        half.end = Termination::kCorrectorFailed;
        half.end_message = fmt::format(
            "the corrector reached the branch of {} behind the branch's last point even with the "
            "smallest step {:g} at {} = {:.10g}",
            ShorterName(), options_.min_step, problem_.Parameter(), from.parameter);
        return half;
      }
      if (beyond) {
        EndOnBound(from, *next, &half);
        return half;
      }
      LocateSpecialPoints(from, *next, &half);
      Accept(*next, &half);
      if (!sticks_ && half.points.size() >= 2 &&
          detail::ZeroAhead(half.points.end()[-2], half.points.back(), step, BranchPointMonitor) &&
          EndAtGrazing(half, /*last_resort=*/false)) {
        return half;
      }
      step = NextStep(step, iterations, options_.min_step, options_.max_step);
    }
  }

 private:
  /// The corrected point at arclength s along from's tangent (on the
  /// hyperplane t · (X - X_from) = s), or empty if the corrector fails or
  /// jumps farther than max_correction * s from the prediction.
  std::optional<BranchPoint> Advance(const BranchPoint& from, double s, int* iterations,
                                     double tolerance_scale = 1.0) const {
    const Eigen::VectorXd x0 = BranchProblem::PointX(from);
    const Eigen::VectorXd& t = from.tangent;
    NewtonOptions newton = newton_;
    newton.residual_tolerance *= tolerance_scale;
    const std::optional<Eigen::VectorXd> x =
        PredictCorrect(problem_, x0, t, s, newton, options_.max_correction, iterations);
    if (sticks_ && problem_.TakeStoppedSticking()) {
      refused_ = {StickingEnd::kNoSticking, BranchProblem::Mu(x0 + s * t)};
    }
    if (!x) return std::nullopt;
    std::optional<BranchPoint> point = problem_.Describe(*x, t);
    if (point) point->arclength = from.arclength + s;
    if (point && sticks_) return OnStickingFamily(from, *std::move(point));
    return point;
  }

  /// `point` if it is on the sticking family of `from`; else nothing, the
  /// end it is beyond remembered.
  std::optional<BranchPoint> OnStickingFamily(const BranchPoint& from, BranchPoint point) const {
    std::optional<StickingEnd> beyond = detail::Violation(point.orbit);
    if (!beyond) beyond = detail::ImpactChange(from.orbit, point.orbit);
    if (!beyond) return point;
    refused_ = {*beyond, point.parameter};
    return std::nullopt;
  }

  /// Ends a sticking family at its last point, if an end lies just beyond
  /// it: named by the monitor extrapolated to 0 nearest ahead (within
  /// kExtrapolationReach: a refused trial's report can come from beyond the
  /// event, as past a graze a map may stop accumulating), else by what a
  /// refused trial showed, and moved to it by bisection in μ between the
  /// last point and a refused trial, or where none was refused (the
  /// corrector failing next to a new impact, whose map is not smooth) a μ
  /// twice as far as the monitor's extrapolated zero (sticking_end.hpp).
  /// The bisection's Newton solves get the orbit solver's iterations: a
  /// solve next to a vanishing impact may bounce off the map's non-smooth
  /// boundary before it converges. The march's own last point lies up to
  /// min_step short of the end, where the stuck duration still varies as
  /// a fractional power of the distance to it (theory.md §5a).
  bool EndOfSticking(HalfBranch& half) const {
    std::optional<StickingEnd> end = refused_.end;
    double beyond = refused_.beyond;
    const std::size_t n = half.points.size();
    if (n >= 2) {
      if (std::optional<detail::ExtrapolatedEnd> nearest =
              detail::NearestEnd(half.points[n - 2], half.points[n - 1], kExtrapolationReach)) {
        end = nearest->end;
        if (!refused_.end) beyond = nearest->beyond;
      }
    }
    if (!end) return false;
    if (std::optional<BranchPoint> located = detail::LocateStickingEnd(
            problem_, half.points.back(), beyond, options_.end_tolerance, options_.orbit.newton)) {
      Accept(*located, &half);
    }
    const SpecialPoint special = detail::EndPoint(half.points.back(), *end);
    half.special_points.push_back(special);
    half.end = detail::TerminationOf(*end);
    half.end_message = special.Describe(problem_.Parameter());
    return true;
  }

  /// The point of the branch on the parameter bound crossed between `from`
  /// and `beyond`.
  std::optional<BranchPoint> OnBound(const BranchPoint& from, const Eigen::VectorXd& beyond) const {
    const double mu = BranchProblem::Mu(beyond);
    const double bound = mu > options_.Upper() ? options_.Upper() : options_.Lower();
    const double w = (bound - from.parameter) / (mu - from.parameter);
    const Eigen::VectorXd x0 = BranchProblem::PointX(from);
    const Eigen::VectorXd guess = x0 + w * (beyond - x0);
    int iterations = 0;
    const Eigen::VectorXd e_mu = Eigen::VectorXd::Unit(problem_.Size(), problem_.Size() - 1);
    const std::optional<Eigen::VectorXd> x =
        problem_.Correct(guess, e_mu, bound, newton_, &iterations);
    if (!x) return std::nullopt;
    std::optional<BranchPoint> point = problem_.Describe(*x, from.tangent);
    if (point) point->arclength = from.arclength + from.tangent.dot(*x - x0);
    return point;
  }

  /// Ends the branch at `on`, the point on a bound after `from`.
  void EndOnBound(const BranchPoint& from, const BranchPoint& on, HalfBranch* half) const {
    LocateSpecialPoints(from, on, half);
    Accept(on, half);
    half->end = Termination::kParameterBound;
    half->end_message = fmt::format("reached {} = {:.10g}", problem_.Parameter(), on.parameter);
  }

  void Accept(const BranchPoint& point, HalfBranch* half) const {
    refused_ = {};
    half->points.push_back(point);
    control_.Report({.stage = "branch", .done = ++accepted_, .parameter = point.parameter});
  }

  /// Locates each test function's sign change between consecutive points
  /// (the bifurcations' if options.locate_bifurcations, the user's always)
  /// and inserts the located points before `b`.
  void LocateSpecialPoints(const BranchPoint& a, const BranchPoint& b, HalfBranch* half) const {
    std::vector<SpecialPoint> found;
    std::array<bool, kBifurcationTestCount> located{};
    bool through_infinity = false;
    for (std::size_t test = 0; test < kBifurcationTestCount; ++test) {
      if (!options_.locate_bifurcations) break;
      if (!ChangesSign(a, b, test)) continue;
      std::optional<SpecialPoint> special = LocateZero(a, b, test);
      located[test] = special.has_value();
      if (special) found.push_back(*special);
      through_infinity |= !special && BifurcationTests()[test].critical_multiplier.has_value();
    }
    if (through_infinity) LocateMaskedZeros(a, b, located, &found, &half->unlocated);
    for (const UserTest& test : options_.user_tests) {
      if ((test.value(a.orbit) > 0) == (test.value(b.orbit) > 0)) continue;
      found.push_back(LocateUserTest(a, b, test));
    }
    std::sort(found.begin(), found.end(), [](const SpecialPoint& x, const SpecialPoint& y) {
      return x.point.arclength < y.point.arclength;
    });
    for (const SpecialPoint& special : found) {
      half->points.push_back(special.point);
      half->special_points.push_back(special);
    }
  }

  /// Whether bifurcation test `test` has opposite signs at a and b.
  static bool ChangesSign(const BranchPoint& a, const BranchPoint& b, std::size_t test) {
    return (a.test_values[test] > 0) != (b.test_values[test] > 0);
  }

  /// Whether a real multiplier passes through infinity between a and b,
  /// and nothing else happens there: every fold and period-doubling test
  /// changes sign, and the multiplier of largest modulus goes from beyond
  /// ±1 on one side to beyond ∓1 on the other (from inside the unit circle
  /// it would cross ±1 on the way, a fold or period doubling hidden there).
  static bool PassesInfinity(const BranchPoint& a, const BranchPoint& b) {
    for (std::size_t test = 0; test < kBifurcationTestCount; ++test) {
      if (BifurcationTests()[test].critical_multiplier && !ChangesSign(a, b, test)) return false;
    }
    const double from = LargestRealMultiplier(a), to = LargestRealMultiplier(b);
    return std::abs(from) > 1.0 && std::abs(to) > 1.0 && (from > 0) != (to > 0);
  }

  /// The multiplier of largest modulus if it is real, else 0.
  static double LargestRealMultiplier(const BranchPoint& point) {
    const Eigen::VectorXcd& multipliers = point.orbit.multipliers;
    Eigen::Index largest = 0;
    multipliers.cwiseAbs().maxCoeff(&largest);
    return multipliers(largest).imag() == 0.0 ? multipliers(largest).real() : 0.0;
  }

  /// The folds and period doublings of a step a–b over which a fold or
  /// period-doubling test changed sign and was not located there, as where
  /// a multiplier passes through infinity: that flips both det(D P ∓ I), so
  /// a zero of the other in the same step leaves that one's sign as it was
  /// (on the paper's P(88,128) a multiplier goes from 0.16 through −1 and
  /// round through infinity to 14.95 in one step). The step is sampled at
  /// kMaskSamples equal steps, each corrected from the one before. Of the
  /// tests not `located` over the whole step, each sign change between
  /// samples is located and added to `found`, or where that fails added to
  /// `unlocated` — but for the samples between which both tests flip: the
  /// passage itself (locating there costs a whole failed bracketing).
  void LocateMaskedZeros(const BranchPoint& a, const BranchPoint& b,
                         const std::array<bool, kBifurcationTestCount>& located,
                         std::vector<SpecialPoint>* found,
                         std::vector<UnlocatedZero>* unlocated) const {
    std::vector<BranchPoint> samples = {a};
    const double step = (b.arclength - a.arclength) / kMaskSamples;
    for (int k = 1; k < kMaskSamples; ++k) {
      int iterations = 0;
      std::optional<BranchPoint> next = Advance(samples.back(), step, &iterations);
      if (!next) break;
      samples.push_back(*std::move(next));
    }
    samples.push_back(b);
    for (std::size_t test = 0; test < kBifurcationTestCount; ++test) {
      if (!BifurcationTests()[test].critical_multiplier || located[test]) continue;
      for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
        const BranchPoint &from = samples[k], &to = samples[k + 1];
        if (!ChangesSign(from, to, test) || PassesInfinity(from, to)) continue;
        if (std::optional<SpecialPoint> special = LocateZero(from, to, test)) {
          found->push_back(*special);
        } else {
          unlocated->push_back({BifurcationTests()[test].type, from.parameter, to.parameter});
        }
      }
    }
  }

  /// The zero of test function `test` between a and b, classified. A
  /// multiplier +1 is a fold where the branch turns back in μ (its
  /// tangent's μ component changes sign), a pitchfork where it goes on:
  /// there det(D P − I) changes sign because another branch crosses.
  std::optional<SpecialPoint> LocateZero(const BranchPoint& a, const BranchPoint& b,
                                         std::size_t test) const {
    std::optional<BranchPoint> located =
        LocateZero(a, b, [test](const BranchPoint& point) { return point.test_values[test]; });
    if (const std::optional<double> lambda = BifurcationTests()[test].critical_multiplier) {
      located = SolvedCriticalPoint(a, b, *located, *lambda);
    }
    if (!located) return std::nullopt;
    std::optional<SpecialPoint> special = Classify(*located, test);
    const Eigen::Index mu = a.tangent.size() - 1;
    if (special && special->type == SpecialPointType::kFold &&
        (a.tangent(mu) > 0) == (b.tangent(mu) > 0)) {
      special->type = SpecialPointType::kPitchfork;
      special->eigenvector = RealEigenvector(special->point.orbit.jacobian, 1.0);
    }
    return special;
  }

  /// The zero of the user's test between a and b, where it changes sign.
  SpecialPoint LocateUserTest(const BranchPoint& a, const BranchPoint& b,
                              const UserTest& test) const {
    SpecialPoint special;
    special.type = SpecialPointType::kUserTest;
    special.user_test = test.name;
    special.point =
        LocateZero(a, b, [&test](const BranchPoint& point) { return test.value(point.orbit); });
    special.parameter = special.point.parameter;
    special.monitor = test.value(special.point.orbit);
    return special;
  }

  /// The fold or period doubling (multiplier `lambda`) that the Illinois
  /// method bracketed between a and b, given its best point `located`: that
  /// point where its multiplier is within kCriticalSolved of lambda, else
  /// the critical point solved directly from it (critical_point.hpp) — the
  /// bracketing falls short where trials between a and b do not converge,
  /// as on long orbits near a graze — unless the solved multiplier is
  /// farther from lambda than the best point's. Empty if the direct solve
  /// fails or lands off the stretch a–b (OnStretch): a sign change of
  /// det(D P ∓ I) that no multiplier at ±1 explains (one passing through
  /// infinity) is no point, and a solve that runs back to a point located
  /// before is none either.
  std::optional<BranchPoint> SolvedCriticalPoint(const BranchPoint& a, const BranchPoint& b,
                                                 const BranchPoint& located, double lambda) const {
    if (CriticalDistance(located, lambda) <= kCriticalSolved) return located;
    const std::optional<Eigen::VectorXd> x = detail::SolveCriticalPoint(
        problem_, BranchProblem::PointX(located), lambda, options_.orbit.newton);
    if (!x) return std::nullopt;
    if (!OnStretch(*x, BranchProblem::PointX(a), BranchProblem::PointX(b))) return std::nullopt;
    std::optional<BranchPoint> point = problem_.Describe(*x, a.tangent);
    if (!point) return std::nullopt;
    point->arclength = a.arclength + a.tangent.dot(*x - BranchProblem::PointX(a));
    // The solve holds σ to Newton's tolerance, which on a long orbit can
    // leave the multiplier farther from lambda (2.5e-7 on P(40,32) at
    // 1.706015066) than the bracketing's best point (2e-9).
    if (CriticalDistance(*point, lambda) > CriticalDistance(located, lambda)) return located;
    return point;
  }

  /// |λ_i − lambda| for the multiplier of `point` nearest lambda.
  static double CriticalDistance(const BranchPoint& point, double lambda) {
    return (point.orbit.multipliers.array() - lambda).abs().minCoeff();
  }

  /// The zero of `value` between a and b, where it changes sign, by the
  /// Illinois method on arclength (arclength.hpp), each trial corrected
  /// onto the branch from a (or nearer the bracket's end where it cannot be).
  template <typename Value>
  BranchPoint LocateZero(const BranchPoint& a, const BranchPoint& b, Value value) const {
    auto advance = [this](const BranchPoint& from, double s) {
      int iterations = 0;
      return Advance(from, s, &iterations);
    };
    return IllinoisZero(a, b, advance, value);
  }

  /// True when the branch passed between a and b through a point where its
  /// orbit is a shorter one traversed several times (the repeat gap flips).
  static bool PassesRepeat(const BranchPoint& a, const BranchPoint& b) {
    if (a.repeat_gap.size() == 0 || b.repeat_gap.size() == 0) return false;
    // Or reached it: on the branch of the repeated orbit the gap is rounding.
    const double noise = 1e-9 * (1.0 + b.orbit.eta.cwiseAbs().maxCoeff());
    return a.repeat_gap.dot(b.repeat_gap) < 0 || (b.repeat_gap.cwiseAbs().maxCoeff() <= noise &&
                                                  a.repeat_gap.cwiseAbs().maxCoeff() > noise);
  }

  /// The branch's point where it meets the shorter orbit P(p/d, q/d): where
  /// that orbit has the multiplier e^{2πi/d} (−1 for d = 2: its period
  /// doubling), by secant steps in μ from the last two points. The branch
  /// reaches that point with a vertical tangent (μ − μ* ∝ |repeat gap|²), so
  /// its own points locate μ* poorly; the shorter orbit is regular there.
  std::optional<BranchPoint> PrimitiveBifurcation(const BranchPoint& from,
                                                  const BranchPoint& next) const {
    OrbitOptions primitive = options_.orbit;
    const int events = problem_.Events() / problem_.RepeatDivisor();
    if (sticks_) {
      primitive.releases = events;
    } else {
      primitive.p = events;
    }
    primitive.q = problem_.q() / problem_.RepeatDivisor();
    // d = 2: det(DP + I); d >= 3: a complex pair on the unit circle.
    const std::size_t test = problem_.RepeatDivisor() == 2 ? 1 : 2;
    Eigen::VectorXd seed = from.orbit.eta;
    auto value = [&](double mu) -> std::optional<double> {
      PeriodicOrbit orbit;
      System system;
      try {
        system = problem_.SystemAt(mu);
      } catch (const InvalidInput&) {
        return std::nullopt;
      }
      const OrbitSummary found = FindOrbit(system, seed, primitive, &orbit);
      if (found.termination != Termination::kConverged) return std::nullopt;
      seed = orbit.eta;
      return EvaluateBifurcationTests(orbit.jacobian, orbit.multipliers)[test];
    };
    double mu0 = from.parameter, mu1 = next.parameter;
    std::optional<double> f0 = value(mu0), f1 = value(mu1);
    for (int k = 0; k < kMaxLocateIterations && f0 && f1 && *f1 != *f0; ++k) {
      const double delta = -*f1 * (mu1 - mu0) / (*f1 - *f0);
      mu0 = mu1;
      f0 = f1;
      mu1 += delta;
      f1 = value(mu1);
      if (std::abs(delta) <= 1e-14 * std::max(1.0, std::abs(mu1)) && f1) {
        // The shorter orbit at μ*, traversed d times, is this branch's end.
        const Eigen::VectorXd x = BranchProblem::Join(seed, mu1);
        std::optional<BranchPoint> point = problem_.Describe(x, from.tangent);
        if (point) point->arclength = from.arclength + (x - BranchProblem::PointX(from)).norm();
        return point;
      }
    }
    return std::nullopt;
  }

  /// The point between `from` and `next` where the branch's orbit repeats,
  /// if the branch passed it: the branch approaches the shorter orbit at
  /// `from` (Approaches), and the point is located ahead of `from` along
  /// its tangent and on the stretch from–next (OnStretch). A step that
  /// lands on the shorter orbit's branch, or on the mirror half of this
  /// one, from a point leaving it (a doubled branch's start, 1e-3 from its
  /// period doubling, and the points after it) or with the meeting point
  /// behind `from` (or where none is located but `from` itself) jumped to
  /// another branch and passed nothing: on the far side of the meeting
  /// point lie the points the branch has walked already, not those it walks
  /// next. So does a step whose meeting point is located off the stretch:
  /// the shorter orbit started from another of its impacts (a P(18,8) next
  /// to P(9,4) twice has impacts 0 and 9 close), whose branch also solves
  /// this family's equations.
  std::optional<BranchPoint> BranchPointAhead(const BranchPoint& from,
                                              const BranchPoint& next) const {
    if (!Approaches(from)) return std::nullopt;
    const Eigen::VectorXd direction = from.repeat_gap;
    const BranchPoint located = PrimitiveBifurcation(from, next)
                                    .value_or(LocateZero(from, next, [&](const BranchPoint& point) {
                                      return point.repeat_gap.dot(direction);
                                    }));
    const Eigen::VectorXd x = BranchProblem::PointX(located), a = BranchProblem::PointX(from);
    if (!(from.tangent.dot(x - a) > 0) || !OnStretch(x, a, BranchProblem::PointX(next))) {
      return std::nullopt;
    }
    return located;
  }

  /// Whether the branch at `point` heads for the orbit repeated along its
  /// tangent (BranchProblem::ApproachesRepeat). Near the meeting point the
  /// gap is linear in arclength, so a branch that reaches it within a step
  /// approaches it there, and one leaving it does not. Where the map fails
  /// at the difference's point it cannot tell: true.
  bool Approaches(const BranchPoint& point) const {
    return problem_.ApproachesRepeat(BranchProblem::PointX(point), point.repeat_gap, point.tangent)
        .value_or(true);
  }

  /// Whether x lies on the stretch of branch between the points a and b:
  /// its distances to them sum to at most 1.5 times the chord (the
  /// stretch's curvature allows a little more than the chord, and where a
  /// step crosses onto a branch that meets this one at right angles, √2
  /// times; a point off the stretch much more).
  static bool OnStretch(const Eigen::VectorXd& x, const Eigen::VectorXd& a,
                        const Eigen::VectorXd& b) {
    return (x - a).norm() + (x - b).norm() <= 1.5 * (b - a).norm();
  }

  /// Ends the branch at `located`, where its orbit repeats: beyond it the
  /// branch would walk the same orbits again with their impacts renumbered.
  void EndAtBranchPoint(const BranchPoint& located, HalfBranch* half) const {
    Accept(located, half);
    SpecialPoint special;
    special.type = SpecialPointType::kBranchPoint;
    special.point = located;
    special.parameter = located.parameter;
    special.monitor = located.repeat_gap.cwiseAbs().maxCoeff();
    half->special_points.push_back(special);
    half->end = Termination::kBranchPoint;
    half->end_message = special.Describe(problem_.Parameter()) +
                        fmt::format(": the orbit is {} traversed {} times", ShorterName(),
                                    problem_.RepeatDivisor());
  }

  /// The shorter orbit this family's orbit may be several times of, named
  /// as FamilyName names its family.
  std::string ShorterName() const {
    const int d = problem_.RepeatDivisor(), k = problem_.Events() / d, q = problem_.q() / d;
    if (!sticks_) return fmt::format("P({},{})", k, q);
    return k == 1 ? fmt::format("P(inf,{})", q) : fmt::format("P(inf,{}) k={}", q, k);
  }

  /// The special point of a located zero of test function `test`, with its
  /// critical multiplier; empty when that multiplier is too far from the
  /// critical set (a neutral saddle for Neimark–Sacker).
  static std::optional<SpecialPoint> Classify(const BranchPoint& point, std::size_t test) {
    const TestFunction& function = BifurcationTests()[test];
    SpecialPoint special;
    special.type = function.type;
    special.point = point;
    special.parameter = point.parameter;
    special.monitor = point.test_values[test];
    const Eigen::VectorXcd& lambda = point.orbit.multipliers;
    Eigen::Index nearest = 0;
    for (Eigen::Index i = 1; i < lambda.size(); ++i) {
      if (function.distance(lambda(i)) < function.distance(lambda(nearest))) nearest = i;
    }
    special.multiplier = lambda(nearest);
    if (function.distance(special.multiplier) > function.max_distance) return std::nullopt;
    if (function.keeps_eigenvector) {
      special.eigenvector = RealEigenvector(point.orbit.jacobian, *function.critical_multiplier);
    }
    return special;
  }

  /// The real eigenvector of D P for its eigenvalue nearest `value` (-1 at
  /// a period doubling, +1 at a pitchfork), unit length.
  static Eigen::VectorXd RealEigenvector(const Eigen::MatrixXd& jacobian, double value) {
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(jacobian);
    Eigen::Index best = 0;
    for (Eigen::Index i = 1; i < solver.eigenvalues().size(); ++i) {
      if (std::abs(solver.eigenvalues()(i) - value) <
          std::abs(solver.eigenvalues()(best) - value)) {
        best = i;
      }
    }
    return solver.eigenvectors().col(best).real().normalized();
  }

  /// Looks for a grazing or sticking point just ahead of the last point;
  /// if one is found, ends the branch there (with the points that led to
  /// it) and returns true. `last_resort`: the corrector failed even with
  /// the smallest step, so the branch ends here either way.
  bool EndAtGrazing(HalfBranch& half, bool last_resort) const {
    if (half.points.size() < 2) return false;
    std::optional<SpecialPoint> best;
    std::vector<BranchPoint> best_path;
    for (Monitor monitor : {Monitor::kClearance, Monitor::kDepth}) {
      std::vector<BranchPoint> path;
      std::optional<SpecialPoint> special = LocateGrazing(
          half.points[half.points.size() - 2], half.points.back(), monitor, last_resort, &path);
      if (special && (!best || special->point.arclength < best->point.arclength)) {
        best = special;
        best_path = std::move(path);
      }
    }
    if (!best) return false;
    // The approach is part of the branch: a fold or period doubling just
    // before the grazing lies between its points.
    BranchPoint previous = half.points.back();
    for (const BranchPoint& point : best_path) {
      LocateSpecialPoints(previous, point, &half);
      Accept(point, &half);
      previous = point;
    }
    half.special_points.push_back(*best);
    const bool sticking = best->type == SpecialPointType::kSticking;
    half.end = sticking ? Termination::kSticking : Termination::kGrazing;
    half.end_message = best->Describe(problem_.Parameter());
    return true;
  }

  /// The grazing or sticking point where `monitor` reaches zero beyond b
  /// (ApproachMonitorZero: the approach from the branch side).
  std::optional<SpecialPoint> LocateGrazing(const BranchPoint& a, const BranchPoint& b,
                                            Monitor monitor, bool last_resort,
                                            std::vector<BranchPoint>* path) const {
    auto advance = [this](const BranchPoint& from, double s, double tolerance_scale) {
      int iterations = 0;
      return Advance(from, s, &iterations, tolerance_scale);
    };
    const bool reducible_depth = last_resort && monitor == Monitor::kDepth;
    const double reach = reducible_depth ? kReducibleDepth : detail::kEventReach;
    const std::optional<detail::MonitorApproach<BranchPoint>> approach =
        detail::ApproachMonitorZero(
            a, b, monitor, BranchPointMonitor, advance, options_.max_step, reach,
            [](const BranchPoint&) { return false; }, path);
    if (!approach) return std::nullopt;
    const BranchPoint& previous = approach->previous;
    const BranchPoint& best = approach->best;
    const double m_lo = approach->linear;
    // A vanishing impact of a long orbit, whose rounding grows with its
    // multipliers like 1/v, may stall farther out than kEventReach:
    // when the branch cannot go on (`last_resort`), its reduced orbit still
    // locates it (below).
    const bool reached = MonitorLength(m_lo, monitor) <= detail::kEventReach;
    const bool reducible = reducible_depth && m_lo * m_lo <= kReducibleDepth;
    if (!reached && !reducible) return std::nullopt;
    SpecialPoint special;
    special.point = best;
    special.monitor = MonitorLength(m_lo, monitor);
    const OrbitContacts& contacts = best.orbit.contacts;
    const bool pressed = monitor == Monitor::kDepth && contacts.slowest_pressed;
    special.type = pressed ? SpecialPointType::kSticking : SpecialPointType::kGrazing;
    special.vanishing_impact = monitor == Monitor::kDepth ? contacts.slowest_impact : -1;
    special.parameter = best.parameter;
    if (monitor == Monitor::kDepth && !pressed) {
      // The depth locates μ only to v / (dv/dμ): the reduced orbit's
      // defining equation does better (vanishing_impact.hpp).
      const std::optional<detail::VanishingImpactPoint> end = detail::LocateVanishingImpact(
          problem_, previous, best, contacts.slowest_impact, options_.orbit);
      // Short of the tolerance, only a zero where the approach was heading
      // (within ten times its linear extrapolation from a: the secant
      // points of a stalled approach are too close to extrapolate from) is
      // this one.
      const double m_first = *BranchPointMonitor(a, monitor);
      const double ahead = std::abs(best.parameter - a.parameter) * m_lo / (m_first - m_lo);
      if (end && (reached || std::abs(end->parameter - best.parameter) <= 10 * ahead)) {
        special.parameter = end->parameter;
      } else if (!reached) {
        return std::nullopt;
      }
    } else if (!reached) {
      return std::nullopt;
    }
    return special;
  }

  /// How far (arclength) an extrapolated monitor zero may lie from a
  /// sticking family's last point for its end to be called that event.
  static constexpr double kExtrapolationReach = 1e-3;
  const BranchProblem& problem_;
  const ContinuationOptions& options_;
  const RunControl& control_;
  mutable std::int64_t accepted_ = 0;  ///< points accepted, both directions: the progress
  const bool sticks_;                  ///< a family of sticking orbits
  NewtonOptions newton_;
  /// A sticking family's end that a trial since the last accepted point
  /// was beyond, and its μ.
  struct Refused {
    std::optional<StickingEnd> end;
    double beyond = std::numeric_limits<double>::quiet_NaN();
  };
  mutable Refused refused_;
};

/// A special point of a sticking family in brackets: its first stick and
/// release phases and what the type watches.
std::string DescribeSticking(const SpecialPoint& special) {
  const StuckPhase& stuck = special.point.orbit.stuck.front();
  const std::string phases = fmt::format("stick phase {:.9g}, release phase {:.9g}",
                                         stuck.stick_phase, stuck.release_phase);
  switch (special.type) {
    case SpecialPointType::kNoSticking:
      return fmt::format("{}, Fs(t*) {:.3g}", phases, special.monitor);
    case SpecialPointType::kEarlyRelease:
      return fmt::format("{}, hold margin {:.1e}", phases, special.monitor);
    case SpecialPointType::kGrazing:
      return special.vanishing_impact < 0
                 ? fmt::format("{}, a new impact; clearance {:.1e}", phases, special.monitor)
                 : fmt::format("{}, impact {} vanishes; speed {:.1e}", phases,
                               special.vanishing_impact + 1, special.monitor);
    default:
      return fmt::format("{}, multiplier {:.9f}{:+.9f}i", phases, special.multiplier.real(),
                         special.multiplier.imag());
  }
}

/// The start as an oriented branch point.
BranchPoint StartPoint(const BranchProblem& problem, const BranchStart& start,
                       const ContinuationOptions& options, double sense) {
  const Eigen::VectorXd x =
      BranchProblem::Join(start.orbit.eta, GetParameter(start.system, options.parameter));
  Eigen::VectorXd previous = start.direction;
  std::optional<BranchPoint> point = problem.Describe(x, previous);
  Require(point.has_value(), "the start orbit's section map fails: not an orbit to continue");
  if (previous.size() == 0 && point->tangent(problem.Size() - 1) * sense < 0) {
    point->tangent = -point->tangent;
  }
  if (previous.size() != 0 && sense < 0) point->tangent = -point->tangent;
  return *point;
}

}  // namespace

std::string FamilyName(const Branch& branch) {
  if (branch.section == OrbitSection::kImpact) return fmt::format("P({},{})", branch.p, branch.q);
  return branch.releases == 1 ? fmt::format("P(inf,{})", branch.q)
                              : fmt::format("P(inf,{}) k={}", branch.q, branch.releases);
}

std::string SpecialPoint::Describe(const std::string& parameter_name) const {
  std::string name = ToString(type);
  std::replace(name.begin(), name.end(), '_', ' ');
  const std::string where = fmt::format("{} at {} = {:.10g}", name, parameter_name, parameter);
  if (type == SpecialPointType::kBranchPoint) {
    return fmt::format("{} (repeat gap {:.1e})", where, monitor);
  }
  if (type == SpecialPointType::kUserTest) {
    return fmt::format("{} '{}' at {} = {:.10g} (value {:.1e})", name, user_test, parameter_name,
                       parameter, monitor);
  }
  if (point.orbit.Sticks()) return fmt::format("{} ({})", where, DescribeSticking(*this));
  if (type == SpecialPointType::kGrazing || type == SpecialPointType::kSticking) {
    return vanishing_impact < 0
               ? fmt::format("{} (a new contact; clearance {:.1e})", where, monitor)
               : fmt::format("{} (impact {} vanishes; depth {:.1e})", where, vanishing_impact + 1,
                             monitor);
  }
  return fmt::format("{} (multiplier {:.9f}{:+.9f}i)", where, multiplier.real(), multiplier.imag());
}

std::string UnlocatedZero::Describe(const std::string& parameter_name) const {
  std::string name = ToString(type);
  std::replace(name.begin(), name.end(), '_', ' ');
  return fmt::format("{} not located between {} = {:.10g} and {:.10g}", name, parameter_name, from,
                     to);
}

bool ContinuationOptions::IsValid(std::string* error) const {
  auto fail = [&](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  if (parameter == "n") {
    return fail("n (the number of masses) is an integer and cannot be continued");
  }
  if (!(std::isfinite(from) && std::isfinite(to) && from != to)) {
    return fail(
        fmt::format("the parameter's range must have two finite, different ends, got {} "
                    "and {}",
                    from, to));
  }
  if (const auto problem = StepControlProblem(min_step, initial_step, max_step, max_points,
                                              corrector_iterations, max_correction)) {
    return fail(*problem);
  }
  if (!(end_tolerance > 0))
    return fail(fmt::format("end_tolerance must be > 0, got {}", end_tolerance));
  if (const auto problem = UserTestProblem(user_tests)) return fail(*problem);
  return orbit.IsValid(error);
}

namespace {

/// Each grazing's normal form, or why there is none.
void DescribeGrazings(const System& system, const ContinuationOptions& options, Branch* branch) {
  for (SpecialPoint& special : branch->special_points) {
    if (special.type != SpecialPointType::kGrazing) continue;
    try {
      special.normal_form = ComputeGrazingNormalForm(
          GrazingOrbitAt(system, *branch, special, options), branch->parameter);
    } catch (const InvalidInput& error) {
      special.normal_form_note = error.what();
    }
  }
}

}  // namespace

Branch ContinueBranch(const BranchStart& start, const ContinuationOptions& options,
                      const RunControl& control) {
  const auto clock_start = std::chrono::steady_clock::now();
  std::string error;
  Require(options.IsValid(&error), error);
  // The family is the start orbit's: its section, at its stop (and for a
  // sticking orbit its releases and q).
  const PeriodicOrbit& orbit = start.orbit;
  ContinuationOptions family = options;
  family.orbit.map.stop = family.orbit.release_map.stop = orbit.stop;
  const int k = orbit.Sticks() ? orbit.releases : options.orbit.p;
  const int q = orbit.Sticks() ? orbit.q : options.orbit.q;
  const BranchProblem problem =
      detail::FamilyProblem(start.system, family, orbit.section, orbit.stop, k, q);
  const double mu = GetParameter(start.system, options.parameter);
  Require(mu >= options.Lower() && mu <= options.Upper(),
          fmt::format("the start {} = {} is outside the bounds [{}, {}]", options.parameter, mu,
                      options.Lower(), options.Upper()));
  for (double bound : {options.Lower(), options.Upper()}) {
    try {
      Validate(problem.SystemAt(bound));
    } catch (const InvalidInput& e) {
      throw InvalidInput(
          fmt::format("the bound {} = {} is not valid: {}", options.parameter, bound, e.what()));
    }
  }
  const std::string name =
      orbit.Sticks() ? fmt::format("sticking P(inf,{})", q) : fmt::format("P({},{})", k, q);
  Require(orbit.eta.size() == problem.Size() - 1,
          fmt::format("the start is not a {} orbit of the system (its state has size {}, not {})",
                      name, orbit.eta.size(), problem.Size() - 1));
  const PeriodicOrbit described = problem.OrbitAt(orbit.eta, mu);
  const double residual = described.residual;
  // Near grazing FindOrbit accepts an orbit up to U's rounding floor: so here.
  Require(residual <= std::max(1e3 * options.orbit.newton.residual_tolerance,
                               ResidualFloor(described.jacobian, described.eta)),
          fmt::format("the start is not a {} orbit: residual {:.2e}", name, residual));
  // A P(2,2) that is P(1,1) traversed twice is followed as P(1,1): as P(2,2)
  // its multipliers are squared (P(1,1)'s period doubling would read as a
  // fold) and the branch would be walked once per relabelling.
  if (!orbit.Sticks()) {
    const auto* map = problem.ImpactMapAt(mu);
    const OrbitPeriod primitive = PrimitivePeriod(*map, orbit.eta, k, q);
    if (primitive.p != k) {
      ContinuationOptions reduced = family;
      reduced.orbit.p = primitive.p;
      reduced.orbit.q = primitive.q;
      BranchStart shorter = start;
      shorter.orbit = DescribeOrbit(*map, orbit.eta, primitive.p, primitive.q);
      return ContinueBranch(shorter, reduced, control);
    }
  }

  BranchTracer tracer(problem, family, control);
  Branch branch;
  branch.parameter = options.parameter;
  branch.section = orbit.section;
  branch.stop = orbit.stop;
  branch.p = orbit.Sticks() ? 0 : k;
  branch.q = q;
  branch.releases = orbit.Sticks() ? k : 0;
  const bool both = options.direction == ContinuationDirection::kBoth;
  const double sense = options.direction == ContinuationDirection::kDecreasing ? -1.0 : 1.0;
  HalfBranch forward = tracer.Trace(StartPoint(problem, start, options, sense));
  if (both) {
    HalfBranch backward = tracer.Trace(StartPoint(problem, start, options, -sense));
    for (auto it = backward.points.rbegin(); it + 1 != backward.points.rend(); ++it) {
      it->arclength = -it->arclength;
      branch.points.push_back(*it);
    }
    for (auto it = backward.special_points.rbegin(); it != backward.special_points.rend(); ++it) {
      it->point.arclength = -it->point.arclength;
      branch.special_points.push_back(*it);
    }
    for (auto it = backward.unlocated.rbegin(); it != backward.unlocated.rend(); ++it) {
      branch.unlocated.push_back({it->type, it->to, it->from});
    }
    branch.begin = backward.end;
    branch.begin_message = backward.end_message;
  }
  branch.points.insert(branch.points.end(), forward.points.begin(), forward.points.end());
  branch.special_points.insert(branch.special_points.end(), forward.special_points.begin(),
                               forward.special_points.end());
  branch.unlocated.insert(branch.unlocated.end(), forward.unlocated.begin(),
                          forward.unlocated.end());
  branch.end = forward.end;
  branch.end_message = forward.end_message;
  DescribeGrazings(start.system, family, &branch);
  branch.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return branch;
}

}  // namespace impactkit
