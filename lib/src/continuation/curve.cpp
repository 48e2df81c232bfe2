#include "impactkit/continuation/curve.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "continuation/arclength.hpp"
#include "continuation/curve_problem.hpp"
#include "continuation/curve_tests.hpp"
#include "continuation/grazing_corner.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit {
namespace {

using detail::CurveProblem;
using detail::kGrazingTolerance;
using detail::Monitor;
using detail::PointMonitor;

/// A second test's located zero must be this small relative to its values
/// at the ends of the interval: where the Illinois method cannot close a
/// sign change (the test jumps, as the tangent did on P(3,1)'s fold curve
/// in (omega, A1) while σ was differenced across a new contact) there is
/// no zero. Smooth tests are located to ~1e-12 of their size.
constexpr double kLocatedZero = 1e-6;

/// Why a curve may stop short of its located end (its corrector failed or
/// it reached max_points): "; impact 1 vanishes nearby (depth 2.2e-07, not
/// located to 1e-10)" when a monitor is small.
std::string NearLimit(const CurvePoint& point) {
  if (point.orbit.multipliers.size() == 0) return "";  // the response's grazing: no orbit
  return detail::ShortOfEvent(point.orbit.contacts, 1e-4, "nearby", point.defining.size() == 1);
}

struct HalfCurve {
  std::vector<CurvePoint> points;
  std::vector<Codim2Point> codim2;
  Termination end = Termination::kMaxPoints;
  std::string message;
};

/// False on the non-impacting response's grazing curve: no orbit there.
bool HasOrbit(const CurvePoint& point) { return point.orbit.multipliers.size() > 0; }

/// A second test's zero located at `point`, its value there `residual`.
Codim2Point Located(Codim2Type type, const CurvePoint& point, double residual) {
  Codim2Point special;
  special.type = type;
  special.point = point;
  special.defining_residual = point.defining.cwiseAbs().maxCoeff();
  special.second_residual = residual;
  return special;
}

/// Traces one direction of a curve from an oriented start point.
class CurveTracer {
 public:
  CurveTracer(CurveProblem& problem, SpecialPointType type, const CurveOptions& options,
              const RunControl& control)
      : problem_(problem),
        type_(type),
        tests_(detail::SecondTests(type)),
        options_(options),
        control_(control) {
    newton_ = options.orbit.newton;
    newton_.max_iterations = options.corrector_iterations;
  }

  HalfCurve Trace(const CurvePoint& start) {
    HalfCurve half;
    corner_tried_depth_ = std::numeric_limits<double>::infinity();
    Accept(start, &half);
    if (Leaving(start)) {
      half.end = Termination::kParameterBound;
      half.message =
          fmt::format("starts on a bound: {} = {:.10g}, {} = {:.10g}", options_.parameter,
                      start.parameter, options_.parameter2, start.parameter2);
      return half;
    }
    double step = options_.initial_step;
    while (static_cast<int>(half.points.size()) < options_.max_points) {
      if (control_.Cancelled()) {
        half.end = Termination::kStopped;
        half.message = Describe(Termination::kStopped);
        return half;
      }
      const CurvePoint from = half.points.back();
      int iterations = 0;
      std::optional<CurvePoint> next = Advance(from, step, &iterations);
      // The corrector cannot work where a parameter leaves its range (r > 1)
      // either: a prediction beyond a bound goes to the bound too.
      const Eigen::VectorXd predicted = from.x + step * from.tangent;
      const bool beyond = next ? Beyond(next->parameter, next->parameter2)
                               : Beyond(CurveProblem::Mu1(predicted), CurveProblem::Mu2(predicted));
      if (beyond) {
        next = OnBound(from, next ? next->x : predicted);
        if (next) {
          if (options_.locate_codim2) LocateCodim2(from, *next, &half);
          Accept(*next, &half);
          half.end = Termination::kParameterBound;
          half.message = fmt::format("reached {} = {:.10g}, {} = {:.10g}", options_.parameter,
                                     next->parameter, options_.parameter2, next->parameter2);
          return half;
        }
      }
      if (!next) {
        if (step > options_.min_step) {
          step = std::max(step / 2.0, options_.min_step);
          continue;
        }
        if (EndAtExistenceLimit(half) || EndAtCorner(half)) return half;
        half.end = Termination::kCorrectorFailed;
        half.message = fmt::format(
            "the corrector did not converge with the smallest step {:g} at {} = {:.10g}, {} = "
            "{:.10g}{}",
            options_.min_step, options_.parameter, from.parameter, options_.parameter2,
            from.parameter2, NearLimit(from));
        return half;
      }
      if (options_.locate_codim2) LocateCodim2(from, *next, &half);
      Accept(*next, &half);
      if (Closes(start, from, *next)) {
        CurvePoint again = start;
        again.arclength = next->arclength + std::copysign((start.x - next->x).norm(), step);
        Accept(again, &half);
        half.end = Termination::kClosed;
        half.message =
            fmt::format("the curve closes on itself (arclength {:.6g})", std::abs(again.arclength));
        return half;
      }
      if (detail::ZeroAhead(half.points.end()[-2], half.points.back(), step, PointMonitor) &&
          EndAtExistenceLimit(half)) {
        return half;
      }
      if (EndAtCorner(half)) return half;
      step = NextStep(step, iterations, options_.min_step, options_.max_step);
    }
    half.end = Termination::kMaxPoints;
    // Near a vanishing impact the corrector may creep on by tiny steps to
    // the cap: say so.
    half.message =
        fmt::format("{} points reached{}", options_.max_points, NearLimit(half.points.back()));
    return half;
  }

