#pragma once
/// \file curve_tests.hpp (private)
/// The second test functions watched along a two-parameter curve, each
/// zero at one kind of codimension-two point (curve.hpp), and the grazing
/// and sticking monitors that end a curve.

#include <optional>
#include <vector>

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

/// An existence monitor of a curve point: positive while the orbit exists,
/// in the form linear in arclength near its zero (the clearance; the square
/// root of the depth, as continuation.cpp explains). Empty when absent.
enum class Monitor { kClearance, kDepth };
std::optional<double> LinearMonitor(const CurvePoint& point, Monitor monitor);
/// The monitor as a length, from its linear form.
double MonitorLength(double linear, Monitor monitor);

}  // namespace impactkit::detail
