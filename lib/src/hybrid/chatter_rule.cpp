#include "hybrid/chatter_rule.hpp"

#include <cmath>
#include <limits>

namespace impactkit {

std::optional<double> ChatterRule::EndsAt(double te, double previous, double speed, double rebound,
                                          double acceleration, double jerk,
                                          double length_scale) const {
  if (rebound == 0.0) return te;
  if (options_.chatter == ChatterMethod::kThreshold) {
    if (te - previous < options_.chatter_threshold) return te;
  } else if (PredictionHolds(speed, acceleration, jerk, options_.chatter_span * time_scale_)) {
    return te + Span(speed, acceleration);
  }
  if (!(acceleration > 0)) return std::nullopt;
  // A micro-bounce is contact. If it is unresolved in height, its bounces
  // end where Budd & Dux put them when the acceleration holds over them,
  // however long that is, or here (r = 1, or r so near 1 that they would
  // outlast the acceleration). A bounce merely shorter than the chatter
  // resolution ends the chatter here only where Budd & Dux cannot (their
  // span criterion above ends it otherwise, a few bounces later).
  const bool predicted = PredictionHolds(speed, acceleration, jerk, kUnbounded);
  if (Unresolved(rebound, acceleration, length_scale)) {
    return predicted ? te + Span(speed, acceleration) : te;
  }
  const bool short_bounce = 2.0 * rebound / acceleration <= options_.chatter_span * time_scale_;
  if (short_bounce && !predicted) return te;
  return std::nullopt;
}

bool ChatterRule::MayEnd(double te, double previous, double rebound, double bound,
                         double length_scale) const {
  if (rebound == 0.0) return true;
  if (options_.chatter == ChatterMethod::kThreshold && te - previous < options_.chatter_threshold) {
    return true;
  }
  if (!(bound > 0)) return false;
  // EndsAt's other ends need an acceleration a > 0 with an unresolved
  // micro-bounce or a bounce 2 u / a shorter than the chatter span (a Budd
  // & Dux span, 2 u / (a (1 − r)), is longer): both hold for every a above
  // some least value.
  return Unresolved(rebound, bound, length_scale) ||
         2.0 * rebound / bound <= options_.chatter_span * time_scale_;
}

/// Budd & Dux: with rebound speed u = r v and acceleration a > 0 towards the
/// stop, the impacts that follow come at intervals 2 r^k u / a and end after
/// 2 u / (a (1 − r)).
double ChatterRule::Span(double speed, double acceleration) const {
  return 2.0 * restitution_ * speed / (acceleration * (1.0 - restitution_));
}

/// The geometric model's premise: a finite span no longer than
/// `longest`, over which the acceleration barely changes.
bool ChatterRule::PredictionHolds(double speed, double acceleration, double jerk,
                                  double longest) const {
  if (restitution_ >= 1.0 || !(acceleration > 0)) return false;
  const double span = Span(speed, acceleration);
  return span <= longest && std::abs(jerk) * span <= 0.01 * acceleration;
}

}  // namespace impactkit
