#include "analysis/settling.hpp"

#include <algorithm>
#include <cmath>

#include "dynamics/subsystem.hpp"
#include "impactkit/core/errors.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit {
namespace {

/// What FindOrbit is asked: the orbit through the seed, and the seed.
struct Candidate {
  OrbitOptions options;
  Eigen::VectorXd seed;
  int time_index = 0;  ///< of the section's coordinates (ImpactMap, StickingMap::TimeIndex)
};

/// The impact section at the window's last impact: η = (x without the
/// contact DOF, τ, v), the p impacts of its q periods.
Candidate ImpactCandidate(const System& system, const ImpactView& last,
                          const MotionPeriod& period) {
  Candidate c;
  c.options.p = static_cast<int>(period.p);
  c.options.q = period.q;
  c.options.map.stop = last.stop;
  const Eigen::VectorXd x = last.x, v = last.v;
  c.seed.resize(2 * system.Dof());
  c.seed << WithoutIndex(x, system.stops[last.stop].dof), last.t, v;
  c.time_index = system.Dof() - 1;
  return c;
}

/// The release section at the window's last repeating release.
Candidate ReleaseCandidate(const StickingSeed& seed) {
  return {OrbitOptionsFor(seed), seed.state, static_cast<int>(seed.state.size()) - 1};
}

/// max |seed − orbit| relative to 1 + max |seed entry|, the times compared
/// modulo T (the orbit's is in [0, T), the seed's absolute).
double Distance(const Candidate& c, const Eigen::VectorXd& orbit, double period) {
  Eigen::VectorXd d = c.seed - orbit;
  d(c.time_index) = std::remainder(d(c.time_index), period);
  Eigen::VectorXd state = c.seed;
  state(c.time_index) = 0.0;
  return d.cwiseAbs().maxCoeff() / (1.0 + state.cwiseAbs().maxCoeff());
}

/// Section-map iterations n >= 1 with rate^n distance <= accuracy (0 when
/// already there).
double Iterations(double rate, double distance, double accuracy) {
  if (distance <= accuracy) return 0.0;
  if (rate == 0.0) return 1.0;
  return std::max(1.0, std::ceil(std::log(accuracy / distance) / std::log(rate)));
}

}  // namespace

TransientProbe::Window::Window(const System& system, double period)
    : steady(period), releases(system) {
  observers.Add(steady);
  observers.Add(releases);
}

TransientProbe::TransientProbe(const System& system, double period, const ProbeOptions& options)
    : system_(system),
      period_(period),
      options_(options),
      window_(std::make_unique<Window>(system, period)),
      window_end_((2 * options.period.max_q + 1) * period),
      attempts_left_(options.attempts) {}

void TransientProbe::OnSegment(const Segment& segment) {
  if (!window_) return;
  window_->observers.OnSegment(segment);
  if (segment.End() >= window_end_) Check(segment.End());
}

void TransientProbe::OnImpact(const Impact& impact) {
  if (window_) window_->observers.OnImpact(impact);
}

void TransientProbe::OnChatter(const ChatterEnd& chatter) {
  if (window_) window_->observers.OnChatter(chatter);
}

void TransientProbe::OnRelease(const Release& release) {
  if (window_) window_->observers.OnRelease(release);
}

void TransientProbe::Check(double t) {
  const MotionPeriod period = window_->steady.Period(options_.period);
  // Without a period or impacts there is no orbit to confirm yet (and a
  // non-impacting motion has no section map).
  if (period.periodic && !window_->steady.Impacts().empty()) {
    --attempts_left_;
    settling_ = Settle(period);
    // The settling periods, from the next whole period on, must end in time.
    if (settling_ && std::ceil(t / period_) + settling_->periods >= options_.end) {
      settling_.reset();
    }
  }
  if (settling_ || attempts_left_ == 0) {
    window_.reset();
    return;
  }
  window_ = std::make_unique<Window>(system_, period_);
  window_end_ = t + (2 * options_.period.max_q + 1) * period_;
}

std::optional<Settling> TransientProbe::Settle(const MotionPeriod& period) const {
  std::optional<Candidate> c;
  if (!period.sticking) {
    c = ImpactCandidate(system_, window_->steady.Impacts().back(), period);
  } else if (const std::optional<StickingSeed> seed =
                 window_->releases.Seed(period_, options_.period.max_q)) {
    c = ReleaseCandidate(*seed);
  }
  if (!c) return std::nullopt;
  // Newton alone: a seed that needs a fallback is not on the orbit's doorstep.
  c->options.least_squares_fallback = false;
  c->options.shooting_fallback = false;
  PeriodicOrbit orbit;
  try {
    const OrbitSummary summary = FindOrbit(system_, c->seed, c->options, &orbit);
    if (summary.termination != Termination::kConverged) return std::nullopt;
  } catch (const InvalidInput&) {
    return std::nullopt;  // a seed the map cannot start from: no certainty
  }
  const double rate = orbit.multipliers.size() > 0 ? std::abs(orbit.multipliers(0)) : 0.0;
  const double distance = Distance(*c, orbit.eta, period_);
  if (!(rate < 1.0) || !(distance <= options_.period.tolerance)) return std::nullopt;
  const double periods = Iterations(rate, distance, options_.accuracy) * orbit.q;
  // Beyond any run (an int): Check refuses it.
  if (!(periods <= options_.end)) return std::nullopt;
  return Settling{period, orbit.q, static_cast<int>(periods)};
}

}  // namespace impactkit
