#include "hybrid/chatter_rule.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

namespace impactkit {
namespace {

/// A polynomial in s of degree < 12, by its coefficients.
using Polynomial = std::array<double, 12>;

double Evaluate(const Polynomial& p, double s) {
  double value = 0.0;
  for (auto c = p.rbegin(); c != p.rend(); ++c) value = value * s + *c;
  return value;
}

/// ∫0^s p, truncated to the degrees kept.
Polynomial Integral(const Polynomial& p) {
  Polynomial q{};
  for (std::size_t k = 0; k + 1 < q.size(); ++k) q[k + 1] = p[k] / static_cast<double>(k + 1);
  return q;
}

Polynomial Derivative(const Polynomial& p) {
  Polynomial q{};
  for (std::size_t k = 1; k < p.size(); ++k) q[k - 1] = p[k] * static_cast<double>(k);
  return q;
}

/// The acceleration towards the stop at rest and its first three rates.
struct AccelerationRates {
  double a, j, a2, a3;
};

struct Bounce {
  double duration;
  double arrival;
};

/// One bounce of rebound speed u off the stop: h the distance from it,
/// h(0) = 0, h'(0) = u, under h'' = −a(t) − γ h' − κ h with the
/// acceleration's Taylor polynomial a(t0 + s) = a + j s + a2 s²/2 + a3 s³/6.
/// Written as h = h0 + L h, h0 = u s − ∫∫a, L h = −γ ∫h − κ ∫∫h, and solved
/// by three Picard iterations h ← h0 + L h: a polynomial in s exact up to
/// relative terms (γ s)⁴, (κ s²)⁴ and a's fourth derivative. The bounce
/// lasts the first positive root of h(s)/s, found by Newton's method from
/// Budd & Dux's 2u/a, and arrives at the speed −h'(s). None when the mass
/// does not come back.
std::optional<Bounce> FollowBounce(double u, const AccelerationRates& rates,
                                   const ContactResponse& contact) {
  const Polynomial acceleration{rates.a, rates.j, rates.a2 / 2, rates.a3 / 6};
  Polynomial free = Integral(Integral(acceleration));
  for (double& c : free) c = -c;
  free[1] += u;
  Polynomial h = free;
  for (int iteration = 0; iteration < 3; ++iteration) {
    const Polynomial once = Integral(h), twice = Integral(once);
    for (std::size_t k = 0; k < h.size(); ++k) {
      h[k] = free[k] - contact.damping * once[k] - contact.stiffness * twice[k];
    }
  }
  Polynomial quotient{};  // h(s)/s (h(0) = 0)
  std::copy(h.begin() + 1, h.end(), quotient.begin());
  const Polynomial slope = Derivative(quotient), velocity = Derivative(h);
  double s = 2.0 * u / rates.a;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const double d = Evaluate(slope, s);
    if (!(d < 0)) return std::nullopt;
    const double next = s - Evaluate(quotient, s) / d;
    if (!(next > 0)) return std::nullopt;
    const bool converged = std::abs(next - s) <= 4 * std::numeric_limits<double>::epsilon() * s;
    s = next;
    if (converged) return Bounce{s, -Evaluate(velocity, s)};
  }
  return std::nullopt;
}

/// A restitution at or above this is elastic for the rules: from a bounce
/// of 1e-2 L its bounces would take more than 10^4 impacts to fall to a
/// height of 1e-14 L (r^(2k) = 1e-12).
constexpr double kElasticRestitution = 0.99862;

}  // namespace

double GapLengthScale(const HybridSystem& hybrid, int stop, const Eigen::VectorXd& x,
                      const Eigen::VectorXd& v, const Signal& gap) {
  const double per_radian = hybrid.TimeScale() / (2 * std::numbers::pi);
  return std::abs(hybrid.GetStop(stop).Position()) + x.lpNorm<Eigen::Infinity>() +
         v.lpNorm<Eigen::Infinity>() * per_radian + gap.Scale();
}

EventOptions ArrivalSearch(EventOptions base, double length_scale) {
  base.resolution = ChatterRule::kRounding * length_scale;
  return base;
}

ChatterDecision ChatterRule::Decide(double te, double previous, double rebound, double acceleration,
                                    double length_scale) const {
  if (rebound == 0.0) return ChatterDecision::kEndsNow;
  const bool threshold = options_.chatter == ChatterMethod::kThreshold;
  if (threshold && te - previous < options_.chatter_threshold) return ChatterDecision::kEndsNow;
  if (!(acceleration > 0)) return ChatterDecision::kGoesOn;
  const bool unresolved = Unresolved(rebound, acceleration, length_scale);
  if (restitution_ >= kElasticRestitution) {
    const bool short_bounce = 2.0 * rebound / acceleration <= options_.chatter_span * time_scale_;
    return unresolved || short_bounce ? ChatterDecision::kCut : ChatterDecision::kGoesOn;
  }
  if (unresolved || TailIsExact(rebound, acceleration, length_scale)) {
    return ChatterDecision::kSumTail;
  }
  return ChatterDecision::kGoesOn;
}

