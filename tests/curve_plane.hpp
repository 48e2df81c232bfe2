#pragma once
/// \file curve_plane.hpp
/// How the curve tests start a curve of P(p, q) in (omega, second), omega
/// in [0.5, 3]: its options and its start point.

#include <catch2/catch.hpp>
#include <optional>
#include <string>

#include "impactkit/continuation/curve.hpp"
#include "seeded_orbit.hpp"
#include "system_at.hpp"

namespace impactkit::testing {

inline CurveOptions Plane(const std::string& second, double lower2, double upper2, int p, int q) {
  CurveOptions options;
  options.parameter = "omega";
  options.parameter2 = second;
  options.from = 0.5;
  options.to = 3.0;
  options.from2 = lower2;
  options.to2 = upper2;
  options.orbit.p = p;
  options.orbit.q = q;
  return options;
}

/// The special point of `type` in omega nearest the start, from a branch
/// through the seeded orbit of `system`.
inline CurveStart Start(const System& system, SpecialPointType type, int p, int q) {
  ContinuationOptions options;
  options.from = 0.5;
  options.to = 3.0;
  options.orbit.p = p;
  options.orbit.q = q;
  const std::optional<SpecialPoint> special =
      LocateSpecialPoint({system, SeededOrbit(system, p, q), {}}, options, type);
  REQUIRE(special.has_value());
  return {At(system, "omega", special->parameter), *special};
}

}  // namespace impactkit::testing
