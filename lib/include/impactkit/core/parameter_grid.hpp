#pragma once

#include <vector>

namespace impactkit {

/// The k-th of `count` evenly spaced values from `from` to `to` (both ends
/// included exactly; count = 1 gives `from`).
///
/// Why not plain `from + k * step`: in binary, 0.1 + 52 * 0.04 is
/// 2.1799999999999997, and a table or an axis then shows a value nobody asked
/// for. The grid point is computed with std::lerp (exact at the ends,
/// monotonic), then replaced by the shortest decimal lying within a few ulps
/// of it, so the value the computation uses is exactly the one printed (fmt
/// prints doubles as their shortest round-trip decimal). The tolerance is also
/// kept below a thousandth of the spacing, so a grid finer than the rounding
/// keeps its raw values and never merges two points.
double GridValue(double from, double to, int count, int k);

/// All `count` values of GridValue, in order from `from` to `to`.
std::vector<double> GridValues(double from, double to, int count);

}  // namespace impactkit
