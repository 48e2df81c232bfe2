#include "impactkit/analysis/grazing_prediction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "impactkit/analysis/steady_window.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/hybrid/recorders.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/hybrid/stop.hpp"
#include "impactkit/hybrid/system_flows.hpp"
#include "impactkit/model/parameters.hpp"

namespace impactkit {
namespace {

/// An attractor that stays near the grazing orbit shrinks like √μ between
/// distances 100 apart (a factor 10); one outside the normal form's reach
/// keeps its size. Between the two: shrinking by at least 100^{1/4}.
constexpr double kLocalShrink = 0.316;
/// Iterates equal to this, relative to the attractor's extent, repeat.
constexpr double kPeriodTolerance = 1e-8;
/// A largest exponent above this (per iteration) is chaos; periodic
/// attractors give clearly negative ones.
constexpr double kChaosThreshold = 1e-3;

/// How the command line names a motion of the grazing orbit's kind with
/// `impacts` impacts in q periods: P(p,q), P(inf,q) if it sticks.
std::string MotionLike(const GrazingNormalForm& form, long impacts, int q) {
  const MotionKind kind = form.releases > 0 ? MotionKind::kSticking
                          : impacts > 0     ? MotionKind::kPeriodic
                                            : MotionKind::kNonImpacting;
  return MotionLabel(kind, impacts, q);
}

/// The grazing orbit as the command line names motions.
std::string GrazingOrbitLabel(const GrazingNormalForm& form) {
  return MotionLike(form, form.p, form.q);
}

/// The normal form's attractor at distance `distance` past the grazing.
LocalAttractor IterateNormalForm(const GrazingNormalForm& form, double distance,
                                 const GrazingPredictionOptions& options) {
  LocalAttractor attractor;
  attractor.distance = distance;
  const double mu = form.unfolding * distance;
  attractor.within_reach = std::abs(mu) <= form.reach;
  const Eigen::Index n = form.linear.rows();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  // A tangent vector for the largest exponent: D map = A (I + W nᵀ / (2 √δ))
  // where the contact acts, A where it does not.
  Eigen::VectorXd tangent = Eigen::VectorXd::Ones(n).normalized();
  double growth = 0.0;
  const int total = options.transient_iterations + options.recorded_iterations;
  std::vector<Eigen::VectorXd> recorded;
  std::vector<bool> contact;
  for (int k = 0; k < total; ++k) {
    const double depth = form.normal.dot(z) + mu;
    const bool hits = depth > 0;
    if (hits) tangent += form.root * (form.normal.dot(tangent) / (2.0 * std::sqrt(depth)));
    tangent = form.linear * tangent;
    z = form.Map(z, mu);
    const double norm = tangent.norm();
    tangent /= norm;
    if (!z.allFinite() || !(norm > 0)) break;
    if (k >= options.transient_iterations) {
      growth += std::log(norm);
      recorded.push_back(z);
      contact.push_back(hits);
    }
  }
  if (static_cast<int>(recorded.size()) < options.recorded_iterations) {
    attractor.extent = std::numeric_limits<double>::infinity();
    attractor.motion = "unresolved";
    return attractor;
  }
  for (const Eigen::VectorXd& y : recorded) {
    attractor.extent = std::max(attractor.extent, y.cwiseAbs().maxCoeff());
  }
  attractor.lyapunov = growth / static_cast<double>(recorded.size());
  const double tolerance = kPeriodTolerance * std::max(attractor.extent, 1e-300);
  const int count = static_cast<int>(recorded.size());
  for (int period = 1; period <= std::min(options.max_period, count / 2); ++period) {
    bool repeats = true;
    for (int k = period; k < count && repeats; ++k) {
      repeats = (recorded[k] - recorded[k - period]).cwiseAbs().maxCoeff() <= tolerance;
    }
    if (!repeats) continue;
    attractor.period = period;
    attractor.contacts = static_cast<int>(std::count(contact.end() - period, contact.end(), true));
    const long impacts = static_cast<long>(period) * form.p + attractor.contacts;
    attractor.motion = MotionLike(form, impacts, period * form.q);
    return attractor;
  }
  attractor.motion = MotionLabel(
      attractor.lyapunov > kChaosThreshold ? MotionKind::kChaotic : MotionKind::kUnresolved, 0, 0);
  return attractor;
}

/// The grazing orbit's touch, drawn back from the stop by a hair (a
/// simulation cannot start on it), at its time t*.
HybridState GrazingOrbitStart(const System& system, const GrazingNormalForm& form) {
  const int n = system.Dof();
  const Stop stop(system, form.stop);
  HybridState state;
  state.t = form.time;
  state.x = form.touch.head(n);
  state.v = form.touch.tail(n);
  state.x(stop.Dof()) =
      stop.Position() - stop.Sign() * 1e-9 * std::max(1.0, std::abs(stop.Position()));
  return state;
}

/// `system` (near the grazing) run from the grazing orbit to the first
/// whole forcing period `periods` periods on: the state there, t = kT.
HybridState RunFromGrazingOrbit(const System& system, const GrazingNormalForm& form, int periods) {
  HybridState state = GrazingOrbitStart(system, form);
  const double period = system.ForcingPeriod();
  Simulator(system, SimulationOptions{})
      .Run(state, (std::ceil(form.time / period) + periods) * period);
  return state;
}

/// Along one smooth family of orbits, the distance to the grazing orbit at
/// the last value before it is about the change over the step before that
/// (equal for a linear dependence, (√2 − 1)⁻¹ = 2.4 times it for a speed
/// that goes like the square root of the distance to a point just past the
/// grazing: a fold or a vanishing impact there). A coexisting orbit of one
/// P(p, q) lies O(1) away while its own speeds change O(step): the
/// clearance's two P(8,3) at 1.2884 are 0.047 apart against steps of 1e-4.
constexpr double kFamilyStepRatio = 3.0;

/// One period's impact speeds, by stop and then speed (so that the
/// impact a period starts at does not matter).
using SpeedSet = std::vector<std::pair<int, double>>;

/// The last `count` of `impacts`, as a SpeedSet.
SpeedSet LastSpeeds(const std::vector<SweepImpact>& impacts, std::size_t count) {
  SpeedSet speeds;
  for (std::size_t k = impacts.size() - std::min(count, impacts.size()); k < impacts.size(); ++k) {
    speeds.emplace_back(impacts[k].stop, impacts[k].velocity);
  }
  std::sort(speeds.begin(), speeds.end());
  return speeds;
}

/// `system` at the parameter `distance` from the grazing.
System AtDistance(const System& system, const GrazingNormalForm& form, double distance) {
  System at = system;
  SetParameter(at, form.parameter, form.parameter_value + distance);
  Validate(at);
  return at;
}

/// The steady motion of `system` past the grazing, simulated from the
/// grazing orbit.
std::string RemoteMotion(const System& system, const GrazingNormalForm& form, double distance,
                         const GrazingPredictionOptions& options) {
  const System past = AtDistance(system, form, distance);
  HybridState state = RunFromGrazingOrbit(past, form, options.transient_periods);
  const double period = past.ForcingPeriod();
  SteadyWindowRecorder window(period);
  const Simulator simulator(past, SimulationOptions{});
  if (simulator.Run(state, state.t + options.recorded_periods * period, window).termination !=
      Termination::kCompleted) {
    return "unresolved";
  }
  const Classification c = ClassifyMotion(past, window.Strobe(), window.Impacts(),
                                          window.ChatterEnds(), options.classify);
  return MotionLabel(c.kind, c.period.p, c.period.q);
}

/// The grazing orbit's impacts (the touch not counted) over its q periods,
/// from one pass of `system` (at the grazing) from its touch.
SpeedSet GrazingOrbitSpeeds(const System& system, const GrazingNormalForm& form) {
  HybridState state = GrazingOrbitStart(system, form);
  ImpactRecorder recorder;
  Simulator(system, SimulationOptions{})
      .Run(state, form.time + form.q * system.ForcingPeriod(), recorder);
  // The touch's return, q periods on, may register as an impact at the
  // hair's speed: only the p before it are the orbit's.
  const auto& impacts = recorder.Impacts();
  SpeedSet speeds;
  for (std::size_t k = 0; k < std::min(impacts.size(), static_cast<std::size_t>(form.p)); ++k) {
    speeds.emplace_back(impacts[k].stop, impacts[k].velocity);
  }
  std::sort(speeds.begin(), speeds.end());
  return speeds;
}

/// The sweep's motion at its last two values before the grazing
/// (`nearer`, `farther`; both of the grazing orbit's P(p, q)) against the
/// grazing orbit: `gap` the largest difference between `nearer`'s impact
/// speeds and the grazing orbit's, `step` that between `nearer`'s and
/// `farther`'s, both relative to the grazing orbit's largest speed. None
/// where they cannot be paired (other numbers of impacts, other stops).
struct FamilyDistance {
  double gap = 0.0;
  double step = 0.0;
};
std::optional<FamilyDistance> DistanceToFamily(const System& system, const GrazingNormalForm& form,
                                               const SweepPoint& nearer,
                                               const SweepPoint& farther) {
  if (form.p == 0) return FamilyDistance{};  // one non-impacting response
  const auto count = static_cast<std::size_t>(form.p);
  const SpeedSet grazing = GrazingOrbitSpeeds(system, form);
  const SpeedSet near = LastSpeeds(nearer.impacts, count), far = LastSpeeds(farther.impacts, count);
  if (grazing.size() != count || near.size() != count || far.size() != count) return std::nullopt;
  FamilyDistance distance;
  double scale = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    if (near[k].first != grazing[k].first || far[k].first != grazing[k].first) return std::nullopt;
    distance.gap = std::max(distance.gap, std::abs(near[k].second - grazing[k].second));
    distance.step = std::max(distance.step, std::abs(near[k].second - far[k].second));
    scale = std::max(scale, std::abs(grazing[k].second));
  }
  distance.gap /= std::max(scale, 1e-300);
  distance.step /= std::max(scale, 1e-300);
  return distance;
}

/// The classical scenario of y ↦ λ y + (1 − λ) μ + κ √y.
std::string OneDimensionalScenario(const SquareRootReduction& reduced) {
  const double lambda = reduced.lambda;
  if (!(std::abs(lambda) < 1.0)) return "unstable_grazing_orbit";
  if (reduced.kappa > 0 || lambda < 0) return "no_local_attractor";
  if (lambda < 0.25) return "period_adding_hysteresis";
  if (lambda < 2.0 / 3.0) return "period_adding_chaos";
  return "chaos";
}

/// The scenario the local attractors show, nearest first.
std::string LocalScenario(const std::vector<LocalAttractor>& attractors) {
  const LocalAttractor& nearest = attractors.front();
  if (nearest.period == 0) return "chaos";
  for (const LocalAttractor& a : attractors) {
    if (a.period != nearest.period || a.contacts != nearest.contacts) {
      return a.period != 0 && a.period < nearest.period ? "period_adding" : "mixed";
    }
  }
  return "periodic";
}

}  // namespace

