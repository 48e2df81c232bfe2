#include "impactkit/dynamics/events.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace impactkit {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// How far below 0 (relative to the signal's scale) a bound on w must stay
/// for the whole future to be settled at once: well above the bound's own
/// rounding.
constexpr double kUnreachableMargin = 1e-12;
/// How far above 0 (relative to sup|w|) the cubic lower bound must rise
/// for a crossing to be certain: well above w's rounding.
constexpr double kCertainMargin = 1e-12;

/// w, w' and w'' at one time.
struct Point {
  double t;
  double w;
  double dw;
  double d2w;
};

Point Evaluate(const Signal& signal, double t) {
  Point p{t, 0.0, 0.0, 0.0};
  signal.ValueSlopeCurvature(t, &p.w, &p.dw, &p.d2w);
  return p;
}

/// The same from the signal's anchor, if it has one (Signal::AnchorAt):
/// the root refinement's points, whose rounding places the crossing.
Point EvaluatePrecisely(const Signal& signal, double t) {
  Point p{t, 0.0, 0.0, 0.0};
  signal.PreciseValueSlopeCurvature(t, &p.w, &p.dw, &p.d2w);
  return p;
}

/// B3 >= sup|w'''| over a flight, with the multiples every step uses
/// (computed once per flight: each step took five divisions by it).
struct ThirdBound {
  explicit ThirdBound(double b3)
      : b3(b3), half(0.5 * b3), sixth(b3 / 6.0), inverse(b3 > 0 ? 1.0 / b3 : 0.0) {}
  double b3, half, sixth, inverse;
};

/// The cubic upper bound P(s) = w + w' s + w'' s²/2 + B3 s³/6 >= w(t + s).
struct UpperCubic {
  UpperCubic(const Point& p, const ThirdBound& bound)
      : w(p.w),
        dw(p.dw),
        d2w(p.d2w),
        half_d2w(0.5 * p.d2w),
        b3(bound.b3),
        half_b3(bound.half),
        sixth_b3(bound.sixth),
        inverse_b3(bound.inverse) {}
  double operator()(double s) const { return w + s * (dw + s * (half_d2w + s * sixth_b3)); }
  double Slope(double s) const { return dw + s * (d2w + s * half_b3); }
  /// P'' = w'' + B3 s, rising (B3 >= 0).
  double Curvature(double s) const { return d2w + b3 * s; }
  double w, dw, d2w, half_d2w, b3, half_b3, sixth_b3, inverse_b3;
};

/// The root of P in [low, high], where P is increasing, P(low) < 0 <=
/// P(high), narrowed until the bracket is within 10% of `high`; returns
/// its left end (P < 0 there). Split at P's inflection, P is convex or
/// concave on the bracket; then Newton from the end where the tangent
/// stays on one side of the root and the chord from the other converge
/// from both sides (Fourier's method): about two iterations per step in
/// the paper's runs, where the Illinois method, whose one end lags, took
/// five and a half to 2% (docs/performance.md). A step 10% short of the
/// cubic's root costs no more evaluations of w than one 2% short: the next
/// step starts nearer the crossing (counts within 1% at Ω = 0.6, 1.4,
/// 1.75). Each new point joins the side its computed P gives, so rounding
/// cannot break the bracket.
double NarrowRoot(const UpperCubic& cubic, double low, double high) {
  double f_low = cubic(low), f_high = cubic(high);
  auto include = [&](double s) {
    if (!(s > low && s < high)) s = 0.5 * (low + high);
    const double f = cubic(s);
    (f < 0 ? low : high) = s;
    (f < 0 ? f_low : f_high) = f;
  };
  if (cubic.b3 > 0) {
    if (const double inflection = -cubic.d2w * cubic.inverse_b3;
        inflection > low && inflection < high) {
      include(inflection);
    }
  }
  const bool convex = cubic.Curvature(low) + cubic.Curvature(high) >= 0;
  for (int iteration = 0; iteration < 64 && high - low > 0.1 * high; ++iteration) {
    // Convex: the tangent at `high` and the chord bound the root from above and below;
    // concave: the tangent at `low` from below, the chord from above.
    const double newton =
        convex ? high - f_high / cubic.Slope(high) : low - f_low / cubic.Slope(low);
    const double chord = (low * f_high - high * f_low) / (f_high - f_low);
    include(newton);
    include(chord);
  }
  return low;
}

