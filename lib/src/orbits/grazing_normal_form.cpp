#include "impactkit/orbits/grazing_normal_form.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>

#include "impactkit/core/errors.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/hybrid/simulator.hpp"
#include "impactkit/hybrid/stop.hpp"
#include "impactkit/model/parameters.hpp"
#include "impactkit/orbits/orbit.hpp"
#include "impactkit/orbits/sticking_map.hpp"
#include "orbits/orbit_shooting.hpp"

namespace impactkit {
namespace {

/// A touch must have speed and gap 0 to this (relative to the orbit's
/// scale): a located grazing holds them to ~1e-12.
constexpr double kTouchTolerance = 1e-8;
/// The unfolding's central-difference step, relative to max(1, |p*|):
/// the smooth orbit's penetration is smooth in p on both sides of the
/// grazing, so the error is ~h² p''' ~ 1e-10 plus the orbit's rounding
/// over h, ~1e-15 / h ~ 1e-10.
constexpr double kUnfoldingStep = 1e-5;
/// A sticking family's one-sided step: second-order one-sided differences
/// err by h² p''' / 3, twice the central ones' at the same h and with a
/// larger p''' (on paper-mass1-stop's new contact 1.4e-6 at h = 1e-5,
/// against the converged m to 1e-7); at 3e-6 that is ~1.3e-7, beside the
/// sticking orbits' Newton rounding over h (~1e-7 at 1e-6).
constexpr double kOneSidedUnfoldingStep = 3e-6;
/// A multiplier counts as real when its imaginary part is below this
/// (relative to its modulus).
constexpr double kRealTolerance = 1e-10;

void RequireTouch(const GrazingOrbit& orbit, const HybridSystem& hybrid) {
  Require(!orbit.contacts.empty(), "a grazing orbit needs its touch among its contacts");
  const StopContact& touch = orbit.contacts.front();
  Require(touch.stop >= 0 && touch.stop < orbit.system.StopCount(),
          fmt::format("the stop touched must be one of the system's {} stops (0 to {}), got {}",
                      orbit.system.StopCount(), orbit.system.StopCount() - 1, touch.stop));
  const Stop& stop = hybrid.GetStop(touch.stop);
  const double scale = std::max(1.0, touch.state.v.cwiseAbs().maxCoeff());
  const double speed = stop.SpeedTowards(touch.state.v(stop.Dof()));
  const double gap = stop.GapOf(touch.state.x);
  Require(std::abs(speed) <= kTouchTolerance * scale &&
              std::abs(gap) <= kTouchTolerance * std::max(1.0, std::abs(stop.Position())),
          fmt::format("a grazing orbit's first contact must touch its stop (speed and gap 0), "
                      "got speed {:.3g} and gap {:.3g}",
                      speed, gap));
}

/// The penetration s (x_c − xs) at time t of the sticking orbit of
/// `orbit`'s family at `system` (on its smooth side: it keeps off the
/// touched stop), solved from the grazing orbit's release state.
double StickingOrbitPenetration(const GrazingOrbit& orbit, const System& system, double t) {
  const StickingGrazing& sticking = *orbit.sticking;
  OrbitOptions options;
  options.q = orbit.q;
  options.releases = sticking.releases;
  options.release_map = sticking.map;
  PeriodicOrbit solved;
  const OrbitSummary summary = FindOrbit(system, sticking.release, options, &solved);
  Require(summary.termination == Termination::kConverged,
          "the grazing orbit's sticking family could not be followed for its unfolding: " +
              summary.message);
  const StickingMap map(system, sticking.map);
  HybridState start = map.ToState(solved.eta);
  // FindOrbit puts the release in [0, T): back to the grazing orbit's.
  const double period = system.ForcingPeriod();
  start.t += std::round((sticking.release(map.TimeIndex()) - start.t) / period) * period;
  const StickingFlight flight = map.Follow(start, t, false, sticking.map.stop);
  Require(flight.termination == Termination::kCompleted,
          "the grazing orbit's sticking family could not be followed to its touch: " +
              Describe(flight.termination));
  return Stop(system, orbit.contacts.front().stop).GapOf(flight.state.x);
}

/// The penetration s (x_c − xs) at time t of the orbit of `orbit`'s
/// family at `system` that keeps the grazing orbit's impacts and ignores
/// the touched stop — past the grazing a virtual orbit, which is what the
/// unfolding measures. Without impacts it is the non-impacting response.
double SmoothOrbitPenetration(const GrazingOrbit& orbit, const System& system, double t) {
  if (orbit.sticking) return StickingOrbitPenetration(orbit, system, t);
  const auto hybrid = std::make_shared<const HybridSystem>(system);
  const Stop& stop = hybrid->GetStop(orbit.contacts.front().stop);
  HybridState state;
  if (orbit.contacts.size() == 1) {
    hybrid->FreeFlow().SteadyState(t, &state.x, &state.v);
    return stop.GapOf(state.x);
  }
  std::vector<int> stops;
  for (std::size_t k = 1; k < orbit.contacts.size(); ++k) stops.push_back(orbit.contacts[k].stop);
  ImpactMapOptions map_options;
  map_options.stop = stops.front();
  const ImpactMap map(hybrid, map_options);
  std::vector<Eigen::VectorXd> etas;
  for (std::size_t k = 1; k < orbit.contacts.size(); ++k) {
    const HybridState& at = orbit.contacts[k].state;
    etas.push_back(map.ToEta(at.t, at.x, at.v, orbit.contacts[k].stop));
  }
  const ShootingProblem problem(*hybrid, map, stops, orbit.q);
  Eigen::VectorXd z = problem.Pack(etas);
  const SolveSummary solve = problem.Solve(NewtonOptions{}, &z);
  Require(solve.termination == Termination::kConverged,
          "the grazing orbit's smooth family could not be followed for its unfolding: " +
              solve.message);
  // The touch lies in the flight after the last impact, a period earlier.
  const int last = problem.Impacts() - 1;
  state = map.FlightState(problem.Eta(z, last), t + orbit.q * system.ForcingPeriod(),
                          problem.Stop(last));
  return stop.GapOf(state.x);
}

/// m = dμ/dp: the smooth orbit's penetration at the touch's time, by
/// central differences; a sticking family's by second-order one-sided
/// ones on its smooth side (the same error, O(h²)). At fixed time
/// suffices: the penetration is a maximum there, so its time's shift
/// changes it only to second order.
double Unfolding(const GrazingOrbit& orbit, const NamedParameter& parameter, double t) {
  const double value = parameter.Get(orbit.system);
  const double h =
      (orbit.sticking ? kOneSidedUnfoldingStep : kUnfoldingStep) * std::max(1.0, std::abs(value));
  auto penetration_at = [&](double p) {
    System system = orbit.system;
    parameter.Set(system, p);
    try {
      return SmoothOrbitPenetration(orbit, system, t);
    } catch (const InvalidInput& error) {
      throw InvalidInput(fmt::format("the unfolding needs {} = {} on both sides of the grazing: {}",
                                     parameter.Name(), p, error.what()));
    }
  };
  if (orbit.sticking) {
    const double side = orbit.sticking->smooth_side < 0 ? -1.0 : 1.0;
    return (-3.0 * penetration_at(value) + 4.0 * penetration_at(value + side * h) -
            penetration_at(value + 2.0 * side * h)) /
           (2.0 * side * h);
  }
  return (penetration_at(value + h) - penetration_at(value - h)) / (2.0 * h);
}

/// A sticking grazing orbit's monodromy from its touch over its q periods
/// (StickingMap::Follow), and its impacts in them.
Eigen::MatrixXd StickingMonodromy(const GrazingOrbit& orbit, int* impacts) {
  const StickingMap map(orbit.system, orbit.sticking->map);
  const HybridState& touch = orbit.contacts.front().state;
  const StickingFlight flight =
      map.Follow(touch, touch.t + orbit.q * orbit.system.ForcingPeriod(), true);
  Require(flight.termination == Termination::kCompleted,
          "the sticking grazing orbit cannot be followed round from its touch: " +
              Describe(flight.termination));
  *impacts = 0;
  for (const StickingCycle& cycle : flight.cycles) {
    *impacts += static_cast<int>(cycle.impacts.size());
  }
  return flight.jacobian;
}

/// Impacts repeating after this (relative to the orbit's scale) are one.
constexpr double kRepeatTolerance = 1e-9;

/// Whether `orbit`'s impacts (contacts after the touch) repeat every
/// `impacts` of them, `periods` forcing periods apart.
bool ImpactsRepeat(const GrazingOrbit& orbit, std::size_t impacts, int periods) {
  const double shift = periods * orbit.system.ForcingPeriod();
  double scale = 1.0;
  for (const StopContact& c : orbit.contacts) {
    scale = std::max({scale, c.state.x.cwiseAbs().maxCoeff(), c.state.v.cwiseAbs().maxCoeff()});
  }
  for (std::size_t j = 1; j + impacts < orbit.contacts.size(); ++j) {
    const StopContact &a = orbit.contacts[j], &b = orbit.contacts[j + impacts];
    const double gap = std::max({std::abs(b.state.t - a.state.t - shift),
                                 (b.state.x - a.state.x).cwiseAbs().maxCoeff(),
                                 (b.state.v - a.state.v).cwiseAbs().maxCoeff()});
    if (a.stop != b.stop || !(gap <= kRepeatTolerance * scale)) return false;
  }
  return true;
}

/// The eigenvector of `matrix` for its real eigenvalue `lambda`.
Eigen::VectorXd RealEigenvector(const Eigen::MatrixXd& matrix, double lambda) {
  const Eigen::Index n = matrix.rows();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(matrix - lambda * Eigen::MatrixXd::Identity(n, n),
                                              Eigen::ComputeFullV);
  return svd.matrixV().col(n - 1);
}

/// The reduction to y ↦ λ y + (1 − λ) μ + κ √y, or why there is none.
void Reduce(GrazingNormalForm* form) {
  const Eigen::VectorXcd& lambda = form->eigenvalues;
  const std::complex<double> leading = lambda(0);
  if (std::abs(leading.imag()) > kRealTolerance * std::abs(leading)) {
    form->reduction_note =
        "the leading multipliers are a complex pair: no one-dimensional reduction";
    return;
  }
  const double dominance = lambda.size() > 1 ? std::abs(lambda(1)) / std::abs(leading) : 0.0;
  if (!(dominance < 1.0 - kRealTolerance)) {
    form->reduction_note =
        "two leading multipliers have the same modulus: no one-dimensional reduction";
    return;
  }
  const Eigen::VectorXd right = RealEigenvector(form->linear, leading.real());
  Eigen::VectorXd left = RealEigenvector(form->linear.transpose(), leading.real());
  left /= left.dot(right);
  SquareRootReduction reduced;
  reduced.lambda = leading.real();
  reduced.kappa = reduced.lambda * form->normal.dot(right) * left.dot(form->root);
  reduced.dominance = dominance;
  if (!(std::abs(reduced.kappa) > 0.0)) {
    form->reduction_note =
        "the square-root term does not reach the leading direction: no one-dimensional reduction";
    return;
  }
  reduced.s = reduced.kappa < 0 ? 1.0 : -1.0;
  reduced.break_rate = form->unfolding / (reduced.kappa * reduced.kappa);
  form->reduced = reduced;
}

/// The reach is where one step of the normal form errs by this fraction of
/// its square-root term against the true map.
constexpr double kReachError = 0.1;
/// Penetrations tried, relative to the orbit's scale: from this (where the
/// simulated map's rounding, ~1e-13, is 1e-8 of the √δ term) up by √10.
constexpr double kSmallestPenetration = 1e-10;

/// How far before t* the true map starts: a quarter period, or half the
/// time since the orbit's previous contact if that is shorter.
double BackFlight(const GrazingOrbit& orbit, const GrazingNormalForm& form) {
  const double period = orbit.system.ForcingPeriod();
  if (!orbit.sticking && orbit.contacts.size() < 2) return 0.25 * period;
  const double previous = orbit.sticking ? orbit.sticking->previous_event
                                         : orbit.contacts.back().state.t - orbit.q * period;
  return std::min(0.25 * period, 0.5 * (form.time - previous));
}

/// One step of the normal form at the grazing (μ = 0) from the penetration
/// z = δ s e_c, against the true map: the difference relative to the
/// square-root term |A W| √δ (infinite where the simulation failed).
double StepError(const GrazingOrbit& orbit, const GrazingNormalForm& form, double delta) {
  const Stop stop(orbit.system, form.stop);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(form.touch.size());
  z(stop.Dof()) = stop.Sign() * delta;
  // The located touch's own gap (~1e-12) acts as a penetration.
  const double gap = stop.GapOf(form.touch.head(orbit.system.Dof()));
  const double error = (TrueGrazingMap(orbit, form, z) - form.Map(z, gap)).norm() /
                       ((form.linear * form.root).norm() * std::sqrt(delta));
  return std::isfinite(error) ? error : std::numeric_limits<double>::infinity();
}

/// Sets the largest penetration at which one step of the normal form errs
/// by at most kReachError against the true map: the first of the
/// penetrations tried that errs more, bisected (in log δ) to 2 %; or, if
/// none does, the largest the true map can be set up for (the contact
/// within half its back-flight of t*), with reach_bounded: the reach is at
/// least that.
void SetReach(const GrazingOrbit& orbit, GrazingNormalForm* form) {
  // A penetration δ meets the stop √(2δ/a) before t*.
  const double half = 0.5 * BackFlight(orbit, *form);
  const double largest = 0.5 * form->curvature * half * half;
  const double scale = std::max(1.0, form->touch.cwiseAbs().maxCoeff());
  const double step = std::sqrt(10.0);
  double good = 0.0;
  for (double delta = std::min(kSmallestPenetration * scale, largest);;
       delta = std::min(delta * step, largest)) {
    if (StepError(orbit, *form, delta) > kReachError) {
      double bad = delta;
      while (good > 0.0 && bad / good > 1.02) {
        const double middle = std::sqrt(good * bad);
        (StepError(orbit, *form, middle) > kReachError ? bad : good) = middle;
      }
      form->reach = good;
      form->reach_bounded = false;
      return;
    }
    good = delta;
    if (delta >= largest) break;
  }
  form->reach = largest;
  form->reach_bounded = true;
}

}  // namespace

GrazingOrbit ShortestPeriod(const GrazingOrbit& orbit) {
  if (orbit.sticking) return orbit;
  const std::size_t impacts = orbit.contacts.empty() ? 0 : orbit.contacts.size() - 1;
  // The most repetitions first: the shortest period.
  for (int k = orbit.q; k >= 2; --k) {
    if (orbit.q % k != 0 || impacts % static_cast<std::size_t>(k) != 0) continue;
    const std::size_t each = impacts / static_cast<std::size_t>(k);
    if (!ImpactsRepeat(orbit, each, orbit.q / k)) continue;
    GrazingOrbit shortest{orbit.system, orbit.q / k, {}};
    shortest.contacts.assign(orbit.contacts.begin(),
                             orbit.contacts.begin() + static_cast<std::ptrdiff_t>(each + 1));
    return shortest;
  }
  return orbit;
}

Eigen::VectorXd TrueGrazingMap(const GrazingOrbit& orbit, const GrazingNormalForm& form,
                               const Eigen::VectorXd& z) {
  const int n = orbit.system.Dof();
  const HybridSystem hybrid(orbit.system);
  const LinearFlow& flow = hybrid.FreeFlow();
  auto free_flight = [&](HybridState* state, double t) {
    const Eigen::VectorXd x = state->x, v = state->v;
    flow.StateFrom(state->t, x, v, flow.Transient(state->t, x, v), t, &state->x, &state->v);
    state->t = t;
  };
  const double margin = BackFlight(orbit, form);
  HybridState state;
  state.t = form.time;
  state.x = form.touch.head(n) + z.head(n);
  state.v = form.touch.tail(n) + z.tail(n);
  free_flight(&state, form.time - margin);
  const double end = form.time + orbit.q * orbit.system.ForcingPeriod();
  if (Simulator(orbit.system, SimulationOptions{}).Run(state, end - margin).termination !=
      Termination::kCompleted) {
    return Eigen::VectorXd::Constant(2 * n, std::numeric_limits<double>::quiet_NaN());
  }
  free_flight(&state, end);
  Eigen::VectorXd y(2 * n);
  y << state.x, state.v;
  return y - form.touch;
}

Eigen::VectorXd GrazingNormalForm::Map(const Eigen::VectorXd& z, double mu) const {
  const double depth = normal.dot(z) + mu;
  if (!(depth > 0)) return linear * z;
  return linear * (z + root * std::sqrt(depth));
}

std::string GrazingNormalForm::Describe() const {
  std::string multipliers;
  // A sticking orbit's exact zeros come out at rounding (~1e-17).
  const double zero = 1e-12 * (eigenvalues.size() ? std::max(1.0, std::abs(eigenvalues(0))) : 1.0);
  for (Eigen::Index k = 0; k < eigenvalues.size(); ++k) {
    const std::complex<double> m = eigenvalues(k);
    multipliers += k ? ", " : "";
    multipliers += std::abs(m) < zero ? "0"
                   : std::abs(m.imag()) > kRealTolerance * std::abs(m)
                       ? fmt::format("{:.6g}{:+.6g}i", m.real(), m.imag())
                       : fmt::format("{:.6g}", m.real());
  }
  std::string line = fmt::format(
      "grazing normal form at stop {}, phase {:.6g}: multipliers {}; |W| = {:.6g}, "
      "penetration {:.6g} per unit {}",
      stop + 1, phase, multipliers, root.norm(), unfolding, parameter);
  if (std::abs(unfolding) > 0) {
    line += fmt::format(", reach {}{:.2g} in {}", reach_bounded ? "at least " : "",
                        reach / std::abs(unfolding), parameter);
  }
  if (reduced) {
    line += fmt::format("; one-dimensional: lambda = {:.6g}, kappa = {:.6g}", reduced->lambda,
                        reduced->kappa);
  } else {
    line += "; " + reduction_note;
  }
  return line;
}

std::string GrazingPrediction::Describe() const {
  const std::string where =
      motion.starts_with("P(") ? "jumps to " + motion : "jumps away (simulated: " + motion + ")";
  std::string what;
  if (unstable_grazing_orbit) {
    what = "the grazing orbit is unstable; the motion " + where;
  } else if (local) {
    what = fmt::format("{} near the grazing orbit ({})", motion, scenario);
    if (!attractors.empty() && !attractors.front().within_reach) {
      what += fmt::format(", found {:.2g} past, beyond the normal form's reach", distance);
    }
  } else {
    what = "no attractor near the grazing orbit; the motion " + where;
  }
  return fmt::format("past the grazing ({}): {}", side > 0 ? "increasing" : "decreasing", what);
}

GrazingNormalForm ComputeGrazingNormalForm(const GrazingOrbit& orbit,
                                           const std::string& parameter) {
  const HybridSystem hybrid(orbit.system);
  RequireTouch(orbit, hybrid);
  const NamedParameter named(orbit.system, parameter);
  const SpeedSplitMonodromy split = SplitMonodromy(orbit.system, orbit.contacts, orbit.q);
  const StopContact& touch = orbit.contacts.front();
  const Stop& stop = hybrid.GetStop(touch.stop);
  const int n = orbit.system.Dof();

  GrazingNormalForm form;
  form.parameter = parameter;
  form.parameter_value = named.Get(orbit.system);
  form.stop = touch.stop;
  form.p = static_cast<int>(orbit.contacts.size()) - 1;
  form.q = orbit.q;
  form.time = touch.state.t;
  const double period = orbit.system.ForcingPeriod();
  form.phase = form.time - std::floor(form.time / period) * period;
  form.touch.resize(2 * n);
  form.touch << touch.state.x, touch.state.v;
  const Eigen::VectorXd field = hybrid.VectorField(touch.state.t, touch.state.x, touch.state.v);
  form.curvature = -stop.Sign() * field(n + stop.Dof());
  Require(form.curvature > 0,
          fmt::format("a grazing orbit's touch must turn back from its stop; the mass is pressed "
                      "into it (acceleration {:.3g} towards it): a sticking onset",
                      -form.curvature));
  if (orbit.sticking) {
    form.linear = StickingMonodromy(orbit, &form.p);
    form.releases = orbit.sticking->releases;
  } else {
    form.linear = split.smooth;
  }
  form.eigenvalues =
      SortedByModulus(Eigen::EigenSolver<Eigen::MatrixXd>(form.linear).eigenvalues());
  form.normal = split.normal;
  form.root = split.jump * std::sqrt(2.0 / form.curvature);
  form.unfolding = Unfolding(orbit, named, form.time);
  Reduce(&form);
  SetReach(orbit, &form);
  return form;
}

}  // namespace impactkit
