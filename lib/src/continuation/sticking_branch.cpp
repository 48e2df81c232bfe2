#include "impactkit/continuation/sticking_branch.hpp"

#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "continuation/section_curve.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit {

std::string ToString(StickingEvent event) {
  switch (event) {
    case StickingEvent::kNoSticking:
      return "no_sticking";
    case StickingEvent::kNewImpact:
      return "new_impact";
    case StickingEvent::kEarlyRelease:
      return "early_release";
    case StickingEvent::kVanishingImpact:
      return "vanishing_impact";
    case StickingEvent::kFold:
      return "fold";
    case StickingEvent::kPeriodDoubling:
      return "period_doubling";
  }
  return "unknown";
}

std::string ToString(StickingBranchEnd end) {
  switch (end) {
    case StickingBranchEnd::kParameterBound:
      return "parameter_bound";
    case StickingBranchEnd::kNoSticking:
      return "no_sticking";
    case StickingBranchEnd::kNewImpact:
      return "new_impact";
    case StickingBranchEnd::kEarlyRelease:
      return "early_release";
    case StickingBranchEnd::kVanishingImpact:
      return "vanishing_impact";
    case StickingBranchEnd::kMaxPoints:
      return "max_points";
    case StickingBranchEnd::kCorrectorFailed:
      return "corrector_failed";
  }
  return "unknown";
}

std::string StickingSpecialPoint::Describe(const std::string& parameter_name) const {
  const PeriodicOrbit& o = point.orbit;
  return fmt::format("{} at {} = {:.10g} (stick phase {:.9g}, release phase {:.9g}, Fs(t*) {:.3g})",
                     ToString(type), parameter_name, point.parameter, o.stuck.front().stick_phase,
                     o.stuck.front().release_phase, o.contacts.contact_margin);
}

bool StickingBranchOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!(std::isfinite(lower) && std::isfinite(upper) && lower < upper)) {
    return fail(
        fmt::format("the bounds must be finite with lower < upper, got [{}, {}]", lower, upper));
  }
  if (!(min_step > 0 && min_step <= initial_step && initial_step <= max_step &&
        std::isfinite(max_step))) {
    return fail(
        fmt::format("steps must satisfy 0 < min_step <= initial_step <= max_step, got {}, "
                    "{}, {}",
                    min_step, initial_step, max_step));
  }
  if (max_points < 1) return fail(fmt::format("max_points must be >= 1, got {}", max_points));
  if (!(locate_tolerance > 0)) {
    return fail(fmt::format("locate_tolerance must be > 0, got {}", locate_tolerance));
  }
  return orbit.IsValid(error);
}

namespace {

/// The release map's SectionCurve (continuation/section_curve.hpp) with
/// what a sticking family adds: its points' orbits, its corrector's
/// iteration bound, and its start's sense by `increasing`.
class StickingCurve {
 public:
  StickingCurve(const System& base, const StickingBranchOptions& options)
      : curve_(base, options.parameter, options.orbit.releases, options.orbit.q, 2 * base.Dof() - 1,
               [map = options.orbit.map](const System& system) {
                 return std::make_unique<StickingMap>(system, map);
               }),
        options_(options) {}

  int Size() const { return curve_.Size(); }
  static double Mu(const Eigen::VectorXd& x) { return detail::SectionCurve::Mu(x); }

  /// U(X) = 0 with c · X = value, from `guess`.
  std::optional<Eigen::VectorXd> Correct(const Eigen::VectorXd& guess, const Eigen::VectorXd& c,
                                         double value) const {
    NewtonOptions newton = options_.orbit.newton;
    newton.max_iterations = kCorrectorIterations;
    int iterations = 0;
    return curve_.Correct(guess, c, value, newton, &iterations);
  }

  /// The unit tangent, continuing `previous` (or along ±μ by `increasing`
  /// when it is empty).
  std::optional<Eigen::VectorXd> Tangent(const Eigen::VectorXd& x, const Eigen::VectorXd& previous,
                                         bool increasing) const {
    std::optional<Eigen::VectorXd> t = curve_.Tangent(x, previous);
    if (t && previous.size() == 0 && (increasing ? t->tail(1)(0) : -t->tail(1)(0)) < 0) *t = -*t;
    return t;
  }

