#pragma once
/// \file common/arclength_flags.hpp
/// The arclength flags of `continue`, `curve` and `diagram` (steps and
/// points per direction), checked
/// before any work with a message that names the flags. The library's own
/// message names its fields (min_step, initial_step, max_step: the Python
/// keywords, max_points), which a command-line user never typed.

#include <string>

namespace impactkit::cli {

/// Throws InvalidInput unless 0 < min_step <= step <= max_step < ∞ and
/// max_points >= 2. `min_flag` names the smallest step for the message:
/// "--min-step", or a description where the command has no such flag.
void RequireArclengthFlags(double step, double min_step, double max_step, long long max_points,
                           const std::string& min_flag = "--min-step");

}  // namespace impactkit::cli
