#pragma once
/// \file common/require.hpp
/// The one check every command makes of its flags before any work.

#include <string>

#include "impactkit/core/errors.hpp"

namespace impactkit::cli {

/// Throws InvalidInput(message) unless `condition`: bad input, which main()
/// reports as exit status 2 before anything runs or is written.
inline void Require(bool condition, const std::string& message) {
  if (!condition) throw InvalidInput(message);
}

}  // namespace impactkit::cli
