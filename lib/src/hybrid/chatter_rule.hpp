#pragma once
/// \file chatter_rule.hpp (private)
/// When an arrival at the stop is an impact, and when a sequence of impacts
/// ends (docs/theory.md §4): the rules the simulator and the sticking map
/// share, so that an orbit and a simulation of it end their chatter at the
/// same instant.
///
/// Heights are compared with the resolution of the event search: a bounce
/// of speed u off the stop under an acceleration a towards it rises u²/(2a).
/// Below `bounce_height_resolution` times the length scale L of the gap
/// signal (the sum of its coefficients' magnitudes, the scale of its
/// rounding) the flight is not resolved: an arrival that low lands (contact,
/// no impact) and a rebound that low ends the chatter at once. The state
/// error of either is at most that height in x_c and √(2 a h) in v_c. This
/// is the only rule that ends elastic chatter (r = 1), whose bounces decay
/// only through the energy damping takes in flight (u_k ~ 1/k: the sequence
/// never accumulates).

#include <cmath>
#include <limits>
#include <optional>

#include "impactkit/hybrid/simulator.hpp"

namespace impactkit {

class ChatterRule {
 public:
  ChatterRule(const SimulationOptions& options, double restitution, double time_scale)
      : options_(options), restitution_(restitution), time_scale_(time_scale) {}

  /// An arrival at speed `speed` >= 0 with the gap's second derivative
  /// `acceleration` (either sign), on a gap signal of length scale
  /// `length_scale`: true when its height is unresolved (a landing, or a
  /// grazing touch when the acceleration leads away from the stop).
  bool IsLanding(double speed, double acceleration, double length_scale) const {
    return speed <= kSpeedNoise * length_scale / time_scale_ ||
           Unresolved(speed, std::abs(acceleration), length_scale);
  }

  /// After the reset of an impact at `te` of speed `speed` (rebound
  /// `rebound` = r·speed, `previous` the impact before), with the contact
  /// mass's acceleration `acceleration` towards the stop and its rate
  /// `jerk` after the reset: the time the chatter ends (the mass at rest on
  /// the stop there), or nothing to keep simulating impacts.
  std::optional<double> EndsAt(double te, double previous, double speed, double rebound,
                               double acceleration, double jerk, double length_scale) const;
  /// False when EndsAt returns nothing for every acceleration towards the
  /// stop up to `bound` (and any jerk): each way it ends chatter needs the
  /// acceleration above a least value that falls with the rebound. Most
  /// impacts rebound far too fast, and the simulator then skips computing
  /// the acceleration and its rate (8 % of an impact's instructions).
  bool MayEnd(double te, double previous, double rebound, double bound, double length_scale) const;

 private:
  bool Unresolved(double speed, double acceleration, double length_scale) const {
    return speed * speed <= 2.0 * acceleration * options_.bounce_height_resolution * length_scale;
  }
  /// The remaining span of a chatter sequence after an impact of `speed`.
  double Span(double speed, double acceleration) const;
  bool PredictionHolds(double speed, double acceleration, double jerk, double longest) const;
  /// Speeds below this many ulps of the gap's velocity scale L / τ are
  /// rounding: where the acceleration is zero to rounding too (a release's
  /// tangency) no height test can tell them from rest.
  static constexpr double kSpeedNoise = 64 * std::numeric_limits<double>::epsilon();
  static constexpr double kUnbounded = std::numeric_limits<double>::infinity();

  const SimulationOptions& options_;
  double restitution_;
  double time_scale_;
};

}  // namespace impactkit