  std::optional<StickingBranchPoint> Describe(const Eigen::VectorXd& x) const {
    const auto* map = static_cast<const StickingMap*>(curve_.MapAt(Mu(x)));
    if (!map) return std::nullopt;
    try {
      return StickingBranchPoint{Mu(x),
                                 DescribeStickingOrbit(*map, detail::SectionCurve::State(x),
                                                       options_.orbit.releases, options_.orbit.q)};
    } catch (const InvalidInput&) {
      return std::nullopt;
    }
  }

  /// Whether the map found chatter not ending in sticking since the last
  /// call (at a trial point of the corrector, say), and forget it.
  bool TakeNoSticking() const { return curve_.TakeStoppedSticking(); }

 private:
  static constexpr int kCorrectorIterations = 8;
  detail::SectionCurve curve_;
  const StickingBranchOptions& options_;
};

/// Π(λ_i − 1) and Π(λ_i + 1) over the section multipliers: real, and zero
/// at a fold or a period doubling.
double TestFunction(const PeriodicOrbit& orbit, StickingEvent type) {
  const double shift = type == StickingEvent::kFold ? -1.0 : 1.0;
  std::complex<double> product = 1.0;
  for (const std::complex<double>& lambda : orbit.multipliers) product *= lambda + shift;
  return product.real();
}

/// The relative jump of the first impact's delay after a release that
/// marks an impact appearing or vanishing before it (ImpactChange).
constexpr double kDelayJump = 0.25;

/// Why a point cannot be on the sticking family, if it cannot.
std::optional<StickingEvent> Violation(const PeriodicOrbit& orbit) {
  const OrbitContacts& c = orbit.contacts;
  if (!(c.contact_margin > 0)) return StickingEvent::kNoSticking;
  if (!(c.clearance.value_or(1.0) > 0)) return StickingEvent::kNewImpact;
  if (!(c.hold_margin > 0)) return StickingEvent::kEarlyRelease;
  return std::nullopt;
}

/// The delay from each release to the first impact after it (NaN for a
/// cycle without impacts), in the order of the orbit's stuck phases.
std::vector<double> FirstImpactDelays(const PeriodicOrbit& orbit) {
  std::vector<double> delays;
  std::size_t first = 0;  // the cycle's first impact
  for (std::size_t k = 0; k < orbit.stuck.size(); ++k) {
    // The cycle starts at the release of the section state, or the last.
    const double release = k == 0 ? orbit.eta(orbit.eta.size() - 1) : orbit.stuck[k - 1].release;
    const int impacts = orbit.stuck[k].impacts;
    delays.push_back(impacts > 0 ? orbit.impacts[first].t - release
                                 : std::numeric_limits<double>::quiet_NaN());
    first += impacts;
  }
  return delays;
}

/// Where the impacts before the chatter changed between two neighbouring
/// orbits of the family: the first impact after some release jumped to an
/// earlier time (an impact appeared before it: a flight grazed the stop)
/// or to a later one (it vanished). Along the family that delay moves
/// continuously; a jump of a quarter of it between two points is none of
/// that motion.
std::optional<StickingEvent> ImpactChange(const PeriodicOrbit& a, const PeriodicOrbit& b) {
  if (a.stuck.size() != b.stuck.size()) return std::nullopt;
  const std::vector<double> from = FirstImpactDelays(a), to = FirstImpactDelays(b);
  for (std::size_t k = 0; k < from.size(); ++k) {
    if (to[k] < (1.0 - kDelayJump) * from[k]) return StickingEvent::kNewImpact;
    if (to[k] > (1.0 + kDelayJump) * from[k]) return StickingEvent::kVanishingImpact;
  }
  return std::nullopt;
}

/// The ending monitors of an orbit, in StickingEvent order.
std::array<double, 4> Monitors(const PeriodicOrbit& orbit) {
  const OrbitContacts& c = orbit.contacts;
  return {c.contact_margin, c.clearance.value_or(std::numeric_limits<double>::infinity()),
          c.hold_margin, c.first_impact_speed};
}

/// The monitor that linear extrapolation from the last two points drives
/// to 0 first, within `reach` in arclength; none if none does.
std::optional<StickingEvent> NearestZero(const Eigen::VectorXd& a, const PeriodicOrbit& orbit_a,
                                         const Eigen::VectorXd& b, const PeriodicOrbit& orbit_b,
                                         double reach) {
  const double step = (b - a).norm();
  const std::array<double, 4> before = Monitors(orbit_a), after = Monitors(orbit_b);
  std::optional<StickingEvent> nearest;
  double best = reach;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const double fall = (before[i] - after[i]) / step;  // per unit arclength
    if (!std::isfinite(after[i]) || !(fall > 0)) continue;
    if (const double distance = after[i] / fall; distance < best) {
      best = distance;
      nearest = static_cast<StickingEvent>(i);
    }
  }
  return nearest;
}