/// A step h with P < 0 on [0, h) (w < 0 at p), within 10% of P's first
/// positive root: no crossing can lie in [t, t + h). P is monotone between
/// its critical points, so the root is bracketed on the first monotone
/// piece whose end is not negative (NarrowRoot). On the last piece, which
/// rises for ever, the first end tried is `hint`, the search's previous
/// step (consecutive steps of a flight are alike): a point there with
/// P < 0 becomes the bracket's left end, and the next is tried a quarter
/// of the way further. The bracket is then usually tight from the start:
/// at Ω = 0.6 the Newton–chord iterations fell from 2.7 to 1.7 per step,
/// and the evaluations of w from 10.5 to 10.0 per impact, the steps landing
/// nearer the cubic's root (docs/performance.md).
double CertifiedStep(const Point& p, const ThirdBound& bound, double hint) {
  if (p.w >= 0) return 0.0;
  const UpperCubic cubic(p, bound);
  const double b3 = bound.b3;
  double pieces[2];
  int count = 0;
  // Critical points: P'(s) = w' + w'' s + B3 s²/2 = 0.
  if (b3 > 0) {
    const double discriminant = p.d2w * p.d2w - 2.0 * b3 * p.dw;
    if (discriminant > 0) {
      const double root = std::sqrt(discriminant);
      for (double s : {(-p.d2w - root) * bound.inverse, (-p.d2w + root) * bound.inverse}) {
        if (s > 0) pieces[count++] = s;
      }
    }
  } else if (p.d2w != 0 && -p.dw / p.d2w > 0) {
    pieces[count++] = -p.dw / p.d2w;
  }
  double low = 0.0, high = kInfinity;
  for (int i = 0; i < count && high == kInfinity; ++i) {
    if (cubic(pieces[i]) >= 0) {
      high = pieces[i];
    } else {
      low = pieces[i];
    }
  }
  if (high == kInfinity) {
    // The last piece rises to +inf when B3 > 0; find an end that is not negative.
    double span = hint > low ? hint - low : std::max(1.0, low);
    int tries = 0;
    while (cubic(low + span) < 0) {
      if (++tries > 64) return kInfinity;
      low += span;  // P is monotone on the piece and < 0 at both ends: < 0 up to here
      span *= tries == 1 ? 0.25 : 2.0;
    }
    high = low + span;
  }
  return NarrowRoot(cubic, low, high);
}

/// max over [a, b] of min(upper bound from a, upper bound from b), with
/// B >= sup|w''|. The two parabolas differ by a linear function of s, so the
/// maximum is at an end or where they meet.
double TwoSidedUpperBound(const Point& a, const Point& b, double bound) {
  const double h = b.t - a.t;
  double upper = std::max(a.w, b.w);
  // P_a(s) = wa + wa' s + B s²/2;  P_b(s) = wb - wb' (h - s) + B (h - s)²/2.
  // P_a - P_b = (wa - wb + wb' h - B h²/2) + (wa' - wb' + B h) s.
  const double slope = a.dw - b.dw + bound * h;
  if (slope != 0) {
    const double s = -(a.w - b.w + b.dw * h - 0.5 * bound * h * h) / slope;
    if (s > 0 && s < h) upper = std::max(upper, a.w + a.dw * s + 0.5 * bound * s * s);
  }
  return upper;
}

/// An upper bound of |w''| over [a, b] from its values at the ends and
/// B3 >= sup|w'''|: |w''| rises from each end by at most B3 per unit time,
/// so it stays below where the two lines meet. Where w'' nearly cancels (a
/// mass resting at its stop's level while the others swing) this is far
/// below the flight's sup|w''|, and an interval where w stays within the
/// resolution of 0 is dismissed after a few halvings, not millions. The
/// ends' w'' carry rounding of about ε S ω² (S: the magnitude of w's
/// parts); over an interval of up to one time scale, 2π/ω, that moves the
/// parabola by at most ε S (2π)²/8 ≈ 5 ε S, below the resolution, 64 ε S.
double CurvatureBound(const Point& a, const Point& b, const ThirdBound& third) {
  return 0.5 * (std::abs(a.d2w) + std::abs(b.d2w) + third.b3 * (b.t - a.t));
}