 private:
  /// The corrected point at arclength s along from's tangent, or empty if
  /// the corrector fails or jumps farther than max_correction * s.
  std::optional<CurvePoint> Advance(const CurvePoint& from, double s, int* iterations,
                                    double tolerance_scale = 1.0) const {
    const Eigen::VectorXd& t = from.tangent;
    NewtonOptions newton = newton_;
    newton.residual_tolerance *= tolerance_scale;
    const std::optional<Eigen::VectorXd> x =
        PredictCorrect(problem_, from.x, t, s, newton, options_.max_correction, iterations);
    if (!x) return std::nullopt;
    std::optional<CurvePoint> point = problem_.Describe(*x, t);
    if (point) point->arclength = from.arclength + s;
    return point;
  }

  /// True where the step from a to b comes back to the start: it crosses,
  /// from behind, the hyperplane through the start normal to its tangent,
  /// within two steps of the start. (Going away, a loop crosses that plane
  /// the other way; a curve that only passes near its start is farther.)
  static bool Closes(const CurvePoint& start, const CurvePoint& a, const CurvePoint& b) {
    const double before = start.tangent.dot(a.x - start.x);
    const double after = start.tangent.dot(b.x - start.x);
    return before < 0 && after >= 0 &&
           (b.x - start.x).norm() <= 2.0 * std::abs(b.arclength - a.arclength);
  }

  bool Beyond(double mu1, double mu2) const {
    return mu1 < options_.Lower() || mu1 > options_.Upper() || mu2 < options_.Lower2() ||
           mu2 > options_.Upper2();
  }

  /// True for a point on a bound whose tangent leads out of the bounds.
  bool Leaving(const CurvePoint& point) const {
    const Eigen::Index size = point.tangent.size();
    const double d1 = point.tangent(size - 2), d2 = point.tangent(size - 1);
    return (point.parameter <= options_.Lower() && d1 < 0) ||
           (point.parameter >= options_.Upper() && d1 > 0) ||
           (point.parameter2 <= options_.Lower2() && d2 < 0) ||
           (point.parameter2 >= options_.Upper2() && d2 > 0);
  }

  /// The curve's point on the first bound crossed between `from` and `beyond`.
  std::optional<CurvePoint> OnBound(const CurvePoint& from, const Eigen::VectorXd& beyond) const {
    double w = 1.0, bound = 0.0;
    int index = 0;
    const int size = problem_.Size();
    const std::array<std::pair<double, double>, 2> limits = {
        {{options_.Lower(), options_.Upper()}, {options_.Lower2(), options_.Upper2()}}};
    for (int k = 0; k < 2; ++k) {
      const double a = from.x(size - 2 + k), b = beyond(size - 2 + k);
      for (double limit : {limits[k].first, limits[k].second}) {
        if ((a - limit) * (b - limit) < 0 && (limit - a) / (b - a) < w) {
          w = (limit - a) / (b - a);
          bound = limit;
          index = size - 2 + k;
        }
      }
    }
    if (w == 1.0) return std::nullopt;
    int iterations = 0;
    const std::optional<Eigen::VectorXd> x =
        problem_.Correct(from.x + w * (beyond - from.x), Eigen::VectorXd::Unit(size, index), bound,
                         newton_, &iterations);
    if (!x) return std::nullopt;
    std::optional<CurvePoint> point = problem_.Describe(*x, from.tangent);
    if (point) point->arclength = from.arclength + from.tangent.dot(*x - from.x);
    return point;
  }

