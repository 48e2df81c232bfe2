#include "impactkit/core/parameter_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "impactkit/core/errors.hpp"

namespace impactkit {
namespace {

/// `value` rounded to `digits` significant decimal digits, read back as a double.
double RoundToDigits(double value, int digits) {
  const std::string text = fmt::format("{:.{}e}", value, digits - 1);
  return std::strtod(text.c_str(), nullptr);
}

}  // namespace

double GridValue(double from, double to, int count, int k) {
  if (count < 1 || k < 0 || k >= count) {
    throw InvalidInput(fmt::format("grid index {} is outside a grid of {} values", k, count));
  }
  if (!std::isfinite(from) || !std::isfinite(to)) {
    throw InvalidInput(fmt::format("a grid needs finite ends, got {} and {}", from, to));
  }
  if (k == 0) return from;
  if (k == count - 1) return to;
  const double raw = std::lerp(from, to, static_cast<double>(k) / (count - 1));
  const double scale = std::max(std::abs(from), std::abs(to));
  const double spacing = std::abs(to - from) / (count - 1);
  const double tolerance =
      std::min(4.0 * std::numeric_limits<double>::epsilon() * scale, 1e-3 * spacing);
  for (int digits = 1; digits < std::numeric_limits<double>::max_digits10; ++digits) {
    const double candidate = RoundToDigits(raw, digits);
    if (std::abs(candidate - raw) <= tolerance) return candidate;
  }
  return raw;
}

std::vector<double> GridValues(double from, double to, int count) {
  std::vector<double> values(count);
  for (int k = 0; k < count; ++k) values[k] = GridValue(from, to, count, k);
  return values;
}

}  // namespace impactkit
