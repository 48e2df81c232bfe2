#pragma once
/// \file curve_plane.hpp
/// The options of a curve of P(p, q) in (omega, second), omega in
/// [0.5, 3], as the curve tests write them.

#include <string>

#include "impactkit/continuation/curve.hpp"

namespace impactkit::testing {

inline CurveOptions Plane(const std::string& second, double lower2, double upper2, int p, int q) {
  CurveOptions options;
  options.parameter = "omega";
  options.parameter2 = second;
  options.lower = 0.5;
  options.upper = 3.0;
  options.lower2 = lower2;
  options.upper2 = upper2;
  options.orbit.p = p;
  options.orbit.q = q;
  return options;
}

}  // namespace impactkit::testing