  void Accept(const CurvePoint& point, HalfCurve* half) {
    half->points.push_back(point);
    problem_.UpdateBorders(point.x);
    control_.Report({.stage = "curve",
                     .done = ++accepted_,
                     .parameter = point.parameter,
                     .parameter2 = point.parameter2});
  }

  /// Locates each second test's sign change between consecutive points and
  /// inserts the located points before `b`.
  void LocateCodim2(const CurvePoint& a, const CurvePoint& b, HalfCurve* half) const {
    std::vector<Codim2Point> found;
    for (const detail::SecondTest& test : tests_) {
      const double fa = test.value(a, a), fb = test.value(b, a);
      if (!std::isfinite(fa) || !std::isfinite(fb) || (fa > 0) == (fb > 0)) continue;
      const CurvePoint located =
          LocateZero(a, b, [&](const CurvePoint& p) { return test.value(p, a); });
      const double residual = std::abs(test.value(located, a));
      if (!(residual <= kLocatedZero * std::max(std::abs(fa), std::abs(fb))) ||
          !test.accept(located)) {
        continue;
      }
      found.push_back(Located(test.type, located, residual));
    }
    for (const UserTest& test : options_.user_tests) {
      if (!HasOrbit(a) || !HasOrbit(b) || (test.value(a.orbit) > 0) == (test.value(b.orbit) > 0)) {
        continue;
      }
      const CurvePoint located =
          LocateZero(a, b, [&test](const CurvePoint& p) { return test.value(p.orbit); });
      found.push_back(Located(Codim2Type::kUserTest, located, std::abs(test.value(located.orbit))));
      found.back().user_test = test.name;
    }
    std::sort(found.begin(), found.end(), [](const Codim2Point& x, const Codim2Point& y) {
      return x.point.arclength < y.point.arclength;
    });
    for (const Codim2Point& special : found) {
      half->points.push_back(special.point);
      half->codim2.push_back(special);
    }
  }

  /// The zero of `value` between a and b, where it changes sign, by the
  /// Illinois method on arclength (arclength.hpp), each trial corrected
  /// onto the curve from a (or nearer the bracket's end where it cannot be).
  template <typename Value>
  CurvePoint LocateZero(const CurvePoint& a, const CurvePoint& b, Value value) const {
    auto advance = [this](const CurvePoint& from, double s) {
      int iterations = 0;
      return Advance(from, s, &iterations);
    };
    return IllinoisZero(a, b, advance, value);
  }

  /// Looks for the grazing or sticking just ahead of the last point where
  /// the orbit stops existing; if found, ends the curve there.
  bool EndAtExistenceLimit(HalfCurve& half) {
    if (half.points.size() < 2) return false;
    std::optional<Codim2Point> best;
    std::vector<CurvePoint> best_path;
    for (Monitor monitor : {Monitor::kClearance, Monitor::kDepth}) {
      std::vector<CurvePoint> path;
      std::optional<Codim2Point> end =
          LocateLimit(half.points[half.points.size() - 2], half.points.back(), monitor, &path);
      if (end && (!best || end->point.arclength < best->point.arclength)) {
        best = end;
        best_path = std::move(path);
      }
    }
    if (!best) return false;
    for (const CurvePoint& point : best_path) Accept(point, &half);
    half.codim2.push_back(*best);
    half.end =
        best->type == Codim2Type::kStickingOnset ? Termination::kSticking : Termination::kGrazing;
    half.message = best->Describe(options_.parameter, options_.parameter2);
    return true;
  }