/// A lower bound of w' over [a, b].
double SlopeLowerBound(const Point& a, const Point& b, double bound) {
  return 0.5 * (a.dw + b.dw - bound * (b.t - a.t));
}

/// The tolerance for time t: the requested one, or a few ulps of t.
double TimeTolerance(double t, const EventOptions& options) {
  return std::max(options.time_tolerance,
                  4.0 * std::numeric_limits<double>::epsilon() * std::abs(t));
}

/// The root of w in [a, b], where w(a) < 0 <= w(b) and w' >= slope_bound > 0
/// on [a, b]: Newton on the exact derivative from t (the caller's estimate),
/// kept inside the shrinking bracket (bisection when a Newton step would
/// leave it). Hand-written because the certified bracket and the exact w'
/// make it converge in a few steps, and the bracket invariant is what the
/// caller relies on. A Newton step from t, at distance e <= |w(t)|/slope_bound
/// from the root, lands within curvature_bound e² / (2 w'(t)) of it (Taylor);
/// once that is below the rounding of t (half an ulp) the step is returned
/// without the evaluation that would only confirm it (one of about ten per
/// flight). Below the tolerance but above the rounding it is not: in a
/// chatter sequence the accumulation point moves by 10³–10⁴ times an
/// impact's time error (docs/theory.md §4).
double RefineRoot(const Signal& w, Point a, Point b, double t, double slope_bound,
                  double curvature_bound, const EventOptions& options) {
  for (int iteration = 0; iteration < 100; ++iteration) {
    if (!(t > a.t && t < b.t)) t = 0.5 * (a.t + b.t);
    const Point p = EvaluatePrecisely(w, t);
    if (p.w == 0) return t;
    (p.w < 0 ? a : b) = p;
    const double tolerance = TimeTolerance(t, options);
    const double newton = t - p.w / p.dw;
    const double distance = std::abs(p.w) / slope_bound;
    const double rounding = 0.5 * std::numeric_limits<double>::epsilon() * std::abs(t);
    const bool converged = std::abs(newton - t) <= tolerance ||
                           0.5 * curvature_bound * distance * distance <= rounding * p.dw;
    if (converged) return std::clamp(newton, a.t, b.t);
    if (b.t - a.t <= tolerance) return b.t;
    t = newton;
  }
  return b.t;
}

/// How w leaves the surface at p: the sign of w if it is not rounding noise
/// (order 0), else of its first derivative w^(k), k <= 3, that is not
/// (order k); sign 0 if all are noise. Noise in w^(k) is relative to its
/// bound, and never below the rounding the caller states for a start on
/// the surface (EventOptions::start_noise, times rate^k for w^(k), rate =
/// 2π / time_scale): a motion much smaller than the state it is computed
/// from (a mass barely leaving the stop while the others swing) has bounds
/// far below that rounding; without the floor its start would read as a
/// crossing, and the mass would land and leave again one ulp later, over
/// and over.
struct Departure {
  int sign = 0;
  int order = 0;
  double derivative = 0.0;
};

Departure Depart(const Signal& w, const Point& p, const double* bounds,
                 const EventOptions& options) {
  constexpr double kNoise = 1e-11;
  const double rate = 2 * std::numbers::pi / options.time_scale;
  double rounding = options.start_noise;
  constexpr int kHighestOrder = 3;
  for (int k = 0; k <= kHighestOrder; ++k, rounding *= rate) {
    const double derivative = k == 0   ? p.w
                              : k == 1 ? p.dw
                              : k == 2 ? p.d2w
                                       : w.Derivative(k).Value(p.t);
    if (std::abs(derivative) <= std::max(kNoise * bounds[k], rounding)) continue;
    return {derivative > 0 ? 1 : -1, k, derivative};
  }
  return {};
}