bool GrazingPredictionOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (distances.size() < 2) return fail("the prediction needs at least two distances");
  for (std::size_t k = 0; k < distances.size(); ++k) {
    if (!(distances[k] > 0) || (k > 0 && !(distances[k] > distances[k - 1]))) {
      return fail("the prediction's distances must be positive and increasing");
    }
  }
  if (transient_iterations < 0 || recorded_iterations < 2 || max_period < 1) {
    return fail(
        "the prediction needs transient_iterations >= 0, recorded_iterations >= 2 and "
        "max_period >= 1");
  }
  if (!(remote_distance > 0) || transient_periods < 0 || recorded_periods < 1) {
    return fail(
        "the prediction needs remote_distance > 0, transient_periods >= 0 and "
        "recorded_periods >= 1");
  }
  return classify.IsValid(error);
}

GrazingPrediction PredictGrazing(const System& system, const GrazingNormalForm& form,
                                 const GrazingPredictionOptions& options) {
  std::string error;
  Require(options.IsValid(&error), error);
  const Eigen::Index n = form.linear.rows();
  Require(n > 0 && form.linear.cols() == n && form.eigenvalues.size() == n &&
              form.normal.size() == n && form.root.size() == n,
          "a grazing prediction needs a whole normal form: A square, with its eigenvalues, n and "
          "W of its size");
  GrazingPrediction prediction;
  prediction.side = form.unfolding < 0 ? -1.0 : 1.0;
  prediction.unstable_grazing_orbit = !(std::abs(form.eigenvalues(0)) < 1.0);
  const double scale = std::max(1.0, std::abs(form.parameter_value));
  for (double distance : options.distances) {
    prediction.attractors.push_back(
        IterateNormalForm(form, prediction.side * distance * scale, options));
  }
  const LocalAttractor& nearest = prediction.attractors[0];
  prediction.local = !prediction.unstable_grazing_orbit && std::isfinite(nearest.extent) &&
                     nearest.extent <= kLocalShrink * prediction.attractors[1].extent;
  if (form.reduced) prediction.one_dimensional = OneDimensionalScenario(*form.reduced);
  if (prediction.local) {
    prediction.motion = nearest.motion;
    prediction.distance = nearest.distance;
    prediction.scenario = LocalScenario(prediction.attractors);
  } else {
    prediction.distance = prediction.side * options.remote_distance * scale;
    prediction.motion = RemoteMotion(system, form, prediction.distance, options);
    prediction.scenario = "jump";
  }
  return prediction;
}

