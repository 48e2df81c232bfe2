#pragma once
/// \file errors.hpp
/// The library's exception for bad user input. Numerical outcomes (no
/// convergence, a branch ended at grazing) are never exceptions: they are the
/// termination of a summary (termination.hpp).

#include <stdexcept>
#include <string>

namespace impactkit {

/// Thrown for bad user input and misuse: the message names the parameter and
/// the allowed range, on one line.
class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Throws InvalidInput(message) unless `condition` holds.
inline void Require(bool condition, const std::string& message) {
  if (!condition) throw InvalidInput(message);
}

}  // namespace impactkit