  /// Ends the curve at the corner where its impact vanishes if the last
  /// point is near it (grazing_corner.hpp); tried again only once the depth
  /// has fallen tenfold, since a failed try costs a Newton solve.
  bool EndAtCorner(HalfCurve& half) {
    if (half.points.size() < 2) return false;
    const CurvePoint& last = half.points.back();
    const double depth = last.orbit.contacts.slowest_depth;
    if (last.orbit.multipliers.size() == 0 || !(depth < 0.1 * corner_tried_depth_)) return false;
    const std::optional<Codim2Point> corner =
        detail::GrazingCornerAhead(problem_, type_, half.points[half.points.size() - 2], last);
    if (depth < detail::kCornerDepth) corner_tried_depth_ = depth;
    if (!corner || Beyond(corner->point.parameter, corner->point.parameter2)) return false;
    half.points.push_back(corner->point);
    half.codim2.push_back(*corner);
    half.end = Termination::kGrazing;
    half.message = corner->Describe(options_.parameter, options_.parameter2);
    return true;
  }

  /// The curve's end where `monitor` reaches zero beyond b
  /// (ApproachMonitorZero: the approach from the side where the orbit
  /// exists). A limit beyond a bound is not this curve's end: it reaches
  /// the bound first.
  std::optional<Codim2Point> LocateLimit(const CurvePoint& a, const CurvePoint& b, Monitor monitor,
                                         std::vector<CurvePoint>* path) const {
    auto advance = [this](const CurvePoint& from, double s, double tolerance_scale) {
      int iterations = 0;
      return Advance(from, s, &iterations, tolerance_scale);
    };
    auto beyond = [this](const CurvePoint& p) { return Beyond(p.parameter, p.parameter2); };
    const std::optional<detail::MonitorApproach<CurvePoint>> approach = detail::ApproachMonitorZero(
        a, b, monitor, PointMonitor, advance, options_.max_step, detail::kEventReach, beyond, path);
    if (!approach) return std::nullopt;
    const CurvePoint& best = approach->best;
    const double length = detail::MonitorLength(approach->linear, monitor);
    if (!(length <= detail::kEventReach)) return std::nullopt;
    const OrbitContacts& contacts = best.orbit.contacts;
    const bool pressed = monitor == Monitor::kDepth && contacts.slowest_pressed;
    Codim2Point end;
    end.type = pressed ? Codim2Type::kStickingOnset : detail::GrazingMeeting(type_);
    end.point = best;
    end.defining_residual = best.defining.cwiseAbs().maxCoeff();
    end.second_residual = length;
    return end;
  }