bool GrazingSweepOptions::IsValid(std::string* error) const {
  if (span > 0 && steps >= 3 && steps % 2 == 1 && transient_periods >= 0 && recorded_periods >= 1 &&
      settle_periods >= 0) {
    return true;
  }
  if (error) {
    *error =
        "grazing sweeps need span > 0, an odd number of steps >= 3, transient_periods >= 0, "
        "recorded_periods >= 1 and settle_periods >= 0";
  }
  return false;
}

GrazingSweeps SweepThroughGrazing(const System& system, const GrazingNormalForm& form,
                                  const GrazingSweepOptions& options,
                                  const GrazingPredictionOptions& prediction_options) {
  std::string error;
  Require(options.IsValid(&error), error);
  Require(form.prediction.has_value(), "grazing sweeps check a prediction: predict it first");
  const GrazingPrediction& prediction = *form.prediction;
  const double span = options.span * std::max(1.0, std::abs(form.parameter_value));
  const double before = -prediction.side * span, past = prediction.side * span;
  SweepOptions sweep;
  sweep.parameter = form.parameter;
  sweep.from = form.parameter_value - span;
  sweep.to = form.parameter_value + span;
  sweep.steps = options.steps;
  sweep.transient_periods = options.transient_periods;
  sweep.recorded_periods = options.recorded_periods;
  sweep.chunk_values = 0;  // one chain of states through the grazing
  // Whole transients: the check is the paper's method, each value's motion
  // from the last one's state exactly as a whole run hands it on.
  sweep.full_transient = true;
  // Each sweep's points in increasing parameter order.
  auto run = [&](double start, SweepDirection direction) {
    sweep.direction = direction;
    sweep.fixed_state =
        RunFromGrazingOrbit(AtDistance(system, form, start), form, options.settle_periods);
    std::vector<SweepPoint> points = RunSweep(system, sweep).points;
    if (direction == SweepDirection::kDown) std::reverse(points.begin(), points.end());
    return points;
  };
  auto motions = [](const std::vector<SweepPoint>& points) {
    std::vector<std::string> labels;
    for (const SweepPoint& point : points) {
      const Classification& c = point.classification;
      labels.push_back(MotionLabel(c.kind, c.period.p, c.period.q));
    }
    return labels;
  };
  const SweepDirection toward = prediction.side > 0 ? SweepDirection::kUp : SweepDirection::kDown;
  const SweepDirection away = prediction.side > 0 ? SweepDirection::kDown : SweepDirection::kUp;
  GrazingSweeps result;
  result.values = SweepValues(sweep);
  std::sort(result.values.begin(), result.values.end());
  const std::vector<SweepPoint> toward_points = run(before, toward);
  result.toward = motions(toward_points);
  result.back = motions(run(past, away));
  const std::size_t middle = result.values.size() / 2;  // p* itself
  const std::size_t first_past = prediction.side > 0 ? middle + 1 : middle - 1;
  const std::size_t last_before = prediction.side > 0 ? middle - 1 : middle + 1;
  result.past_distance = result.values[first_past] - form.parameter_value;
  result.past = result.toward[first_past];
  if (prediction.local) {
    const LocalAttractor expected =
        IterateNormalForm(form, result.past_distance, prediction_options);
    result.expected = expected.motion;
    result.expected_within_reach = expected.within_reach;
  } else {
    result.expected = RemoteMotion(system, form, result.past_distance, prediction_options);
  }
  // An unstable grazing orbit is no sweep's steady motion; a stable one's
  // label may be shared by a coexisting orbit, so its impact speeds decide.
  const std::size_t before_that = 2 * last_before - middle;
  const std::string family_label = GrazingOrbitLabel(form);
  if (!prediction.unstable_grazing_orbit && result.toward[last_before] == family_label &&
      result.toward[before_that] == family_label) {
    if (const auto distance = DistanceToFamily(system, form, toward_points[last_before],
                                               toward_points[before_that])) {
      result.family_speed_gap = distance->gap;
      result.family_speed_step = distance->step;
      // Rounding: speeds agree to ~1e-12 where they do not change at all.
      result.follows = distance->gap <= kFamilyStepRatio * distance->step + 1e-12;
    }
  }
  result.agrees = result.follows && result.past == result.expected;
  result.hysteresis = result.toward != result.back;
  return result;
}

