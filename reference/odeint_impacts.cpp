#include "odeint_impacts.hpp"

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <optional>
#include <vector>

#include "oscillator_model.hpp"

namespace impactkit::reference {
namespace {

namespace odeint = boost::numeric::odeint;

using State = std::vector<double>;
using Stepper = decltype(odeint::make_dense_output(0.0, 0.0, odeint::runge_kutta_dopri5<State>()));

// Only a first guess: the step controller corrects it within a few steps.
constexpr double kInitialStep = 1e-4;

// The right-hand side in odeint's calling convention, counting its calls.
// odeint copies it; the copies share the counter.
struct CountingRhs {
  const LinearOscillator& oscillator;
  long& evaluations;

  void operator()(const State& y, State& dydt, double t) const {
    ++evaluations;
    oscillator.Derivative(t, y.data(), dydt.data());
  }
};

Eigen::Map<Eigen::VectorXd> AsVector(State& y) {
  return {y.data(), static_cast<Eigen::Index>(y.size())};
}

// A step that starts short of the stop (g < 0; after an impact, always) and
// ends with g >= 0 holds at least one upward crossing. Two crossings in one
// step (a graze) leave g < 0 at both ends and are missed: the known limit of
// the method.
bool CrossedStop(const Stepper& stepper, const ImpactSequence& sequence) {
  return sequence.Gap(0, stepper.previous_state().data()) < 0.0 &&
         sequence.Gap(0, stepper.current_state().data()) >= 0.0;
}

// Bisection on the dense output of the last step, where g went from negative
// to non-negative. Returns the left end of the final bracket, with its state
// in y: still short of the stop, so a restart there cannot see the same
// crossing again.
double LocateCrossing(const Stepper& stepper, const ImpactSequence& sequence, double tolerance,
                      State& y) {
  double t_lo = stepper.previous_time();
  double t_hi = stepper.current_time();
  y = stepper.previous_state();
  State y_mid(y.size());
  while (t_hi - t_lo > tolerance) {
    const double t_mid = 0.5 * (t_lo + t_hi);
    if (t_mid <= t_lo || t_mid >= t_hi) break;  // the bracket is two adjacent doubles
    stepper.calc_state(t_mid, y_mid);
    if (sequence.Gap(0, y_mid.data()) < 0.0) {
      t_lo = t_mid;
      y.swap(y_mid);
    } else {
      t_hi = t_mid;
    }
  }
  return t_lo;
}

// Steps on to the next impact before t_end: returns its time, with the state
// just before it in y; or nullopt, with the state at t_end in y.
std::optional<double> NextImpact(Stepper& stepper, const CountingRhs& rhs,
                                 const ImpactSequence& sequence, double t_end, double crossing_tol,
                                 State& y) {
  while (true) {
    stepper.do_step(rhs);
    if (CrossedStop(stepper, sequence)) {
      const double t_impact = LocateCrossing(stepper, sequence, crossing_tol, y);
      if (t_impact < t_end) return t_impact;
    }
    if (stepper.current_time() >= t_end) {
      stepper.calc_state(t_end, y);
      return std::nullopt;
    }
  }
}

}  // namespace

ReferenceRun OdeintImpacts(const System& s, Eigen::VectorXd x0, Eigen::VectorXd v0, double t0,
                           double t_end, const OdeintOptions& o) {
  // The classic step-and-check style watches one stop; the CVODE reference
  // watches any number.
  if (s.stops.size() != 1) throw std::invalid_argument("OdeintImpacts: one stop only");
  const LinearOscillator oscillator(s);
  ImpactSequence sequence(s, oscillator, o.max_impacts, o.min_interimpact,
                          o.abs_tol + o.rel_tol * std::abs(s.stops[0].position));
  const Eigen::VectorXd y0 = oscillator.StackState(x0, v0);
  State y(y0.begin(), y0.end());
  if (!sequence.Begin(t0, AsVector(y)) || t_end <= t0) return sequence.Finish(t0, AsVector(y), 0);

  long rhs_evaluations = 0;
  const CountingRhs rhs{oscillator, rhs_evaluations};
  Stepper stepper =
      odeint::make_dense_output(o.abs_tol, o.rel_tol, odeint::runge_kutta_dopri5<State>());
  stepper.initialize(y, t0, kInitialStep);
  while (const std::optional<double> t_impact =
             NextImpact(stepper, rhs, sequence, t_end, o.crossing_tol, y)) {
    if (!sequence.Impact(*t_impact, AsVector(y), 0)) {
      return sequence.Finish(*t_impact, AsVector(y), rhs_evaluations);
    }
    // The acceleration jumps at the impact; initialize() also discards the
    // stored (first-same-as-last) derivative, which is now stale.
    stepper.initialize(y, *t_impact, stepper.current_time_step());
  }
  return sequence.Finish(t_end, AsVector(y), rhs_evaluations);
}

}  // namespace impactkit::reference