  CurveProblem& problem_;
  SpecialPointType type_;
  std::vector<detail::SecondTest> tests_;
  const CurveOptions& options_;
  const RunControl& control_;
  std::int64_t accepted_ = 0;  ///< points accepted, both directions: the progress
  NewtonOptions newton_;
  /// The depth at which EndAtCorner last tried (per direction).
  double corner_tried_depth_ = std::numeric_limits<double>::infinity();
};

/// The start as a point on the curve: corrected at fixed μ2, its tangent
/// oriented towards increasing μ2.
CurvePoint StartPoint(CurveProblem& problem, const Eigen::VectorXd& x0,
                      const CurveOptions& options) {
  const int size = problem.Size();
  problem.UpdateBorders(x0);
  NewtonOptions newton = options.orbit.newton;
  newton.max_iterations = 4 * options.corrector_iterations;
  int iterations = 0;
  const std::optional<Eigen::VectorXd> x = problem.Correct(
      x0, Eigen::VectorXd::Unit(size, size - 1), CurveProblem::Mu2(x0), newton, &iterations);
  Require(x.has_value(),
          "the start could not be put on the curve: the corrector did not converge from it");
  problem.UpdateBorders(*x);
  std::optional<CurvePoint> point = problem.Describe(*x, {});
  Require(point.has_value(), "the start orbit's impact map fails: not a point to continue");
  if (point->tangent(size - 1) < 0) point->tangent = -point->tangent;
  return *point;
}

/// What a curve is followed in: its orbit's p, q and section, and for a
/// grazing the flight holding the touch and the stop touched.
struct CurveSetup {
  CurveOptions options;
  bool response = false;  ///< P(1,q)'s vanishing impact: the response's grazing
  Eigen::VectorXd eta;
  int flight = 0, touched = 0;
  double contact_time = 0.0;
};

CurveSetup SetUp(const CurveStart& start, const CurveOptions& options) {
  const SpecialPoint& special = start.special;
  const PeriodicOrbit& orbit = special.point.orbit;
  CurveSetup setup;
  setup.options = options;
  // P(1,q)'s impact vanishes where the non-impacting response touches the
  // stop: that is the curve (p = 0 says so). It keeps q: the resonant
  // grazings on it are those of P(1,q), the orbit over q periods.
  setup.response = special.vanishing_impact >= 0;
  setup.options.orbit.p = setup.response ? 0 : orbit.p;
  setup.options.orbit.q = orbit.q;
  if (setup.response) return setup;
  // η is at the orbit's own section stop, whichever stop that is.
  setup.options.orbit.map.stop = orbit.stop;
  setup.eta = orbit.eta;
  setup.flight = orbit.contacts.clearance_flight;
  setup.touched = orbit.contacts.clearance_stop;
  setup.contact_time = orbit.contacts.clearance_time;
  if (special.type != SpecialPointType::kGrazing || setup.flight == 0) return setup;
  // A grazing curve's orbit is described from the impact that starts the
  // touching flight, so that the grazing rows follow that one flight and no
  // other: reached through earlier flights, a difference step could cross
  // another flight's touch of a stop (a symmetric orbit in a clearance
  // touches both stops at once) and start the flight at another impact.
  System at = start.system;
  SetParameter(at, options.parameter, special.point.parameter);
  const MapResult path = ImpactMap(at, setup.options.orbit.map).Apply(orbit.eta, orbit.p, false);
  if (path.termination != Termination::kCompleted) return setup;
  const auto before = static_cast<std::size_t>(setup.flight - 1);
  setup.eta = path.path[before];
  setup.options.orbit.map.stop = path.stops[before];
  setup.flight = 0;
  return setup;
}

void CheckStart(const CurveStart& start, const CurveOptions& options, double mu1, double mu2) {
  const SpecialPointType type = start.special.type;
  Require(HasCurve(type),
          fmt::format("a {} point has no two-parameter curve here (fold, period_doubling, "
                      "neimark_sacker and grazing have)",
                      ToString(type)));
  const bool vanishing = type == SpecialPointType::kGrazing && start.special.vanishing_impact >= 0;
  Require(!vanishing || start.special.point.orbit.p == 1,
          "a vanishing impact's curve is the grazing of the orbit with one impact fewer: start "
          "from that orbit's grazing (ReducedGrazingStart)");
  Require(type != SpecialPointType::kGrazing || vanishing ||
              start.special.point.orbit.contacts.clearance,
          "the grazing start has no flight maximum to follow");
  Require(mu1 >= options.Lower() && mu1 <= options.Upper(),
          fmt::format("the start {} = {} is outside the bounds [{}, {}]", options.parameter, mu1,
                      options.Lower(), options.Upper()));
  Require(mu2 >= options.Lower2() && mu2 <= options.Upper2(),
          fmt::format("the start {} = {} is outside the bounds [{}, {}]", options.parameter2, mu2,
                      options.Lower2(), options.Upper2()));
}

}  // namespace

namespace {

/// The grazing orbit's normal form at a point located on a grazing curve,
/// or why there is none; at a bifurcation curve's grazing end, where it is.
void DescribeGrazing(const CurveProblem& problem, Codim2Point* special) {
  const bool meeting = special->type == Codim2Type::kFoldGrazing ||
                       special->type == Codim2Type::kPeriodDoublingGrazing ||
                       special->type == Codim2Type::kNeimarkSackerGrazing;
  if (!problem.IsGrazing()) {
    if (meeting) {
      special->normal_form_note =
          "on the grazing curve through this point (--type grazing) it is located again, with "
          "the grazing orbit's normal form";
    }
    return;
  }
  if (special->type == Codim2Type::kDoubleGrazing) {
    special->normal_form_note =
        "two contacts at once: the normal form of one contact does not describe it";
    return;
  }
  if (special->type == Codim2Type::kUserTest) return;
  try {
    const std::optional<GrazingOrbit> orbit = problem.GrazingOrbitAt(special->point.x);
    Require(orbit.has_value(), "the grazing orbit cannot be followed round");
    special->normal_form = ComputeGrazingNormalForm(*orbit, problem.Options().parameter);
  } catch (const InvalidInput& error) {
    special->normal_form_note = error.what();
  }
}

}  // namespace

bool HasCurve(SpecialPointType type) {
  return type == SpecialPointType::kFold || type == SpecialPointType::kPeriodDoubling ||
         type == SpecialPointType::kNeimarkSacker || type == SpecialPointType::kGrazing;
}