/// Leaving the surface (w = 0 up to rounding at p) downwards: if w^(k) is
/// the first derivative that is not noise and is negative, Taylor's theorem
/// with B >= sup|w^(k+1)| keeps w < 0 on (0, (k+1)|w^(k)|/B): after an
/// impact k = 1, at a release from sticking k = 2 or 3. Returns that step,
/// or 0 when w is not at the surface or not certainly leaving it. Without
/// this, an interval starting on the surface could never be certified empty.
/// `bounds` holds orders 0 to 3 (from p.t); order 4, needed only at a
/// release of order 3, is computed here.
double SurfaceExitStep(const Signal& w, const Point& p, const double* bounds,
                       const EventOptions& options) {
  const Departure departure = Depart(w, p, bounds, options);
  if (departure.order == 0 || departure.sign >= 0) return 0.0;
  const int k = departure.order;
  const double next_bound = k < 3 ? bounds[k + 1] : w.DerivativeBound(4, p.t);
  if (!(next_bound > 0)) return kInfinity;
  const double step = (k + 1) * -departure.derivative / next_bound;
  if (k > 1) return step;
  // After an impact the known w'' often pulls w away from the surface:
  // w <= s (w' + w'' s/2 + B3 s²/6) keeps w < 0 up to the quadratic's
  // positive root (written without cancellation), often well beyond the
  // step above.
  const double half_curvature = 0.25 * p.d2w;
  const double root = std::sqrt(half_curvature * half_curvature - bounds[3] / 6.0 * p.dw);
  return std::max(step, -p.dw / (half_curvature + root));
}

/// The first crossing after p when the cubic lower bound certifies it close
/// ahead, else none (the caller steps on). With L(s) = w + w' s + w'' s²/2
/// − B3 s³/6 <= w(t + s) and the certified step h (U < 0 on [0, h)): if
/// L(s_l) >= margin (the rounding of w, or the search's resolution) and the
/// lower bound of w', w' + w'' s − B3 s²/2 (concave: least at an end), is
/// positive at h and s_l, then w < 0 at t + h, w > 0 at t + s_l and w
/// rises in between, so the first crossing is the one root there: refined
/// by Newton from the root of the Taylor quadratic T = (U + L)/2, which lies
/// between. s_l is tried where L's root would be by the symmetry of U and L
/// about T: 2 s_T − h, plus the margin's share. Without this, the search
/// approached the root in shrinking certified steps (two or three more
/// evaluations per flight) and, near grazing, by bisection.
std::optional<double> CertainCrossing(const Signal& w, const Point& p, double certified,
                                      const ThirdBound& bound, double t_end, double margin,
                                      const EventOptions& options) {
  // The lower bound of w' must be positive at the step's end: three
  // products, and most steps fail it, so it comes before the Taylor root's
  // square root and divisions.
  auto slope_bound = [&](double s) { return p.dw + s * (p.d2w - bound.half * s); };
  const double slope_at_step = slope_bound(certified);
  if (!(slope_at_step > 0)) return std::nullopt;
  // The Taylor quadratic's first positive root, where it rises.
  const double a2 = 0.5 * p.d2w;
  double s_taylor;
  if (a2 == 0) {
    if (!(p.dw > 0)) return std::nullopt;
    s_taylor = -p.w / p.dw;
  } else {
    const double discriminant = p.dw * p.dw - 4.0 * a2 * p.w;
    if (!(discriminant >= 0)) return std::nullopt;
    // The root where T' = w' + w'' s > 0, written without cancellation.
    s_taylor = 2.0 * -p.w / (p.dw + std::sqrt(discriminant));
  }
  const double rise = p.dw + p.d2w * s_taylor;  // T'(s_T)
  if (!(s_taylor > certified && rise > 0)) return std::nullopt;
  const double far = 2.0 * s_taylor - certified + 2.0 * margin / rise;
  if (p.t + far > t_end) return std::nullopt;
  const double lower = p.w + far * (p.dw + far * (a2 - far * bound.sixth));
  const double slope = std::min(slope_at_step, slope_bound(far));
  if (!(lower >= margin && slope > 0)) return std::nullopt;
  const Point a{p.t + certified, -kInfinity, 0.0, 0.0};
  const Point b{p.t + far, kInfinity, 0.0, 0.0};
  return RefineRoot(w, a, b, p.t + s_taylor, slope, bound.b3 * far + std::abs(p.d2w), options);
}

