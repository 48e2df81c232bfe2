#pragma once
/// \file events.hpp
/// Event location on exact flows, without ever skipping a crossing.
///
/// An event is a witness function w(t) (a Signal: the gap x_c - xs for
/// impacts, minus the contact force for release) reaching 0 from below.
/// Sampling w and checking its sign misses a pair of crossings inside one
/// step, the classic failure near grazing. Here every step is certified:
/// with B >= sup |w''| (computable in closed form for a Signal, see
/// Signal::DerivativeBound), Taylor's theorem gives
///
///     w(t + s) <= w(t) + w'(t) s + B s² / 2,
///
/// so no crossing can lie before the first positive root h* of the right
/// side, and the search steps by h*. Near a contact (h* tiny) an interval
/// [a, b] is examined with the two-sided bound (from a and from b; their
/// difference is linear in s, so the bound's maximum is at an end or where
/// the two parabolas meet) and bisected, left half first, until it is
/// certified empty or certified to hold a single crossing (w' > 0
/// throughout by the same bound on w''), which is then refined.

#include <optional>
#include <vector>

#include "impactkit/dynamics/flow.hpp"

namespace impactkit {

struct EventOptions {
  /// Refinement stops when the bracket is below this (time units); it is
  /// raised to a few ulps of t where t is large.
  double time_tolerance = 1e-13;
  /// The system's shortest time scale; steps shorter than 1e-3 of it switch
  /// from stepping to examining intervals.
  double time_scale = 1.0;
  /// The rounding of w at t_begin when the search starts where w = w' = 0
  /// in truth (a mass leaving the stop from rest): w^(k) below this times
  /// (2π / time_scale)^k counts as zero there. 0: judged by w's bounds alone.
  double start_noise = 0.0;
  /// Rises of w above 0 smaller than this are not events: where w hovers
  /// within rounding of 0 (a mass moving along the stop) certifying every
  /// piece of it empty would take ever shorter intervals. 0: every crossing.
  double resolution = 0.0;
};

/// The first t in (t_begin, t_end] where w reaches 0 from below; w(t_begin)
/// must be <= 0 (an event at t_begin itself, w = 0 with w' <= 0, is not
/// reported again). A tangency that cannot be resolved above the time
/// tolerance (w touching 0 with w' = 0) counts as a crossing only if w >= 0
/// at the touching point.
std::optional<double> FirstUpcrossing(const Signal& w, double t_begin, double t_end,
                                      const EventOptions& options);

/// Every t in (t_begin, t_end) where w changes sign, in increasing order
/// (with w a velocity: the interior extrema of the position).
std::vector<double> SignChanges(const Signal& w, double t_begin, double t_end,
                                const EventOptions& options);

/// The side of 0 that w is on or moves to at t: the sign of w, or where w
/// is 0 to rounding (within EventOptions::start_noise or 1e-11 of its
/// bound) of its first derivative up to the third that is not; if all are
/// rounding, of the first nonzero of w, w', w'' as computed (0 if none).
/// FirstUpcrossing leaves the surface by the same judgement.
int SurfaceSign(const Signal& w, double t, const EventOptions& options);

}  // namespace impactkit