/// The chatter map neglects, per bounce of duration s, terms of relative
/// size (ρ s)⁴ (1 + A/a): the damping and stiffness beyond the third order,
/// the other masses' response to the contact mass's displacement and the
/// acceleration's fourth derivative (A = L ρ² its scale), with ρ = 2π/τ
/// (or the damping rate γ where larger) bounding their rates. Over the tail
/// that is span times its value at the first bounce at the most. Following
/// the bounces exactly instead costs their timing, which is weighed here at
/// ε L ρ s / u: the rounding of the gap's first-order increments over the
/// bounce. (The refinement places a crossing better still, from the
/// remainders past the first order, Signal::AnchorAt; the map taking over
/// at this larger figure keeps the bounces followed few, and its share of
/// the error, ~2 ε L ρ / a, is what the tests measure.) And the other masses follow the
/// stuck flow, missing the pull of the contact mass's bounces: ∫h over the
/// tail is 2u³/(3a²(1 − r³)), times the coupling in their velocities. The
/// map takes over where its time error is below the timing's, or the
/// rounding of time, and the others' velocities are good to rounding.
bool ChatterRule::TailIsExact(double rebound, double acceleration, double length_scale) const {
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  const double time_rate = 2.0 * std::numbers::pi / time_scale_;
  const double rate = std::max(time_rate, contact_.damping);
  const double bounce = 2.0 * rebound / acceleration;
  const double r = restitution_;
  const double span = bounce * r / (1.0 - r);
  const double relative = rate * bounce, squared = relative * relative;
  const double neglected =
      span * squared * squared * (1.0 + length_scale * time_rate * time_rate / acceleration);
  const double timing = kEpsilon * length_scale * rate * bounce / rebound;
  const double pull = contact_.coupling * 2.0 * rebound * rebound * rebound /
                      (3.0 * acceleration * acceleration * (1.0 - r * r * r));
  return neglected <= std::max(TimeRounding(), timing) &&
         pull <= kRounding * length_scale * time_rate;
}

ChatterTail ChatterRule::SumTail(const Signal& release, const ContactResponse& contact, double te,
                                 double rebound) const {
  const double r = restitution_;
  const Signal third = release.Derivative(3);
  ChatterTail tail;
  double t = te, u = rebound;
  for (int k = 0; k < kMaxTailBounces; ++k) {
    tail.end = t;
    double w, dw, d2w;
    release.ValueSlopeCurvature(t, &w, &dw, &d2w);
    // −Fs on the stuck flow gives the acceleration at rest and its rates.
    const double a = -contact.compliance * w, jerk = -contact.compliance * dw,
                 snap = -contact.compliance * d2w;
    if (!(a > 0)) {
      tail.accumulates = false;
      return tail;
    }
    // Budd & Dux's span with its first-order correction: summing the
    // bounces 2u_k/a_k (1 − α u_k), speeds u_{k+1} = r u_k (1 + β u_k) and
    // a_k = a + j t_k (α = 2j/(3a²) + γ/(3a), β = 2j/(3a²) − 2γ/(3a))
    // gives 2u/(a(1−r)) (1 − u (2j/(3a²) + γ/(3a)) / (1−r)).
    const double correction =
        u / (1.0 - r) * (2.0 * jerk / (3.0 * a * a) + contact.damping / (3.0 * a));
    const double span = 2.0 * u / (a * (1.0 - r)) * (1.0 - correction);
    const double neglected = span * (correction * correction + std::abs(snap) * span * span / a);
    if (std::abs(correction) < 0.1 && neglected <= TimeRounding()) {
      tail.end = t + span;
      return tail;
    }
    const AccelerationRates rates{a, jerk, snap, -contact.compliance * third.Value(t)};
    const std::optional<Bounce> bounce = FollowBounce(u, rates, contact);
    if (!bounce) {
      tail.accumulates = false;
      return tail;
    }
    t += bounce->duration;
    u = r * bounce->arrival;
    if (!(u > 0)) {  // arrived at rest: the sequence has ended
      tail.end = t;
      return tail;
    }
  }
  tail.end = t;
  tail.cut = true;
  return tail;
}

}  // namespace impactkit