/// The first crossing in (a, b], or none, by certified bisection.
std::optional<double> Examine(const Signal& w, const Point& a, const Point& b, double bound,
                              const ThirdBound& third, const EventOptions& options) {
  if (b.w >= 0 && a.w < 0) {
    if (const double slope = SlopeLowerBound(a, b, bound); slope > 0) {
      const Point& nearer = -a.w < b.w ? a : b;
      return RefineRoot(w, a, b, nearer.t - nearer.w / nearer.dw, slope, bound, options);
    }
  }
  // Empty, or w could rise above 0 only by less than the resolution: a
  // touch of the surface that is not resolved (EventOptions::resolution).
  if (b.w < 0 &&
      TwoSidedUpperBound(a, b, std::min(bound, CurvatureBound(a, b, third))) < options.resolution) {
    return std::nullopt;
  }
  if (b.t - a.t <= TimeTolerance(b.t, options)) {
    // A tangency resolved to the tolerance: an event only if w got to 0.
    return b.w >= 0 ? std::optional<double>(b.t) : std::nullopt;
  }
  const Point m = Evaluate(w, 0.5 * (a.t + b.t));
  // By induction Examine returns a crossing whenever its right end has
  // w >= 0, so the right half is searched only from m with w(m) < 0.
  if (auto left = Examine(w, a, m, bound, third, options)) return left;
  return Examine(w, m, b, bound, third, options);
}

}  // namespace

std::optional<double> FirstUpcrossing(const Signal& w, double t_begin, double t_end,
                                      const EventOptions& options) {
  const double short_step = 1e-3 * options.time_scale;
  // Bounds of |w^(k)| valid for every t >= t_begin (Signal::DerivativeBound),
  // k = 0 to 3; order 4 is rarely needed (SurfaceExitStep).
  double bounds[4];
  w.DerivativeBounds(t_begin, 3, bounds);
  if (bounds[0] == 0) return std::nullopt;  // w = 0 throughout
  // w <= R + (bound of the rest) < 0 for every t >= t_begin: a stop far
  // beyond the motion's reach is settled without a step.
  const double constant = w.Constant();
  if (constant + (bounds[0] - std::abs(constant)) < -kUnreachableMargin * w.Scale()) {
    return std::nullopt;
  }
  const double b2 = bounds[2];
  const ThirdBound third(bounds[3]);
  const double margin = std::max(kCertainMargin * bounds[0], options.resolution);
  Point p = Evaluate(w, t_begin);
  if (const double exit = SurfaceExitStep(w, p, bounds, options); exit > 0) {
    if (exit >= t_end - t_begin) return std::nullopt;
    p = Evaluate(w, t_begin + exit);
  }
  double step = 0.0;
  while (p.t < t_end) {
    step = CertifiedStep(p, third, step);
    if (step >= t_end - p.t) return std::nullopt;
    if (auto crossing = CertainCrossing(w, p, step, third, t_end, margin, options)) return crossing;
    if (step >= short_step) {
      const Point next = Evaluate(w, p.t + step);
      // The bound makes next.w <= 0; rounding can make it touch 0.
      if (next.w >= 0) return Examine(w, p, next, b2, third, options);
      p = next;
      continue;
    }
    const Point b = Evaluate(w, std::min(t_end, p.t + std::max(4.0 * step, short_step)));
    if (auto crossing = Examine(w, p, b, b2, third, options)) return crossing;
    p = b;
  }
  return std::nullopt;
}

std::vector<double> SignChanges(const Signal& w, double t_begin, double t_end,
                                const EventOptions& options) {
  std::vector<double> times;
  const Signal negated = w.Negated();
  double value, slope;
  w.ValueAndSlope(t_begin, &value, &slope);
  bool rising = value < 0 || (value == 0 && slope < 0);  // looking for w to rise through 0
  double t = t_begin;
  while (auto crossing = FirstUpcrossing(rising ? w : negated, t, t_end, options)) {
    if (*crossing >= t_end) break;
    times.push_back(*crossing);
    t = *crossing;
    rising = !rising;
  }
  return times;
}

int SurfaceSign(const Signal& w, double t, const EventOptions& options) {
  double bounds[4];
  w.DerivativeBounds(t, 3, bounds);
  const Point p = Evaluate(w, t);
  if (const int sign = Depart(w, p, bounds, options).sign; sign != 0) return sign;
  // All rounding: the raw values decide, so that asking twice at one
  // instant gets one answer.
  for (const double value : {p.w, p.dw, p.d2w}) {
    if (value != 0) return value > 0 ? 1 : -1;
  }
  return 0;
}

}  // namespace impactkit
