#include "common/arclength_flags.hpp"

#include <fmt/format.h>

#include <cmath>

#include "impactkit/core/errors.hpp"

namespace impactkit::cli {

void RequireArclengthFlags(double step, double min_step, double max_step, long long max_points,
                           const std::string& min_flag) {
  Require(max_points >= 2,
          fmt::format("--max-points must be >= 2 (a branch needs two points), got {}", max_points));
  Require(min_step > 0, fmt::format("{} must be > 0, got {}", min_flag, min_step));
  Require(
      std::isfinite(max_step) && max_step >= min_step,
      fmt::format("--max-step {} must be finite and at least {} {}", max_step, min_flag, min_step));
  Require(step >= min_step && step <= max_step,
          fmt::format("--step {} must lie between {} {} and --max-step {}", step, min_flag,
                      min_step, max_step));
}

}  // namespace impactkit::cli
