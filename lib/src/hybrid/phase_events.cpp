#include "hybrid/phase_events.hpp"

namespace impactkit {

PhaseEvents::PhaseEvents(const HybridSystem& hybrid, const SimulationOptions& options)
    : hybrid_(hybrid),
      events_{options.event_time_tolerance, hybrid.TimeScale()},
      witnesses_(hybrid.StopCount()),
      length_scales_(hybrid.StopCount(), 1.0),
      due_(hybrid.StopCount(), 0),
      from_rest_(hybrid.StopCount(), 0) {
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

EventOptions PhaseEvents::HeldSearch(const Signal& release) const {
  EventOptions events = events_;
  events.start_noise = ChatterRule::kRounding * release.Scale();
  events.resolution = ChatterRule::kRounding * release.Scale();
  return events;
}

}  // namespace impactkit
