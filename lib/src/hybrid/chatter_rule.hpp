#pragma once
/// \file chatter_rule.hpp (private)
/// When an arrival at the stop is an impact, and how a sequence of impacts
/// ends (docs/theory.md §4): the rules the simulator, the sticking map and
/// the impact map share, so that an orbit and a simulation of it agree on
/// which arrivals are impacts and end their chatter at the same instant.
///
/// Heights are compared with the rounding of the gap: a bounce of speed u
/// off the stop under an acceleration a towards it rises u²/(2a). Below
/// `bounce_height_resolution` (64 ulps by default) times the length scale
/// L of the gap (the sum of the magnitudes it is computed from) its sign
/// is rounding: an arrival that low is a landing (contact, no impact).
///
/// A sequence of impacts with r < 1 is followed impact by impact while its
/// bounces are resolved, and its tail summed by the chatter map (SumTail)
/// once that sum is more accurate than following them, or the bounces fall
/// below the height resolution. Elastic chatter (r = 1, or r so near 1 that
/// following it would take more than 10^4 impacts) never
/// accumulates: it is cut at its first bounce shorter than `chatter_span`
/// of the time scale, and counted (SimulationSummary::chatter_cuts).

#include <cmath>
#include <limits>

#include "impactkit/dynamics/events.hpp"
#include "impactkit/dynamics/flow.hpp"
#include "impactkit/hybrid/hybrid_system.hpp"
#include "impactkit/hybrid/mode.hpp"
#include "impactkit/hybrid/simulator.hpp"

namespace impactkit {

/// How a sequence of impacts goes on after one of them.
enum class ChatterDecision {
  kGoesOn,   ///< keep following impacts
  kEndsNow,  ///< at rest on the stop from this impact (r = 0, or the threshold rule)
  kSumTail,  ///< the rest summed by ChatterRule::SumTail
  kCut,      ///< elastic chatter cut at a short bounce: not an accumulation point
};

/// Where the tail of a chatter sequence ends.
struct ChatterTail {
  double end = 0.0;  ///< the accumulation point (when it accumulates)
  /// False where the force at the stop turns, or a bounce does not come
  /// back, before the bounces accumulate: the impacts then go on exactly.
  bool accumulates = true;
  bool cut = false;  ///< the chatter map's bound on bounces was reached
};

/// The length scale L of stop `stop`'s gap on a flight from (x, v): the
/// gap's rounding comes from the state and the forced response, of which
/// the gap signal's own coefficients (`gap`.Scale()) can be far smaller,
/// for a mass barely moving off the stop while the others swing.
double GapLengthScale(const HybridSystem& hybrid, int stop, const Eigen::VectorXd& x,
                      const Eigen::VectorXd& v, const Signal& gap);

/// The event search for an arrival at a stop on a gap of length scale L:
/// a rise of the gap above 0 by more than its rounding (ChatterRule::
/// kRounding × L) is an event, so that every crossing resolved in double
/// precision is found and judged by ChatterRule::IsLanding.
EventOptions ArrivalSearch(EventOptions base, double length_scale);

class ChatterRule {
 public:
  /// `contact`: the contact mass's response in free flight (the tail's
  /// error estimate uses its damping).
  ChatterRule(const SimulationOptions& options, double restitution, double time_scale,
              const ContactResponse& contact = {})
      : options_(options), restitution_(restitution), time_scale_(time_scale), contact_(contact) {}

  /// An arrival at speed `speed` >= 0 with the gap's second derivative
  /// `acceleration` (either sign), on a gap of length scale `length_scale`:
  /// true when its height is unresolved (a landing, or a grazing touch when
  /// the acceleration leads away from the stop).
  bool IsLanding(double speed, double acceleration, double length_scale) const {
    return speed <= kSpeedNoise * length_scale / time_scale_ ||
           Unresolved(speed, std::abs(acceleration), length_scale);
  }

  /// After the reset of an impact at `te` with rebound speed `rebound`
  /// (`previous` the impact before), the contact mass's acceleration
  /// towards the stop being `acceleration`: how the sequence goes on.
  /// Every answer but kGoesOn holds for every larger acceleration too, so
  /// that the simulator can decide from a bound (MayEnd) without computing
  /// the acceleration at most impacts.
  ChatterDecision Decide(double te, double previous, double rebound, double acceleration,
                         double length_scale) const;
  /// False when Decide returns kGoesOn for every acceleration up to `bound`.
  bool MayEnd(double te, double previous, double rebound, double bound, double length_scale) const {
    return Decide(te, previous, rebound, bound, length_scale) != ChatterDecision::kGoesOn;
  }

  /// The chatter map: the bounces after an impact at `te` with rebound
  /// `rebound`, the other masses following the stuck flow, on which
  /// `release` is −Fs. Each bounce is solved with the acceleration's
  /// Taylor polynomial to second order at its start, and the damping and
  /// stiffness of the contact mass's own motion to first order; once the remaining span's closed
  /// form (Budd & Dux with its first-order correction) is exact to the rounding of time, it is
  /// summed at once (docs/theory.md §4).
  ChatterTail SumTail(const Signal& release, const ContactResponse& contact, double te,
                      double rebound) const;

  /// The rounding of a time on the system's time scale: kRounding τ (not of
  /// the absolute time, so that an orbit and a simulation of it, at times
  /// a whole number of periods apart, end their chatter alike).
  double TimeRounding() const { return kRounding * time_scale_; }

  /// The rounding relative to a computed value's scale: 64 ulps.
  static constexpr double kRounding = 64 * std::numeric_limits<double>::epsilon();

 private:
  bool Unresolved(double speed, double acceleration, double length_scale) const {
    return speed * speed <= 2.0 * acceleration * options_.bounce_height_resolution * length_scale;
  }
  /// True when the chatter map from a rebound `rebound` under acceleration
  /// `acceleration` errs less than following the bounces would.
  bool TailIsExact(double rebound, double acceleration, double length_scale) const;
  /// Speeds below this many ulps of the gap's velocity scale L / τ are
  /// rounding: where the acceleration is zero to rounding too (a release's
  /// tangency) no height test can tell them from rest.
  static constexpr double kSpeedNoise = 64 * std::numeric_limits<double>::epsilon();
  /// The chatter map's bound on the bounces it follows one by one.
  static constexpr int kMaxTailBounces = 100'000;

  const SimulationOptions& options_;
  double restitution_;
  double time_scale_;
  ContactResponse contact_;
};

}  // namespace impactkit
