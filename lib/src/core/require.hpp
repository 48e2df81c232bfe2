#pragma once
/// \file require.hpp (private)
/// Require (core/errors.hpp) with a message formatted only where the
/// condition fails. A system is validated at every parameter value a
/// continuation visits (μ and μ ± h of each Jacobian), and formatting each
/// check's message whether it failed or not was a tenth of a connected
/// diagram's allocations (docs/performance.md).

#include <fmt/format.h>

#include <utility>

#include "impactkit/core/errors.hpp"

namespace impactkit {

/// Throws InvalidInput(fmt::format(format, args...)) unless `condition` holds.
template <typename... Args>
requires(sizeof...(Args) > 0) void Require(bool condition, fmt::format_string<Args...> format,
                                           Args&&... args) {
  if (!condition) throw InvalidInput(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace impactkit
