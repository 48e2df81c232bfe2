#include "hybrid/phase_events.hpp"

#include <cmath>
#include <numbers>

namespace impactkit {

PhaseEvents::PhaseEvents(const HybridSystem& hybrid, const SimulationOptions& options)
    : hybrid_(hybrid),
      events_{options.event_time_tolerance, hybrid.TimeScale()},
      witnesses_(hybrid.StopCount()),
      length_scales_(hybrid.StopCount(), 1.0),
      due_(hybrid.StopCount(), 0),
      from_rest_(hybrid.StopCount(), 0),
      force_scratch_(hybrid.GetSystem().Dof()),
      acceleration_scratch_(hybrid.GetSystem().Dof()) {
  rules_.reserve(hybrid.StopCount());
  for (int k = 0; k < hybrid.StopCount(); ++k) {
    rules_.emplace_back(options, hybrid.GetStop(k).Restitution(), hybrid.TimeScale(),
                        hybrid.Free().Contact(k));
  }
}

/// At once if the stop does not hold the mass at the phase's start
/// (Stop::Holds), else where −Fs first crosses 0 upwards.
std::optional<double> PhaseEvents::ReleaseTime(int stop, double end) const {
  const Signal& release = witnesses_[stop];
  const EventOptions search = HeldSearch(release);
  if (!Stop::Holds(release, t0_, search)) return t0_;
  return FirstUpcrossing(release, t0_, end, search);
}

double PhaseEvents::AccelerationBound(int stop, const Eigen::VectorXd& v,
                                      const Eigen::VectorXd& v_before,
                                      double arrival_acceleration) const {
  const double change = mode_->AccelerationChange(stop, v - v_before);
  const double rate = 2 * std::numbers::pi / hybrid_.TimeScale();
  return 2.0 * (std::abs(arrival_acceleration) + std::abs(change)) +
         1e-9 * length_scales_[stop] * rate * rate;
}

std::optional<PhaseEvents::SequenceEnd> PhaseEvents::AfterImpact(
    int stop, double te, double previous, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
    const Eigen::VectorXd& v_before, double arrival_acceleration) {
  const Stop& s = hybrid_.GetStop(stop);
  const ChatterRule& rule = rules_[stop];
  const double rebound = -s.SpeedTowards(v(s.Dof())), length_scale = length_scales_[stop];
  if (!rule.MayEnd(te, previous, rebound,
                   AccelerationBound(stop, v, v_before, arrival_acceleration), length_scale)) {
    return std::nullopt;
  }
  // The acceleration after the reset (the rebound's) towards the stop.
  double jerk;
  const double acceleration =
      mode_->Acceleration(stop, te, x, v, &jerk, &force_scratch_, &acceleration_scratch_);
  switch (rule.Decide(te, previous, rebound, s.Sign() * acceleration, length_scale)) {
    case ChatterDecision::kGoesOn:
      return std::nullopt;
    case ChatterDecision::kEndsNow:
      return SequenceEnd{te, false};
    case ChatterDecision::kCut:
      return SequenceEnd{te, true};
    case ChatterDecision::kSumTail:
      break;
  }
  const Mode& held = hybrid_.Holding(mode_->Held() | StopBit(stop));
  held.Flow().Transient(te, held.Reduced(x), held.Reduced(v), &held_transient_);
  held.Flow().Output(held.Witness(stop)->output, te, held_transient_, &held_witness_);
  const ChatterTail tail = rule.SumTail(held_witness_, mode_->Contact(stop), te, rebound);
  if (!tail.accumulates) return std::nullopt;
  return SequenceEnd{tail.end, tail.cut};
}

EventOptions PhaseEvents::HeldSearch(const Signal& release) const {
  EventOptions events = events_;
  events.start_noise = ChatterRule::kRounding * release.Scale();
  events.resolution = ChatterRule::kRounding * release.Scale();
  return events;
}

}  // namespace impactkit
