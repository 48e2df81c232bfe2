#pragma once
/// \file curve_tests.hpp (private)
/// The second test functions watched along a two-parameter curve, each
/// zero at one kind of codimension-two point (curve.hpp), and the curve
/// point's grazing and sticking monitors that end a curve.

#include <optional>
#include <vector>

#include "continuation/existence_monitor.hpp"
#include "impactkit/continuation/curve.hpp"

namespace impactkit::detail {

struct SecondTest {
  Codim2Type type;
  /// The test's value at `point`; `reference` is the point that starts the
  /// interval searched (the cusp's test is relative to its direction).
  /// NaN where the test has no value (no complex pair for a resonance).
  double (*value)(const CurvePoint& point, const CurvePoint& reference);
  /// Whether a located zero is this point (a neutral saddle also zeroes
  /// Π (λ_i λ_j − 1); a sharp turn is no cusp).
  bool (*accept)(const CurvePoint& point);
};

/// The tests along a curve of `type` (the curve's own condition excluded).
std::vector<SecondTest> SecondTests(SpecialPointType type);

/// The codimension-two point where a curve of `type` reaches a grazing
/// (double grazing for a grazing curve).
Codim2Type GrazingMeeting(SpecialPointType type);

/// An existence monitor of a curve point in its linear form
/// (existence_monitor.hpp): on a grazing curve the second-least clearance,
/// the least being the curve's own touch. Empty when absent, and on the
/// non-impacting response's grazing curve, which has no orbit to watch.
std::optional<double> PointMonitor(const CurvePoint& point, Monitor monitor);

}  // namespace impactkit::detail