std::string ToString(Codim2Type type) {
  switch (type) {
    case Codim2Type::kFoldFlip:
      return "fold_flip";
    case Codim2Type::kCusp:
      return "cusp";
    case Codim2Type::kResonance11:
      return "resonance_1_1";
    case Codim2Type::kResonance12:
      return "resonance_1_2";
    case Codim2Type::kResonance13:
      return "resonance_1_3";
    case Codim2Type::kResonance14:
      return "resonance_1_4";
    case Codim2Type::kFoldGrazing:
      return "fold_grazing";
    case Codim2Type::kPeriodDoublingGrazing:
      return "period_doubling_grazing";
    case Codim2Type::kNeimarkSackerGrazing:
      return "neimark_sacker_grazing";
    case Codim2Type::kDoubleGrazing:
      return "double_grazing";
    case Codim2Type::kResonantGrazingFold:
      return "resonant_grazing_fold";
    case Codim2Type::kResonantGrazingPeriodDoubling:
      return "resonant_grazing_period_doubling";
    case Codim2Type::kStickingOnset:
      return "sticking_onset";
    case Codim2Type::kUserTest:
      return "user_test";
  }
  return "unknown";
}

std::string Codim2Point::Describe(const std::string& name1, const std::string& name2) const {
  const std::string what =
      type == Codim2Type::kUserTest ? fmt::format("user_test '{}'", user_test) : ToString(type);
  return fmt::format("{} at {} = {:.10g}, {} = {:.10g} (residuals {:.1e}, {:.1e})", what, name1,
                     point.parameter, name2, point.parameter2, defining_residual, second_residual);
}

bool CurveOptions::IsValid(std::string* error) const {
  auto fail = [&](std::string message) {
    if (error) *error = std::move(message);
    return false;
  };
  for (const std::string* name : {&parameter, &parameter2}) {
    if (*name == "n") return fail("n (the number of masses) is an integer and cannot be continued");
  }
  if (parameter == parameter2) {
    return fail(fmt::format("the two parameters must differ (both {})", parameter));
  }
  for (const auto& [one, other, name] :
       {std::tuple{from, to, parameter}, std::tuple{from2, to2, parameter2}}) {
    if (!(std::isfinite(one) && std::isfinite(other) && one != other)) {
      return fail(fmt::format("the range of {} must have two finite, different ends, got {} and {}",
                              name, one, other));
    }
  }
  if (const auto problem = StepControlProblem(min_step, initial_step, max_step, max_points,
                                              corrector_iterations, max_correction)) {
    return fail(*problem);
  }
  if (const auto problem = UserTestProblem(user_tests)) return fail(*problem);
  return orbit.IsValid(error);
}

Curve ContinueCurve(const CurveStart& start, const CurveOptions& options,
                    const RunControl& control) {
  const auto clock_start = std::chrono::steady_clock::now();
  std::string error;
  Require(options.IsValid(&error), error);
  const SpecialPoint& special = start.special;
  // A vanishing impact's parameter comes from its defining equation, not
  // the branch's last point (continuation.hpp).
  const double mu1 = special.parameter;
  const double mu2 = GetParameter(start.system, options.parameter2);
  CheckStart(start, options, mu1, mu2);
  const CurveSetup setup = SetUp(start, options);
  const CurveOptions& own = setup.options;
  const bool response = setup.response;
  CurveProblem problem(start.system, own, special.type, setup.flight, setup.touched, response);
  const CurvePoint first =
      StartPoint(problem, problem.Join(setup.eta, setup.contact_time, mu1, mu2), own);

  CurveTracer tracer(problem, special.type, own, control);
  HalfCurve forward = tracer.Trace(first);
  HalfCurve backward{{first}, {}, forward.end, forward.message};
  if (forward.end != Termination::kClosed) {  // a loop is whole in one direction
    CurvePoint reversed = first;
    reversed.tangent = -first.tangent;
    problem.UpdateBorders(first.x);
    backward = tracer.Trace(reversed);
  }

  Curve curve;
  curve.type = special.type;
  curve.parameter = options.parameter;
  curve.parameter2 = options.parameter2;
  curve.p = own.orbit.p;
  curve.q = own.orbit.q;
  for (auto it = backward.points.rbegin(); it + 1 != backward.points.rend(); ++it) {
    it->arclength = -it->arclength;
    curve.points.push_back(*it);
  }
  for (auto it = backward.codim2.rbegin(); it != backward.codim2.rend(); ++it) {
    it->point.arclength = -it->point.arclength;
    curve.codim2_points.push_back(*it);
  }
  curve.points.insert(curve.points.end(), forward.points.begin(), forward.points.end());
  curve.codim2_points.insert(curve.codim2_points.end(), forward.codim2.begin(),
                             forward.codim2.end());
  for (Codim2Point& special : curve.codim2_points) DescribeGrazing(problem, &special);
  curve.begin = backward.end;
  curve.begin_message = backward.message;
  curve.end = forward.end;
  curve.end_message = forward.message;
  curve.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return curve;
}

