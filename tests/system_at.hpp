#pragma once
/// \file system_at.hpp
/// A system with one named parameter changed, as tests write their points.

#include <string>

#include "impactkit/model/parameters.hpp"

namespace impactkit::testing {

inline System At(System system, const std::string& name, double value) {
  SetParameter(system, name, value);
  return system;
}

}  // namespace impactkit::testing