std::vector<GrazingCheck> CheckGrazings(const System& system, const Diagram& diagram,
                                        const GrazingSweepOptions& options) {
  std::vector<GrazingCheck> checks;
  for (const DiagramNode& node : diagram.nodes) {
    if (!node.normal_form || !node.normal_form->prediction) continue;
    const GrazingNormalForm& form = *node.normal_form;
    System at = system;
    SetParameter(at, form.parameter, form.parameter_value);
    GrazingCheck check;
    check.parameter = form.parameter_value;
    check.grazing_orbit = GrazingOrbitLabel(form);
    check.new_contact = node.vanishing_impact < 0;
    check.prediction = *form.prediction;
    check.sweeps = SweepThroughGrazing(at, form, options);
    checks.push_back(std::move(check));
  }
  std::sort(checks.begin(), checks.end(),
            [](const GrazingCheck& a, const GrazingCheck& b) { return a.parameter < b.parameter; });
  return checks;
}

void PredictGrazings(const System& system, Branch* branch,
                     const GrazingPredictionOptions& options) {
  for (SpecialPoint& special : branch->special_points) {
    if (!special.normal_form) continue;
    System at = system;
    SetParameter(at, branch->parameter, special.normal_form->parameter_value);
    special.normal_form->prediction = PredictGrazing(at, *special.normal_form, options);
  }
}

void PredictGrazings(const System& system, Curve* curve, const GrazingPredictionOptions& options) {
  for (Codim2Point& special : curve->codim2_points) {
    if (!special.normal_form) continue;
    System at = system;
    SetParameter(at, curve->parameter2, special.point.parameter2);
    SetParameter(at, curve->parameter, special.normal_form->parameter_value);
    special.normal_form->prediction = PredictGrazing(at, *special.normal_form, options);
  }
}

void PredictGrazings(const System& system, Diagram* diagram,
                     const GrazingPredictionOptions& options) {
  for (DiagramBranch& branch : diagram->branches) PredictGrazings(system, &branch.branch, options);
  // A node holds a copy of the special point it was located as.
  for (DiagramNode& node : diagram->nodes) {
    if (!node.normal_form) continue;
    for (const SpecialPoint& s : diagram->branches[node.branch].branch.special_points) {
      if (s.type == node.special && s.point.arclength == node.point.arclength) {
        node.normal_form = s.normal_form;
      }
    }
  }
}

}  // namespace impactkit