StickingBranchEnd EndOf(StickingEvent event) {
  switch (event) {
    case StickingEvent::kNoSticking:
      return StickingBranchEnd::kNoSticking;
    case StickingEvent::kNewImpact:
      return StickingBranchEnd::kNewImpact;
    case StickingEvent::kVanishingImpact:
      return StickingBranchEnd::kVanishingImpact;
    default:
      return StickingBranchEnd::kEarlyRelease;
  }
}

/// Follows one branch; the state of the march between calls of Step().
class StickingMarch {
 public:
  StickingMarch(const StickingCurve& curve, const StickingBranchOptions& options,
                StickingBranch* branch)
      : curve_(curve), options_(options), branch_(*branch) {}

  void Run(const Eigen::VectorXd& start,
           const std::function<void(const StickingBranchPoint&)>& progress);

 private:
  /// One step from x_ of length `step`; the new point, or why not.
  std::optional<Eigen::VectorXd> Try(double step, std::optional<StickingEvent>* blocked);
  void LocateBifurcations(const Eigen::VectorXd& a, const PeriodicOrbit& orbit_a,
                          const Eigen::VectorXd& b, const PeriodicOrbit& orbit_b);
  void End(StickingBranchEnd end, std::string message);
  /// Moves the last point to the family's end: bisection in μ between it
  /// and `beyond_` (a trial μ with no orbit of the family), each μ solved
  /// at fixed μ from the last point inside and judged as the march judges a
  /// point, to locate_tolerance. The march's own last point lies up to
  /// min_step short of the end, where the stuck duration still varies as a
  /// fractional power of the distance to it (theory.md §5a).
  void LocateEnd();
  /// The point of the family at μ, from the state of the last point, or
  /// none if μ is past an end.
  std::optional<StickingBranchPoint> PointAt(double mu) const;
  /// What ended the family at the last point, given what the failed trials
  /// beyond it `reported`: the monitor whose extrapolated zero lies nearest,
  /// within kExtrapolationReach (a trial's status can come from beyond the
  /// event: past a graze a map may stop accumulating), else the report.
  std::optional<StickingEvent> EndingEvent(std::optional<StickingEvent> reported) const;

  /// How far (arclength) an extrapolated monitor zero may lie from the
  /// last point for the end to be called that event.
  static constexpr double kExtrapolationReach = 1e-3;

  const StickingCurve& curve_;
  const StickingBranchOptions& options_;
  StickingBranch& branch_;
  Eigen::VectorXd x_, tangent_, previous_;
  PeriodicOrbit orbit_, previous_orbit_;
  /// μ of the last trial that was blocked (NaN if none since the last point).
  double beyond_ = std::numeric_limits<double>::quiet_NaN();
};

