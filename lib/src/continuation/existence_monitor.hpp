#pragma once
/// \file existence_monitor.hpp (private)
/// The monitors that end a branch or a two-parameter curve where its orbit
/// stops existing — the least clearance of a flight from a stop (a
/// grazing) and the depth of the slowest impact (an impact vanishing, or
/// sticking) — and the one secant approach to their zero that branches and
/// curves share.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "continuation/arclength.hpp"
#include "impactkit/orbits/orbit.hpp"

namespace impactkit::detail {

/// A monitor: positive while the orbit exists, zero at the event.
enum class Monitor { kClearance, kDepth };

/// A point counts as at the event when its monitor (a length) is below
/// this; an approach stops when its step is shorter than kGrazingBracket
/// (arclength). Rounding in the map limits how close the corrector gets
/// (about 1e-10 for the clearance): a zero within ten times the tolerance
/// counts.
inline constexpr double kGrazingTolerance = 1e-10;
inline constexpr double kGrazingBracket = 1e-13;
/// The monitor length at which an approach counts as at the event.
inline constexpr double kEventReach = 10 * kGrazingTolerance;

/// The monitor of `orbit` in the form that varies linearly in arclength
/// near its zero, so that secant steps converge fast: the clearance itself,
/// and the square root of the depth (the slowest impact's speed goes to
/// zero linearly along a branch: Nordmark's normal form has the fixed
/// point's penetration quadratic in the distance to grazing). With
/// `next_clearance` the second-least clearance (on a grazing curve the
/// least is the curve's own touch). Empty when absent.
std::optional<double> LinearMonitor(const PeriodicOrbit& orbit, Monitor monitor,
                                    bool next_clearance = false);

/// The monitor as reported (a length), from its linear form.
double MonitorLength(double linear, Monitor monitor);

/// Why a march may stop short of a located event (its corrector failed,
/// or max_points): "; impact 2 vanishes <where> (depth 2.2e-09, not
/// located to 1e-10)" when the slowest impact's depth is below `within`,
/// the same of a new contact's clearance (with `clearance`), else nothing.
std::string ShortOfEvent(const OrbitContacts& contacts, double within, std::string_view where,
                         bool clearance);

/// True when a monitor (`linear` of a point), extrapolated linearly in
/// arclength from a to b, reaches zero within `step` beyond b.
template <typename Point, typename Linear>
bool ZeroAhead(const Point& a, const Point& b, double step, Linear linear) {
  for (Monitor monitor : {Monitor::kClearance, Monitor::kDepth}) {
    const std::optional<double> ma = linear(a, monitor), mb = linear(b, monitor);
    if (!ma || !mb || !(*mb < *ma)) continue;
    if (*mb * (b.arclength - a.arclength) / (*ma - *mb) < step) return true;
  }
  return false;
}

/// Where an approach to a monitor's zero stopped: its last two points and
/// the monitor's linear form at the last.
template <typename Point>
struct MonitorApproach {
  Point previous, best;
  double linear = 0.0;
};

/// The zero of a monitor beyond b, approached from the side where the
/// orbit exists (past it the orbit does not exist, so the far side is only
/// known to fail): secant steps on the monitor's linear form from the last
/// two points, each from the newest point along its own tangent (near a
/// vanishing impact the branch bends fast), at most `max_step`, halved when
/// they land where `advance(from, s, tolerance_scale)` fails or the monitor
/// does not fall. Near a vanishing impact the multipliers grow like 1/v
/// and so does the rounding in U (the impact time's): Newton is asked for
/// what that conditioning allows. Stops once the monitor is below
/// kGrazingTolerance, the step below kGrazingBracket, or after
/// kMaxLocateIterations; nothing where the monitor does not fall from a
/// to b or `refuse` rejects a trial. The points passed, in order, in *path.
///
/// A step that failed bounds all later ones (they stay short of it), so
/// once the secant, continued to that bound, leaves the monitor above
/// `reach` (the length the caller accepts as the event) by more than half
/// its remaining fall, the approach stops: the monitor would have
/// to fall twice as steeply as it has been to be reached. Without that
/// stop an approach towards a zero beyond the bound (a corrector failing
/// for rounding, not for the event) creeps up to the bound by halvings,
/// some 35 Newton solves each (docs/performance.md).
template <typename Point, typename Advance, typename Linear, typename Refuse>
std::optional<MonitorApproach<Point>> ApproachMonitorZero(const Point& a, const Point& b,
                                                          Monitor monitor, Linear linear,
                                                          Advance advance, double max_step,
                                                          double reach, Refuse refuse,
                                                          std::vector<Point>* path) {
  const double reach_linear = monitor == Monitor::kClearance ? reach : std::sqrt(reach);
  MonitorApproach<Point> at{a, b, 0.0};
  std::optional<double> m_prev = linear(a, monitor), m_lo = linear(b, monitor);
  if (!m_prev || !m_lo || !(*m_lo < *m_prev)) return std::nullopt;
  double failed = std::numeric_limits<double>::infinity();  // a step from `best` that failed
  for (int k = 0; k < kMaxLocateIterations && MonitorLength(*m_lo, monitor) > kGrazingTolerance;
       ++k) {
    const double slope = (*m_prev - *m_lo) / (at.best.arclength - at.previous.arclength);
    if (slope * failed < 0.5 * (*m_lo - reach_linear)) break;  // out of reach before the bound
    double s = std::min(*m_lo / slope, max_step);
    if (s >= failed) s = 0.5 * failed;
    if (!(s > kGrazingBracket)) break;
    const double conditioning = std::abs(at.best.orbit.multipliers(0));
    const std::optional<Point> trial = advance(at.best, s, std::max(1.0, 1e-4 * conditioning));
    if (trial && refuse(*trial)) return std::nullopt;
    const std::optional<double> m = trial ? linear(*trial, monitor) : std::nullopt;
    if (!m || !(*m < *m_lo)) {  // failed, or the monitor jumped
      failed = s;
      continue;
    }
    at.previous = at.best;
    m_prev = m_lo;
    at.best = *trial;
    m_lo = m;
    failed -= s;
    path->push_back(at.best);
  }
  at.linear = *m_lo;
  return at;
}

}  // namespace impactkit::detail