std::optional<SpecialPoint> LocateSpecialPoint(const BranchStart& start,
                                               const ContinuationOptions& options,
                                               SpecialPointType type) {
  ContinuationOptions both = options;
  both.direction = ContinuationDirection::kBoth;
  const Branch branch = ContinueBranch(start, both);
  const double mu = GetParameter(start.system, options.parameter);
  std::optional<SpecialPoint> nearest;
  for (const SpecialPoint& s : branch.special_points) {
    if (s.type != type) continue;
    if (!nearest || std::abs(s.parameter - mu) < std::abs(nearest->parameter - mu)) nearest = s;
  }
  return nearest;
}

std::optional<CurveStart> ReducedGrazingStart(const System& system, const Branch& branch,
                                              const SpecialPoint& graze,
                                              const ContinuationOptions& options) {
  Require(graze.type == SpecialPointType::kGrazing && graze.vanishing_impact >= 0 && branch.p >= 2,
          "ReducedGrazingStart needs a vanishing impact of an orbit with two impacts or more");
  // The impact after the vanishing one starts the reduced orbit (as in
  // vanishing_impact.hpp), taken from the branch's last point at its own μ.
  System last = system;
  SetParameter(last, branch.parameter, graze.point.parameter);
  const MapResult path =
      ImpactMap(last, options.orbit.map).Apply(graze.point.orbit.eta, branch.p, false);
  if (path.termination != Termination::kCompleted) return std::nullopt;
  OrbitOptions reduced = options.orbit;
  reduced.p = branch.p - 1;
  reduced.q = branch.q;
  reduced.map.stop = path.stops[static_cast<std::size_t>(graze.vanishing_impact)];
  const Eigen::VectorXd& seed = path.path[static_cast<std::size_t>(graze.vanishing_impact)];
  // The grazing itself (clearance 0 within rounding), or just beside it on
  // the side where the reduced orbit clears the stop.
  const double scale = std::max(1.0, std::abs(graze.parameter));
  for (double offset : {0.0, 1e-9, -1e-9, 1e-8, -1e-8}) {
    CurveStart start{system, {}};
    SetParameter(start.system, branch.parameter, graze.parameter + offset * scale);
    PeriodicOrbit orbit;
    try {
      if (FindOrbit(start.system, seed, reduced, &orbit).termination != Termination::kConverged ||
          !orbit.contacts.clearance || !(*orbit.contacts.clearance > 0)) {
        continue;
      }
    } catch (const InvalidInput&) {
      continue;  // μ outside the parameter's range
    }
    start.special.type = SpecialPointType::kGrazing;
    start.special.parameter = GetParameter(start.system, branch.parameter);
    start.special.point.parameter = start.special.parameter;
    start.special.point.orbit = orbit;
    start.special.monitor = *orbit.contacts.clearance;
    return start;
  }
  return std::nullopt;
}

double CompareCurveJacobian(const CurveStart& start, const CurveOptions& options,
                            const CurvePoint& point) {
  const CurveSetup setup = SetUp(start, options);
  CurveProblem problem(start.system, setup.options, start.special.type, setup.flight, setup.touched,
                       setup.response);
  Require(point.x.size() == problem.Size(), "the point is not one of this start's curve");
  problem.UpdateBorders(point.x);
  Eigen::MatrixXd used, coarse, middle;
  Require(problem.Jacobian(point.x, &used) && problem.Jacobian(point.x, &coarse, 100.0) &&
              problem.Jacobian(point.x, &middle, 50.0),
          "the curve's Jacobian cannot be evaluated at this point");
  // Central differences err by c h²: Richardson from h and h/2 cancels it.
  const Eigen::Index rows = point.defining.size();
  const Eigen::MatrixXd reference = (4.0 * middle - coarse).bottomRows(rows) / 3.0;
  const Eigen::MatrixXd difference = used.bottomRows(rows) - reference;
  return difference.cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

}  // namespace impactkit