std::optional<Eigen::VectorXd> StickingMarch::Try(double step,
                                                  std::optional<StickingEvent>* blocked) {
  const Eigen::VectorXd predicted = x_ + step * tangent_;
  const double mu = StickingCurve::Mu(predicted);
  const bool beyond = mu < options_.lower || mu > options_.upper;
  std::optional<Eigen::VectorXd> corrected;
  if (beyond) {
    // The last point sits on the bound: μ fixed there, s corrected.
    const Eigen::VectorXd e_mu = Eigen::VectorXd::Unit(curve_.Size(), curve_.Size() - 1);
    corrected =
        curve_.Correct(predicted, e_mu, mu < options_.lower ? options_.lower : options_.upper);
  } else {
    corrected = curve_.Correct(predicted, tangent_, tangent_.dot(x_) + step);
  }
  if (curve_.TakeNoSticking()) {
    *blocked = StickingEvent::kNoSticking;
    beyond_ = mu;
  }
  if (!corrected) return std::nullopt;
  if ((*corrected - predicted).norm() > 0.5 * step && !beyond) return std::nullopt;
  return corrected;
}

std::optional<StickingEvent> StickingMarch::EndingEvent(
    std::optional<StickingEvent> reported) const {
  if (previous_.size() == 0) return reported;
  if (std::optional<StickingEvent> reached =
          NearestZero(previous_, previous_orbit_, x_, orbit_, kExtrapolationReach)) {
    return reached;
  }
  return reported;
}

void StickingMarch::End(StickingBranchEnd end, std::string message) {
  branch_.end = end;
  branch_.end_message = std::move(message);
}

std::optional<StickingBranchPoint> StickingMarch::PointAt(double mu) const {
  Eigen::VectorXd guess = x_;
  guess(guess.size() - 1) = mu;
  const Eigen::VectorXd e_mu = Eigen::VectorXd::Unit(curve_.Size(), curve_.Size() - 1);
  const std::optional<Eigen::VectorXd> x = curve_.Correct(guess, e_mu, mu);
  curve_.TakeNoSticking();
  if (!x) return std::nullopt;
  std::optional<StickingBranchPoint> point = curve_.Describe(*x);
  if (!point || Violation(point->orbit) || ImpactChange(orbit_, point->orbit)) return std::nullopt;
  return point;
}

void StickingMarch::LocateEnd() {
  if (!std::isfinite(beyond_) || PointAt(beyond_)) return;  // no bracket
  double inside = StickingCurve::Mu(x_), outside = beyond_;
  std::optional<StickingBranchPoint> last;
  while (std::abs(outside - inside) > options_.locate_tolerance) {
    const double mid = 0.5 * (inside + outside);
    if (mid == inside || mid == outside) break;  // a tolerance below μ's rounding
    if (std::optional<StickingBranchPoint> point = PointAt(mid)) {
      inside = mid;
      last = std::move(point);
    } else {
      outside = mid;
    }
  }
  if (!last) return;
  x_ << last->orbit.eta, last->parameter;
  orbit_ = last->orbit;
  branch_.points.push_back(*std::move(last));
}

void StickingMarch::LocateBifurcations(const Eigen::VectorXd& a, const PeriodicOrbit& orbit_a,
                                       const Eigen::VectorXd& b, const PeriodicOrbit& orbit_b) {
  for (const StickingEvent type : {StickingEvent::kFold, StickingEvent::kPeriodDoubling}) {
    double g_a = TestFunction(orbit_a, type);
    if ((g_a > 0) == (TestFunction(orbit_b, type) > 0)) continue;
    // Bisection along the chord, each trial point corrected onto the curve
    // at its fraction of the chord.
    Eigen::VectorXd low = a, high = b;
    std::optional<StickingBranchPoint> found;
    for (int i = 0; i < 100 && std::abs(StickingCurve::Mu(high) - StickingCurve::Mu(low)) >
                                   options_.locate_tolerance;
         ++i) {
      const Eigen::VectorXd chord = high - low;
      const std::optional<Eigen::VectorXd> mid =
          curve_.Correct(low + 0.5 * chord, chord, chord.dot(low) + 0.5 * chord.squaredNorm());
      if (!mid) break;
      found = curve_.Describe(*mid);
      if (!found) break;
      const double g = TestFunction(found->orbit, type);
      ((g > 0) == (g_a > 0) ? low : high) = *mid;
    }
    if (found) branch_.special_points.push_back({type, *found});
  }
}

void StickingMarch::Run(const Eigen::VectorXd& start,
                        const std::function<void(const StickingBranchPoint&)>& progress) {
  x_ = start;
  const std::optional<StickingBranchPoint> first = curve_.Describe(x_);
  const std::optional<Eigen::VectorXd> tangent = curve_.Tangent(x_, {}, options_.increasing);
  if (!first || !tangent) throw InvalidInput("the start is not a sticking orbit of the system");
  orbit_ = first->orbit;
  tangent_ = *tangent;
  branch_.points.push_back(*first);
  double step = options_.initial_step;
  std::optional<StickingEvent> blocked;
  while (static_cast<int>(branch_.points.size()) < options_.max_points) {
    const double mu = StickingCurve::Mu(x_);
    if (mu <= options_.lower || mu >= options_.upper) {
      if (branch_.points.size() > 1) {
        return End(StickingBranchEnd::kParameterBound,
                   fmt::format("reached {} = {}", options_.parameter, mu));
      }
    }
    if (step < options_.min_step) {
      if (const std::optional<StickingEvent> ending = EndingEvent(blocked)) {
        LocateEnd();
        branch_.special_points.push_back({*ending, branch_.points.back()});
        return End(EndOf(*ending), branch_.special_points.back().Describe(options_.parameter));
      }
      return End(StickingBranchEnd::kCorrectorFailed,
                 fmt::format("no convergence even with step {}", step));
    }
    const std::optional<Eigen::VectorXd> next = Try(step, &blocked);
    const std::optional<StickingBranchPoint> point =
        next ? curve_.Describe(*next) : std::optional<StickingBranchPoint>();
    if (point) {
      std::optional<StickingEvent> violation = Violation(point->orbit);
      if (!violation) violation = ImpactChange(orbit_, point->orbit);
      if (violation) {
        blocked = violation;
        beyond_ = point->parameter;
        step *= 0.5;
        continue;
      }
    }
    if (!point) {
      step *= 0.5;
      continue;
    }
    LocateBifurcations(x_, orbit_, *next, point->orbit);
    const std::optional<Eigen::VectorXd> t = curve_.Tangent(*next, tangent_, options_.increasing);
    if (!t) {
      step *= 0.5;
      continue;
    }
    previous_ = x_;
    previous_orbit_ = orbit_;
    x_ = *next;
    tangent_ = *t;
    orbit_ = point->orbit;
    branch_.points.push_back(*point);
    if (progress) progress(*point);
    blocked.reset();
    beyond_ = std::numeric_limits<double>::quiet_NaN();
    step = std::min(1.5 * step, options_.max_step);
  }
  End(StickingBranchEnd::kMaxPoints, fmt::format("{} points", options_.max_points));
}

}  // namespace

StickingBranch ContinueStickingBranch(
    const System& system, const PeriodicOrbit& start, const StickingBranchOptions& requested,
    const std::function<void(const StickingBranchPoint&)>& progress) {
  const auto begin = std::chrono::steady_clock::now();
  StickingBranchOptions options = requested;  // the family is the start's
  options.orbit.releases = start.releases;
  options.orbit.q = start.q;
  options.orbit.map.stop = start.stop;
  std::string error;
  if (!options.IsValid(&error)) throw InvalidInput(error);
  const StickingCurve curve(system, options);
  const double mu = GetParameter(system, options.parameter);
  if (!(mu >= options.lower && mu <= options.upper)) {
    throw InvalidInput(fmt::format("the start {} = {} lies outside [{}, {}]", options.parameter, mu,
                                   options.lower, options.upper));
  }
  if (start.eta.size() != curve.Size() - 1) {
    throw InvalidInput("the start is not a sticking orbit of this system (wrong size)");
  }
  StickingBranch branch;
  branch.parameter = options.parameter;
  branch.releases = options.orbit.releases;
  branch.q = options.orbit.q;
  Eigen::VectorXd x(curve.Size());
  x << start.eta, mu;
  StickingMarch(curve, options, &branch).Run(x, progress);
  branch.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return branch;
}

}  // namespace impactkit
